"""The closed forms shared across threads: several threads call them at once on different arms
(catalogue chains, URDF-like dict arms, the PUMA, limits and none), each answer equal, bit for bit,
to the same call made alone. closed.py keeps no solver between calls (a dict's chain is built per
call); a chain reads its closed form's layout at its first call and keeps it (thread-safe); no
thread may be handed another arm's answer."""

import sys
import threading

import numpy as np
import pytest

import robokin as rk

ARMS = [rk.robots.ur3(), rk.robots.ur5(), rk.robots.ur10(), rk.robots.ur5e(), rk.robots.ur16e(),
        {"d1": 0.2, "a2": -0.5, "a3": -0.4, "d4": 0.12, "d5": 0.1, "d6": 0.09},
        {"d1": 0.1, "a2": -0.3, "a3": -0.25, "d4": 0.11, "d5": 0.09, "d6": 0.08}]
LIMITS = ["default", None]


def _chain_of(arm):
    """The arm as a chain: a catalogue chain, or the UR table of a dict (standard DH)."""
    if isinstance(arm, rk.Chain):
        return arm
    p = np.pi
    return rk.Chain.from_dh([(0.0, p / 2, arm["d1"], 0.0, "R"), (arm["a2"], 0.0, 0.0, 0.0, "R"),
                             (arm["a3"], 0.0, 0.0, 0.0, "R"), (0.0, p / 2, arm["d4"], 0.0, "R"),
                             (0.0, -p / 2, arm["d5"], 0.0, "R"), (0.0, 0.0, arm["d6"], 0.0, "R")])


def _calls(rng, count):
    """``count`` (description, call) pairs over every arm, both limits and the PUMA."""
    out = []
    for _ in range(count):
        k = int(rng.integers(len(ARMS) + 1))
        limits = LIMITS[int(rng.integers(2))]
        if k == len(ARMS):
            T = rk.robots.puma560().fk(rng.uniform(-2, 2, 6))
            out.append((lambda T=T, limits=limits: rk.closed.puma560(T, limits=limits)))
            continue
        arm = ARMS[k]
        T = _chain_of(arm).fk(rng.uniform(-3, 3, 6))  # reachable: every call has solutions
        out.append((lambda T=T, arm=arm, limits=limits: rk.closed.ur(T, arm, limits=limits)))
    return out


def _answer(solutions):
    return (np.asarray(solutions.q).tobytes(), tuple(solutions.postures), np.asarray(solutions.within_limits).tobytes(),
            bool(solutions.singular))


@pytest.fixture
def fast_switching():
    before = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # threads interleave between nearly every bytecode
    yield
    sys.setswitchinterval(before)


def _together(work, count=8):
    """work(i) in ``count`` threads started at once (a barrier) -> their answers, in order; fails
    with each thread's exception."""
    got, errors = [None] * count, []
    start = threading.Barrier(count)

    def run(i):
        try:
            start.wait()
            got[i] = work(i)
        except Exception as exc:  # noqa: BLE001 - reported below, with the thread
            errors.append((i, repr(exc)))

    threads = [threading.Thread(target=run, args=(i,)) for i in range(count)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    return got


def test_closed_forms_from_eight_threads_match_the_calls_made_alone(fast_switching):
    rng = np.random.default_rng(7)
    calls = [_calls(rng, 3000) for _ in range(8)]
    alone = [[_answer(c()) for c in thread_calls] for thread_calls in calls]
    got = _together(lambda i: [_answer(c()) for c in calls[i]])
    for i in range(8):
        wrong = [j for j, (a, b) in enumerate(zip(got[i], alone[i])) if a != b]
        assert not wrong, f"thread {i}: {len(wrong)} of {len(alone[i])} answers differ from the call alone"


def test_threads_making_the_first_calls_on_fresh_chains_agree_with_a_chain_of_their_own(fast_switching):
    """Eight threads start together on the same fresh chains (the layout not yet read), each a
    solver's first call and then closed.ur; every answer equals that of a chain built for it alone."""
    rng = np.random.default_rng(11)
    tables = [ARMS[5], ARMS[6], {"d1": 0.15, "a2": -0.45, "a3": -0.35, "d4": 0.1, "d5": 0.1, "d6": 0.07}]
    poses = [[_chain_of(t).fk(rng.uniform(-3, 3, 6)) for _ in range(50)] for t in tables]
    alone = [[_answer(rk.closed.ur(T, _chain_of(t))) for T in P] for t, P in zip(tables, poses)]
    for _ in range(20):
        shared = [_chain_of(t) for t in tables]

        def work(i, shared=shared):
            k = i % len(tables)
            solver = rk.closed.ClosedSolver(shared[k]) if i % 2 else None
            return [_answer(solver.solve(T) if solver else rk.closed.ur(T, shared[k])) for T in poses[k]]

        got = _together(work)
        for i in range(8):
            assert got[i] == alone[i % len(tables)], f"thread {i}: answers differ from a chain of its own"
