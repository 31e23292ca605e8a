"""Property tests of the serial-arm toolkit: robokin.traj, robokin.pose,
Chain.manipulability / Chain.ellipsoid, rk.resolved_rate and rk.servo.

Every argument arbitrary (arrays of any shape, dtype and layout, wild numbers): a call returns
finite results of the documented shape or raises ValueError / TypeError naming an argument. And on
well-formed input the documented properties hold: trajectories start and end exactly where asked
and keep their limits, pose conversions round-trip, manipulability equals numpy's SVD, resolved
rates realise the twist."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk
from fuzz import arrays, assert_finite, check_call, finite_arrays, wild_floats
from fuzz_chains import dh_chains
from robokin import plots, pose, traj

COVERS = {
    "traj.quintic", "traj.trapezoidal", "traj.via_points", "traj.cartesian",
    "pose.from_rpy", "pose.rpy", "pose.from_quaternion", "pose.quaternion", "pose.from_axis_angle",
    "pose.axis_angle", "pose.exp", "pose.log", "pose.error",
    "Chain.manipulability", "Chain.ellipsoid", "resolved_rate", "servo", "plots.trajectory_figure",
}

#: Samples are cheap but not free: a tenth of the profile's examples for the sampling calls.
FEWER = settings(max_examples=max(10, settings.default.max_examples // 10))

CHAINS = [rk.robots.rpr(), rk.robots.planar_3r(), rk.robots.ur5(), rk.robots.rp(),
          rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True)]
numbers = st.one_of(wild_floats, st.floats(1e-3, 10.0), st.sampled_from([None, "1", [1.0], 1e-300, 0.05]))
periods = st.one_of(st.sampled_from([0.01, 0.05, 0.3, 0.0, -1.0, math.nan, math.inf, 1e-300, None, "0.1"]),
                    st.floats(0.01, 1.0))
limits = st.one_of(numbers, arrays([(1,), (2,), (3,), (6,), (0,)]))
joint_shapes = [(1,), (2,), (3,), (6,), (0,), (2, 3)]
frame_shapes = [(4, 4), (3, 3), (2, 4, 4), (3, 3, 3), (4,), (0, 4, 4), (4, 3)]
frames = st.one_of(arrays(frame_shapes), st.sampled_from([np.eye(4), np.eye(3), np.tile(np.eye(4), (3, 1, 1))]))


@st.composite
def rigid(draw, batch=None):
    """Well-formed frames (4, 4), or (batch, 4, 4), from random quaternions and positions."""
    shape = (4,) if batch is None else (batch, 4)
    q = draw(finite_arrays(shape, -1.0, 1.0))
    q = np.where(np.linalg.norm(q, axis=-1, keepdims=True) < 1e-3, [1.0, 0, 0, 0], q)
    p = draw(finite_arrays(shape[:-1] + (3,), -2.0, 2.0))
    return pose.from_quaternion(q, position=p)


# --- traj ----------------------------------------------------------------------------------------

@FEWER
@given(q0=arrays(joint_shapes), q1=arrays(joint_shapes), t=st.one_of(arrays([(2,), (5,), (1,), (3, 2)]), st.just(np.linspace(0, 1, 7))),
       qd0=st.one_of(st.none(), arrays(joint_shapes)), qd1=st.one_of(st.none(), arrays(joint_shapes)))
def test_quintic_with_arbitrary_arguments(q0, q1, t, qd0, qd1):
    tr = check_call(lambda: traj.quintic(q0, q1, t, qd0=qd0, qd1=qd1), "q0", "q1", "t", "qd0", "qd1")
    if tr is None:
        return
    k, n = len(tr.t), np.asarray(q0).shape[-1]
    assert tr.q.shape == tr.qd.shape == tr.qdd.shape == (k, n)
    assert_finite(tr.t, tr.q, tr.qd, tr.qdd)
    assert np.array_equal(tr.q[0], np.asarray(q0, dtype=float)) and np.array_equal(tr.q[-1], np.asarray(q1, dtype=float))


@FEWER
@given(q0=arrays(joint_shapes), q1=arrays(joint_shapes), vmax=limits, amax=limits, dt=periods)
def test_trapezoidal_with_arbitrary_arguments(q0, q1, vmax, amax, dt):
    tr = check_call(lambda: traj.trapezoidal(q0, q1, vmax, amax, dt=dt), "q0", "q1", "vmax", "amax", "dt")
    if tr is None:
        return
    assert_finite(tr.t, tr.q, tr.qd, tr.qdd)
    assert np.array_equal(tr.q[-1], np.asarray(q1, dtype=float))


@FEWER
@given(q0=finite_arrays((3,), -5, 5), q1=finite_arrays((3,), -5, 5), vmax=finite_arrays((3,), 0.1, 5),
       amax=finite_arrays((3,), 0.1, 20), dt=st.floats(0.005, 0.2))
def test_trapezoidal_keeps_its_limits(q0, q1, vmax, amax, dt):
    tr = traj.trapezoidal(q0, q1, vmax, amax, dt=dt)
    assert np.all(np.abs(tr.qd) <= vmax * (1 + 1e-12)) and np.all(np.abs(tr.qdd) <= amax * (1 + 1e-12))
    assert np.array_equal(tr.q[0], q0) and np.array_equal(tr.q[-1], q1)
    # Positions stay between the ends (no overshoot), joint by joint.
    lo, hi = np.minimum(q0, q1), np.maximum(q0, q1)
    assert np.all(tr.q >= lo - 1e-12 * (1 + np.abs(lo))) and np.all(tr.q <= hi + 1e-12 * (1 + np.abs(hi)))


@FEWER
@given(points=arrays([(1, 2), (4, 2), (3, 3), (0, 2), (3,), (2, 0)]), vmax=limits, amax=limits, dt=periods)
def test_via_points_with_arbitrary_arguments(points, vmax, amax, dt):
    tr = check_call(lambda: traj.via_points(points, vmax, amax, dt=dt), "points", "vmax", "amax", "dt")
    if tr is None:
        return
    assert_finite(tr.t, tr.q, tr.qd, tr.qdd, tr.via_times)
    p = np.asarray(points, dtype=float)
    assert np.array_equal(tr.q[0], p[0]) and np.array_equal(tr.q[-1], p[-1])


@FEWER
@given(points=finite_arrays(st.tuples(st.integers(1, 6), st.just(2)), -3, 3), vmax=finite_arrays((2,), 0.1, 3),
       amax=finite_arrays((2,), 0.1, 20))
def test_via_points_keep_their_limits(points, vmax, amax):
    tr = traj.via_points(points, vmax, amax, dt=0.02)
    assert np.all(np.abs(tr.qd) <= vmax * (1 + 1e-9)) and np.all(np.abs(tr.qdd) <= amax * (1 + 1e-9))
    assert np.array_equal(tr.q[0], points[0]) and np.array_equal(tr.q[-1], points[-1])
    # Continuous: no sample moves a joint faster than its limit allows.
    assert np.all(np.abs(np.diff(tr.q, axis=0)) <= vmax * np.diff(tr.t)[:, None] * (1 + 1e-9) + 1e-12)


@FEWER
@given(T0=st.one_of(frames, rigid()), T1=st.one_of(frames, rigid()), t=st.one_of(st.none(), arrays([(2,), (4,)]), st.just([0.0, 0.5, 1.0])),
       law=st.sampled_from(["quintic", "trapezoidal", "cubic", None]), vmax=limits, amax=limits, dt=periods)
def test_cartesian_with_arbitrary_arguments(T0, T1, t, law, vmax, amax, dt):
    ct = check_call(lambda: traj.cartesian(T0, T1, t, law=law, vmax=vmax, amax=amax, dt=dt),
                    "T0", "T1", "t", "law", "vmax", "amax", "dt")
    if ct is None:
        return
    k = len(ct.t)
    assert ct.poses.shape == (k, 4, 4) and ct.velocity.shape == ct.acceleration.shape == (k, 6)
    assert_finite(ct.t, ct.poses, ct.velocity, ct.acceleration)
    assert np.array_equal(ct.poses[0], np.asarray(T0, dtype=float))
    if len(ct) > 1:
        assert np.array_equal(ct.poses[-1], np.asarray(T1, dtype=float))


@FEWER
@given(T0=rigid(), T1=rigid(), v=st.floats(0.05, 2), w=st.floats(0.05, 2))
def test_cartesian_lines_are_straight_and_keep_their_limits(T0, T1, v, w):
    ct = traj.cartesian(T0, T1, law="trapezoidal", vmax=(v, w), amax=(4 * v, 4 * w), dt=0.05)
    assert np.array_equal(ct.poses[0], T0)
    if len(ct) == 1:  # no motion: T1 equals T0 but for rounding
        np.testing.assert_allclose(T1, T0, atol=1e-15)
    else:
        assert np.array_equal(ct.poses[-1], T1)
    assert np.all(np.linalg.norm(ct.velocity[:, :3], axis=1) <= v * (1 + 1e-9))
    assert np.all(np.linalg.norm(ct.velocity[:, 3:], axis=1) <= w * (1 + 1e-9))
    d = T1[:3, 3] - T0[:3, 3]
    np.testing.assert_allclose(np.cross(ct.poses[:, :3, 3] - T0[:3, 3], d), 0, atol=1e-12)
    # The orientation turns about one fixed axis: every step's rotation vector is parallel to it.
    steps = pose.error(ct.poses[1:], ct.poses[:-1])[:, 3:]
    axis, _ = pose.axis_angle(T0[:3, :3].T @ T1[:3, :3])
    np.testing.assert_allclose(np.cross(steps, T0[:3, :3] @ axis), 0, atol=1e-9)


# --- pose ----------------------------------------------------------------------------------------

vectors3 = arrays([(3,), (2, 3), (4,), (0, 3), (3, 3)])
positions = st.one_of(st.none(), arrays([(3,), (2, 3), (5, 3), (2,)]))


@given(rpy=vectors3, position=positions)
def test_from_rpy_and_rpy_with_arbitrary_arguments(rpy, position):
    T = check_call(lambda: pose.from_rpy(rpy, position=position), "rpy", "position")
    if T is not None:
        assert T.shape[-2:] == (4, 4)
        assert_finite(T)
        back = pose.rpy(T)
        np.testing.assert_allclose(pose.from_rpy(back)[..., :3, :3], T[..., :3, :3], atol=1e-9)


@given(T=frames)
def test_readers_with_arbitrary_frames(T):
    for call, width in ((pose.rpy, 3), (pose.quaternion, 4), (pose.log, 6)):
        r = check_call(lambda: call(T), "T")
        if r is not None:
            assert r.shape[-1] == width
            assert_finite(r)
    r = check_call(lambda: pose.axis_angle(T), "T")
    if r is not None:
        assert_finite(*r)


@given(quaternion=arrays([(4,), (2, 4), (3,), (0, 4)]), position=positions)
def test_from_quaternion_with_arbitrary_arguments(quaternion, position):
    T = check_call(lambda: pose.from_quaternion(quaternion, position=position), "quaternion", "position")
    if T is not None:
        assert_finite(T)
        q = pose.quaternion(T)
        ref = np.asarray(quaternion, dtype=float)
        ref = ref / np.max(np.abs(ref), axis=-1, keepdims=True)  # no overflow nor underflow in the norm
        ref = ref / np.linalg.norm(ref, axis=-1, keepdims=True)
        ref = ref * np.where(ref[..., :1] < 0, -1.0, 1.0)
        # Equal up to the sign (w = 0 exactly leaves it open) and rounding.
        assert np.allclose(q, ref, atol=1e-9) or np.allclose(np.abs(q), np.abs(ref), atol=1e-9)


@given(axis=vectors3, angle=st.one_of(wild_floats, arrays([(2,), (3,)])), position=positions)
def test_from_axis_angle_with_arbitrary_arguments(axis, angle, position):
    T = check_call(lambda: pose.from_axis_angle(axis, angle, position=position), "axis", "angle", "position")
    if T is not None:
        assert_finite(T)


@given(xi=arrays([(6,), (2, 6), (5,), (0, 6)]))
def test_exp_with_arbitrary_arguments(xi):
    T = check_call(lambda: pose.exp(xi), "xi")
    if T is not None:
        assert_finite(T)


@given(xi=finite_arrays((6,), -3.0, 3.0))
def test_exp_log_round_trip(xi):
    xi = xi.copy()
    if np.linalg.norm(xi[3:]) >= math.pi - 1e-3:
        xi[3:] *= 3.0 / np.linalg.norm(xi[3:])
    np.testing.assert_allclose(pose.log(pose.exp(xi)), xi, atol=1e-9)


@given(target=st.one_of(frames, rigid(), rigid(batch=3)), current=st.one_of(frames, rigid(), rigid(batch=3)))
def test_error_with_arbitrary_arguments(target, current):
    e = check_call(lambda: pose.error(target, current), "target", "current")
    if e is not None:
        assert e.shape[-1] == 6
        assert_finite(e)
        assert np.all(np.linalg.norm(e[..., 3:], axis=-1) <= math.pi + 1e-12)


# --- manipulability ------------------------------------------------------------------------------

@given(chain=st.sampled_from(CHAINS), q=arrays([(3,), (6,), (7,), (2,), (4, 3), (4, 6), (0, 6)]),
       measure=st.sampled_from(["yoshikawa", "condition", "min_singular", "bad", None]),
       task=st.sampled_from(["pose", "position", "xy", "xyphi", "bad", None]))
def test_manipulability_with_arbitrary_arguments(chain, q, measure, task):
    m = check_call(lambda: chain.manipulability(q, measure=measure, task=task), "q", "measure", "task")
    if m is not None:
        assert_finite(m)
        assert np.all(np.asarray(m) >= 0)
        if measure == "condition":
            assert np.all(np.asarray(m) <= 1)


@FEWER
@given(case=dh_chains(), q=finite_arrays((7,), -3, 3), measure=st.sampled_from(["yoshikawa", "condition", "min_singular"]),
       task=st.sampled_from(["pose", "position", "xy", "xyphi"]))
def test_manipulability_is_numpys_svd(case, q, measure, task):
    chain = case["chain"]
    q = q[: chain.dof]
    s = np.linalg.svd(chain.jacobian(q, task=task), compute_uv=False)
    expected = {"yoshikawa": np.prod(s), "min_singular": s[-1], "condition": s[-1] / s[0] if s[0] > 0 else 0.0}[measure]
    scale = max(1.0, s[0]) ** len(s) if measure == "yoshikawa" else max(1.0, s[0])
    assert abs(chain.manipulability(q, measure, task) - expected) <= 1e-9 * scale


@given(chain=st.sampled_from(CHAINS), q=arrays([(3,), (6,), (7,), (2, 6)]), part=st.sampled_from(["translation", "rotation", "x", None]))
def test_ellipsoid_with_arbitrary_arguments(chain, q, part):
    r = check_call(lambda: chain.ellipsoid(q, part=part), "q", "part")
    if r is not None:
        axes, lengths = r
        assert axes.shape == (3, 3) and lengths.shape == (3,)
        assert_finite(axes, lengths)
        np.testing.assert_allclose(axes.T @ axes, np.eye(3), atol=1e-9)
        assert np.all(np.diff(lengths) <= 0) and np.all(lengths >= 0)


# --- resolved rate and servo ---------------------------------------------------------------------

nullspaces = st.one_of(st.sampled_from([None, "joint_limits", "bad"]), arrays([(3,), (6,), (7,), (2,)]))
tasks = st.sampled_from(["pose", "position", "xy", "xyphi", "bad", None])


@given(chain=st.sampled_from(CHAINS), q=arrays([(3,), (6,), (7,), (2,)]), twist=arrays([(6,), (3,), (2,), (4,)]),
       damping=numbers, nullspace=nullspaces, task=tasks)
def test_resolved_rate_with_arbitrary_arguments(chain, q, twist, damping, nullspace, task):
    qd = check_call(lambda: rk.resolved_rate(chain, q, twist, damping=damping, nullspace=nullspace, task=task),
                    "q", "twist", "damping", "nullspace", "task")
    if qd is not None:
        assert qd.shape == (chain.dof,)
        assert_finite(qd)


@FEWER
@given(case=dh_chains(), q=finite_arrays((7,), -3, 3), twist=finite_arrays((6,), -1, 1))
def test_resolved_rate_realises_a_reachable_twist(case, q, twist):
    chain = case["chain"]
    q = q[: chain.dof]
    J = chain.jacobian(q)
    reachable = J @ np.linalg.pinv(J) @ twist  # the part of the twist J can produce
    qd = rk.resolved_rate(chain, q, reachable, task="pose")
    s = np.linalg.svd(J, compute_uv=False)
    if s[0] > 0 and s[min(J.shape) - 1] / s[0] > 1e-6:  # away from singularities
        np.testing.assert_allclose(J @ qd, reachable, atol=1e-7 * (1 + np.abs(qd).max() * s[0]))


@FEWER
@given(chain=st.sampled_from(CHAINS), poses=st.one_of(arrays([(3, 4, 4), (4, 4), (2, 2), (3, 3), (0, 4, 4)]),
                                                       st.just(np.tile(np.eye(4), (3, 1, 1)))),
       q0=arrays([(3,), (6,), (7,), (2,)]), dt=periods, gain=numbers, damping=numbers, nullspace=nullspaces, task=tasks,
       saturate=st.one_of(st.booleans(), st.sampled_from([None, "yes"])))
def test_servo_with_arbitrary_arguments(chain, poses, q0, dt, gain, damping, nullspace, task, saturate):
    r = check_call(lambda: rk.servo(chain, poses, q0, dt, gain=gain, damping=damping, nullspace=nullspace, task=task,
                                    saturate=saturate), "poses", "q0", "dt", "gain", "damping", "nullspace", "task",
                   "saturate")
    if r is not None:
        k = len(r.t)
        assert r.q.shape == r.qd.shape == (k, chain.dof) and r.error_p.shape == r.error_r.shape == (k,)
        assert_finite(r.t, r.q, r.qd, r.error_p, r.error_r)
        if saturate:
            lo, hi = chain.limits
            assert np.all(r.q[1:] >= lo) and np.all(r.q[1:] <= hi)


# --- the figure ----------------------------------------------------------------------------------

class _Samples:
    def __init__(self, t, q, qd, qdd):
        self.t, self.q, self.qd, self.qdd = t, q, qd, qdd


@settings(max_examples=5)
@given(t=arrays([(5,), (4,), (5, 1)]), q=arrays([(5, 2), (4, 2), (5,)]), names=st.one_of(st.none(), st.just(["a", "b"]), st.just(["a"])))
def test_trajectory_figure_with_arbitrary_arguments(t, q, names):
    fig = check_call(lambda: plots.trajectory_figure(_Samples(t, q, q, q), names=names), "trajectory", "names")
    if fig is not None:
        assert len(fig.axes) == 3


def test_trajectory_figure_draws_each_joint():
    fig = plots.trajectory_figure(traj.quintic([0.0, 1.0], [1.0, 0.0], np.linspace(0, 1, 11)), names=["a", "b"])
    assert len(fig.axes) == 3 and all(len(ax.lines) == 2 for ax in fig.axes)
    np.testing.assert_allclose(fig.axes[0].lines[1].get_ydata()[[0, -1]], [1.0, 0.0])
