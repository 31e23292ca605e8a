"""The test suite's own rules: a collection error fails the run loudly without hiding the other
tests, a module's random generator restarts for each test, and the planted-bug list of `make mutate`
is well formed."""

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def test_a_collection_error_fails_the_run_but_the_other_tests_still_run(tmp_path):
    (tmp_path / "test_broken.py").write_text("raise RuntimeError('broken at import')\n")
    (tmp_path / "test_fine.py").write_text("def test_one():\n    pass\n\ndef test_two():\n    pass\n")
    run = subprocess.run([sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"), "--rootdir", str(tmp_path),
                          "-p", "no:cacheprovider", str(tmp_path)], capture_output=True, text=True, timeout=120,
                         cwd=tmp_path)
    assert run.returncode != 0, run.stdout
    assert "2 passed" in run.stdout and "1 error" in run.stdout, run.stdout
    assert "broken at import" in run.stdout


def test_a_modules_generator_restarts_for_each_test(tmp_path):
    """conftest restarts a module's RNG from its RNG_SEED before each test: a test sees the same cases
    whichever tests ran before it in its process (make test spreads them over processes)."""
    shutil.copy(ROOT / "tests" / "conftest.py", tmp_path / "conftest.py")
    (tmp_path / "test_draws.py").write_text(
        "import numpy as np\n\nRNG_SEED = 5\nRNG = np.random.default_rng(RNG_SEED)\n\n"
        "def test_first_draws_many():\n    RNG.random(1000)\n\n"
        "def test_second_sees_the_seeds_first_draw():\n"
        "    assert RNG.random() == np.random.default_rng(RNG_SEED).random()\n")
    run = subprocess.run([sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"), "--rootdir", str(tmp_path),
                          "-p", "no:cacheprovider", "-p", "no:xdist", str(tmp_path)], capture_output=True, text=True,
                         timeout=120, cwd=tmp_path)
    assert run.returncode == 0 and "2 passed" in run.stdout, run.stdout


def load_mutate():
    """scripts/mutate.py as a module (registered: its dataclasses look their module up)."""
    if "robokin_mutate" not in sys.modules:
        spec = importlib.util.spec_from_file_location("robokin_mutate", ROOT / "scripts" / "mutate.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules["robokin_mutate"] = module
        spec.loader.exec_module(module)
    return sys.modules["robokin_mutate"]


def test_the_planted_bugs_are_well_formed():
    mutate = load_mutate()
    mutants = mutate.load()
    assert len(mutants) >= 30
    for m in mutants:
        assert (ROOT / m.file).is_file(), m.name
        assert m.why, m.name
        for arg in m.tests:
            if arg.startswith("tests/"):
                assert (ROOT / arg.split("::")[0]).is_file(), (m.name, arg)
    raw = mutate.tomllib.loads((ROOT / "tests" / "mutants" / "mutants.toml").read_text())
    assert {frozenset(entry) for entry in raw["mutant"]} <= {frozenset(("name", "file", "find", "replace", "tests", "why")),
                                                             frozenset(("name", "file", "find", "replace", "tests", "why",
                                                                        "timeout"))}


def test_a_mutant_is_taken_out_again_when_its_tests_raise(tmp_path, monkeypatch):
    """The planted file is restored byte for byte, in the worktree and in the installed copy, also
    when the run is interrupted; a snippet that is not there exactly once is stale, never applied."""
    mutate = load_mutate()
    root, site = tmp_path / "root", tmp_path / "site"
    (root / "python" / "robokin").mkdir(parents=True)
    (site / "robokin").mkdir(parents=True)
    original = b"def f():\n    return 1  # one\n\n\ndef g():\n    return 2\r\n"
    for where in (root / "python" / "robokin" / "x.py", site / "robokin" / "x.py"):
        where.write_bytes(original)
    monkeypatch.setattr(mutate, "ROOT", root)
    seen = []

    def interrupted(tests, timeout):
        seen.append((root / "python" / "robokin" / "x.py").read_text())
        seen.append((site / "robokin" / "x.py").read_text())
        raise KeyboardInterrupt

    monkeypatch.setattr(mutate, "run_tests", interrupted)
    planter = mutate.Planter(site, builder=None)
    m = mutate.Mutant("one", "python/robokin/x.py", "return 1", "return 0", ["tests/x.py"], "why")
    with pytest.raises(KeyboardInterrupt):
        mutate.run_mutant(m, planter, 10)
    assert all("return 0  # one" in text for text in seen)
    assert (root / "python" / "robokin" / "x.py").read_bytes() == original
    assert (site / "robokin" / "x.py").read_bytes() == original
    for find in ("return 3", "return"):  # absent; twice
        stale = mutate.run_mutant(mutate.Mutant("s", "python/robokin/x.py", find, "x", ["t"], "w"), planter, 10)
        assert stale.status == "stale"
    assert (root / "python" / "robokin" / "x.py").read_bytes() == original
