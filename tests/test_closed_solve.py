"""rk.closed.solve: the subproblems' closed form of every arm rk.closed.family recognises.

Truth: the chain's own forward model (every solution reaches the pose to 1e-9), the joints each
pose was made from (among the solutions to 1e-6), the existing closed forms of the PUMA 560 and
the UR arms (the same solutions under the same labels), and the numerical IK from random starts
(no solution it finds is missing). Arms: the catalogue's, the UR5 from its URDF, and random arms
with a spherical wrist or three parallel axes (random lengths, offsets, twists)."""

import math
import pickle

import numpy as np
import pytest
from ur_urdf import UR5_URDF

import robokin as rk
from robokin import _testing

P = math.pi
TWISTS = [P / 2, -P / 2, 0.6, -1.1, 2.3]


def angle_gap(a, b):
    return np.max(np.abs(np.remainder(np.asarray(a) - np.asarray(b) + P, 2 * P) - P), axis=-1)


def random_spherical_wrist(rng, flip=False):
    """Axes 2, 3 parallel (alpha2 = 0, or pi with flip: axis 3 pointing against axis 2), axes 4,
    5, 6 through one point (a4 = a5 = d5 = 0)."""
    u = lambda: rng.uniform(-0.6, 0.6)  # noqa: E731
    tw = lambda: TWISTS[rng.integers(len(TWISTS))]  # noqa: E731
    rows = [(u(), tw(), u(), u(), "R"), (rng.uniform(0.2, 0.8), P if flip else 0.0, u(), u(), "R"),
            (u(), tw(), u(), u(), "R"), (0.0, tw(), rng.uniform(0.2, 0.8), u(), "R"), (0.0, tw(), 0.0, u(), "R"),
            (u(), tw(), u(), u(), "R")]
    return rk.Chain.from_dh(rows)


def random_three_parallel(rng, flip=False):
    """Axes 2, 3, 4 parallel (alpha2 = alpha3 = 0; with flip alpha2 = pi: axes 3 and 4 pointing
    against axis 2), axes 5, 6 meeting (a5 = 0)."""
    u = lambda: rng.uniform(-0.6, 0.6)  # noqa: E731
    tw = lambda: TWISTS[rng.integers(len(TWISTS))]  # noqa: E731
    rows = [(u(), tw(), u(), u(), "R"), (rng.uniform(0.2, 0.8), P if flip else 0.0, u(), u(), "R"),
            (rng.uniform(0.2, 0.8), 0.0, u(), u(), "R"), (u(), tw(), u(), u(), "R"), (0.0, tw(), u(), u(), "R"),
            (u(), tw(), u(), u(), "R")]
    return rk.Chain.from_dh(rows)


def check_arm(chain, rng, poses=200):
    """Every solution reaches its pose; the source is among them off singularities."""
    solver = rk.closed.ClosedSolver(chain, None)
    counts = []
    for q in rng.uniform(-P, P, (poses, 6)):
        T = chain.fk(q)
        s = solver.solve(T)
        assert len(s) >= 1, (chain, q)
        assert np.max(np.abs(chain.fk(s.q) - T)) < 1e-9
        if not s.singular:
            assert angle_gap(s.q, q).min() < 1e-6, (chain, q, s)
        assert len(set(s.postures)) == len(s)
        counts.append(len(s))
    return counts


@pytest.mark.parametrize("name", ["puma560", "irb120", "ur3", "ur5", "ur10", "ur3e", "ur5e", "ur10e", "ur16e"])
def test_catalogue_arms(name, rng):
    counts = check_arm(rk.robots.get(name), rng)
    assert max(counts) == 8


def test_the_ur5_urdf(rng):
    counts = check_arm(rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), rng)
    assert max(counts) == 8


@pytest.mark.parametrize("make, flip", [(random_spherical_wrist, False), (random_three_parallel, False),
                                        (random_spherical_wrist, True), (random_three_parallel, True)])
def test_random_arms(make, flip, rng):
    names = set()
    for _ in range(25):
        chain = make(rng, flip)
        names.add(rk.closed.family(chain).name)
        check_arm(chain, rng, poses=40)
    assert len(names) == 1


def labelled(s):
    return {p: q for p, q in zip(s.postures, s.q)}


@pytest.mark.parametrize("arm", ["puma560", "ur5 urdf"])
def test_labels_are_the_existing_closed_forms(arm, rng):
    """The subproblems' solutions (robokin._testing.closed_solve_subproblems: closed.solve's own
    layouts bypassed, the labels from their geometric definitions) under the same labels as
    closed.puma560 (the PUMA's DH form) and closed.ur on the DH table (here the URDF chain)."""
    if arm == "puma560":
        chain, reference = rk.robots.puma560(), lambda T: rk.closed.puma560(T, limits=None)
    else:
        chain, ur5 = rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), rk.robots.ur5()
        reference = lambda T: rk.closed.ur(T, ur5, limits=None)  # noqa: E731
    for q in rng.uniform(-P, P, (300, 6)):
        T = chain.fk(q)
        a, b = labelled(reference(T)), labelled(_testing.closed_solve_subproblems(chain, T))
        assert sorted(a) == sorted(b), (q, sorted(a), sorted(b))
        for k in a:
            assert angle_gap(a[k], b[k]) < 1e-6, (q, k)


def test_closed_ur_accepts_the_urdf_chain(rng):
    chain, ur5 = rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), rk.robots.ur5()
    poses = ur5.fk(rng.uniform(-P, P, (20, 6)))
    for T in poses:
        assert labelled(rk.closed.ur(T, chain, None)).keys() == labelled(rk.closed.ur(T, ur5, None)).keys()
    q, singular, within = rk.closed.ur_batch(poses, chain, None)
    q2, _, _ = rk.closed.ur_batch(poses, ur5, None)
    assert np.array_equal(np.isnan(q), np.isnan(q2)) and np.nanmax(angle_gap(q, q2)) < 1e-6
    with pytest.raises(ValueError, match="robot"):
        rk.closed.ur(poses[0], rk.robots.puma560())
    with pytest.raises(ValueError, match="robot"):
        rk.closed.ur_batch(poses, rk.robots.puma560())


def test_numerical_ik_finds_no_solution_the_closed_form_misses(rng):
    chain = rk.robots.irb120()
    for q in rng.uniform(-P, P, (8, 6)):
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, None)
        for q0 in rng.uniform(-P, P, (24, 6)):
            r = rk.ik(chain, T, q0, restarts=0, tol_p=1e-10, tol_r=1e-10)
            if r.success:
                assert angle_gap(s.q, r.q).min() < 1e-5, (q, r.q)


def test_batch_pickle_and_limits(rng):
    chain = rk.Chain.from_urdf(UR5_URDF, "base", "tool0")
    solver = rk.closed.ClosedSolver(chain)
    assert solver.family == "three parallel axes 2, 3, 4" and solver.limits is not None
    poses = chain.fk(rng.uniform(-P, P, (50, 6)))
    q, singular, within = solver.solve_batch(poses)
    for i, T in enumerate(poses):
        s = solver.solve(T)
        slots = [rk.closed.UR_POSTURES.index(p) for p in s.postures]
        assert np.array_equal(q[i, slots], s.q) and np.array_equal(within[i, slots], s.within_limits)
        assert np.isnan(q[i]).all(axis=1).sum() == 8 - len(s) and singular[i] == s.singular
    copy = pickle.loads(pickle.dumps(solver))
    assert copy.family == solver.family and np.array_equal(copy.solve(poses[0]).q, solver.solve(poses[0]).q)
    narrow = rk.closed.solve(poses[0], chain, (np.full(6, -0.5), np.full(6, 0.5)))
    assert np.all(np.abs(narrow.q[narrow.within_limits]) <= 0.5)


@pytest.mark.parametrize("arm", ["ur5 urdf", "puma560", "irb120"])
@pytest.mark.parametrize("joint, value", [(4, 0.0), (4, P), (4, 1e-7), (2, 0.0), (2, 1e-9)])
def test_near_singular_poses(arm, joint, value, rng):
    """The wrist's singularity (q5 at 0 or pi, and 1e-7 from it: a subproblem's two roots within
    its margin) and the stretched elbow (q3 = 0, 1e-9 from it; axis 3 through the line from axis 2
    to the wrist for these arms only approximately): a solution is found, every one within the
    verified tolerance (position 1e-9 x the arm's size, rotation entries 1e-8)."""
    chain = rk.Chain.from_urdf(UR5_URDF, "base", "tool0") if arm == "ur5 urdf" else rk.robots.get(arm)
    size = 3.0
    for q in rng.uniform(-P, P, (100, 6)):
        q[joint] = value
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, None)
        assert len(s) >= 1, q
        F = chain.fk(s.q)
        assert np.max(np.abs(F[:, :3, 3] - T[:3, 3])) <= 1e-9 * size
        assert np.max(np.abs(F[:, :3, :3] - T[:3, :3])) <= 1e-8
        if joint == 4 and value in (0.0, P) and arm == "ur5 urdf":
            assert s.singular
