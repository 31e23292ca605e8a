"""The closed forms hide no solution for the joint limits: every solution is returned and marked
within the limits or not, the mask checked against an independent rule (tests/limits_reference.py):
a solution marked outside fits no whole-turn shift, one marked within is within the limits as
returned, and each reaches the target (KDL's forward kinematics)."""

import math

import numpy as np
import pytest

import robokin as rk
from limits_reference import turns_fit

PUMA = rk.robots.puma560()


def wrapped(a, b):
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))).max(axis=-1)


def check_mask(s, lo, hi, prismatic=None):
    """within_limits against turns_fit; within rows within [lo, hi] as returned; only_within_limits
    keeps exactly those."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    for row, within in zip(s.q, s.within_limits):
        if within:
            assert np.all(row >= lo) and np.all(row <= hi), row
        else:
            assert not turns_fit(row, lo, hi, prismatic), row
    kept = s.only_within_limits()
    assert np.array_equal(kept.q, s.q[s.within_limits]) and len(kept) == s.within_limits.sum()


def test_puma560_returns_all_eight_and_marks_those_its_limits_exclude():
    """rk.closed.puma560(T) returned 2 of the 8 postures here, the 6 others silently dropped by the
    PUMA's limits (the full set only with limits=None)."""
    q = np.array([0.3, 0.4, -0.5, 0.4, 0.5, 0.6])
    T = PUMA.fk(q)
    s = rk.closed.puma560(T)
    free = rk.closed.puma560(T, limits=None)
    assert len(s) == 8 == len(set(s.postures)) and s.postures == free.postures
    assert np.all(wrapped(s.q, free.q) < 1e-12) and free.within_limits.all()
    assert 0 < s.within_limits.sum() < 8
    check_mask(s, *PUMA.limits)
    for row in s.q:
        assert np.abs(PUMA._fk_kdl(row) - T).max() < 1e-10
    assert wrapped(s.q[s.within_limits], q).min() < 1e-9  # the start posture, within the limits
    assert "outside the limits" in repr(s)
    # nearest: among the solutions within the limits
    k = s.nearest(s.q[~s.within_limits][0])
    assert s.within_limits[k]


@pytest.mark.parametrize("seed", range(20))
def test_puma560_mask_at_random_poses(seed):
    rng = np.random.default_rng(seed)
    lo, hi = PUMA.limits
    T = PUMA.fk(rng.uniform(lo, hi))
    s = rk.closed.puma560(T)
    assert len(s) == len(rk.closed.puma560(T, limits=None))
    check_mask(s, lo, hi)


def test_ur_marks_the_solutions_outside_tight_limits():
    ur5 = rk.robots.ur5()
    T = ur5.fk([0.3, -1.0, 1.2, 0.4, 0.5, 0.6])
    lo, hi = np.full(6, -math.pi), np.full(6, math.pi)
    lo[1], hi[1] = -math.pi, 0.0  # shoulder lift down only
    lo[2], hi[2] = 0.0, math.pi  # elbow one way only
    s = rk.closed.ur(T, ur5, limits=(lo, hi))
    assert len(s) == 8 and 0 < s.within_limits.sum() < 8
    check_mask(s, lo, hi)
    for row in s.q:
        assert np.abs(ur5._fk_kdl(row) - T).max() < 1e-10
    p = math.pi / 2
    rows = [(0.0, p, 0.089159, 0.0, "R"), (-0.425, 0.0, 0.0, 0.0, "R"), (-0.39225, 0.0, 0.0, 0.0, "R"),
            (0.0, p, 0.10915, 0.0, "R"), (0.0, -p, 0.09465, 0.0, "R"), (0.0, 0.0, 0.0823, 0.0, "R")]
    chain = rk.Chain.from_dh(rows, limits=(lo, hi))  # the UR5 with these limits
    assert np.abs(chain.fk(np.full(6, 0.7)) - ur5.fk(np.full(6, 0.7))).max() < 1e-15
    by_default = rk.closed.ur(T, chain)  # "default": the chain's own limits
    assert np.array_equal(by_default.within_limits, s.within_limits)


def test_ur_batch_marks_the_same_solutions_in_their_slots():
    ur5 = rk.robots.ur5()
    lo, hi = np.full(6, -math.pi), np.full(6, math.pi)
    lo[2], hi[2] = 0.0, math.pi
    rng = np.random.default_rng(5)
    targets = ur5.fk(rng.uniform(-math.pi, math.pi, (40, 6)))
    targets[3, 0, 3] = 5.0  # out of reach
    q, singular, within = rk.closed.ur_batch(targets, ur5, limits=(lo, hi))
    names = list(rk.closed.UR_POSTURES)
    for i, T in enumerate(targets):
        s = rk.closed.ur(T, ur5, limits=(lo, hi))
        present = ~np.isnan(q[i, :, 0])
        assert present.sum() == len(s) and not np.any(within[i] & ~present)
        if not s.singular:
            for row, posture, w in zip(s.q, s.postures, s.within_limits):
                k = names.index(posture)
                np.testing.assert_array_equal(q[i, k], row)
                assert within[i, k] == w
    assert not within[3].any() and np.isnan(q[3]).all()
    assert within.any() and (~within & ~np.isnan(q[:, :, 0])).any()  # some outside, kept


def test_planar_arms_mark_their_postures():
    p3 = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 3, limits=([-1.0, 0.0, -2.0], [1.0, 2.5, 2.0]))
    for pose in ([1.5, 0.5, 0.3], [1.2, -0.4, -0.8], [0.3, 1.6, 1.2]):
        s = rk.closed.planar_3r(pose, limits=p3)
        assert len(s) == 2
        check_mask(s, *p3.limits)
        for row in s.q:
            T = p3._fk_kdl(row)
            assert np.allclose([T[0, 3], T[1, 3]], pose[:2], atol=1e-12)
    rp = rk.robots.rp(stroke=1.0)
    s = rk.closed.planar_rp([0.3, 0.4], limits=rp)
    assert s.postures == ["stroke forward", "stroke backward"] and s.within_limits.tolist() == [True, False]
    check_mask(s, *rp.limits, prismatic=[False, True])
    far = rk.closed.planar_rp([3.0, 4.0], limits=rp)  # beyond the stroke: both outside, both reach
    assert len(far) == 2 and not far.within_limits.any()
    for row in far.q:
        assert np.allclose(rp._fk_kdl(row)[:2, 3], [3.0, 4.0], atol=1e-12)


def test_general_3r_and_anthropomorphic_mark_their_solutions():
    rows = [(0.0, math.pi / 2, 0.3, 0.0, "R"), (0.5, 0.0, 0.0, 0.0, "R"), (0.4, 0.0, 0.0, 0.0, "R")]
    lo, hi = [-1.0, -0.5, -2.0], [1.0, 2.0, 0.5]
    arm = rk.Chain.from_dh(rows, limits=(lo, hi))
    p = arm.fk([0.2, 0.7, -1.1])[:3, 3]
    s = rk.closed.general_3r(p, arm)
    assert len(s) == len(rk.closed.general_3r(p, arm, limits=None)) == 4 and 0 < s.within_limits.sum() < 4
    check_mask(s, lo, hi)
    a = rk.closed.anthropomorphic(p, 0.5, 0.4, 0.3, limits=arm)
    assert len(a) == 4
    check_mask(a, lo, hi)
    for row in list(s.q) + list(a.q):
        assert np.linalg.norm(arm._fk_kdl(row)[:3, 3] - p) < 1e-9


def test_puma560_path_says_where_only_the_limits_exclude_a_frame():
    """A path keeps within the limits: where every solution of a frame is outside them, ok is False
    (the joints stay) and reachable True: not taken for a frame out of reach."""
    q0 = np.array([0.3, 0.4, -0.5, 0.4, 0.5, 0.6])
    targets = np.repeat(PUMA.fk(q0)[None], 3, axis=0)
    lo, hi = (np.asarray(v, dtype=float).copy() for v in PUMA.limits)
    q, ok, reachable = rk.closed.puma560_path(targets, q0, limits=(lo, hi))
    assert ok.all() and reachable.all()
    lo[0], hi[0] = 1.0, 1.2  # joint 1 away from both shoulders' q1 (0.3 and 2.81)
    q, ok, reachable = rk.closed.puma560_path(targets, np.clip(q0, lo, hi), limits=(lo, hi))
    assert not ok.any() and reachable.all()
    far = targets.copy()
    far[1, 0, 3] = 3.0
    _, ok, reachable = rk.closed.puma560_path(far, q0)
    assert ok.tolist() == reachable.tolist() == [True, False, True]
