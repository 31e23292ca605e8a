"""Every public call is safe to share between threads: each public callable (the list
test_fuzz_coverage.public_api() walks: robokin's functions, its public modules' functions, the
model classes' constructors, methods and properties, the simulator's entries) is called from eight
threads at once on different models (thread_cases.CASES: catalogue arms, URDF chains, 3-RRR
geometries, options), and each answer must equal, bit for bit, the same call made alone before.
Any state kept between calls (solver caches, bound evaluators, scratch buffers, plotting state)
must be per call or per thread: a thread handed another's would give a different answer here."""

import dataclasses
import sys
import threading
import warnings

import numpy as np
import pytest
import sim_helpers  # noqa: F401  (SDL dummy drivers before pygame is imported)
import thread_cases
from test_fuzz_coverage import public_api

THREADS = 8
LIGHT_ROUNDS = 5  # passes each thread makes over the quick calls, each in an order of its own
#: Calls that take tenths of a second (figures, the demo, Dask, reachability maps, simulator
#: scenes): each is made once by half of the threads (the demo, which draws and saves a large
#: figure, by two), amid the others' calls.
HEAVY = ("plots", "demo", "dask", "sim.", "reachability", "rrr3_design")
STRIDE = {"demo.main": 4}  # thread i makes heavy call n when n % stride == i % stride; default 2


def digest(value, depth=0):
    """A comparable, exact form of a result: arrays by their bytes, objects by their public data."""
    if isinstance(value, np.ndarray):
        return ("array", value.shape, value.dtype.str, value.tobytes())
    if isinstance(value, (bool, int, str, bytes, type(None))):
        return value
    if isinstance(value, (float, np.floating, np.integer, np.bool_)):
        return ("scalar", np.asarray(value).tobytes(), type(value).__name__)
    if isinstance(value, (list, tuple, frozenset, set)):
        items = sorted(value, key=repr) if isinstance(value, (set, frozenset)) else value
        return tuple(digest(v, depth + 1) for v in items)
    if isinstance(value, dict):
        return tuple((k, digest(v, depth + 1)) for k, v in sorted(value.items()))
    if depth > 4:
        return repr(value)
    if dataclasses.is_dataclass(value):
        return tuple((f.name, digest(getattr(value, f.name), depth + 1)) for f in dataclasses.fields(value))
    out = []
    for name in dir(value):
        if name.startswith("_"):
            continue
        item = getattr(value, name)
        if not callable(item):
            out.append((name, digest(item, depth + 1)))
    return (type(value).__name__, tuple(out))


def _calls():
    """(name, index, call) of every case, in the table's order."""
    return [(name, k, call) for name, calls in thread_cases.CASES.items() for k, call in enumerate(calls)]


def _schedule(calls):
    """Each thread's list of calls: every quick call LIGHT_ROUNDS times, its share of the heavy
    calls once, all in an order of its own."""
    light = [j for j, (name, _, _) in enumerate(calls) if not name.startswith(HEAVY)]
    heavy = [j for j, (name, _, _) in enumerate(calls) if name.startswith(HEAVY)]
    orders = []
    for i in range(THREADS):
        mine = light * LIGHT_ROUNDS + [j for n, j in enumerate(heavy)
                                       if n % STRIDE.get(calls[j][0], 2) == i % STRIDE.get(calls[j][0], 2)]
        orders.append(np.random.default_rng(100 + i).permutation(mine))
    return orders


@pytest.fixture
def fast_switching():
    before = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)  # threads interleave often, inside Python and around released GILs
    yield
    sys.setswitchinterval(before)


@pytest.mark.filterwarnings("ignore::robokin.PrecisionWarning")
def test_public_calls_from_eight_threads_match_the_calls_made_alone(fast_switching):
    calls = _calls()
    alone = [digest(call()) for _, _, call in calls]
    orders = _schedule(calls)
    differ, errors = set(), []
    start = threading.Barrier(THREADS)

    def work(i):
        try:
            start.wait()
            for j in orders[i]:
                if digest(calls[j][2]()) != alone[j]:
                    differ.add((i, calls[j][0], calls[j][1]))
        except Exception as exc:  # noqa: BLE001 - reported below, with the thread
            errors.append((i, repr(exc)))

    threads = [threading.Thread(target=work, args=(i,)) for i in range(THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert not differ, f"(thread, name, case) answers that differ from the call made alone: {sorted(differ)}"


def test_every_public_call_has_a_case():
    missing = sorted(public_api() - set(thread_cases.CASES) - set(thread_cases.EXCLUDED))
    assert not missing, f"public calls the threads test does not make: {missing}"
    stale = sorted((set(thread_cases.CASES) | set(thread_cases.EXCLUDED)) - public_api())
    assert not stale, f"cases of names that are not public calls: {stale}"
    assert all(isinstance(why, str) and why for why in thread_cases.EXCLUDED.values())
    assert not set(thread_cases.CASES) & set(thread_cases.EXCLUDED)


@pytest.mark.filterwarnings("ignore::robokin.PrecisionWarning")
def test_the_cases_tell_their_models_apart():
    """A call handed another model's solver must answer differently: the closed forms on the
    different UR arms (and the other per-model calls) give answers that all differ."""
    for name in ("closed.ur", "closed.ur_batch", "closed.puma560", "ik", "Chain.fk", "RRR3.ik_batch", "RRR3.workspace",
                 "sim.SerialScene", "plots_rrr3.plot_robot"):
        answers = [digest(call()) for call in thread_cases.CASES[name]]
        assert len(set(answers)) == len(answers), name
    assert len(thread_cases.CASES["closed.ur"]) >= 8


def test_the_digest_sees_one_bit():
    a = np.array([1.0, 2.0])
    b = a.copy()
    b.view(np.uint64)[1] ^= 1
    assert digest(a) != digest(b) and digest(a) == digest(a.copy())
    assert digest({"x": [a]}) != digest({"x": [b]})


def test_figures_leave_pyplot_alone():
    """The figures are made outside pyplot: its list of open figures is one global state (and
    not safe to change from several threads at once)."""
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    for name, calls in thread_cases.CASES.items():
        if name.startswith(("plots", "demo")):
            for call in calls:
                call()
                assert plt.get_fignums() == before, name


def test_scenes_stepped_from_threads_leave_the_warning_filters_as_they_were(fast_switching):
    """The scenes silence Reach's PrecisionWarning (they report precision themselves) in blocks that
    save and restore the process's warning filters: blocks of several threads must nest, not put
    back each other's filters (which would leave the silencing on for the whole process)."""
    scenes = [thread_cases.RprScene("line", True) if i % 2 else thread_cases.SerialScene(
        thread_cases.M["ur5"], "ur5") for i in range(THREADS)]
    before = list(warnings.filters)
    start = threading.Barrier(THREADS)

    def work(scene):
        start.wait()
        for _ in range(60):
            scene.step(frozenset({"right"}))

    threads = [threading.Thread(target=work, args=(s,)) for s in scenes]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert warnings.filters == before
