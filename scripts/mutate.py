#!/usr/bin/env python3
"""Mutation check of the test suite: plants small bugs one at a time and runs the tests that should
catch each.

The bugs ("mutants") are listed in tests/mutants/mutants.toml, each with the file it changes, an
exact snippet of that file, its replacement, and the pytest selection that covers it. For each
mutant this script

1. checks the snippet occurs exactly once in the file (else the mutant is "stale": the code moved on
   and the list must follow it);
2. writes the replacement; a C++ file is rebuilt incrementally in the worktree's build directory
   (``cmake --build build/<tag>``, one object and the links) and the rebuilt extensions are copied
   where the venv imports them; a Python file is copied over the venv's installed copy;
3. runs the selection (``pytest -x``, a timeout per mutant): a failing test means "caught";
4. restores the file byte for byte (also on Ctrl-C or an error: try/finally) and puts the clean
   build back.

At the end it prints a table (caught / NOT CAUGHT / stale / build failed / no tests / error /
baseline fails) and exits 1 unless every mutant was caught. Before the mutants, each selection is
run once on the clean build: a selection that fails already cannot tell anything ("baseline
fails"). After the run it checks that ``git diff`` of every file it touched is what it was before.

Usage: scripts/mutate.py [--list] [--check] [--only NAME[,NAME...]] [--timeout S] [--no-baseline]
(``make mutate``, ``make mutate ONLY=name``; a name ending in ``*`` selects by prefix). Not part of
``make test``: it takes long.
"""

from __future__ import annotations

import argparse
import dataclasses
import filecmp
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
MUTANTS = ROOT / "tests" / "mutants" / "mutants.toml"
VENV_PYTHON = ROOT / ".venv" / "bin" / "python"
#: The Python packages as the venv installs them: source directory -> package name.
PACKAGES = {"python/robokin": "robokin", "sim/robokin_sim": "robokin_sim"}
#: The compiled extensions the build makes and the venv imports (in the robokin package).
EXTENSIONS = ("_core", "_testing")
CPP_SUFFIXES = (".cpp", ".hpp", ".h")
BUILD_TIMEOUT = 1800  # s, one incremental build on a loaded machine


@dataclasses.dataclass
class Mutant:
    """One planted bug: ``find`` (exactly once in ``file``) becomes ``replace``; ``tests`` are the
    pytest arguments that must then fail; ``why`` is the wrong result it stands for."""

    name: str
    file: str
    find: str
    replace: str
    tests: List[str]
    why: str = ""
    timeout: Optional[float] = None


@dataclasses.dataclass
class Outcome:
    """A mutant's result: ``status`` as the table prints it, the seconds it took, and the first
    failing test (or pytest's last line, or the build's error)."""

    mutant: Mutant
    status: str
    seconds: float = 0.0
    detail: str = ""


def load(path: Path = MUTANTS) -> List[Mutant]:
    """The mutants of the list, checked for unique names, a change and a test selection each."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    mutants = [Mutant(**entry) for entry in data["mutant"]]
    names = [m.name for m in mutants]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise SystemExit(f"{path}: duplicate mutant names {duplicates}")
    for m in mutants:
        if m.find == m.replace:
            raise SystemExit(f"{path}: mutant {m.name} changes nothing")
        if not m.tests:
            raise SystemExit(f"{path}: mutant {m.name} names no tests")
    return mutants


# --- where the venv imports the package from ------------------------------------------------------

def site_packages() -> Path:
    out = subprocess.run([str(VENV_PYTHON), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                         check=True, capture_output=True, text=True)
    return Path(out.stdout.strip())


def installed_copy(source: str, site: Path) -> Optional[Path]:
    """The venv's copy of a Python source file of the package, or None for other files."""
    for directory, package in PACKAGES.items():
        if source.startswith(directory + "/"):
            return site / package / source[len(directory) + 1:]
    return None


def drop_bytecode(installed: Path) -> None:
    """Removes the cached bytecode of an installed module: an edit within the same second and of
    the same size would otherwise be taken for the cached one."""
    for pyc in glob.glob(str(installed.parent / "__pycache__" / f"{installed.stem}.*.pyc")):
        os.remove(pyc)


def check_installed_is_current(site: Path) -> List[str]:
    """Python files of the worktree that differ from the venv's copies (the venv is stale)."""
    stale = []
    for directory in PACKAGES:
        for source in sorted((ROOT / directory).rglob("*.py")):
            rel = source.relative_to(ROOT).as_posix()
            copy = installed_copy(rel, site)
            if copy is not None and (not copy.exists() or not filecmp.cmp(source, copy, shallow=False)):
                stale.append(rel)
    return stale


# --- the C++ build --------------------------------------------------------------------------------

def build_dir() -> Path:
    """The worktree's build directory of the venv's interpreter (not the sanitizer build)."""
    out = subprocess.run([str(VENV_PYTHON), "-c", "import sysconfig; print(sysconfig.get_config_var('EXT_SUFFIX'))"],
                         check=True, capture_output=True, text=True)
    suffix = out.stdout.strip()
    for cache in sorted((ROOT / "build").glob("*/CMakeCache.txt")):
        text = cache.read_text(errors="replace")
        if "ROBOKIN_SANITIZE:BOOL=ON" in text:
            continue
        if (cache.parent / f"_core{suffix}").exists():
            return cache.parent
    raise SystemExit("no build directory with the extension for the venv's Python: run `make setup` first")


class Builder:
    """Incremental rebuilds of the extensions, and their installation into the venv."""

    def __init__(self, site: Path):
        self.dir = build_dir()
        self.site = site
        self.cmake = shutil.which("cmake", path=str(VENV_PYTHON.parent)) or "cmake"
        self.backup = Path(ROOT / "build" / "mutate-backup")
        self.saved = False

    def _extensions(self, where: Path) -> List[Path]:
        return [p for name in EXTENSIONS for p in where.glob(f"{name}.*.so")]

    def save_installed(self) -> None:
        """Keeps the venv's own extensions, put back when the run ends."""
        self.backup.mkdir(parents=True, exist_ok=True)
        for so in self._extensions(self.site / "robokin"):
            shutil.copy2(so, self.backup / so.name)
        self.saved = True

    def restore_installed(self) -> None:
        """Puts the venv's own extensions back (the run ends as it found the venv)."""
        if not self.saved:
            return
        for so in self._extensions(self.backup):
            shutil.copy2(so, self.site / "robokin" / so.name)
        shutil.rmtree(self.backup, ignore_errors=True)

    def build(self) -> subprocess.CompletedProcess:
        """``cmake --build`` of the build directory: what changed since the last build, nothing more."""
        env = dict(os.environ)
        env.setdefault("CCACHE_BASEDIR", "/work")
        env.setdefault("CCACHE_DIR", "/work/.ccache")
        return subprocess.run([self.cmake, "--build", str(self.dir)], capture_output=True, text=True, env=env,
                              timeout=BUILD_TIMEOUT)

    def install(self) -> None:
        """Copies the built extensions where the venv imports them."""
        for so in self._extensions(self.dir):
            shutil.copy2(so, self.site / "robokin" / so.name)


# --- one mutant -----------------------------------------------------------------------------------

def pytest_command(tests: List[str]) -> List[str]:
    """pytest on the selection: stop at the first failure, name it, no tracebacks."""
    return [str(VENV_PYTHON), "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "--no-header", "-rfE",
            "--tb=no", *tests]


def run_tests(tests: List[str], timeout: float) -> tuple:
    """(pytest exit code or "timeout", the first failing test's id)."""
    env = dict(os.environ, HYPOTHESIS_PROFILE="mutate", PYTHONDONTWRITEBYTECODE="1")
    proc = subprocess.Popen(pytest_command(tests), cwd=ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        return "timeout", ""
    except BaseException:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise
    failed = re.findall(r"^(?:FAILED|ERROR) (\S+)", out, flags=re.M)
    if not failed:
        failed = re.findall(r"^(\S+::\S+) FAILED", out, flags=re.M)
    return proc.returncode, failed[0] if failed else out.strip().splitlines()[-1] if out.strip() else ""


def status_of(code) -> str:
    """The table's word for pytest's exit code: 1 (tests failed) is caught, 0 is not."""
    if code == "timeout":
        return "caught (timeout)"
    return {0: "NOT CAUGHT", 1: "caught", 5: "no tests"}.get(code, f"error (pytest exit {code})")


class Planter:
    """Writes a mutant into its file (and the venv's copy or the build), and takes it out again."""

    def __init__(self, site: Path, builder: Builder):
        self.site = site
        self.builder = builder

    def plant(self, m: Mutant, text: str) -> Optional[str]:
        """Writes the mutant; returns the build's error output when it does not compile."""
        path = ROOT / m.file
        path.write_bytes(text.replace(m.find, m.replace, 1).encode("utf-8"))
        return self._propagate(m.file)

    def restore(self, m: Mutant, original: bytes) -> None:
        """Writes the file's original bytes back, and the venv's copy or the build after them."""
        (ROOT / m.file).write_bytes(original)
        error = self._propagate(m.file)
        if error:
            raise RuntimeError(f"the clean build failed after restoring {m.file}:\n{error}")

    def _propagate(self, rel: str) -> Optional[str]:
        """Makes the tests import the file as it now is; the build's error output when it fails."""
        copy = installed_copy(rel, self.site)
        if copy is not None:
            shutil.copyfile(ROOT / rel, copy)
            drop_bytecode(copy)
            return None
        if rel.endswith(CPP_SUFFIXES) or rel == "CMakeLists.txt":
            done = self.builder.build()
            if done.returncode != 0:
                return (done.stdout + done.stderr)[-3000:]
            self.builder.install()
            return None
        raise SystemExit(f"{rel}: neither a package's Python file nor a C++ source; mutate cannot apply it")


def snippet_count(m: Mutant) -> int:
    """How often the mutant's snippet occurs in its file (0 when the file is gone)."""
    path = ROOT / m.file
    return path.read_bytes().decode("utf-8").count(m.find) if path.exists() else 0


def run_mutant(m: Mutant, planter: Planter, timeout: float) -> Outcome:
    """Plants m, runs its tests, and takes it out again whatever happens."""
    count = snippet_count(m)
    if count != 1:
        return Outcome(m, "stale", detail=f"the snippet occurs {count} times in {m.file}")
    path = ROOT / m.file
    original = path.read_bytes()
    text = original.decode("utf-8")
    t0 = time.monotonic()
    try:
        error = planter.plant(m, text)
        if error is not None:
            return Outcome(m, "build failed", time.monotonic() - t0, error.strip().splitlines()[-1])
        code, first = run_tests(m.tests, m.timeout or timeout)
        return Outcome(m, status_of(code), time.monotonic() - t0, first)
    finally:
        planter.restore(m, original)


# --- the run --------------------------------------------------------------------------------------

def git_diff(files: List[str]) -> str:
    """``git diff`` of the files (compared before and after the run: it must not change)."""
    return subprocess.run(["git", "diff", "--no-ext-diff", "--", *files], cwd=ROOT, capture_output=True,
                          text=True, check=True).stdout


def print_table(outcomes: List[Outcome]) -> None:
    width = max([len(o.mutant.name) for o in outcomes] + [6])
    print()
    print(f"{'mutant':<{width}}  {'result':<16}  {'s':>5}  detail")
    for o in outcomes:
        print(f"{o.mutant.name:<{width}}  {o.status:<16}  {o.seconds:5.0f}  {o.detail[:110]}")
    caught = sum(o.status.startswith("caught") for o in outcomes)
    print(f"\n{caught} of {len(outcomes)} caught")


def baseline(mutants: List[Mutant], timeout: float) -> Dict[str, str]:
    """Runs each distinct selection once on the clean build: {selection: failure} for those failing."""
    failing = {}
    for tests in dict.fromkeys(tuple(m.tests) for m in mutants):
        code, first = run_tests(list(tests), timeout)
        if code != 0:
            failing[" ".join(tests)] = f"{status_of(code)}: {first}"
    return failing


def interrupt(signum, frame):
    """SIGTERM ends the run as Ctrl-C does: through the finally clauses that restore the files."""
    raise KeyboardInterrupt


def matches(name: str, pattern: str) -> bool:
    return name == pattern or (pattern.endswith("*") and name.startswith(pattern[:-1]))


def select(mutants: List[Mutant], only: str) -> List[Mutant]:
    """The mutants named in ``only`` (comma-separated names or prefixes ending in ``*``), all when empty."""
    wanted = [w.strip() for w in only.split(",") if w.strip()]
    if not wanted:
        return mutants
    unknown = [w for w in wanted if not any(matches(m.name, w) for m in mutants)]
    if unknown:
        raise SystemExit(f"unknown mutants: {', '.join(unknown)} (see --list)")
    return [m for m in mutants if any(matches(m.name, w) for w in wanted)]


def check_snippets(mutants: List[Mutant]) -> int:
    stale = [(m.name, n) for m in mutants for n in [snippet_count(m)] if n != 1]
    for name, n in stale:
        print(f"stale: {name} (its snippet occurs {n} times)")
    print(f"{len(mutants) - len(stale)} of {len(mutants)} mutants apply")
    return 1 if stale else 0


def run_all(mutants: List[Mutant], builder: Builder, planter: Planter, args) -> List[Outcome]:
    """The clean build brought up to date and installed, the baseline, then each mutant in turn."""
    done = builder.build()
    if done.returncode != 0:
        print(done.stdout + done.stderr, file=sys.stderr)
        raise SystemExit("the clean build fails: nothing to mutate")
    builder.install()
    failing = {} if args.no_baseline else baseline(mutants, args.timeout)
    outcomes = []
    for k, m in enumerate(mutants, 1):
        print(f"[{k}/{len(mutants)}] {m.name} ({m.file}) ...", end=" ", flush=True)
        key = " ".join(m.tests)
        o = Outcome(m, "baseline fails", detail=failing[key]) if key in failing else run_mutant(m, planter, args.timeout)
        outcomes.append(o)
        print(f"{o.status} ({o.seconds:.0f} s)", flush=True)
    return outcomes


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    parser.add_argument("--check", action="store_true", help="only check every snippet occurs once")
    parser.add_argument("--only", default="", help="comma-separated mutant names (or name prefixes ending in *)")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per mutant's tests (default 600)")
    parser.add_argument("--no-baseline", action="store_true", help="skip the clean run of each selection")
    args = parser.parse_args(argv)
    mutants = select(load(), args.only)
    if args.list:
        for m in mutants:
            print(f"{m.name:<36} {m.file:<40} {' '.join(m.tests)}")
        return 0
    if args.check:
        return check_snippets(mutants)
    site = site_packages()
    stale = check_installed_is_current(site)
    if stale:
        print("the venv's installed package differs from the worktree (run `make setup`): " + ", ".join(stale),
              file=sys.stderr)
        return 2
    files = sorted({m.file for m in mutants})
    diff_before = git_diff(files)
    builder = Builder(site)
    signal.signal(signal.SIGTERM, interrupt)
    try:
        builder.save_installed()
        outcomes = run_all(mutants, builder, Planter(site, builder), args)
    except KeyboardInterrupt:
        print("\ninterrupted: the files are restored", file=sys.stderr)
        return 130
    finally:
        builder.restore_installed()
        if git_diff(files) != diff_before:
            print("ERROR: git diff of the mutated files changed: check " + ", ".join(files), file=sys.stderr)
    print_table(outcomes)
    return 0 if outcomes and all(o.status.startswith("caught") for o in outcomes) else 1


if __name__ == "__main__":
    sys.exit(main())
