"""The NaN rule: no call reports success with NaN. The calls that return a fixed-shape table mark a
missing entry with a NaN row, by design (and say so in their docstrings): RRR3.ik_all, RRR3.ik_batch,
RRR3.plan / connect (RRR3Plan.alpha, det_a_norm, det_b_norm, distance), robots.rpr_self_motion
(closed.rpr_self_motion is the same function) and closed.ur_batch. Each is walked here: every NaN row is exactly an
entry that does not exist (checked by independent geometry), and every other row is verified.
The numerical ik_batch has no NaN rows, reachable targets or not."""

import math

import numpy as np
import pytest

import robokin as rk
from rrr3_truth import base, cross, elbows, platform

ROBOT = rk.RRR3()


def legs_reach(robot, pose):
    """Each leg can close (|O_i B_i| within [|l1 - l2|, l1 + l2]): from DESIGN.md's geometry."""
    d = np.linalg.norm(platform(robot, pose) - base(robot), axis=1)
    return np.all((d <= robot.l1 + robot.l2) & (d >= abs(robot.l1 - robot.l2)))


def check_legs(robot, pose, mode, alpha):
    """A row of actuated angles closes every leg in the mode: |A_i B_i| = l2, elbow sign m_i."""
    a, b, o = elbows(robot, alpha), platform(robot, pose), base(robot)
    np.testing.assert_allclose(np.linalg.norm(b - a, axis=1), robot.l2, atol=1e-12)
    assert np.all(np.sign(cross(a - o, b - a)) == np.array(mode))


def poses(count, seed):
    """Poses inside, near the edge of and beyond the workspace."""
    rng = np.random.default_rng(seed)
    return np.column_stack((rng.uniform(-0.2, 0.2, (count, 2)), rng.uniform(-1.5, 1.5, count)))


def test_rrr3_ik_all_and_ik_batch_nan_rows_are_the_unreachable_modes():
    P = poses(300, 1)
    batch = {mode: ROBOT.ik_batch(P, mode) for mode in ROBOT.modes}
    nan_rows = 0
    for i, pose in enumerate(P):
        rows = ROBOT.ik_all(pose)
        assert rows.shape == (8, 3)
        for k, mode in enumerate(ROBOT.modes):
            missing = np.isnan(rows[k])
            assert missing.all() or not missing.any()  # whole rows
            assert missing.all() == (not legs_reach(ROBOT, pose))  # the mode changes the elbows, not the reach
            np.testing.assert_array_equal(batch[mode][i], rows[k])
            if missing.all():
                nan_rows += 1
                with pytest.raises(rk.UnreachableError):
                    ROBOT.ik(pose, mode)
            else:
                check_legs(ROBOT, pose, mode, rows[k])
    assert 0 < nan_rows < 8 * len(P)


def test_rrr3_plan_nan_rows_are_the_unreachable_poses():
    plan = ROBOT.plan(rk.paths.circle(40, radius=0.2))
    missing = np.isnan(plan.alpha).any(axis=1)
    assert 0 < missing.sum() < len(missing) and not plan.feasible
    for k, pose in enumerate(plan.poses):
        assert missing[k] == (not legs_reach(ROBOT, pose))
        for values in (plan.det_a_norm, plan.det_b_norm, plan.distance):
            assert np.isnan(values[k]) == missing[k]
        if not missing[k]:
            check_legs(ROBOT, pose, (1, 1, 1), plan.alpha[k])


def rpr_solutions(point, t1):
    """The RPR study's joints (t2, t3) for t1 putting the tip at point, within the limits, by the
    law of cosines: s = L1 + t2 solves |point - s u(t1)| = L3 (the shorter s first)."""
    L1, L3 = rk.robots.RPR_L1, rk.robots.RPR_L3
    lo, hi = rk.robots.RPR_LIMITS
    u1 = np.array([math.cos(t1), math.sin(t1)])
    b = point @ u1
    disc = b * b - point @ point + L3 * L3
    out = []
    for s in ((b - math.sqrt(disc), b + math.sqrt(disc)) if disc >= 0 else ()):
        w = point - s * u1
        t3 = math.remainder(math.atan2(w[1], w[0]) - t1, 2 * math.pi)
        t3 = t3 + 2 * math.pi if t3 < lo[2] else t3
        ok = lo[1] <= s - L1 <= hi[1] and lo[2] <= t3 <= hi[2]
        out.append((s - L1, t3) if ok else None)
    return out + [None] * (2 - len(out))


@pytest.mark.parametrize("point", [(1.5, 1.0), (0.5, 2.4), (2.0, 0.2), (3.9, 0.1), (5.0, 5.0)])
def test_rpr_self_motion_nan_rows_are_the_samples_without_a_solution(point):
    point = np.array(point)
    t1 = np.linspace(0.0, math.pi / 2, 181)
    S = rk.robots.rpr_self_motion(point, t1)
    assert S.shape == (2, len(t1), 3)
    chain = rk.robots.rpr()
    for j, a in enumerate(t1):
        expected = rpr_solutions(point, a)
        for branch in range(2):
            row = S[branch, j]
            missing = np.isnan(row)
            assert missing.all() or not missing.any()
            # Away from the limits' edges (where rounding decides), NaN exactly where no solution fits.
            if expected[branch] is None:
                assert missing.all(), (point, a, branch, row)
            else:
                assert not missing.all(), (point, a, branch)
                np.testing.assert_allclose(row[1:], expected[branch], atol=1e-9)
                np.testing.assert_allclose(chain.fk(row)[:2, 3], point, atol=1e-12)


def test_ur_batch_nan_rows_are_the_postures_without_a_solution():
    ur5 = rk.robots.ur5()
    rng = np.random.default_rng(7)
    targets = ur5.fk(rng.uniform(-math.pi, math.pi, (60, 6)))
    targets[::10, 0, 3] += 2.0  # out of reach
    q, singular, within = rk.closed.ur_batch(targets, ur5)
    names = list(rk.closed.UR_POSTURES)
    for i, T in enumerate(targets):
        s = rk.closed.ur(T, ur5, limits=None)
        missing = np.isnan(q[i])
        assert np.array_equal(missing.all(axis=1), missing.any(axis=1))  # whole rows
        if not s.singular:
            assert [names[k] for k in np.nonzero(~missing[:, 0])[0]] == sorted(s.postures, key=names.index)
        assert (~missing[:, 0]).sum() == len(s)
        for row in q[i][~missing[:, 0]]:
            assert np.abs(ur5._fk_kdl(row) - T).max() < 1e-10
    assert np.isnan(q[::10]).all()


def test_numerical_ik_batch_has_no_nan_rows():
    ur5 = rk.robots.ur5()
    targets = ur5.fk(np.random.default_rng(2).uniform(-2, 2, (8, 6)))
    targets[::2, 0, 3] += 5.0  # out of reach: not solved, the best point found, finite
    r = rk.ik_batch(ur5, targets, np.zeros(6), restarts=2, seed=0)
    assert np.all(np.isfinite(r.q)) and np.all(np.isfinite(r.error_p))
    assert not r.success[::2].any() and r.success[1::2].all()
