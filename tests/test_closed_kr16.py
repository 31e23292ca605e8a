"""The KUKA KR 16-2 from its URDF (ROS-Industrial's description: tests/kr16_urdf.py), the spherical
wrist read from its geometry: a joint about -z, two about -x, the wrist 35 mm off the forearm's
line. Truth: the chain's own forward model (every solution reaches the pose, 1e-9 of its size), the
joints each pose was made from (among the solutions, 1e-6), and numerical IK from random starts
(no solution it finds is missing). The 2,000-pose run is marked slow (make test and CI run it)."""

import math

import numpy as np
import pytest
from closed_helpers import angle_distance, random_q
from kr16_urdf import KR16_URDF

import robokin as rk

KR16 = rk.Chain.from_urdf(KR16_URDF)
SIZE = 0.675 + 0.26 + 0.68 + math.hypot(0.67, 0.035) + 0.158  # the sum of its fixed translations, about


def check_poses(Q, singular_ok=False):
    """Every pose of Q's rows: its solutions reach it and Q's row is among them (off singularities)."""
    T = KR16.fk(Q)
    q8, singular, _ = rk.closed.ClosedSolver(KR16, limits=None).solve_batch(T)
    found = ~np.isnan(q8[:, :, 0])
    assert found.any(axis=1).all()
    assert np.abs(KR16.fk(q8[found]) - T[np.nonzero(found)[0]]).max() <= 1e-9 * SIZE
    d = np.where(found, angle_distance(q8, Q[:, None, :]), np.inf).min(axis=1)
    assert np.all(d[~singular] < 1e-6)
    if not singular_ok:
        assert (~singular).mean() > 0.95
    return T, q8, found


def test_the_family_is_read_from_the_urdf():
    f = rk.closed.family(KR16)
    assert f.solvable and f.name == "spherical wrist, axes 2, 3 parallel"
    assert f.meet == ((4, 5), (5, 6)) and f.parallel == ((2, 3),)
    assert rk.closed.ClosedSolver(KR16).family == f.name


def test_poses_within_the_limits(rng):
    Q = random_q(KR16, rng, 300)
    T, q8, found = check_poses(Q)
    assert found.sum(axis=1).max() == 8  # all eight postures where the arm reaches them
    s = rk.closed.solve(T[0], KR16)  # the chain's limits: the generating q is within them
    assert s.within_limits.any() and angle_distance(s.q[s.within_limits], Q[0]).min() < 1e-6
    assert len(set(s.postures)) == len(s) and all(p.startswith("shoulder") for p in s.postures)


def test_numerical_ik_finds_no_solution_the_closed_form_misses(rng):
    Q = random_q(KR16, rng, 12)
    T, q8, found = check_poses(Q, singular_ok=True)
    k = np.repeat(np.arange(len(Q)), 48)
    r = rk.ik_batch(KR16, T[k], random_q(KR16, rng, len(k)), seed=1, restarts=0, max_iter=200)
    assert r.success.sum() > 0.3 * len(k)
    for i in np.nonzero(r.success)[0]:
        assert angle_distance(q8[k[i]][found[k[i]]], r.q[i]).min() < 1e-4


@pytest.mark.parametrize("joint, value", [(4, 0.0), (4, 1e-7), (4, -1e-9)])
def test_near_the_wrist_singularity(joint, value, rng):
    Q = random_q(KR16, rng, 100)
    Q[:, joint] = value
    T = KR16.fk(Q)
    for q, t in zip(Q, T):
        s = rk.closed.solve(t, KR16, None)
        assert len(s) >= 1, q
        F = KR16.fk(s.q)
        assert np.max(np.abs(F[:, :3, 3] - t[:3, 3])) <= 1e-9 * SIZE
        assert np.max(np.abs(F[:, :3, :3] - t[:3, :3])) <= 1e-8
        assert s.singular or value != 0.0


def test_a_line_is_tracked_in_closed_form(rng):
    q = np.linspace(np.radians([-20, -80, 70, 10, 40, -30]), np.radians([40, -50, 100, -30, 60, 20]), 40)
    poses = KR16.fk(q)
    r = rk.track_postures(KR16, poses, 0.05, qdot_max=2.0, method="closed")
    assert np.all(r.success) and np.allclose(KR16.fk(r.q), poses, atol=1e-9)
    assert len(r.reconfigurations) == 0 and all(p.startswith("shoulder") for p in r.postures)
    assert len(set(r.postures)) == 1  # one posture along a path from joints that move smoothly


@pytest.mark.slow
def test_2000_random_poses(rng):
    check_poses(random_q(KR16, rng, 2000, margin=0.02))


def lines_meet(p, u, r, v):
    """The point of line (p, u) nearest line (r, v): where two axes that meet meet."""
    w, b = p - r, u @ v
    return p + u * ((b * (v @ w) - (u @ w)) / (1 - b * b))


def shoulder_and_wrist(chain, q):
    """The labels' definitions (closed.solve), from the joint axes at q (rk.plots.joint_axes: read
    from the Jacobian, whatever the chain was built from): shoulder left / right, the wrist point
    (axes 4 and 5 meet) on the - / + side of x1 = axis 1 x axis 2 from axis 1; wrist no flip /
    flip, (a4 x a6) . a5 >= 0 / < 0."""
    axes = rk.plots.joint_axes(chain, q)
    (p1, a1), (_, a2), (p4, a4), (p5, a5), (_, a6) = axes[0], axes[1], axes[3], axes[4], axes[5]
    c = lines_meet(p4, a4, p5, a5)
    side = (c - p1) @ np.cross(a1, a2)
    shoulder = "shoulder left" if side < 0 else "shoulder right"
    return shoulder, "wrist no flip" if np.cross(a4, a6) @ a5 >= 0 else "wrist flip", abs(side)


@pytest.mark.parametrize("arm", ["KR16 urdf", "puma560"])
def test_shoulder_and_wrist_labels_are_their_geometric_definitions(arm):
    """Both spherical-wrist layouts' shoulder and wrist labels against their definitions, read from
    the axes (not from the solver's DH angles); near the shoulder's singularity, where the side is
    a rounding, the pose is skipped."""
    chain = KR16 if arm == "KR16 urdf" else rk.robots.puma560()
    rng = np.random.default_rng(8)
    seen = set()
    for q in rng.uniform(-3.0, 3.0, (60, 6)):
        s = rk.closed.solve(chain.fk(q), chain, limits=None)
        for qk, posture in zip(s.q, s.postures):
            shoulder, wrist, side = shoulder_and_wrist(chain, qk)
            if side < 1e-6 or "singular" in posture:
                continue
            assert posture.startswith(shoulder + ", ") and posture.endswith(", " + wrist), (posture, qk)
            seen.add((shoulder, wrist))
    assert len(seen) == 4
