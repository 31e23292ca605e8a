#!/usr/bin/env bash
# Installs the Debian packages that building and testing robokin needs, only those missing.
#
#   PYTHON=python3 scripts/install-system-deps.sh [extra-package ...]
#
# What a bare Debian lacks is found by trying, not by package name alone, so that a machine whose
# Python or compiler does not come from Debian (pyenv, conda, a CXX of its own) installs nothing:
#   - the C++ libraries: libeigen3-dev, liborocos-kdl-dev, liburdfdom-dev, libconsole-bridge-dev,
#     libsleef-dev (vectorised sin, cos, atan2 for the batch paths);
#   - the X server and key sender of the real-window tests: xvfb, xdotool;
#   - a C++17 compiler ($CXX, c++ or g++): g++;
#   - $PYTHON itself (python3), its venv module with ensurepip (python3-venv) and its headers,
#     Python.h (python3-dev);
#   - the extra packages named on the command line.
# It installs with apt-get (one `apt-get update` first), through sudo when not root. When it cannot
# (no apt-get, or neither root nor sudo) it prints one line naming the packages and exits 1.
set -euo pipefail
python=${PYTHON:-python3}
missing=()

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
need() { installed "$1" || missing+=("$1"); }

for p in libeigen3-dev liborocos-kdl-dev liburdfdom-dev libconsole-bridge-dev libsleef-dev xvfb xdotool "$@"; do need "$p"; done

has_compiler() { command -v "${CXX:-c++}" >/dev/null 2>&1 || command -v g++ >/dev/null 2>&1; }
has_python() { command -v "$python" >/dev/null 2>&1; }
has_venv() { "$python" -c 'import ensurepip, venv' >/dev/null 2>&1; }
has_headers() {
  "$python" -c 'import os, sys, sysconfig
sys.exit(not os.path.isfile(os.path.join(sysconfig.get_paths()["include"], "Python.h")))' >/dev/null 2>&1
}
# Debian's packages serve Debian's python3: another interpreter that lacks venv or headers needs
# them from wherever it came from.
python_or_stop() {
  has_python && has_venv && has_headers && return 0
  echo "robokin needs $python with its venv module and headers (Python.h); $(command -v "$python" || echo "$python") lacks them: use Debian's python3 (make PYTHON=/usr/bin/python3) or install them for that interpreter" >&2
  exit 1
}

has_compiler || need g++
if ! has_python; then
  need python3; need python3-venv; need python3-dev
else
  has_venv || need python3-venv
  has_headers || need python3-dev
fi

if [ ${#missing[@]} -eq 0 ]; then python_or_stop; exit 0; fi

if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "robokin needs these Debian packages: ${missing[*]}. Install them as root: apt-get install ${missing[*]}" >&2
  exit 1
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "robokin needs these Debian packages (or your system's equivalents): ${missing[*]}; apt-get was not found to install them" >&2
  exit 1
fi

echo "Installing Debian packages: ${missing[*]}"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
export DEBIAN_FRONTEND=noninteractive
if ! { "${sudo[@]}" apt-get update -qq && "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
  tail -20 "$log" >&2
  echo "robokin could not install the Debian packages ${missing[*]} (apt-get's last lines above)" >&2
  exit 1
fi
python_or_stop
