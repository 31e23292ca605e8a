#!/usr/bin/env bash
# Installs the Debian packages robokin builds against, only those missing.
# Usage: scripts/install-system-deps.sh [extra-package ...]
set -euo pipefail
packages=(libeigen3-dev liborocos-kdl-dev libkdl-parser-dev liburdfdom-dev "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "Installing Debian packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
