"""Property tests of the 3-RRR (robokin.RRR3 and robokin.rrr3_design).

Two kinds. The argument fuzz drives every method with arbitrary arrays, modes, options and robot
geometries: each call returns finite, correctly shaped results (NaN only where documented: the
rows of ik_all / ik_batch / plan.alpha for unreachable poses), raises UnreachableError where
documented, or raises ValueError / TypeError naming the argument. The success properties check
that every solver's reported success equals success verified here, in numpy, against the loop
closures |A_i B_i| = l2 (rrr3_truth.py), over random targets including unreachable ones and poses
on or next to singularities.
"""

import math

import numpy as np
import pytest
from hypothesis import event, given
from hypothesis import strategies as st

import robokin as rk
from robokin import _core, rrr3_design

from fuzz import arrays, assert_finite, check_call, floats, wild_floats
from rrr3_truth import U, base, cross, elbows, platform, seed_jacobians

COVERS = {
    "RRR3PlanOptions", "RRR3ConnectOptions", "RRR3_DEFAULTS",
    "RRR3.__init__", "RRR3.__repr__", "RRR3.base_radius", "RRR3.platform_radius", "RRR3.l1", "RRR3.l2",
    "RRR3.base_joints", "RRR3.modes", "RRR3.ik", "RRR3.ik_all", "RRR3.ik_batch", "RRR3.ik_newton", "RRR3.fk",
    "RRR3.fk_all", "RRR3.points", "RRR3.jacobians", "RRR3.singularity", "RRR3.workspace", "RRR3.plan",
    "RRR3Newton.alpha", "RRR3Newton.beta", "RRR3Newton.converged", "RRR3Newton.iterations", "RRR3Newton.error",
    "RRR3Newton.__iter__", "RRR3Newton.__repr__",
    "RRR3Fk.pose", "RRR3Fk.converged", "RRR3Fk.iterations", "RRR3Fk.error", "RRR3Fk.__repr__",
    "RRR3Singularity.kind", "RRR3Singularity.det_a", "RRR3Singularity.det_b", "RRR3Singularity.det_a_norm",
    "RRR3Singularity.det_b_norm", "RRR3Singularity.distance", "RRR3Singularity.leg", "RRR3Singularity.lines",
    "RRR3Singularity.__repr__",
    "RRR3Plan.poses", "RRR3Plan.alpha", "RRR3Plan.det_a_norm", "RRR3Plan.det_b_norm", "RRR3Plan.distance",
    "RRR3Plan.sign", "RRR3Plan.feasible", "RRR3Plan.__repr__", "RRR3.connect",
    "RRR3.plan_loop", "RRR3LoopOptions", "RRR3Loop.plan", "RRR3Loop.nominal", "RRR3Loop.found", "RRR3Loop.reason",
    "RRR3Loop.__repr__",
    "RRR3Workspace.cells", "RRR3Workspace.x", "RRR3Workspace.y", "RRR3Workspace.extent",
    "RRR3Workspace.cell_size", "RRR3Workspace.reachable_area", "RRR3Workspace.regular_area",
    "RRR3Workspace.area", "RRR3Workspace.__repr__",
    "_core.rrr3_region_areas",
    "rrr3_design.area_vs_platform_radius", "rrr3_design.best_l2", "AreaCurve.best",
}

MODES = rk.RRR3.modes
EPS = np.finfo(float).eps

# Valid geometries of every kind: the seed's, links much longer than the base, a platform larger
# than the base, l1 == l2 (the platform joint may reach its base joint), l2 >> l1, tiny and huge.
GEOMETRIES = [
    (0.13, 0.07, 0.12, 0.12),
    (0.15, 0.0866, 0.10, 0.10),
    (0.05, 0.03, 2.0, 0.1),
    (0.05, 0.2, 0.1, 0.1),
    (0.1, 0.1, 0.1, 0.1),
    (0.13, 0.07, 0.05, 0.3),
    (1.3e-5, 0.7e-5, 1.2e-5, 1.2e-5),
    (1.3e4, 0.7e4, 1.2e4, 1.2e4),
]
ROBOTS = [rk.RRR3(*g) for g in GEOMETRIES]
robots = st.sampled_from(ROBOTS)

# Modes: the eight valid ones in several containers, and wrong ones (length, values, types).
good_modes = st.sampled_from(MODES)
mode_values = st.sampled_from([1.0, -1.0, 1.0, -1.0, 0.0, 2.0, 0.5, -3.0, math.nan, math.inf])
modes = st.one_of(
    good_modes, good_modes.map(list), good_modes.map(np.array), good_modes.map(lambda m: np.array(m, dtype=np.int8)),
    arrays(shape=[(3,), (2,), (4,), (3, 1), ()], elements=mode_values),
    st.sampled_from([None, "abc", (1, 1), (1, 1, 1, 1), (1, 0, 1), ("a", 1, 1), 1, {1: 2}]),
)
options = st.one_of(wild_floats, st.floats(1e-9, 1.0), st.sampled_from(["abc", None, [1.0]]))
int_options = st.one_of(st.integers(-3, 60), st.sampled_from([-(2**31), 2**31 - 1, 2**31, 10**6, 2**63]),
                        st.sampled_from([1.5, "5", None]))


class Unreachable:
    """Marker: the call raised UnreachableError, as documented."""


def run(call, *argnames, unreachable=False):
    """check_call, where UnreachableError is an accepted outcome when ``unreachable``."""
    def inner():
        try:
            return call()
        except rk.UnreachableError as e:
            assert unreachable, f"UnreachableError where none is documented: {e}"
            assert e.leg in (0, 1, 2) and f"leg {e.leg}" in str(e)
            return Unreachable
    return check_call(inner, *argnames)


def as_pose(pose):
    """The pose the binding saw, once it accepted it."""
    p = np.asarray(pose, dtype=float)
    assert p.shape == (3,) and np.all(np.isfinite(p))
    return p


def size(robot, *poses):
    """A length scale for rounding tolerances: the robot plus how far from the origin it works."""
    s = robot.base_radius + robot.platform_radius + robot.l1 + robot.l2
    return s + sum(float(np.abs(np.asarray(p)[..., :2]).max(initial=0)) for p in poses)


def closure(robot, pose, alpha):
    """max_i | |A_i B_i| - l2 |, A_i from the actuated angles, B_i from the pose."""
    return float(np.max(np.abs(np.linalg.norm(platform(robot, pose) - elbows(robot, alpha), axis=1) - robot.l2)))


def leg_reach(robot, pose):
    """|O_i B_i| of each leg and whether it lies in [|l1 - l2|, l1 + l2] (with rounding slack both ways)."""
    with np.errstate(over="ignore"):  # a pose at 1e300 m is simply out of reach
        r = np.linalg.norm(platform(robot, pose) - base(robot), axis=1)
    slack = 1e-12 * size(robot, pose)
    lo, hi = abs(robot.l1 - robot.l2), robot.l1 + robot.l2
    surely_in = (r > lo + slack) & (r < hi - slack) & (r > slack)
    surely_out = (r < lo - slack) | (r > hi + slack)
    return surely_in, surely_out


def check_ik_answer(robot, pose, mode, alpha):
    """alpha places every elbow at l2 from its platform joint, with the elbow sign of the mode."""
    pose = np.asarray(pose, float)
    assert alpha.shape == (3,) and np.all(np.isfinite(alpha)) and np.all(np.abs(alpha) <= math.pi)
    s = size(robot, pose)
    assert closure(robot, pose, alpha) <= 1e-9 * s
    a, b, o = elbows(robot, alpha), platform(robot, pose), base(robot)
    turn = cross(a - o, b - a) / (robot.l1 * robot.l2)  # sin(beta_i)
    clear = np.abs(turn) > 1e-6
    assert np.all(np.sign(turn[clear]) == np.array(mode)[clear]), (turn, mode)


# --- the argument fuzz --------------------------------------------------------------------------


lengths = st.one_of(wild_floats, st.floats(1e-4, 10.0), st.floats(-1.0, 0.0), st.sampled_from(["abc", None, [0.1]]))


@given(rb=lengths, re=lengths, l1=lengths, l2=lengths)
def test_constructor_with_any_geometry(rb, re, l1, l2):
    robot = check_call(lambda: rk.RRR3(rb, re, l1, l2), "base_radius", "platform_radius", "l1", "l2")
    if robot is None:
        return
    assert (robot.base_radius, robot.platform_radius, robot.l1, robot.l2) == (rb, re, l1, l2)
    joints = robot.base_joints
    assert joints.shape == (3, 2) and not joints.flags.writeable
    assert_finite(joints)
    np.testing.assert_allclose(joints, rb * U, rtol=1e-15, atol=0)
    text = repr(robot)
    assert text.startswith("RRR3(base_radius=") and "nan" not in text and "inf" not in text
    assert eval(text.replace("RRR3", "dict")) == dict(base_radius=rb, platform_radius=re, l1=l1, l2=l2)
    assert all(1e-6 <= v <= 1e6 for v in (rb, re, l1, l2))
    assert len(rk.RRR3.modes) == 8 and robot.modes == rk.RRR3.modes


@given(robot=robots, pose=arrays(shape=[(3,), (2,), (4,), (1, 3), ()]), mode=modes, tol=options)
def test_pose_queries_with_any_arguments(robot, pose, mode, tol):
    alpha = run(lambda: robot.ik(pose, mode), "pose", "mode", unreachable=True)
    if alpha is not None and alpha is not Unreachable:
        check_ik_answer(robot, pose, mode, alpha)
    elif alpha is Unreachable:
        assert not leg_reach(robot, as_pose(pose))[0].all()

    rows = run(lambda: robot.ik_all(pose), "pose")
    if rows is not None:
        p = as_pose(pose)
        assert rows.shape == (8, 3)
        for k, m in enumerate(MODES):
            if np.isnan(rows[k]).any():
                assert np.isnan(rows[k]).all() and not leg_reach(robot, p)[0].all()
            else:
                check_ik_answer(robot, p, m, rows[k])

    pts = run(lambda: robot.points(pose, mode), "pose", "mode", unreachable=True)
    if pts is not None and pts is not Unreachable:
        p = as_pose(pose)
        assert set(pts) == {"O", "A", "B"} and all(v.shape == (3, 2) for v in pts.values())
        assert_finite(pts)
        np.testing.assert_allclose(pts["O"], base(robot), rtol=1e-14, atol=0)
        np.testing.assert_allclose(pts["B"], platform(robot, p), rtol=1e-12, atol=1e-12 * size(robot, p))
        np.testing.assert_allclose(np.linalg.norm(pts["A"] - pts["O"], axis=1), robot.l1, rtol=1e-12)

    jac = run(lambda: robot.jacobians(pose, mode), "pose", "mode", unreachable=True)
    if jac is not None and jac is not Unreachable:
        assert len(jac) == 2 and jac[0].shape == (3, 3) and jac[1].shape == (3, 3)
        assert_finite(jac)
        assert np.all(jac[1] == np.diag(np.diag(jac[1])))
        np.testing.assert_allclose(np.hypot(jac[0][:, 0], jac[0][:, 1]), 1.0, rtol=1e-12)

    sing = run(lambda: robot.singularity(pose, mode, tol), "pose", "mode", "tol", unreachable=True)
    if sing is not None and sing is not Unreachable:
        assert sing.kind in ("none", "parallel", "serial")
        assert_finite(sing.det_a, sing.det_b, sing.det_a_norm, sing.det_b_norm, sing.distance)
        assert 0 <= sing.distance <= 1 + 1e-12
        assert (sing.leg in (0, 1, 2)) == (sing.kind == "serial") and (sing.lines is not None) == (sing.kind == "parallel")
        if sing.kind == "serial":
            assert abs(sing.det_b_norm) < tol
        elif sing.kind == "parallel":
            assert abs(sing.det_a_norm) < tol <= abs(sing.det_b_norm) and sing.lines in ("parallel", "concurrent")
        else:
            assert abs(sing.det_a_norm) >= tol and abs(sing.det_b_norm) >= tol
        assert repr(sing).startswith(f"RRR3Singularity(kind='{sing.kind}'")


@given(robot=robots, poses=arrays(shape=[(0, 3), (1, 3), (5, 3), (7, 3), (3,), (4, 2), (2, 3, 1)]), mode=modes)
def test_ik_batch_with_any_arguments(robot, poses, mode):
    out = run(lambda: robot.ik_batch(poses, mode), "poses", "mode")
    if out is None:
        return
    p = np.asarray(poses, dtype=float)
    assert out.shape == p.shape and p.ndim == 2 and p.shape[1] == 3
    for row, pose in zip(out, p):
        if np.isnan(row).any():  # documented: a NaN row where a leg cannot reach
            assert np.isnan(row).all() and not leg_reach(robot, pose)[0].all()
        else:
            check_ik_answer(robot, pose, mode, row)


@given(robot=robots, pose=arrays(shape=[(3,), (2,), (6,)]),
       guess=arrays(shape=[(6,), (2, 3), (3, 2), (3,), (7,)]), max_iter=int_options, tol=options)
def test_ik_newton_with_any_arguments(robot, pose, guess, max_iter, tol):
    res = run(lambda: robot.ik_newton(pose, guess, max_iter=max_iter, tol=tol), "pose", "guess", "max_iter", "tol")
    if res is None:
        return
    alpha, beta = res
    assert alpha.shape == beta.shape == (3,)
    assert_finite(alpha, beta, res.error)
    assert isinstance(res.converged, bool) and 0 <= res.iterations <= max_iter
    assert repr(res) == (f"RRR3Newton(alpha={res.alpha!r}, beta={res.beta!r}, converged={res.converged}, "
                         f"iterations={res.iterations}, error={res.error!r})")
    check_newton(robot, as_pose(pose), res, tol)


@given(robot=robots, alpha=arrays(shape=[(3,), (2,), (4,), (1, 3)]), guess=arrays(shape=[(3,), (6,)]),
       max_iter=int_options, tol=options)
def test_fk_with_any_arguments(robot, alpha, guess, max_iter, tol):
    res = run(lambda: robot.fk(alpha, guess, max_iter=max_iter, tol=tol), "alpha", "guess", "max_iter", "tol")
    if res is not None:
        assert res.pose.shape == (3,)
        assert_finite(res.pose, res.error)
        assert isinstance(res.converged, bool) and 0 <= res.iterations <= max_iter
        assert repr(res) == (f"RRR3Fk(pose={res.pose!r}, converged={res.converged}, iterations={res.iterations}, "
                             f"error={res.error!r})")
        check_fk(robot, np.asarray(alpha, float), res, tol)
    poses = run(lambda: robot.fk_all(alpha), "alpha")
    if poses is not None:
        check_fk_all(robot, np.asarray(alpha, float), poses)


grid_sizes = st.one_of(st.integers(-3, 24), st.sampled_from([5001, 10**6, 2**31, 2**62, -(2**63)]),
                       st.sampled_from([2.5, "20", None]))


@given(robot=robots, phi=options, mode=modes, n=grid_sizes, tol=options)
def test_workspace_with_any_arguments(robot, phi, mode, n, tol):
    w = run(lambda: robot.workspace(phi=phi, mode=mode, n=n, tol=tol), "phi", "mode", "n", "tol")
    if w is None:
        return
    cells = w.cells
    assert cells.shape == (n, n) and cells.dtype == np.uint8 and np.all(cells <= 3)
    assert w.x.shape == w.y.shape == (n,) and len(w.extent) == 4
    assert_finite(w.x, w.y, w.extent, w.cell_size, w.reachable_area, w.regular_area, w.area)
    assert 0 <= w.area <= w.regular_area <= w.reachable_area
    assert w.reachable_area == pytest.approx(np.count_nonzero(cells) * w.cell_size**2, rel=1e-12)
    assert w.regular_area == pytest.approx(np.count_nonzero(cells == 1) * w.cell_size**2, rel=1e-12)
    assert repr(w).startswith(f"RRR3Workspace(n={n}")
    # A few cells against the inverse model: reachable exactly where ik answers.
    for j, i in [(0, 0), (n // 2, n // 2), (n // 3, 2 * n // 3), (n - 1, n // 2)]:
        outcome = run(lambda: robot.ik((w.x[i], w.y[j], phi), mode), "pose", unreachable=True)
        assert (outcome is Unreachable) == (cells[j, i] == 0)


@given(robot=robots, points=arrays(shape=[(0, 2), (1, 2), (4, 2), (3, 3), (2,)]), phi=options, mode=modes,
       avoid=st.sampled_from([True, False, 1, None, "yes"]), max_step=options, margin=options,
       serial_margin=options, span=options, resolution=options, smoothing=options,
       closed=st.sampled_from([False, True, 1, None]))
def test_plan_with_any_arguments(robot, points, phi, mode, avoid, max_step, margin, serial_margin, span, resolution,
                                 smoothing, closed):
    names = ("points", "phi", "mode", "avoid", "max_step", "margin", "serial_margin", "span", "resolution", "smoothing",
             "closed")
    plan = run(lambda: robot.plan(points, phi=phi, mode=mode, avoid=avoid, max_step=max_step, margin=margin,
                                  serial_margin=serial_margin, span=span, resolution=resolution,
                                  smoothing=smoothing, closed=closed), *names)
    if plan is None:
        return
    check_plan(robot, np.asarray(points, float), plan, phi, mode, avoid, max_step, margin, serial_margin, span,
               closed=closed)


@given(robot=robots, points=arrays(shape=[(0, 2), (1, 2), (3, 2), (3, 3), (2,)]),
       sign=st.sampled_from([1, -1, 0, 2, True, 1.0, None]),
       nominals=st.one_of(st.none(), arrays(shape=[(0,), (1,), (3,), (2, 2), ()]),
                          st.lists(st.floats(-1.5, 1.5), min_size=1, max_size=4), st.sampled_from(["abc", 0.5])),
       mode=modes, avoid=st.sampled_from([True, False, 1]), margin=options)
def test_plan_loop_with_any_arguments(robot, points, sign, nominals, mode, avoid, margin):
    """Found: the closed plan about one of the nominals, of the asked sign and feasible with
    avoidance; not found: a reason and no poses; else an error naming the argument."""
    kwargs = dict(sign=sign, mode=mode, avoid=avoid, margin=margin)
    if nominals is not None:
        kwargs["nominals"] = nominals
    loop = run(lambda: robot.plan_loop(points, **kwargs), "points", *kwargs)
    if loop is None:
        return
    tried = rk.RRR3LoopOptions().nominals if nominals is None else tuple(np.asarray(nominals, float))
    assert isinstance(loop.found, bool)
    assert repr(loop) == f"RRR3Loop(plan={loop.plan!r}, nominal={loop.nominal!r}, found={loop.found}, reason={loop.reason!r})"
    if not loop.found:
        assert loop.reason in ("start", "plan") and loop.nominal is None and loop.plan.poses.shape == (0, 3)
        return
    assert loop.reason is None and loop.nominal in tried
    event(f"found, avoid={avoid}")
    plan = loop.plan
    check_plan(robot, np.asarray(points, float), plan, loop.nominal, mode, avoid, 0.01, margin, 0.02, 1.0, closed=True)
    assert np.sign(plan.det_a_norm[0]) == sign or avoid  # without avoidance the start is at the nominal
    if avoid:
        assert plan.feasible and plan.sign == sign


@given(cls=st.sampled_from([rk.RRR3PlanOptions, rk.RRR3ConnectOptions, rk.RRR3LoopOptions]), data=st.data())
def test_plan_and_connect_options_from_any_keywords(cls, data):
    """Any keywords: the options hold what was given, or a TypeError / ValueError names the keyword;
    validate() then passes or names the option out of range."""
    names = st.sampled_from([*cls.fields, "bogus"])
    given = data.draw(st.dictionaries(names, st.one_of(options, modes), max_size=4))
    o = check_call(lambda: cls(**given), *given)
    if o is None:
        return
    for name, value in given.items():
        got = getattr(o, name)
        if name == "mode":
            assert got == tuple(int(v) for v in np.asarray(value, float))
        elif name == "nominals":
            assert got == tuple(float(v) for v in np.asarray(value, float))
        elif isinstance(got, bool):
            assert got is bool(value)
        else:
            assert got == value or (got != got and value != value)
    check_call(o.validate, *given)


def check_route(robot, start, goal, mode, plan, clearance, serial_margin, max_step, max_turn):
    """A connect answer against the seed's formulas: ends, spacing, one sign of det A, clearances."""
    poses = np.asarray(plan.poses)
    assert poses.ndim == 2 and poses.shape[1] == 3 and len(poses) >= 1 and plan.feasible
    assert_finite(poses, plan.alpha, plan.det_a_norm, plan.det_b_norm, plan.distance)
    np.testing.assert_array_equal(poses[0], start)
    np.testing.assert_array_equal(poses[-1], goal)
    if len(poses) > 1:
        steps = np.diff(poses, axis=0)
        assert np.hypot(steps[:, 0], steps[:, 1]).max() <= max_step * (1 + 1e-9)
        assert np.abs(steps[:, 2]).max() <= max_turn * (1 + 1e-9)
    det_a = np.array([np.linalg.det(seed_jacobians(robot, p, robot.ik(p, mode))[0]) for p in poses])
    assert np.all(np.sign(det_a) == plan.sign) and plan.sign in (-1, 1)
    distance = np.asarray(plan.distance)
    assert distance.min() >= min(clearance, distance[0], distance[-1]) * (1 - 1e-12)
    det_b = np.abs(np.asarray(plan.det_b_norm))
    assert det_b.min() >= min(serial_margin, det_b[0], det_b[-1]) * (1 - 1e-12)


@given(robot=robots, start=arrays(shape=[(3,), (2,), (4,), (1, 3)]), goal=arrays(shape=[(3,), (3, 1)]), mode=modes,
       clearance=options, serial_margin=options, max_step=options, max_turn=options, resolution=options, span=options)
def test_connect_with_any_arguments(robot, start, goal, mode, clearance, serial_margin, max_step, max_turn,
                                    resolution, span):
    names = ("start", "goal", "mode", "clearance", "serial_margin", "max_step", "max_turn", "resolution", "span")

    def call():
        try:
            return robot.connect(start, goal, mode=mode, clearance=clearance, serial_margin=serial_margin,
                                 max_step=max_step, max_turn=max_turn, resolution=resolution, span=span)
        except rk.NoRouteError as e:
            assert e.reason in ("start", "goal", "regions") and str(e)
            return None

    plan = check_call(call, *names)
    if plan is not None:
        check_route(robot, as_pose(start), as_pose(goal), tuple(int(m) for m in np.asarray(mode, float)), plan,
                    clearance, serial_margin, max_step, max_turn)


@given(data=st.data(), clearance=st.floats(0.0, 0.3))
def test_connect_routes_are_verified_and_opposite_signs_have_none(data, clearance):
    """Reachable poses of the seed's robot, near and across singularities: a route satisfies
    everything it promises (checked with the seed's formulas); poses whose det A differ in sign
    have none."""
    robot = ROBOTS[0]
    mode = data.draw(good_modes)
    poses = []
    while len(poses) < 2:
        p = np.array(data.draw(st.tuples(st.floats(-0.12, 0.12), st.floats(-0.12, 0.12), st.floats(-1.2, 1.2))))
        try:
            s = robot.singularity(p, mode)
        except rk.UnreachableError:
            continue
        if s.det_a_norm != 0 and s.det_b_norm != 0:
            poses.append((p, np.sign(s.det_a_norm)))
    (start, s0), (goal, s1) = poses
    try:
        plan = robot.connect(start, goal, mode=mode, clearance=clearance, resolution=0.01)
    except rk.NoRouteError as e:
        event(f"no route: {e.reason}, {'same' if s0 == s1 else 'opposite'} signs")
        assert e.reason == "regions"
        return
    event("route")
    assert s0 == s1
    check_route(robot, start, goal, mode, plan, clearance, 0.02, 0.001, 0.01)


@given(rows=arrays(shape=[(0, 4), (1, 4), (3, 4), (2, 3), (4,)]), phi=options, mode=modes, n=grid_sizes, tol=options)
def test_region_areas_with_any_arguments(rows, phi, mode, n, tol):
    areas = run(lambda: _core.rrr3_region_areas(rows, phi=phi, mode=mode, n=n, tol=tol), "robots", "phi", "mode", "n", "tol")
    if areas is None:
        return
    g = np.asarray(rows, float)
    assert areas.shape == (g.shape[0],)
    assert_finite(areas)
    for row, area in zip(g, areas):
        assert area == rk.RRR3(*row).workspace(phi=phi, mode=mode, n=n, tol=tol).area


values = st.one_of(arrays(shape=[(1,), (3,), (0,), (2, 2), ()]), st.sampled_from([None, [0.1, 0.05]]))
scalars = st.one_of(st.floats(0.02, 0.3), wild_floats, st.sampled_from(["abc", None]))
small_n = st.one_of(st.integers(-2, 12), st.sampled_from([10**6, 2**63, "8"]))


@given(radii=values, rb=scalars, l1=scalars, l2=scalars, phi=options, mode=modes, n=small_n, tol=options)
def test_area_vs_platform_radius_with_any_arguments(radii, rb, l1, l2, phi, mode, n, tol):
    names = ("platform_radii", "base_radius", "l1", "l2", "phi", "mode", "n", "tol")
    curve = run(lambda: rrr3_design.area_vs_platform_radius(radii, rb, l1, l2, phi=phi, mode=mode, n=n, tol=tol), *names)
    if curve is None:
        return
    k = 30 if radii is None else np.asarray(radii).size
    assert curve.values.shape == curve.area.shape == (k,)
    assert_finite(curve.values, curve.area)
    assert np.all(curve.area >= 0)
    assert curve.best in curve.values and curve.area[list(curve.values).index(curve.best)] == curve.area.max()
    assert (curve.base_radius, curve.l1, curve.l2) == (rb, l1, l2)


@given(l1s=values, l2s=values, rb=scalars, re=scalars, phi=options, mode=modes, n=small_n, tol=options)
def test_best_l2_with_any_arguments(l1s, l2s, rb, re, phi, mode, n, tol):
    names = ("l1_values", "l2_values", "base_radius", "platform_radius", "phi", "mode", "n", "tol")
    best = run(lambda: rrr3_design.best_l2(l1s, l2s, rb, re, phi=phi, mode=mode, n=n, tol=tol), *names)
    if best is None:
        return
    a, b = np.asarray(l1s, float).ravel(), np.asarray(l2s, float).ravel()
    assert best.area.shape == best.index.shape == (a.size, b.size)
    assert best.best_l2.shape == best.best_area.shape == (a.size,)
    assert_finite(best.area, best.index, best.best_l2, best.best_area)
    for i in range(a.size):
        k = int(np.argmax(best.index[i]))
        assert best.best_l2[i] == b[k] and best.best_area[i] == best.area[i, k]


# --- reported success equals verified success ----------------------------------------------------


def check_newton(robot, pose, res, tol):
    """ik_newton's flag and error against the loop closures O_i + l1 u(a) + l2 u(a + b) = B_i."""
    a, b = res.alpha, res.beta
    assert np.all(np.abs(a) <= math.pi) and np.all(np.abs(b) <= math.pi)
    reach = base(robot) + robot.l1 * np.column_stack((np.cos(a), np.sin(a))) + \
        robot.l2 * np.column_stack((np.cos(a + b), np.sin(a + b)))
    residual = float(np.max(np.linalg.norm(reach - platform(robot, pose), axis=1)))
    slack = 8 * EPS * size(robot, pose)
    assert abs(res.error - residual) <= slack + 1e-12 * residual, (res, residual)
    if res.converged:
        assert residual < tol + slack, (res, residual)
    else:
        assert residual >= tol - slack, (res, residual)


def check_fk(robot, alpha, res, tol):
    """fk's flag and error against | |A_i B_i| - l2 | at the pose it returns."""
    residual = closure(robot, res.pose, alpha)
    slack = 8 * EPS * size(robot, res.pose)
    assert -math.pi <= res.pose[2] <= math.pi
    assert abs(res.error - residual) <= slack + 1e-12 * residual, (res, residual)
    if res.converged:
        assert residual < tol + slack, (res, residual)
    else:
        assert residual >= tol - slack, (res, residual)


def check_fk_all(robot, alpha, poses):
    """Every pose fk_all returns closes the loops to 1e-10 m (1e-10 of the size for a robot larger
    than 1 m: its documented bound), sorted by phi; at most 6, for any robot: a double root is given
    once, and where the assembly modes form a continuum (an alpha where the elbows' triangle is congruent
    to the platform's, e.g. equal alpha_i with base_radius == platform_radius) only the isolated ones."""
    assert poses.ndim == 2 and poses.shape[1] == 3 and poses.shape[0] <= 6
    assert_finite(poses)
    assert np.all(np.diff(poses[:, 2]) >= 0) and np.all((poses[:, 2] >= -math.pi) & (poses[:, 2] < math.pi))
    for pose in poses:
        assert closure(robot, pose, alpha) <= 1e-10 * max(1.0, size(robot)) + 8 * EPS * size(robot, pose), pose


@st.composite
def geometry(draw):
    """A random robot, any proportions (platform larger than the base, links long or short), any size."""
    rb, re = draw(st.floats(0.05, 0.3)), draw(st.floats(0.02, 0.4))
    l1, l2 = draw(st.floats(0.02, 0.4)), draw(st.floats(0.02, 0.4))
    scale = draw(st.sampled_from([1.0, 1.0, 1e-3, 0.1, 10.0, 1e3]))
    return rk.RRR3(rb * scale, re * scale, l1 * scale, l2 * scale)


def bisect(f, t0, t1, iters=60):
    """The point of [t0, t1] where the boolean f changes (f(t0) != f(t1))."""
    f0 = f(t0)
    for _ in range(iters):
        t = 0.5 * (t0 + t1)
        if f(t) == f0:
            t0 = t
        else:
            t1 = t
    return t0 if f0 else t1


def reachable(robot, pose, mode):
    try:
        robot.ik(pose, mode)
        return True
    except rk.UnreachableError:
        return False


def det_a_sign(robot, pose, mode):
    try:
        return robot.singularity(pose, mode, 1e-300).det_a > 0
    except rk.UnreachableError:
        return None


@st.composite
def targets(draw, robot):
    """A pose and a mode: anywhere (often unreachable), on the boundary of the workspace (a leg
    stretched or folded: serial singularity) or where det A changes sign (parallel singularity)."""
    mode = draw(good_modes)
    reach = robot.l1 + robot.l2 + robot.base_radius
    unit = st.floats(-1.5, 1.5)
    p0 = np.array([draw(unit) * reach, draw(unit) * reach, draw(st.floats(-math.pi, math.pi))])
    kind = draw(st.sampled_from(["any", "any", "serial", "parallel"]))
    if kind == "any":
        return p0, mode
    p1 = np.array([draw(unit) * reach, draw(unit) * reach, draw(st.floats(-math.pi, math.pi))])
    line = lambda t: p0 + t * (p1 - p0)  # noqa: E731
    if kind == "serial":
        if reachable(robot, p0, mode) == reachable(robot, p1, mode):
            return p0, mode
        return line(bisect(lambda t: reachable(robot, line(t), mode), 0.0, 1.0)), mode
    s0, s1 = det_a_sign(robot, p0, mode), det_a_sign(robot, p1, mode)
    if s0 is None or s1 is None or s0 == s1:
        return p0, mode
    t = bisect(lambda t: det_a_sign(robot, line(t), mode), 0.0, 1.0)
    return line(t), mode


@given(data=st.data(), robot=geometry())
def test_ik_answers_are_verified(data, robot):
    pose, mode = data.draw(targets(robot))
    surely_in, surely_out = leg_reach(robot, pose)
    try:
        alpha = robot.ik(pose, mode)
    except rk.UnreachableError as e:
        assert not surely_in[e.leg] and not surely_in.all()
        alpha = None
    else:
        check_ik_answer(robot, pose, mode, alpha)
        assert not surely_out.any()
    event(f"reachable={alpha is not None}")
    if surely_in.all():
        assert alpha is not None
    rows = robot.ik_all(pose)
    batch = robot.ik_batch(np.array([pose, pose + 1e-3 * robot.l1]), mode)
    k = MODES.index(mode)
    np.testing.assert_array_equal(rows[k], np.full(3, np.nan) if alpha is None else alpha)
    np.testing.assert_array_equal(batch[0], rows[k])
    for m, row in zip(MODES, rows):
        if not np.isnan(row).any():
            check_ik_answer(robot, pose, m, row)
    if not np.isnan(batch[1]).any():
        check_ik_answer(robot, pose + 1e-3 * robot.l1, mode, batch[1])


tols = st.sampled_from([1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-3])


@given(data=st.data(), robot=geometry(), max_iter=st.integers(0, 60), tol=tols,
       spread=st.sampled_from([0.0, 1e-6, 1e-3, 0.1, 1.0, None]))
def test_ik_newton_converged_iff_verified(data, robot, max_iter, tol, spread):
    pose, mode = data.draw(targets(robot))
    tol = tol * size(robot)
    try:
        alpha = robot.ik(pose, mode)
        a, b, o = elbows(robot, alpha), platform(robot, pose), base(robot)
        beta = np.arctan2(cross(a - o, b - a), np.sum((a - o) * (b - a), axis=1))
    except rk.UnreachableError:
        alpha = beta = None
    if spread is None or alpha is None:  # anywhere, far-off angles included
        guess = data.draw(st.lists(st.one_of(st.floats(-4, 4), st.floats(-1e12, 1e12)), min_size=6, max_size=6))
    else:
        guess = np.concatenate([alpha, beta]) + spread * np.array(data.draw(st.lists(st.floats(-1, 1), min_size=6,
                                                                                     max_size=6)))
    res = robot.ik_newton(pose, guess, max_iter=max_iter, tol=tol)
    event(f"converged={res.converged}")
    assert_finite(res.alpha, res.beta, res.error)
    check_newton(robot, pose, res, tol)


@given(data=st.data(), robot=geometry(), max_iter=st.integers(0, 60), tol=tols,
       spread=st.sampled_from([0.0, 1e-6, 1e-3, 0.1, 1.0, None]), random_alpha=st.booleans())
def test_fk_converged_iff_verified(data, robot, max_iter, tol, spread, random_alpha):
    pose, mode = data.draw(targets(robot))
    tol = tol * size(robot)
    noise = np.array(data.draw(st.lists(st.floats(-1, 1), min_size=6, max_size=6)))
    try:
        alpha = robot.ik(pose, mode)
    except rk.UnreachableError:
        alpha = None
    if alpha is None or random_alpha:
        alpha = math.pi * noise[3:]  # most have no assembly at all
    if spread is None:  # anywhere, far-off orientations included
        guess = np.array([*(size(robot) * 3 * noise[:2]), data.draw(st.one_of(st.floats(-4, 4),
                                                                               st.floats(-1e12, 1e12)))])
    else:
        guess = pose + spread * np.array([size(robot), size(robot), 1.0]) * noise[:3]
    res = robot.fk(alpha, guess, max_iter=max_iter, tol=tol)
    event(f"converged={res.converged}")
    assert_finite(res.pose, res.error)
    check_fk(robot, alpha, res, tol)
    poses = robot.fk_all(alpha)
    event(f"assembly modes: {len(poses)}")
    check_fk_all(robot, alpha, poses)
    if res.converged and res.error < 1e-12 * size(robot):
        # A well-conditioned assembly found by Newton is among fk_all's (not one of a continuum:
        # alpha = 0 with platform_radius == base_radius moves on a circle; det A = 0 there).
        det_b = np.linalg.det(seed_jacobians(robot, res.pose, alpha)[1]) / robot.l1**3
        if numpy_distance(robot, res.pose, alpha) > 1e-3 and abs(det_b) > 1e-3:
            gap = np.abs(poses - res.pose)
            gap[:, 2] = np.abs(np.angle(np.exp(1j * (poses[:, 2] - res.pose[2]))))
            assert np.any(np.all(gap <= [1e-6 * size(robot), 1e-6 * size(robot), 1e-6], axis=1)), (res, poses)


def numpy_distance(robot, pose, alpha):
    A = seed_jacobians(robot, pose, alpha)[0].copy()
    A[:, 2] /= robot.platform_radius
    sv = np.linalg.svd(A, compute_uv=False)
    return sv[-1] / sv[0]


def check_plan(robot, points, plan, phi, mode, avoid, max_step, margin, serial_margin, span, closed=False):
    """The plan's arrays have the documented shapes, and ``feasible`` is what the rows verify:
    every pose reachable in the mode (its alpha closes the loops with the mode's elbow signs),
    |det B| / l1^3 >= serial_margin, distance >= margin, one sign of det A, steps <= max_step (for
    a closed path the step from the last pose to the first too)."""
    k = points.shape[0]
    assert plan.poses.shape == plan.alpha.shape == (k, 3)
    assert plan.det_a_norm.shape == plan.det_b_norm.shape == plan.distance.shape == (k,)
    assert_finite(plan.poses)
    np.testing.assert_array_equal(plan.poses[:, :2], points)
    assert plan.sign in (-1, 0, 1)
    assert repr(plan).startswith("RRR3Plan(poses=" + (f"<array ({k}, 3) float64>" if 3 * k > 8 else repr(plan.poses)))
    assert repr(plan).endswith(f", sign={plan.sign}, feasible={plan.feasible})")
    if not avoid:
        assert np.all(plan.poses[:, 2] == phi)
    else:
        assert np.all(np.abs(plan.poses[:, 2] - phi) <= span + 1e-9)
    ok_strict, ok_loose = k > 0, k > 0
    slack = 1e-9
    for pose, alpha, da, db, dist in zip(plan.poses, plan.alpha, plan.det_a_norm, plan.det_b_norm, plan.distance):
        in_, out = leg_reach(robot, pose)
        if np.isnan(alpha).any():
            assert np.isnan(alpha).all() and np.isnan([da, db, dist]).all() and not in_.all()
            ok_strict = ok_loose = False
            continue
        assert_finite(da, db, dist)
        check_ik_answer(robot, pose, mode, alpha)
        A, B = seed_jacobians(robot, pose, alpha)
        assert da == pytest.approx(np.linalg.det(A) / robot.platform_radius, abs=1e-9)
        assert db == pytest.approx(np.linalg.det(B) / robot.l1**3, abs=1e-9)
        # The core takes sqrt of the eigenvalues of A^T A: some sqrt(eps) ~ 1.5e-8 near a singularity.
        assert dist == pytest.approx(numpy_distance(robot, pose, alpha), abs=1e-7)
        sign = np.sign(np.linalg.det(A))
        ok_strict &= abs(db) >= serial_margin + slack and dist >= margin + 1e-7 and sign == plan.sign
        ok_loose &= abs(db) >= serial_margin - slack and dist >= margin - 1e-7 and (sign == plan.sign or abs(da) < slack)
    phis = np.append(plan.poses[:, 2], plan.poses[0, 2]) if closed and k > 1 else plan.poses[:, 2]
    steps = np.abs(np.diff(phis))
    ok_strict &= bool(np.all(steps <= max_step - slack))
    ok_loose &= bool(np.all(steps <= max_step + slack))
    if plan.feasible:
        assert ok_loose, plan
    else:
        assert not ok_strict, plan


@given(data=st.data(), robot=geometry(), count=st.integers(1, 5), avoid=st.booleans(), phi=st.floats(-1, 1),
       max_step=st.sampled_from([0.02, 0.05, 0.2, 1.0]), ratio=st.integers(1, 4), span=st.floats(0, 1),
       margin=st.sampled_from([0.0, 0.01, 0.05, 0.2]), serial_margin=st.sampled_from([0.0, 0.01, 0.05]),
       smoothing=st.sampled_from([0.0, 1.0, 10.0]), closed=st.booleans())
def test_plan_feasible_iff_verified(data, robot, count, avoid, phi, max_step, ratio, span, margin, serial_margin,
                                    smoothing, closed):
    mode = data.draw(good_modes)
    reach = robot.l1 + robot.l2
    start = np.array(data.draw(st.lists(st.floats(-1, 1), min_size=2, max_size=2))) * reach
    walk = np.array(data.draw(st.lists(st.floats(-0.05, 0.05), min_size=2 * count, max_size=2 * count)))
    points = start + np.cumsum(walk.reshape(count, 2) * reach, axis=0)
    resolution = max(max_step / ratio, 0.01)
    plan = robot.plan(points, phi=phi, mode=mode, avoid=avoid, max_step=max_step, margin=margin,
                      serial_margin=serial_margin, span=span, resolution=resolution, smoothing=smoothing, closed=closed)
    event(f"feasible={plan.feasible}")
    check_plan(robot, points, plan, phi, mode, avoid, max_step, margin, serial_margin, span, closed=closed)



def start_side(robot, point, phi, mode):
    """The sign of det A at the loop's first point at orientation phi, 0 where a leg cannot reach."""
    try:
        return int(np.sign(robot.singularity((*point, phi), mode).det_a_norm))
    except rk.UnreachableError:
        return 0


@given(data=st.data(), robot=geometry(), count=st.integers(2, 6), sign=st.sampled_from([1, -1]),
       nominals=st.lists(st.floats(-1, 1), min_size=1, max_size=4), avoid=st.booleans(),
       margin=st.sampled_from([0.0, 0.05, 0.2]))
def test_plan_loop_takes_the_first_nominal_that_suits(data, robot, count, sign, nominals, avoid, margin):
    """The nominal used is the first of the list that the documented rule accepts, each rule checked
    here on the poses (start's side through RRR3.singularity, the closed plan's rows by check_plan)."""
    mode = data.draw(good_modes)
    reach = robot.l1 + robot.l2
    start = np.array(data.draw(st.lists(st.floats(-0.3, 0.3), min_size=2, max_size=2))) * reach
    walk = np.array(data.draw(st.lists(st.floats(-0.05, 0.05), min_size=2 * count, max_size=2 * count)))
    points = start + np.cumsum(walk.reshape(count, 2) * reach, axis=0)
    loop = robot.plan_loop(points, sign=sign, nominals=nominals, mode=mode, avoid=avoid, margin=margin,
                           resolution=0.01, span=0.5)
    event(f"found={loop.found}, reason={loop.reason}")
    sides = [start_side(robot, points[0], phi, mode) for phi in nominals]
    if not any(s == sign for s in sides):
        assert not loop.found and loop.reason == "start"
        return
    if not avoid:
        keeps = [all(start_side(robot, p, phi, mode) == sign for p in points) for phi in nominals]
        first = 0 if sides[0] == sign else next((i for i, k in enumerate(keeps) if k), sides.index(sign))
        assert loop.found and loop.nominal == nominals[first]
        np.testing.assert_array_equal(loop.plan.poses[:, 2], nominals[first])
        return
    plans = [robot.plan(points, phi=phi, mode=mode, margin=margin, resolution=0.01, span=0.5, closed=True)
             for phi in nominals]
    suits = [s == sign and p.feasible and p.sign == sign for s, p in zip(sides, plans)]
    if not any(suits):
        assert not loop.found and loop.reason == "plan"
        return
    first = suits.index(True)
    assert loop.found and loop.nominal == nominals[first]
    np.testing.assert_array_equal(loop.plan.poses, plans[first].poses)
    check_plan(robot, points, loop.plan, nominals[first], mode, True, 0.01, margin, 0.02, 0.5, closed=True)
    assert loop.plan.feasible and np.all(np.sign(loop.plan.det_a_norm) == sign)


# --- regressions: the cases the fuzzing found --------------------------------------------------------


def test_ik_newton_error_and_flag_are_those_of_the_wrapped_answer():
    # A far-off beta guess: the error was measured before wrapping (1.5e-12 m off the answer).
    robot = rk.RRR3(0.25, 0.25, 0.25, 0.25)
    pose = np.array([0.75, 0.0, 0.0])
    for max_iter in (0, 50):
        res = robot.ik_newton(pose, [0, 0, 0, 0, 0, 165994.0], max_iter=max_iter, tol=1e-14)
        check_newton(robot, pose, res, 1e-14)
    pose = np.array([0.1, 0.05, 0.3])
    alpha = robot.ik(pose, (1, -1, 1))
    res = robot.ik_newton(pose, np.concatenate([alpha + 2 * np.pi * 1e9, [1.0, -1.0, 1.0]]), max_iter=50, tol=1e-9)
    check_newton(robot, pose, res, 1e-9)


def test_fk_error_and_flag_are_those_of_the_wrapped_pose():
    # A far-off orientation guess: the error was measured before phi was wrapped.
    robot = rk.RRR3(0.25, 0.25, 0.25, 0.375)
    for max_iter in (0, 50):
        res = robot.fk([0.0, 0.0, 0.0], [0.0, 0.0, 41649.0], max_iter=max_iter, tol=1e-14)
        check_fk(robot, np.zeros(3), res, 1e-14)


@pytest.mark.parametrize("geometry, name", [
    ((0.25, 0.25, 0.25, 1.3e154), "l2"),   # workspace areas were NaN (cell area overflowed)
    ((1e-300, 0.1, 0.1, 0.1), "base_radius"),
    ((0.1, 0.1, 1e-120, 0.1), "l1"),        # det B / l1^3 divided by an underflowed cube
    ((0.1, 5e-324, 0.1, 0.1), "platform_radius"),
])
def test_geometry_out_of_range_is_rejected(geometry, name):
    with pytest.raises(ValueError, match=f"{name}: must be a length in \\[1e-6, 1e6\\] m"):
        rk.RRR3(*geometry)
    with pytest.raises(ValueError, match=f"robots\\[0\\]: {name}"):
        _core.rrr3_region_areas([geometry], n=10)


def test_design_study_arguments_are_named():
    with pytest.raises(ValueError, match="l2: must be a length"):  # NaN areas before
        rrr3_design.area_vs_platform_radius(l2=1.3e154, n=10)
    with pytest.raises(TypeError, match="platform_radii: expected real numbers"):  # imaginary part dropped
        rrr3_design.area_vs_platform_radius([0.05 + 1j], n=10)
    with pytest.raises(TypeError, match="base_radius: expected a number, got str"):  # numpy's message named nothing
        rrr3_design.area_vs_platform_radius(base_radius="abc", n=10)
    with pytest.raises(ValueError, match="base_radius: must be a positive finite number"):  # blamed platform_radii
        rrr3_design.area_vs_platform_radius(base_radius=float("nan"), n=10)
    with pytest.raises(TypeError, match="platform_radius: expected a number, got NoneType"):
        rrr3_design.best_l2([0.1], [0.1], platform_radius=None, n=10)


def test_far_poses_and_guesses_are_rejected_not_inf():
    # error was inf: |E - B|^2 overflowed.
    robot = rk.RRR3()
    with pytest.raises(ValueError, match="pose: x and y must be within 1e100 m"):
        robot.ik_newton([1e200, 0.0, 0.0], np.zeros(6))
    with pytest.raises(ValueError, match="guess: x and y must be within 1e100 m"):
        robot.fk(np.zeros(3), [0.0, 1e200, 0.0])
    res = robot.fk(np.zeros(3), [1e100, -1e100, 0.0])
    assert_finite(res.pose, res.error)
    assert np.all(np.isnan(robot.ik_batch([[1e200, 0.0, 0.0]])))  # the batch keeps its NaN rows


def test_newton_options_are_bounded():
    # max_iter = 2**31 - 1 at an unreachable pose ran for minutes; tol = inf made any answer "converged".
    robot = rk.RRR3()
    for call in (lambda **k: robot.ik_newton([0.5, 0.0, 0.0], [0.1, 0.2, 0.3, 1.0, 1.0, 1.0], **k),
                 lambda **k: robot.fk([0.1, 0.2, 0.3], [0.5, 0.0, 0.0], **k)):
        with pytest.raises(ValueError, match="max_iter: must be in \\[0, 100000\\]"):
            call(max_iter=2**31 - 1)
        with pytest.raises(ValueError, match="tol: must be a positive finite number"):
            call(tol=float("inf"))
        assert not call(max_iter=100000).converged


def test_repr_keeps_small_lengths():
    # std::to_string printed 1.5e-6 as 0.000002.
    robot = rk.RRR3(1.5e-6, 1e-6, 2.5e-6, 3e-6)
    assert repr(robot) == "RRR3(base_radius=1.5e-06, platform_radius=1e-06, l1=2.5e-06, l2=3e-06)"
    with pytest.raises(rk.UnreachableError, match="is outside \\[5e-07, 5.5e-06\\]"):
        robot.ik([1.0, 0.0, 0.0])


def test_fk_all_on_a_large_robot():
    # The closure filter was 1e-10 m whatever the size: rounding alone exceeds it on a 1000 km robot.
    scale = 5e6
    robot = rk.RRR3(0.13 * scale, 0.07 * scale, 0.12 * scale, 0.12 * scale)
    pose = np.array([0.01 * scale, 0.02 * scale, 0.1])
    poses = robot.fk_all(robot.ik(pose))
    check_fk_all(robot, robot.ik(pose), poses)
    assert np.min(np.abs(poses - pose).max(axis=1) / [1.0]) < 1e-9 * scale
