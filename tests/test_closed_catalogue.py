"""The closed forms on every catalogue arm with one, 2,000 random poses each (marked slow; make test
and CI run it): the 6R arms with a family, and the 7-joint arms with each joint whose hold leaves
one. Truth: the configuration a pose was made from (among the solutions, 1e-6), the chain's own
forward model (every solution reaches the pose, 1e-9), and numerical IK from 48 random starts
(rk.ik_batch; for a held joint, a damped Newton written here on the other joints) finding no
solution the closed form misses."""

import math

import numpy as np
import pytest

import robokin as rk
from closed_helpers import angle_distance, newton_held, newton_steps, random_q

P = math.pi
POSES = 2000
ARMS_6R = [n for n in rk.robots.names() if rk.robots.get(n).dof == 6 and rk.closed.family(rk.robots.get(n)).solvable]
HELD = [(n, j) for n in ("iiwa14", "panda", "gen3") for j in range(7)
        if rk.closed.family(rk.robots.get(n), locked={j: 0.3}).solvable]
DEGENERATE_AT_0_AND_PI = {("iiwa14", 1), ("iiwa14", 5), ("panda", 5)}


def test_the_cases_are_the_catalogue_arms_with_a_closed_form():
    assert set(ARMS_6R) == {"irb120", "puma560", "ur3", "ur5", "ur10", "ur3e", "ur5e", "ur10e", "ur16e"}
    assert len(HELD) == 13


@pytest.mark.slow
@pytest.mark.parametrize("name", ARMS_6R)
def test_6r_arm_on_random_poses(name):
    chain = rk.robots.get(name)
    rng = np.random.default_rng(len(name) * 101)
    Q = random_q(chain, rng, POSES, margin=0.02)
    T = chain.fk(Q)
    q8, singular, _ = rk.closed.ClosedSolver(chain, limits=None).solve_batch(T)
    found = ~np.isnan(q8[:, :, 0])
    assert found.any(axis=1).all()
    rows, which = q8[found], np.nonzero(found)[0]
    assert np.abs(chain.fk(rows) - T[which]).max() <= 1e-9
    d = np.where(found, angle_distance(q8, Q[:, None, :]), np.inf).min(axis=1)
    assert np.all(d[~singular] < 1e-6) and (~singular).sum() > 0.9 * POSES
    # 48 random starts on each of 40 poses: every IK success is one of the closed form's solutions.
    k = np.repeat(np.arange(40), 48)
    r = rk.ik_batch(chain, T[k], random_q(chain, rng, len(k), margin=0.02), seed=1, restarts=0, max_iter=200)
    assert r.success.sum() > 0.3 * len(k)
    for i in np.nonzero(r.success)[0]:
        assert angle_distance(q8[k[i]][found[k[i]]], r.q[i]).min() < 1e-4  # near singular: IK tol 1e-9 ~ 1e-6 rad


@pytest.mark.slow
@pytest.mark.parametrize("name,j", HELD)
def test_held_joint_on_random_poses(name, j):
    chain = rk.robots.get(name)
    rng = np.random.default_rng(len(name) * 31 + j)
    Q = random_q(chain, rng, POSES, margin=0.02)
    converged = 0
    for n, q in enumerate(Q):
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, limits=None, locked={j: q[j]})
        assert len(s) and np.abs(chain.fk(s.q) - T).max() <= 1e-9 and np.all(s.q[:, j] == q[j])
        # Within 1e-3 rad of a value where two axes line up (the iiwa's q[1], q[5], the Panda's
        # q[5] at 0 or pi: no family there) the 6R is near degenerate and the rounding grows.
        near = (name, j) in DEGENERATE_AT_0_AND_PI and abs(math.sin(q[j])) < 1e-3
        assert s.singular or angle_distance(s.q, q).min() < (1e-4 if near else 1e-6)
        if n < 20:
            # The Gen3's elbow held: Newton converges only from near a solution (test_closed_locked).
            local = (name, j) == ("gen3", 3)
            starts = q + rng.normal(0, 0.05, (48, 7)) if local else random_q(chain, rng, 48, margin=0.02)
            starts[:, j] = q[j]
            qn, err = newton_held(chain, T, starts, j, iterations=newton_steps(name, j))
            converged += int(np.count_nonzero(err < 1e-12))
            for row in qn[err < 1e-12]:  # converged to rounding (1e-10 leaves ~1e-6 rad near a singularity)
                assert angle_distance(s.q, row).min() < 1e-6
    assert converged >= 200  # of 20 x 48 starts: the comparison compares something
