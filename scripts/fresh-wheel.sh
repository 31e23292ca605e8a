#!/usr/bin/env bash
# The wheel on a bare Debian bookworm without a compiler, installed and used by an ordinary user.
#
#   scripts/fresh-wheel.sh          (as root, from anywhere in the project's checkout)
#
# It builds the wheel here from the working tree (`make wheel`; in CI a fresh clone), copies it into
# a minimal Debian (debootstrap --variant=minbase) that gets only python3 and python3-venv from
# apt-get, checks that no compiler and no -dev package is there, and as a non-root user in a clean
# environment (env -i) makes a venv, installs the wheel with its [sim] extra from PyPI and checks:
# the import, an FK/IK round trip on the UR5, a chain from a URDF string, a headless simulator run's
# GIF and CSV, and that the extensions load no library but the wheel's own and the base system's
# (ldd).
#
# Exit status (as ../shared/fresh-debian.sh's): 0 every check passed; 1 the wheel failed to build or a
# check failed (its log's tail is printed); 3 the bare system itself could not be made (no
# debootstrap, no package mirror: not the project's fault, and said so). The bare base is cached in
# $FRESH_ROOT (default /var/tmp/robokin-fresh) and shared with fresh-debian.sh.
set -uo pipefail
project=$(git rev-parse --show-toplevel 2>/dev/null) || { echo "fresh-wheel: run it from inside the project's git checkout"; exit 1; }
root=${FRESH_ROOT:-/var/tmp/robokin-fresh}
user=robokin-user
[ "$(id -u)" = 0 ] || { echo "fresh-wheel: needs root (debootstrap, chroot, mount)"; exit 3; }

build_wheel() {
  echo "== make wheel (this machine)"
  SECONDS=0
  if ! make -C "$project" wheel >"$root/make-wheel.log" 2>&1; then
    echo "make wheel: FAILED after ${SECONDS}s; the tail of its log ($root/make-wheel.log):"; tail -30 "$root/make-wheel.log"; exit 1
  fi
  wheel=$(ls "$project"/dist/robokin-*.whl)
  echo "make wheel: built $(basename "$wheel") in ${SECONDS}s"
}

# The same base as fresh-debian.sh's (same packages), so that either script makes it for the other.
make_base() {
  if ! command -v debootstrap >/dev/null; then
    { apt-get update -qq && apt-get install -y -qq debootstrap; } >/dev/null 2>&1 ||
      { echo "fresh-wheel: could not install debootstrap: no bare system made (exit 3)"; exit 3; }
  fi
  [ -x "$root/base/bin/bash" ] && return 0
  rm -rf "$root/base"
  local attempt
  for attempt in 1 2 3; do
    if debootstrap --variant=minbase --include=make,git,ca-certificates bookworm "$root/base.tmp" >"$root/debootstrap.log" 2>&1; then
      mv "$root/base.tmp" "$root/base"; return 0
    fi
    rm -rf "$root/base.tmp"; sleep 5
  done
  echo "fresh-wheel: debootstrap failed 3 times (tail of its log below): no bare system made (exit 3)"; tail -5 "$root/debootstrap.log"; exit 3
}

# The lazy unmounts detach /proc and /dev before anything is removed; a run directory that still
# has a mount under it is left alone rather than removed through it.
cleanup() {
  umount -l "$work/proc" 2>/dev/null; umount -l "$work/dev" 2>/dev/null
  if grep -q " $work/" /proc/mounts; then echo "fresh-wheel: $work still has mounts; left in place"; else rm -rf "$work"; fi
}

# What this machine needs to reach the registries and a fresh machine already has: the DNS
# resolver, the apt sources and, where the registries are reached through a TLS proxy, its extra
# certificate authorities. pip needs nothing more: the index is PyPI (pip's default), the host's
# other pip settings point at its own disk, and Debian's pip trusts the system's certificates.
make_run_dir() {
  work=$root/wheel-run-$$
  rm -rf "$work"; cp -a "$root/base" "$work"
  trap cleanup EXIT
  cp /etc/resolv.conf "$work/etc/resolv.conf" 2>/dev/null
  cp -a /etc/apt/sources.list* "$work/etc/apt/" 2>/dev/null
  if ls /usr/local/share/ca-certificates/*.crt >/dev/null 2>&1; then
    cp /usr/local/share/ca-certificates/*.crt "$work/usr/local/share/ca-certificates/"
    chroot "$work" update-ca-certificates >/dev/null 2>&1
  fi
  mount -t proc proc "$work/proc" && mount --rbind /dev "$work/dev" ||
    { echo "fresh-wheel: could not mount /proc or /dev in the bare system (exit 3)"; exit 3; }
}

in_chroot() { chroot "$work" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin "$@"; }

install_python() {
  echo "== apt-get install python3 python3-venv (bare Debian bookworm)"
  if ! in_chroot /bin/bash -c "export DEBIAN_FRONTEND=noninteractive; apt-get update -qq && apt-get install -y -qq python3 python3-venv" >"$root/wheel-apt.log" 2>&1; then
    echo "fresh-wheel: apt-get could not install python3 in the bare system (tail of its log below; exit 3)"; tail -5 "$root/wheel-apt.log"; exit 3
  fi
  # A compiler or a library's -dev package would let pip build or find what the wheel should have
  # brought, and hide the defect.
  local extra
  extra=$(in_chroot /bin/bash -c 'for c in cc c++ gcc g++ clang; do command -v $c; done
    dpkg-query -W -f="\${Package} \${Status}\n" | grep -- "-dev install ok installed" | cut -d" " -f1')
  [ -z "$extra" ] || { echo "fresh-wheel: the bare system has a compiler or -dev packages ($(echo $extra)): not the system this test needs (exit 3)"; exit 3; }
  in_chroot useradd --create-home --shell /bin/bash "$user" || { echo "fresh-wheel: could not add the user $user (exit 3)"; exit 3; }
  cp "$wheel" "$work/home/$user/"
  in_chroot chown "$user:" "/home/$user/$(basename "$wheel")"
}

# The checks the user runs, in their home directory; each failing check prints why and stops.
write_checks() {
  cat >"$work/home/$user/check-wheel.sh" <<'CHECKS'
set -euo pipefail
cd "$HOME"
python3 -m venv v
v/bin/pip install -q --no-cache-dir "$(ls robokin-*.whl)[sim]"
echo "installed: $(v/bin/pip list 2>/dev/null | grep -E '^(robokin|numpy|pygame) ' | tr -s ' ' | paste -sd, -)"

v/bin/python - <<'PY'
import numpy as np
import robokin as rk

chain = rk.robots.ur5()
q_true = np.array([0.3, -1.1, 1.4, -0.7, 1.2, 0.4])
target = chain.fk(q_true)
res = rk.ik(chain, target, np.zeros(chain.dof), seed=1)
assert res.success, f"IK on the UR5 did not succeed: {res}"
error = np.abs(chain.fk(res.q) - target).max()
assert error < 1e-8, f"FK of the IK solution is {error} away from the target"
print(f"UR5 FK/IK round trip: success, |fk(ik(T)) - T| = {error:.1e}")

urdf = """<robot name="two_link">
  <link name="base"/><link name="upper"/><link name="tool"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="tool"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
</robot>"""
arm = rk.Chain.from_urdf(urdf, base="base", tip="tool")
position = arm.fk(np.array([np.pi / 2, 0.0]))[:3, 3]
assert arm.dof == 2 and np.allclose(position, [0.0, 0.5, 0.1]), (arm.dof, position)
print(f"URDF chain from a string: {arm.dof} joints, tool at {np.round(position, 6).tolist()}")
PY

v/bin/robokin-sim --headless --frames 60 --record x.gif --log x.csv >sim.log 2>&1 || { cat sim.log; exit 1; }
v/bin/python - <<'PY'
import csv
from PIL import Image

with Image.open("x.gif") as gif:
    # A still scene (free mode, no keys) makes few frames: identical frames are merged.
    assert gif.format == "GIF" and gif.size == (480, 480), (gif.format, gif.size)
    for k in range(gif.n_frames):
        gif.seek(k)
        gif.load()
    print(f"x.gif: {gif.n_frames} frame(s) of {gif.size[0]}x{gif.size[1]}, all decoded")
with open("x.csv", newline="") as f:
    rows = list(csv.reader(f))
assert rows[0][:3] == ["step", "time", "mode"], rows[0]
assert [r[0] for r in rows[1:]] == [str(k) for k in range(1, 61)], len(rows)
assert all(len(r) == len(rows[0]) for r in rows)
print(f"x.csv: {len(rows) - 1} rows of {len(rows[0])} columns")
PY

# Every library the extensions load is the wheel's own (robokin.libs) or the base system's.
site=$(realpath "$(v/bin/python -c 'import robokin, os; print(os.path.dirname(os.path.dirname(robokin.__file__)))')")
base_system='^(linux-vdso|libc|libm|libstdc\+\+|libgcc_s|ld-linux[^.]*|libpthread|libdl|librt)\.so'
for so in "$site"/robokin/_*.so; do
  out=$(ldd "$so")
  ! grep -q "not found" <<<"$out" || { echo "$out"; echo "ldd: $so has unresolved libraries"; exit 1; }
  # ldd's lines: "NAME => PATH (ADDRESS)", "PATH (ADDRESS)" for the loader, "NAME (ADDRESS)" for the vdso.
  while read -r name arrow path _; do
    [ "$arrow" = "=>" ] || path=$name
    [[ $(basename "$name") =~ $base_system ]] && continue
    case $(realpath -m "$path") in
      "$site"/robokin.libs/*) ;;
      *) echo "$out"; echo "ldd: $(basename "$so") loads $name from $path: neither the wheel's nor a base system library"; exit 1 ;;
    esac
  done <<<"$out"
  echo "ldd $(basename "$so"): $(grep -c robokin.libs <<<"$out") libraries from robokin.libs, the rest base system"
done
CHECKS
  in_chroot chown "$user:" "/home/$user/check-wheel.sh"
}

run_checks() {
  echo "== as $user: venv, pip install $(basename "$wheel")[sim], import, FK/IK, URDF, robokin-sim, ldd"
  SECONDS=0
  local log=$root/wheel-checks.log
  if chroot "$work" /usr/sbin/runuser -u "$user" -- /usr/bin/env -i HOME="/home/$user" USER="$user" TERM=dumb LANG=C.UTF-8 \
       PATH=/usr/local/bin:/usr/bin:/bin timeout 1800 /bin/bash "/home/$user/check-wheel.sh" >"$log" 2>&1; then
    cat "$log"; echo "fresh-wheel: passed in ${SECONDS}s"
  else
    echo "fresh-wheel: FAILED after ${SECONDS}s; the tail of its log ($log):"; tail -30 "$log"; exit 1
  fi
}

mkdir -p "$root"
build_wheel
make_base
make_run_dir
install_python
write_checks
run_checks
