"""The summary of `make bench` (benchmarks/run_all.py, goals recorded by benchmarks/_timing.goal):
every goal is listed in its own words with its figure, its goal, its reference and "met" or
"MISSED"; an unmeasured figure is a miss; `--strict` fails on any miss, a failed module fails
always; a module that reports no goals is named. Synthetic goals: nothing is timed here."""

import importlib.util
import math
import pathlib
import sys

import pytest

BENCH = pathlib.Path(__file__).resolve().parents[1] / "benchmarks"


def _load(name):
    sys.path.insert(0, str(BENCH))
    try:
        spec = importlib.util.spec_from_file_location(f"_bench_{name}", BENCH / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    finally:
        sys.path.remove(str(BENCH))


timing, run_all = _load("_timing"), _load("run_all")


def _goals():
    goals = []
    timing.goal(goals, "batch FK of 1,000,000 RPR configurations", 0.12, "x", 0.15, "numpy, same run")
    timing.goal(goals, "closed-form PUMA 560 per call", 3.4, "us", 3.0, timing.NO_REFERENCE)
    timing.goal(goals, "share solved", 99.95, "%", 99.9, "none: a solve rate", at_least=True)
    timing.goal(goals, "fk vs Pinocchio", math.nan, "x", 0.7, "Pinocchio: not installed, so not measured")
    timing.goal(goals, "median vs KDL", 0.05, "x", 0.1, "KDL", met=False, note="and 100 % solved (98 %)")
    return goals


def test_goal_decides_met_from_the_figure():
    met = [g["met"] for g in _goals()]
    assert met == [True, False, True, False, False]
    assert timing.goal([], "rate", 99.0, "%", 99.9, "none", at_least=True)["met"] is False
    assert timing.goal([], "exact", 0.15, "x", 0.15, "numpy")["met"] is True


def test_every_goal_is_listed_with_figure_goal_reference_and_verdict():
    text = run_all.summary({"bench_a.py": _goals()[:3], "bench_b.py": _goals()[3:], "bench_sim.py": None})
    assert text.splitlines()[0].startswith("=== goals: 2 met, 3 missed")
    for g, verdict in zip(_goals(), ["met", "MISSED", "met", "MISSED", "MISSED"]):
        i = next(k for k, line in enumerate(text.splitlines()) if line.strip().endswith(g["name"]))
        head, detail = text.splitlines()[i], text.splitlines()[i + 1]
        assert head.split()[0] == verdict
        assert g["reference"] in detail
    assert "0.120 x (goal <= 0.150 x); reference: numpy, same run  [bench_a.py]" in text
    assert "3.4 us (goal <= 3 us); reference: none: an absolute time" in text
    assert "99.95 % (goal >= 99.9 %)" in text
    assert "not measured (goal <= 0.700 x)" in text
    assert "and 100 % solved (98 %)" in text
    assert "no goals reported to this summary by: bench_sim.py" in text
    assert "issue" not in text.lower()


def test_a_failed_module_is_named():
    text = run_all.summary({"bench_a.py": _goals()[:1], "bench_c.py": None}, failed=["bench_c.py"])
    assert "FAILED before reporting all their goals: bench_c.py" in text
    assert "no goals reported" not in text


@pytest.mark.parametrize("goals, failed, strict, status", [
    (lambda: _goals()[:1], [], True, 0),   # all met
    (lambda: _goals(), [], False, 0),      # misses without --strict
    (lambda: _goals(), [], True, 1),       # --strict: any miss
    (lambda: _goals()[3:4], [], True, 1),  # an unmeasured figure is a miss
    (lambda: _goals()[:1], ["bench_c.py"], False, 1),  # a failed module, always
])
def test_exit_status(goals, failed, strict, status):
    assert run_all.exit_status({"bench_a.py": goals(), "bench_sim.py": None}, failed, strict) == status


def test_strict_flag_reaches_main(monkeypatch):
    """main(strict=True) returns 1 on a miss: run over one stand-in module in a temporary folder."""
    calls = []
    monkeypatch.setattr(run_all, "run_module", lambda path: (calls.append(path.name) or _goals()[1:2], False))
    assert run_all.main(strict=True) == 1 and run_all.main(strict=False) == 0
    assert calls and all(name.startswith("bench_") for name in calls)


def test_no_benchmark_speaks_of_issue_numbers():
    """The summary and the benchmarks' own text say what they measure, not which tracker entry asked."""
    for path in sorted(BENCH.glob("*.py")):
        assert "issue " not in path.read_text().lower(), path.name
