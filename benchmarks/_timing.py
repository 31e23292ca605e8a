"""One timing method for every benchmark, also used by the PyKDL worker under /usr/bin/python3.

Plain standard library (Debian's python3 has no numpy). ``per_call`` times a statement with
``timeit``: the loop count is calibrated so that one repeat lasts about ``budget`` seconds, the
statement is run ``repeat`` times that many calls, and the best and median time per call are returned
(the best is the figure used for ratios: on a shared machine it is the least disturbed one).
"""

from __future__ import annotations

import statistics
import timeit


def per_call(stmt: str, namespace: dict, repeat: int = 7, budget: float = 0.05, setup: str = "pass"):
    """(best, median) seconds per execution of ``stmt`` evaluated in ``namespace``."""
    timer = timeit.Timer(stmt, setup=setup, globals=namespace)
    number = 1
    while True:
        if timer.timeit(number) >= budget / 5 or number >= 1 << 24:
            break
        number *= 4
    number = max(1, int(number * budget / max(timer.timeit(number), 1e-9)))
    runs = [t / number for t in timer.repeat(repeat, number)]
    return min(runs), statistics.median(runs)


def once(fn, repeat: int = 3):
    """(best, median) seconds of ``fn()`` over ``repeat`` runs (for long calls: batches, paths)."""
    runs = []
    for _ in range(repeat):
        start = timeit.default_timer()
        fn()
        runs.append(timeit.default_timer() - start)
    return min(runs), statistics.median(runs)
