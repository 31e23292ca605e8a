"""Singularity avoidance along the seed program's paths, checked with the seed's formulas here."""

import numpy as np
import pytest

import robokin as rk

from rrr3_truth import base, cross, elbows, platform, seed_jacobians

MODE = (1, 1, 1)


@pytest.fixture(scope="module")
def robot():
    return rk.RRR3()


@pytest.fixture(scope="module")
def clover():
    return rk.paths.clover(629)  # t advances by about 0.01 rad per step, as in the seed program


def det_a_norm(robot, poses, mode=MODE):
    """det A / R_e along a pose sequence, A from the seed's formulas and each leg's chain."""
    return np.array([np.linalg.det(seed_jacobians(robot, p, robot.ik(p, mode))[0]) for p in poses]) / \
        robot.platform_radius


def det_b_norm(robot, poses, mode=MODE):
    return np.array([np.linalg.det(seed_jacobians(robot, p, robot.ik(p, mode))[1]) for p in poses]) / robot.l1**3


def excursions(phi, nominal):
    """Maximal runs of indices where phi differs from nominal."""
    away = np.abs(phi - nominal) > 1e-12
    runs, k = [], 0
    while k < len(phi):
        if away[k]:
            j = k
            while j < len(phi) and away[j]:
                j += 1
            runs.append((k, j))
            k = j
        else:
            k += 1
    return runs


def test_the_clover_crosses_parallel_singularities_without_avoidance(robot, clover):
    plan = robot.plan(clover, phi=0.0, mode=MODE, avoid=False)
    np.testing.assert_array_equal(plan.poses[:, 2], 0.0)
    d = det_a_norm(robot, plan.poses)
    np.testing.assert_allclose(plan.det_a_norm, d, atol=1e-12)
    assert np.sum(np.sign(d[1:]) != np.sign(d[:-1])) >= 4
    assert np.min(np.abs(d)) < 0.01
    assert not plan.feasible


def test_avoidance_keeps_det_a_away_from_zero_with_one_sign(robot, clover):
    plan = robot.plan(clover, phi=0.0, mode=MODE, max_step=0.01, margin=0.05)
    assert plan.feasible
    np.testing.assert_allclose(plan.poses[:, :2], clover, atol=0)
    d = det_a_norm(robot, plan.poses)
    assert np.all(np.sign(d) == plan.sign)
    assert np.min(np.abs(d)) > 0.1  # against < 0.01 without avoidance
    assert np.min(plan.distance) >= 0.05


def test_avoidance_is_smooth_and_returns_to_nominal(robot, clover):
    plan = robot.plan(clover, phi=0.0, mode=MODE, max_step=0.01)
    phi = plan.poses[:, 2]
    assert np.max(np.abs(np.diff(phi))) <= 0.01 + 1e-12
    assert np.mean(phi == 0.0) > 0.4  # most of the path at the nominal orientation
    nominal = robot.plan(clover, phi=0.0, mode=MODE, avoid=False)
    runs = excursions(phi, 0.0)
    assert 1 <= len(runs) <= 8
    for k0, k1 in runs:
        # Each departure is caused by a nearby singularity at the nominal orientation...
        assert np.min(nominal.distance[max(0, k0 - 60):k1 + 60]) < 0.05
        # ...and goes out and back once (no chattering): |phi| rises to one peak, then falls.
        a = np.abs(phi[k0:k1])
        peak = int(np.argmax(a))
        assert np.all(np.diff(a[:peak + 1]) >= -1e-12) and np.all(np.diff(a[peak:]) <= 1e-12)


def test_avoidance_never_serial_and_stays_in_its_mode(robot, clover):
    plan = robot.plan(clover, phi=0.0, mode=MODE, serial_margin=0.02)
    assert np.min(np.abs(det_b_norm(robot, plan.poses))) >= 0.02 - 1e-12
    for p, alpha in zip(plan.poses, plan.alpha):
        a, b, o = elbows(robot, alpha), platform(robot, p), base(robot)
        np.testing.assert_allclose(np.linalg.norm(b - a, axis=1), robot.l2, atol=1e-12)
        assert np.all(np.sign(cross(a - o, b - a)) == np.array(MODE))


def test_the_circle_needs_no_avoidance(robot):
    circle = rk.paths.circle(629, radius=0.1)
    plan = robot.plan(circle, phi=0.0, mode=MODE)
    assert plan.feasible
    np.testing.assert_array_equal(plan.poses[:, 2], 0.0)
    d = det_a_norm(robot, plan.poses)
    assert np.all(np.sign(d) == np.sign(d[0])) and np.min(np.abs(d)) > 0.1


def test_other_nominal_orientation_and_mode(robot):
    pts = rk.paths.clover(300, center=(0.01, 0.0))
    plan = robot.plan(pts, phi=0.2, mode=(1, -1, 1))
    phi = plan.poses[:, 2]
    assert np.max(np.abs(np.diff(phi))) <= 0.01 + 1e-12
    reachable = ~np.isnan(plan.alpha[:, 0])
    assert reachable.all()
    d = det_a_norm(robot, plan.poses, (1, -1, 1))
    assert np.all(np.sign(d) == plan.sign)


def test_plan_bad_input(robot):
    with pytest.raises(ValueError, match="points"):
        robot.plan(np.zeros((5, 3)))
    with pytest.raises(ValueError, match="points"):
        robot.plan(np.full((5, 2), np.nan))
    with pytest.raises(ValueError, match="resolution"):
        robot.plan(np.zeros((5, 2)), max_step=0.01, resolution=0.02)
    with pytest.raises(ValueError, match="mode"):
        robot.plan(np.zeros((5, 2)), mode=(1, 1, 0))
    with pytest.raises(ValueError, match="phi"):
        robot.plan(np.zeros((5, 2)), phi=float("inf"))
    with pytest.raises(ValueError, match="points"):
        robot.plan(np.zeros((100_000, 2)), span=3.0, resolution=0.001)  # 6001 orientations for each of 1e5 points
    assert robot.plan(np.zeros((0, 2))).poses.shape == (0, 3)
    far = robot.plan(np.array([[1.0, 1.0], [1.0, 1.01]]))  # unreachable everywhere: no crash
    assert not far.feasible and np.isnan(far.alpha).all()


def test_plan_sizes_are_bounded(robot):
    # Review repro: max_step / resolution = 2e6 grid steps (never returned before; w is now <= m - 1).
    import time
    pts = rk.paths.circle(50)
    t0 = time.perf_counter()
    big = robot.plan(pts, max_step=1e4, resolution=0.005)
    assert time.perf_counter() - t0 < 5.0
    ref = robot.plan(pts, max_step=2.0, resolution=0.005)  # the same grid: any step is allowed
    assert np.array_equal(big.poses, ref.poses) and big.feasible == ref.feasible
    # inf / 1e-300 was cast to long (undefined behaviour); now clamped: span = 0 leaves one orientation.
    one = robot.plan(pts, max_step=1e300, resolution=1e-300, span=0)
    assert np.all(one.poses[:, 2] == 0)
    for name, value in [("max_step", 0.0), ("max_step", -1.0), ("max_step", float("inf")), ("max_step", float("nan")),
                        ("resolution", 0.0), ("resolution", -0.01), ("resolution", float("nan")),
                        ("span", -0.1), ("span", float("inf")), ("margin", float("nan")), ("margin", -1.0),
                        ("serial_margin", -1.0), ("smoothing", float("inf")), ("smoothing", -1.0)]:
        with pytest.raises(ValueError, match=name):
            robot.plan(pts, **{name: value})
    # Work count * m * (2 w + 1) and memory are bounded with a clear message, before any allocation.
    with pytest.raises(ValueError, match="max_step"):
        robot.plan(np.zeros((2_000, 2)), span=1.0, resolution=0.001, max_step=1.0)  # 2e3 x 2001 x 4001
    with pytest.raises(ValueError, match="MiB"):
        robot.plan(np.zeros((2_000_000, 2)), span=1.0, resolution=0.005)  # 8e8 cells


def test_plan_and_connect_options_are_the_cores():
    """The seed's robot and tolerance (the 3-RRR project: R_b 0.13, R_e 0.07, l1 = l2 = 0.12 m; det A detected
    at 1e-3) are the core's named constants; plan's and connect's options are core structs, keyword-only."""
    d = rk.RRR3_DEFAULTS
    assert (d["base_radius"], d["platform_radius"], d["l1"], d["l2"], d["singular_tol"]) == (0.13, 0.07, 0.12, 0.12, 1e-3)
    robot = rk.RRR3()
    assert (robot.base_radius, robot.platform_radius, robot.l1, robot.l2) == (0.13, 0.07, 0.12, 0.12)
    assert rk.RRR3PlanOptions().margin == rk.RRR3ConnectOptions().clearance == d["near_distance"] == 0.05
    assert rk.RRR3PlanOptions().serial_margin == rk.RRR3ConnectOptions().serial_margin == d["serial_margin"]
    assert "plan(points, *, phi=0.0, mode=(1, 1, 1), avoid=True" in rk.RRR3.plan.__doc__
    assert "connect(start, goal, *, mode=(1, 1, 1), clearance=0.05" in rk.RRR3.connect.__doc__
    points = rk.paths.circle(50)
    with pytest.raises(TypeError, match="incompatible function arguments"):
        robot.plan(points, 0.3)  # options are keyword-only
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'phase' \(options: phi, mode"):
        robot.plan(points, phase=0.3)
    with pytest.raises(ValueError, match=r"span: must be in \[0, pi\]"):
        robot.plan(points, span=4.0)
    with pytest.raises(ValueError, match=r"span: must be in \[0, pi\]"):
        rk.RRR3PlanOptions(span=-1.0).validate()
    with pytest.raises(ValueError, match="mode: every entry must be"):
        rk.RRR3ConnectOptions(mode=(1, 0, 1))
    o = rk.RRR3PlanOptions(phi=0.45, margin=0.1)
    assert (o.phi, o.margin, o.mode) == (0.45, 0.1, (1, 1, 1))
    a, b = robot.plan(points, phi=0.45, margin=0.1), robot.plan(points, **{n: getattr(o, n) for n in o.fields})
    np.testing.assert_array_equal(a.poses, b.poses)


# --- closed paths (RRR3PlanOptions.closed) ------------------------------------------------------

def simulator_paths():
    from robokin_sim.scene_rrr3 import CIRCLE_RADIUS, CLOVER_K, PATH_POINTS
    return {"circle": rk.paths.circle(PATH_POINTS, radius=CIRCLE_RADIUS), "clover": rk.paths.clover(PATH_POINTS, k=CLOVER_K)}


def check_closed_plan(robot, path, plan, mode=MODE, max_step=0.01, margin=0.05):
    """A closed plan, checked pose by pose through RRR3.singularity (not the plan's own numbers) and
    the seed's formulas: it joins up, keeps one sign of det A, and stays clear by the margin."""
    phi = plan.poses[:, 2]
    np.testing.assert_array_equal(plan.poses[:, :2], path)
    assert abs(phi[-1] - phi[0]) <= max_step + 1e-12  # the join
    assert np.max(np.abs(np.diff(phi))) <= max_step + 1e-12
    sings = [robot.singularity(p, mode) for p in plan.poses]
    det = np.array([s.det_a_norm for s in sings])
    assert np.all(np.sign(det) == plan.sign) and plan.sign in (-1, 1)
    assert min(s.distance for s in sings) >= margin
    assert all(s.kind == "none" for s in sings)
    np.testing.assert_allclose(det, det_a_norm(robot, plan.poses, mode), atol=1e-12)


@pytest.mark.parametrize("name,phi", [("clover", 0.0), ("clover", 0.65), ("circle", 0.0), ("circle", 0.45)])
def test_a_closed_plan_joins_up_with_one_sign_clear_of_singularities(robot, name, phi):
    path = simulator_paths()[name]
    plan = robot.plan(path, phi=phi, mode=MODE, closed=True)
    assert plan.feasible
    check_closed_plan(robot, path, plan)


def test_the_open_clover_plan_does_not_join_and_the_closed_one_does(robot):
    path = simulator_paths()["clover"]
    open_plan, closed = robot.plan(path, mode=MODE), robot.plan(path, mode=MODE, closed=True)
    assert open_plan.feasible and abs(open_plan.poses[-1, 2] - open_plan.poses[0, 2]) > 0.01  # 0.025 rad
    assert closed.feasible and abs(closed.poses[-1, 2] - closed.poses[0, 2]) <= 0.01
    check_closed_plan(robot, path, closed)


@pytest.mark.parametrize("name", ["circle", "clover"])
@pytest.mark.parametrize("phi", [0.0, 0.3, 0.65, -0.5])
def test_closed_plan_is_the_simulators_old_python(robot, name, phi):
    from rrr3_loop_reference import avoidance_plan
    path = simulator_paths()[name]
    np.testing.assert_allclose(robot.plan(path, phi=phi, mode=MODE, closed=True).poses[:, 2],
                               avoidance_plan(robot, path, MODE, phi=phi), rtol=0, atol=1e-12)


def test_closed_changes_nothing_without_avoidance_or_for_one_point(robot):
    path = simulator_paths()["clover"]
    for kwargs in [dict(avoid=False), dict(avoid=False, phi=0.3)]:
        a, b = robot.plan(path, **kwargs), robot.plan(path, closed=True, **kwargs)
        np.testing.assert_array_equal(a.poses, b.poses)
        assert a.feasible == b.feasible and a.sign == b.sign
    one = robot.plan(path[:1], closed=True)
    np.testing.assert_array_equal(one.poses, robot.plan(path[:1]).poses)
    assert robot.plan(np.zeros((0, 2)), closed=True).poses.shape == (0, 3)
    # A loop that is unreachable everywhere: no crash, infeasible.
    far = robot.plan(np.array([[1.0, 1.0], [1.0, 1.01], [1.01, 1.0]]), closed=True)
    assert not far.feasible and np.isnan(far.alpha).all()


def test_closed_bad_input_names_the_argument(robot):
    with pytest.raises(TypeError, match="closed"):
        robot.plan(rk.paths.circle(10), closed="yes")
    with pytest.raises(ValueError, match="points"):
        robot.plan(np.zeros((5, 3)), closed=True)
    with pytest.raises(ValueError, match="max_step"):
        robot.plan(rk.paths.circle(10), closed=True, max_step=0.0)
    assert rk.RRR3PlanOptions().closed is False and rk.RRR3PlanOptions(closed=True).closed is True
