"""IK's restart configurations: a solve whose first attempt fails restarts from the closed-form
solutions of a pose target (a 6R arm with a closed form), then from the chain's stored
configurations whose tools are nearest the target, then from random ones. Checked on constructed
cases where only those starts can succeed (one iteration per attempt: an attempt succeeds only from
a start that already solves the target), and for what they must not change: the same starts for
every copy of a chain, pickled or shared between threads."""

import pickle
import threading

import numpy as np
import pytest

import robokin as rk
from robokin import _testing


def far_start(chain):
    """A start that one iteration cannot take to a target 1e-9 away: the middle of the limits."""
    lo, hi = chain.limits
    bounded = np.isfinite(lo) & np.isfinite(hi)
    start = np.full(chain.dof, 0.3)
    start[bounded] = (lo[bounded] + hi[bounded]) / 2
    return start


@pytest.mark.parametrize("name, task", [("ur5", "position"), ("panda", "pose"), ("puma560", "position"),
                                        ("planar_3r", "xyphi"), ("planar_3r", "xy")])
def test_the_first_restart_starts_from_the_stored_configuration_nearest_the_target(name, task):
    chain = rk.robots.get(name)
    starts = _testing.ik_starts(chain)
    for j in (3, 101, 1000):
        T = chain.fk(starts[j])
        target = {"pose": T, "position": T[:3, 3], "xy": T[:2, 3],
                  "xyphi": np.r_[T[:2, 3], np.arctan2(T[1, 0], T[0, 0])]}[task]
        r = rk.ik(chain, target, far_start(chain), task=task, restarts=1, max_iter=1, seed=0)
        assert r.success and r.attempts == 2 and r.iterations == 1, (j, r)
        assert np.allclose(chain.fk(r.q), T, atol=1e-12) or task in ("position", "xy", "xyphi")


def test_a_random_start_alone_does_not_solve_these_cases():
    # The constructed targets from random starts, one iteration each: none is reached, so the
    # successes above come from the stored starts.
    chain = rk.robots.ur5()
    starts = _testing.ik_starts(chain)
    lo, hi = chain.limits
    for j in (3, 101, 1000):
        T = chain.fk(starts[j])
        for q0 in np.random.default_rng(j).uniform(lo, hi, (20, 6)):
            assert not rk.ik(chain, T, q0, restarts=0, max_iter=1, seed=0).success


@pytest.mark.parametrize("name", ["ur5", "puma560", "irb120"])
def test_the_first_restarts_start_from_the_closed_form_solutions_nearest_the_seed(name):
    # Targets of random configurations (not stored starts): one iteration from the far start fails,
    # so the restart succeeds only from an exact start; it is the closed form's solution within the
    # limits nearest the seed, and the attempts after it run in the closed form's order.
    chain = rk.robots.get(name)
    start = far_start(chain)
    lo, hi = chain.limits
    for q in np.random.default_rng(7).uniform(np.maximum(lo, -3), np.minimum(hi, 3), (10, 6)):
        T = chain.fk(q)
        assert not rk.ik(chain, T, start, restarts=0, max_iter=1).success
        solutions = rk.closed.solve(T, chain)
        inside = solutions.q[solutions.within_limits]
        nearest = inside[np.argsort(np.linalg.norm(inside - start, axis=1))]
        r = rk.ik(chain, T, start, restarts=1, max_iter=1, seed=0)
        assert r.success and r.attempts == 2 and r.iterations == 1, r
        np.testing.assert_allclose(r.q, nearest[0], atol=1e-12)


def test_no_closed_form_start_for_a_position_target_or_outside_the_limits():
    chain = rk.robots.puma560()
    T = chain.fk(np.array([0.4, -0.5, 0.3, 0.8, 0.9, -0.6]))
    start = far_start(chain)
    assert rk.ik(chain, T, start, restarts=1, max_iter=1).success
    assert not rk.ik(chain, T[:3, 3], start, task="position", restarts=1, max_iter=1).success
    # Limits that exclude every closed-form solution: the restart is a stored start and fails.
    lo, hi = chain.limits
    lo[0], hi[0] = 2.0, 2.1
    a, d, alpha = rk.robots.PUMA560_A, rk.robots.PUMA560_D, rk.robots.PUMA560_ALPHA
    fenced = rk.Chain.from_dh([(a[i], alpha[i], d[i], 0.0, "R") for i in range(6)], limits=(lo, hi))
    solutions = rk.closed.solve(T, fenced)
    assert len(solutions.q) > 0 and not solutions.within_limits.any()
    assert not rk.ik(fenced, T, start, restarts=1, max_iter=1).success


def test_starts_lie_within_the_limits_and_are_the_same_for_copies_and_pickles():
    chain = rk.robots.panda()
    starts = _testing.ik_starts(chain)
    lo, hi = chain.limits
    assert starts.shape == (1024, 7)
    assert np.all(starts >= lo) and np.all(starts <= hi)
    assert np.unique(starts, axis=0).shape[0] == 1024
    np.testing.assert_array_equal(_testing.ik_starts(pickle.loads(pickle.dumps(chain))), starts)
    np.testing.assert_array_equal(_testing.ik_starts(rk.robots.panda()), starts)


def test_unlimited_joints_draw_within_one_turn():
    chain = rk.Chain.from_dh([(1.0, 0.0, 0.0, 0.0, "R"), (1.0, 0.0, 0.0, 0.0, "R"), (0.0, 0.0, 0.0, 0.0, "P")])
    starts = _testing.ik_starts(chain)
    assert np.all(np.abs(starts[:, :2]) <= np.pi) and np.all(np.abs(starts[:, 2]) <= 1.0)
    assert np.ptp(starts[:, 0]) > 5.0  # spread over the turn, not bunched


def test_threads_building_the_starts_at_once_get_the_answers_of_one_thread():
    targets = rk.robots.iiwa14().fk(np.random.default_rng(3).uniform(-1, 1, (16, 7)))
    q0 = np.zeros(7)

    def solve_all(chain):
        return [rk.ik(chain, T, q0, restarts=8, max_iter=30, seed=k).q for k, T in enumerate(targets)]

    alone = solve_all(rk.robots.iiwa14())
    shared = rk.robots.iiwa14()  # its starts not built yet: the threads race to build them
    barrier = threading.Barrier(8)
    results = [None] * 8

    def run(i):
        barrier.wait()
        results[i] = solve_all(shared)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for got in results:
        for a, b in zip(got, alone):
            np.testing.assert_array_equal(a, b)
