"""One timing method for every benchmark, also used by the PyKDL worker under /usr/bin/python3.

Plain standard library (Debian's python3 has no numpy). ``per_call`` times a statement with
``timeit``: the loop count is calibrated so that one repeat lasts about ``budget`` seconds, the
statement is run ``repeat`` times that many calls, and the best and median time per call are returned
(the best is the figure used for ratios: on a shared machine it is the least disturbed one).
"""

from __future__ import annotations

import statistics
import timeit


def _calls_per_repeat(timer: timeit.Timer, budget: float) -> int:
    """How many executions of the timer's statement last about ``budget`` seconds."""
    number = 1
    while True:
        if timer.timeit(number) >= budget / 5 or number >= 1 << 24:
            break
        number *= 4
    return max(1, int(number * budget / max(timer.timeit(number), 1e-9)))


def per_call(stmt: str, namespace: dict, repeat: int = 7, budget: float = 0.05, setup: str = "pass"):
    """(best, median) seconds per execution of ``stmt`` evaluated in ``namespace``."""
    timer = timeit.Timer(stmt, setup=setup, globals=namespace)
    number = _calls_per_repeat(timer, budget)
    runs = [t / number for t in timer.repeat(repeat, number)]
    return min(runs), statistics.median(runs)


def per_call_interleaved(stmts, namespace: dict, repeat: int = 7, budget: float = 0.05):
    """[(best, median), ...] seconds per execution of each of ``stmts``, their repeats taken in
    turn (a b a b ...), so that a ratio of two short calls sees the same spells of load on both
    sides (timed one after the other, a ratio of two calls of some 400 ns moved by 15 %)."""
    timers = [timeit.Timer(s, globals=namespace) for s in stmts]
    numbers = [_calls_per_repeat(t, budget) for t in timers]
    runs = [[] for _ in stmts]
    for _ in range(repeat):
        for k, (timer, number) in enumerate(zip(timers, numbers)):
            runs[k].append(timer.timeit(number) / number)
    return [(min(r), statistics.median(r)) for r in runs]


def once(fn, repeat: int = 3):
    """(best, median) seconds of ``fn()`` over ``repeat`` runs (for long calls: batches, paths)."""
    runs = []
    for _ in range(repeat):
        start = timeit.default_timer()
        fn()
        runs.append(timeit.default_timer() - start)
    return min(runs), statistics.median(runs)


def once_interleaved(fns, repeat: int = 5):
    """[(best, median), ...] seconds of each of ``fns``, run in turn ``repeat`` times (a b a b ...):
    on a shared machine each side then sees the same spells of load, which timing one side's
    repeats before the other's does not give (a ratio of two long calls moved by 8 % that way)."""
    runs = [[] for _ in fns]
    for _ in range(repeat):
        for k, fn in enumerate(fns):
            start = timeit.default_timer()
            fn()
            runs[k].append(timeit.default_timer() - start)
    return [(min(r), statistics.median(r)) for r in runs]


def fmt(seconds: float) -> str:
    """A time in the unit that reads best: ns, us or ms."""
    if seconds < 1e-6:
        return f"{seconds * 1e9:7.0f} ns"
    if seconds < 1e-3:
        return f"{seconds * 1e6:7.2f} us"
    return f"{seconds * 1e3:7.1f} ms"


def goal(goals: list, name: str, figure: float, unit: str, limit: float, reference: str, *,
         at_least: bool = False, met: bool | None = None, note: str = "") -> dict:
    """Appends one goal of a benchmark to ``goals`` (what run_all.py's summary lists) and returns it.

    ``name`` says in plain words what is measured; ``figure`` is the measured value in ``unit``
    ("x" for a ratio robokin / reference, else an absolute unit such as "us" or "%"); the goal is
    ``figure <= limit`` (``>=`` with ``at_least``); ``reference`` says what the ratio is taken
    against, measured in the same run, or why there is none (an absolute goal). ``met`` overrides
    the comparison when the goal has a further condition (say which in ``note``). A figure that
    could not be measured (NaN) is a missed goal."""
    figure = float(figure)
    if met is None:
        met = figure == figure and (figure >= limit if at_least else figure <= limit)
    entry = {"name": name, "figure": figure, "unit": unit, "limit": float(limit), "at_least": at_least,
             "reference": reference, "met": bool(met), "note": note}
    goals.append(entry)
    return entry


NO_REFERENCE = "none: an absolute time (no other implementation of this call to run beside it)"


def ratio_line(goals: list, what: str, ours, ref_name: str, ref, goal_ratio: float | None = None,
               note: str = "", name: str | None = None) -> None:
    """Prints robokin's (best, median) beside a reference's and their ratio; with ``goal_ratio`` (a
    ratio to stay under) it says met or missed and records the goal (named ``name``, else ``what``
    against ``ref_name``) in ``goals``."""
    ratio = ours[0] / ref[0]
    text = (f"  {what:<34} robokin {fmt(ours[0])} (median {fmt(ours[1]).strip()})  |  "
            f"{ref_name:<14} {fmt(ref[0])} (median {fmt(ref[1]).strip()})  ->  {ratio:6.3f}x")
    if goal_ratio is not None:
        g = goal(goals, name or f"{what} vs {ref_name}", ratio, "x", goal_ratio, f"{ref_name}, same run")
        text += f"  goal <= {goal_ratio}: {'met' if g['met'] else 'MISSED'}"
    print(text + (f"  {note}" if note else ""), flush=True)
