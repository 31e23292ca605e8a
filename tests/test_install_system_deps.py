"""scripts/install-system-deps.sh decides from what works, installs only what is missing, and says in
one line what to install when it cannot. Run against stand-ins for dpkg-query, id, sudo, apt-get and
Python on a PATH that holds nothing else (the real install is tried by ../shared/fresh-debian.sh)."""

import os
import pathlib
import shutil
import stat
import subprocess
import sys

SCRIPT = pathlib.Path(__file__).resolve().parents[1] / "scripts" / "install-system-deps.sh"
LIBS = "libeigen3-dev liborocos-kdl-dev liburdfdom-dev libconsole-bridge-dev libsleef-dev xvfb xdotool"
BASH = shutil.which("bash")


def _stub(folder, name, body):
    path = folder / name
    path.write_text("#!" + BASH + "\n" + body + "\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)


def _machine(tmp_path, *, installed, uid, sudo, python_ok, compiler):
    """A PATH of stand-ins: dpkg-query says `installed`, id says `uid`; apt-get records its calls and
    'installs' by touching a marker that the stand-in Python then sees."""
    bin_ = tmp_path / "bin"
    bin_.mkdir()
    for tool in ("grep", "mktemp", "rm", "tail", "cp", "touch"):
        os.symlink(shutil.which(tool), bin_ / tool)
    status = "install ok installed" if installed else "unknown ok not-installed"
    _stub(bin_, "dpkg-query", f"echo -n '{status}'")
    _stub(bin_, "id", f"echo {uid}")
    calls, marker = tmp_path / "calls", tmp_path / "installed"
    _stub(bin_, "apt-get", f'echo "apt-get $*" >> {calls}; touch {marker}')
    if sudo:
        _stub(bin_, "sudo", f'echo -n "sudo " >> {calls}; "$@"')
    ok = "exit 0" if python_ok == "always" else f"[ -e {marker} ]" if python_ok == "after" else "exit 1"
    _stub(bin_, "python3", ok)
    if compiler:
        _stub(bin_, "g++", "exit 0")
    env = {"PATH": str(bin_), "PYTHON": "python3", "CXX": "no-such-compiler"}
    return env, calls


def _run(env):
    return subprocess.run([BASH, str(SCRIPT)], env=env, capture_output=True, text=True, timeout=60)


def test_nothing_missing_installs_nothing_and_says_nothing(tmp_path):
    env, calls = _machine(tmp_path, installed=True, uid=1000, sudo=False, python_ok="always", compiler=True)
    r = _run(env)
    assert (r.returncode, r.stdout, r.stderr) == (0, "", "")
    assert not calls.exists()


def test_not_root_without_sudo_names_packages_in_one_line(tmp_path):
    env, calls = _machine(tmp_path, installed=False, uid=1000, sudo=False, python_ok="never", compiler=False)
    r = _run(env)
    packages = f"{LIBS} g++ python3-venv python3-dev"
    assert r.returncode == 1
    assert r.stdout == ""
    assert r.stderr == (f"robokin needs these Debian packages: {packages}. "
                        f"Install them as root: apt-get install {packages}\n")
    assert not calls.exists()


def test_not_root_installs_only_what_is_missing_through_sudo(tmp_path):
    env, calls = _machine(tmp_path, installed=False, uid=1000, sudo=True, python_ok="after", compiler=True)
    r = _run(env)
    assert r.returncode == 0, r.stderr
    packages = f"{LIBS} python3-venv python3-dev"
    assert r.stdout == f"Installing Debian packages: {packages}\n"
    assert calls.read_text().splitlines() == [
        "sudo apt-get update -qq",
        f"sudo apt-get install -y -qq --no-install-recommends {packages}",
    ]


def test_root_installs_without_sudo_and_a_missing_python_brings_python3(tmp_path):
    env, calls = _machine(tmp_path, installed=False, uid=0, sudo=False, python_ok="after", compiler=True)
    bin_ = tmp_path / "bin"
    (bin_ / "python3").unlink()        # no Python at all: Debian's python3 comes with the rest
    _stub(bin_, "apt-get", f'echo "apt-get $*" >> {calls}; cp {bin_ / "g++"} {bin_ / "python3"}')
    r = _run(env)
    assert r.returncode == 0, r.stderr
    assert calls.read_text().splitlines()[-1] == (
        f"apt-get install -y -qq --no-install-recommends {LIBS} python3 python3-venv python3-dev")


def test_an_interpreter_apt_cannot_fix_is_named(tmp_path):
    env, calls = _machine(tmp_path, installed=True, uid=0, sudo=False, python_ok="never", compiler=True)
    r = _run(env)
    assert r.returncode == 1
    assert "robokin needs python3 with its venv module and headers (Python.h)" in r.stderr
    assert "make PYTHON=/usr/bin/python3" in r.stderr
    assert not calls.exists()        # Debian's python3-venv and python3-dev are there: no use installing


def test_the_real_machine_needs_nothing_more():
    """After `make setup` this machine has everything: the script with the suite's own Python is a no-op."""
    r = subprocess.run([BASH, str(SCRIPT)], env={**os.environ, "PYTHON": sys.executable},
                       capture_output=True, text=True, timeout=120)
    assert (r.returncode, r.stdout, r.stderr) == (0, "", "")
