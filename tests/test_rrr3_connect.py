"""RRR3.connect: motions between two poses that never cross a parallel singularity, checked with
the seed's formulas (rrr3_truth) on constructed cases with and without such a route."""

import numpy as np
import pytest

import robokin as rk

from rrr3_truth import seed_jacobians

MODE = (1, 1, 1)
HOME = (0.0, 0.0, 0.0)


@pytest.fixture(scope="module")
def robot():
    return rk.RRR3()


def truth(robot, poses, mode=MODE):
    """det A / R_e, det B / l1^3 and the inverse condition number of A (third column / R_e) from
    the seed's formulas, for each pose."""
    det_a, det_b, distance = [], [], []
    for p in poses:
        A, B = seed_jacobians(robot, p, robot.ik(p, mode))
        det_a.append(np.linalg.det(A) / robot.platform_radius)
        det_b.append(np.linalg.det(B) / robot.l1**3)
        scaled = A.copy()
        scaled[:, 2] /= robot.platform_radius
        s = np.linalg.svd(scaled, compute_uv=False)
        distance.append(s[-1] / s[0])
    return np.array(det_a), np.array(det_b), np.array(distance)


def check_route(robot, plan, start, goal, clearance=0.05, serial_margin=0.02, max_step=0.001, max_turn=0.01,
                mode=MODE):
    poses = np.asarray(plan.poses)
    np.testing.assert_array_equal(poses[0], start)
    np.testing.assert_array_equal(poses[-1], goal)
    steps = np.diff(poses, axis=0)
    assert np.hypot(steps[:, 0], steps[:, 1]).max() <= max_step * (1 + 1e-9)
    assert np.abs(steps[:, 2]).max() <= max_turn * (1 + 1e-9)
    det_a, det_b, distance = truth(robot, poses, mode)
    ends = [0, len(poses) - 1]
    assert np.all(np.sign(det_a) == np.sign(det_a[0])) and plan.sign == np.sign(det_a[0])
    assert distance.min() >= min(clearance, *distance[ends]) * (1 - 1e-9)
    assert np.abs(det_b).min() >= min(serial_margin, *np.abs(det_b[ends])) * (1 - 1e-9)
    np.testing.assert_allclose(plan.det_a_norm, det_a, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(plan.distance, distance, rtol=1e-7, atol=1e-12)
    np.testing.assert_array_equal(plan.alpha, robot.ik_batch(poses, mode))
    assert plan.feasible
    return poses, det_a, distance


def test_a_straight_route_when_nothing_is_in_the_way(robot):
    goal = (0.02, -0.01, 0.1)
    plan = robot.connect(HOME, goal)
    poses, det_a, _ = check_route(robot, plan, HOME, goal)
    assert len(poses) == 24  # max(|dE| / 1 mm, |dphi| / 0.01 rad) = 22.4 steps, rounded up, plus the start
    assert np.all(det_a < 0)


def test_opposite_signs_of_det_a_have_no_route(robot):
    """At phi = 0 in mode (1,1,1), home (det A / R_e = -2.52) and the circle's start (0.1, 0, 0)
    (+0.89) lie on opposite sides of a parallel singularity: every motion between them crosses it."""
    assert robot.singularity(HOME).det_a_norm == pytest.approx(-2.52, abs=0.005)
    assert robot.singularity((0.1, 0, 0)).det_a_norm == pytest.approx(0.89, abs=0.005)
    with pytest.raises(rk.NoRouteError, match="different singularity-free regions") as exc:
        robot.connect(HOME, (0.1, 0.0, 0.0))
    assert exc.value.reason == "regions" and isinstance(exc.value, rk.UnreachableError)
    # The straight line between them does cross (independently of the planner).
    line = np.linspace(HOME, (0.1, 0, 0), 101)
    assert np.any(np.diff(np.sign(truth(robot, line)[0])) != 0)


def test_the_search_is_in_x_y_phi_not_in_the_plane(robot):
    """A constructed case the plane alone cannot solve: two poses at phi = 0, det A > 0 and clear
    of singularities at both, whose region at phi = 0 and clearance 0.1 is cut in two; turning the
    platform (by up to 0.45 rad) goes around the cut."""
    start, goal = np.array([0.079, -0.022, 0.0]), np.array([-0.041, 0.069, 0.0])
    det_a, _, distance = truth(robot, [start, goal])
    assert np.all(det_a > 0) and np.all(distance > 0.2)
    line = np.linspace(start, goal, 400)
    assert truth(robot, line)[2].min() < 0.1  # the straight motion comes nearer than 0.1
    with pytest.raises(rk.NoRouteError, match="phi in \\[0, 0\\]") as exc:
        robot.connect(start, goal, clearance=0.1, span=0.0)
    assert exc.value.reason == "regions"
    plan = robot.connect(start, goal, clearance=0.1)
    poses, _, _ = check_route(robot, plan, start, goal, clearance=0.1)
    assert np.abs(poses[:, 2]).max() > 0.1  # it turns
    # At the default clearance the plane has a way: no turn is needed.
    poses, _, _ = check_route(robot, robot.connect(start, goal, span=0.0), start, goal)
    assert np.all(poses[:, 2] == 0.0)


def test_same_sign_but_no_route_at_a_large_clearance(robot):
    start, goal = np.array([0.079, -0.022, 0.0]), np.array([-0.041, 0.069, 0.0])
    with pytest.raises(rk.NoRouteError, match="different singularity-free regions .* at clearance 0.4") as exc:
        robot.connect(start, goal, clearance=0.4)
    assert exc.value.reason == "regions"


def test_an_end_nearer_than_the_clearance(robot):
    """A start at distance 0.02 < clearance: the path leaves it without coming nearer."""
    line = np.linspace(HOME, (0.1, 0, 0), 2001)
    _, _, distance = truth(robot, line[:1200])
    k = int(np.nonzero(distance < 0.02)[0][0])
    start = line[k]
    plan = robot.connect(start, HOME)
    poses, _, distance = check_route(robot, plan, start, HOME)
    assert distance[0] < 0.05 and distance.min() >= distance[0] * (1 - 1e-9)


def test_unreachable_ends(robot):
    bad = (0.5, 0.0, 0.0)  # beyond every leg's reach
    with pytest.raises(rk.NoRouteError, match="leg 0 cannot reach") as exc:
        robot.connect(bad, HOME)
    assert exc.value.reason == "start"
    with pytest.raises(rk.NoRouteError) as exc:
        robot.connect(HOME, bad, mode=(1, -1, 1))
    assert exc.value.reason == "goal"


@pytest.mark.parametrize("kwargs,name", [
    (dict(start=(0, 0)), "start"), (dict(goal=(0, np.nan, 0)), "goal"), (dict(mode=(1, 0, 1)), "mode"),
    (dict(clearance=-0.1), "clearance"), (dict(clearance=1.0), "clearance"), (dict(max_step=0.0), "max_step"),
    (dict(max_turn=-1.0), "max_turn"), (dict(resolution=1e-4), "resolution"), (dict(span=4.0), "span"),
    (dict(serial_margin=np.inf), "serial_margin"), (dict(resolution=1e-3, max_step=1e-3), "resolution"),
])
def test_bad_arguments_name_themselves(robot, kwargs, name):
    args = dict(start=HOME, goal=(0.02, 0.0, 0.0))
    args.update(kwargs)
    start, goal = args.pop("start"), args.pop("goal")
    with pytest.raises(ValueError, match=name):
        robot.connect(start, goal, **args)


def test_the_same_pose_is_a_path_of_one(robot):
    plan = robot.connect(HOME, HOME)
    assert np.asarray(plan.poses).shape == (1, 3) and plan.feasible
