"""robokin.traj against independent truth: closed forms of the quintic and of the time-optimal
trapezoid, exact boundary conditions, finite differences of the sampled positions and velocities,
limits never exceeded, and SLERP against its closed forms (one axis: the angle moves linearly in the
law's parameter; any two rotations: the quaternion formula sin((1 - s) W) q0 + sin(s W) q1)."""

import math

import numpy as np
import pytest

import robokin as rk
from robokin import pose, traj

RNG_SEED = 13  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)


def central_difference(t, y):
    """(t_mid, dy/dt) at the inner samples of a uniform grid."""
    h = t[1] - t[0]
    return t[1:-1], (y[2:] - y[:-2]) / (2 * h)


# --- quintic -----------------------------------------------------------------------------------

def test_quintic_closed_form_and_exact_boundaries():
    q0, q1 = np.array([0.1, -1.0, 2.0]), np.array([1.1, 0.5, 2.0])
    t = np.linspace(0.5, 2.5, 201)
    tr = traj.quintic(q0, q1, t)
    s = (t - 0.5) / 2.0
    shape = 10 * s**3 - 15 * s**4 + 6 * s**5
    np.testing.assert_allclose(tr.q, q0 + (q1 - q0) * shape[:, None], rtol=0, atol=1e-14)
    np.testing.assert_allclose(tr.qd, (q1 - q0) * ((30 * s**2 - 60 * s**3 + 30 * s**4) / 2.0)[:, None], atol=1e-13)
    np.testing.assert_allclose(tr.qdd, (q1 - q0) * ((60 * s - 180 * s**2 + 120 * s**3) / 4.0)[:, None], atol=1e-13)
    assert np.array_equal(tr.q[0], q0) and np.array_equal(tr.q[-1], q1)
    assert not tr.qd[[0, -1]].any() and not tr.qdd[[0, -1]].any()
    assert np.array_equal(tr.t, t) and tr.duration == 2.0 and len(tr) == 201


def test_quintic_with_end_velocities_matches_finite_differences():
    q0, q1 = RNG.uniform(-2, 2, 6), RNG.uniform(-2, 2, 6)
    qd0, qd1 = RNG.uniform(-1, 1, 6), RNG.uniform(-1, 1, 6)
    t = np.linspace(0.0, 1.5, 3001)
    tr = traj.quintic(q0, q1, t, qd0=qd0, qd1=qd1)
    assert np.array_equal(tr.q[0], q0) and np.array_equal(tr.q[-1], q1)
    assert np.array_equal(tr.qd[0], qd0) and np.array_equal(tr.qd[-1], qd1)
    assert not tr.qdd[[0, -1]].any()
    # Near the ends too: the polynomial's own boundary values (not only the exact special case).
    near = traj.quintic(q0, q1, [0.0, 1e-9, 1.5 - 1e-9, 1.5], qd0=qd0, qd1=qd1)
    np.testing.assert_allclose(near.qd[1], qd0, atol=1e-7)
    np.testing.assert_allclose(near.qd[2], qd1, atol=1e-7)
    np.testing.assert_allclose(near.qdd[[1, 2]], 0, atol=1e-6)
    _, dq = central_difference(t, tr.q)
    _, dqd = central_difference(t, tr.qd)
    np.testing.assert_allclose(dq, tr.qd[1:-1], atol=1e-5)
    np.testing.assert_allclose(dqd, tr.qdd[1:-1], atol=1e-4)


def test_quintic_rejects_bad_times():
    with pytest.raises(ValueError, match="t: times must be strictly increasing"):
        traj.quintic([0.0], [1.0], [0.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="t: expected a 1-D array of at least 2"):
        traj.quintic([0.0], [1.0], [0.0])
    with pytest.raises(ValueError, match="q1: expected shape"):
        traj.quintic([0.0, 1.0], [1.0], [0.0, 1.0])


# --- trapezoid ---------------------------------------------------------------------------------

def test_trapezoid_duration_is_the_slowest_joints_time_optimal_one():
    # Joint 0: 2 rad at 1 rad/s, 2 rad/s^2 -> 2/1 + 1/2 = 2.5 s (trapezoid). Joint 1: 0.5 m at
    # 10 m/s, 2 m/s^2 -> a triangle, 2 sqrt(0.5 / 2) = 1 s. Joint 2 does not move.
    tr = traj.trapezoidal([0.0, 0.0, 1.0], [2.0, -0.5, 1.0], vmax=[1.0, 10.0, 1.0], amax=[2.0, 2.0, 1.0], dt=1e-3)
    assert tr.duration == pytest.approx(2.5, abs=1e-12)
    assert np.max(np.abs(tr.qd[:, 0])) == pytest.approx(1.0, abs=1e-12)  # the slowest joint cruises at vmax
    assert np.array_equal(tr.q[0], [0, 0, 1]) and np.array_equal(tr.q[-1], [2.0, -0.5, 1.0])
    assert not tr.qd[[0, -1]].any() and not np.ptp(tr.q[:, 2]) and not tr.qd[:, 2].any()
    # Joint 1 is synchronised: it accelerates at its limit to the cruise speed v with
    # 0.5 = v (2.5 - v / 2), the smaller root, and arrives with joint 0.
    v = (2 * 2.5 - math.sqrt((2 * 2.5) ** 2 - 4 * 2 * 0.5)) / 2
    assert np.max(np.abs(tr.qd[:, 1])) == pytest.approx(v, rel=1e-12)
    assert abs(tr.q[-2, 1] + 0.5) > 0  # still moving just before the end


@pytest.mark.parametrize("seed", range(5))
def test_trapezoid_respects_limits_and_matches_finite_differences(seed):
    rng = np.random.default_rng(seed)
    n = 6
    q0, q1 = rng.uniform(-3, 3, n), rng.uniform(-3, 3, n)
    vmax, amax = rng.uniform(0.2, 3, n), rng.uniform(0.5, 10, n)
    dt = 1e-3
    tr = traj.trapezoidal(q0, q1, vmax, amax, dt=dt)
    assert np.all(np.abs(tr.qd) <= vmax * (1 + 1e-12)) and np.all(np.abs(tr.qdd) <= amax * (1 + 1e-12))
    fastest = [2 * math.sqrt(d / a) if d < v * v / a else d / v + v / a for d, v, a in zip(abs(q1 - q0), vmax, amax)]
    assert tr.duration == pytest.approx(max(fastest), rel=1e-12)
    assert np.array_equal(tr.q[0], q0) and np.array_equal(tr.q[-1], q1)
    uniform = tr.t[:-1] if tr.t[-1] - tr.t[-2] < dt * (1 - 1e-9) else tr.t
    k = len(uniform)
    _, dq = central_difference(uniform, tr.q[:k])
    _, dqd = central_difference(uniform, tr.qd[:k])
    # Central differences are exact on each quadratic piece; a sample next to one of the (at most
    # 3) instants where the acceleration jumps is off by less than amax dt (q) and amax (qd).
    for diff, exact, bound in ((dq, tr.qd, amax * dt), (dqd, tr.qdd, 2 * amax)):
        near = np.abs(diff - exact[1 : k - 1]) <= 1e-9
        assert np.all(near | (np.abs(diff - exact[1 : k - 1]) <= bound))
        assert np.all(np.sum(~near, axis=0) <= 6)


def test_trapezoid_rejects_bad_limits():
    with pytest.raises(ValueError, match="vmax"):
        traj.trapezoidal([0.0], [1.0], vmax=0.0, amax=1.0)
    with pytest.raises(ValueError, match="amax"):
        traj.trapezoidal([0.0], [1.0], vmax=1.0, amax=[1.0, 2.0])
    with pytest.raises(ValueError, match="dt"):
        traj.trapezoidal([0.0], [1.0], vmax=1.0, amax=1.0, dt=1e-12)


# --- via points ----------------------------------------------------------------------------------

def test_via_points_limits_ends_and_finite_differences():
    points = np.array([[0.0, 0.0], [1.0, 0.5], [1.2, -0.5], [1.2, -0.5], [0.0, 0.0]])
    vmax, amax, dt = np.array([1.0, 0.8]), np.array([2.0, 3.0]), 1e-3
    tr = traj.via_points(points, vmax, amax, dt=dt)
    assert np.array_equal(tr.q[0], points[0]) and np.array_equal(tr.q[-1], points[-1])
    assert not tr.qd[[0, -1]].any()
    assert np.all(np.abs(tr.qd) <= vmax * (1 + 1e-12)) and np.all(np.abs(tr.qdd) <= amax * (1 + 1e-12))
    assert len(tr.via_times) == 4  # the repeated point merged
    k = len(tr.t) - 1
    _, dq = central_difference(tr.t[:k], tr.q[:k])
    # Exact on each quadratic piece; off by less than amax dt next to a blend's start or end.
    near = np.abs(dq - tr.qd[1 : k - 1]) <= 1e-9
    assert np.all(near | (np.abs(dq - tr.qd[1 : k - 1]) <= amax * dt))
    assert np.all(np.sum(~near, axis=0) <= 2 * 2 * len(tr.via_times))
    # Segment 0 is taken at joint 0's velocity limit: it lasts 1 s between the via times.
    assert tr.via_times[1] - tr.via_times[0] >= 1.0 - 1e-12


def test_via_points_segments_last_the_slowest_joints_time_at_its_limit():
    # Blends short next to the segments (a large amax): each segment lasts max_i |dp_i| / vmax_i, the
    # time of the joint that needs longest at its velocity limit, which it reaches.
    points = np.array([[0.0, 0.0], [1.0, 0.5], [1.5, 2.0]])
    vmax = np.array([1.0, 0.8])
    tr = traj.via_points(points, vmax, amax=[1000.0, 1000.0], dt=1e-3)
    np.testing.assert_allclose(np.diff(tr.via_times), [1.0, 1.5 / 0.8], rtol=1e-12)
    assert np.all(np.abs(tr.qd) <= vmax * (1 + 1e-12))
    assert np.abs(tr.qd[:, 0]).max() == pytest.approx(1.0) and np.abs(tr.qd[:, 1]).max() == pytest.approx(0.8)


def test_via_points_pass_a_point_where_the_velocity_does_not_change():
    # Three collinear points equally spaced: no blend at the middle one, passed exactly at its time.
    tr = traj.via_points([[0.0, 0.0], [1.0, 2.0], [2.0, 4.0]], vmax=[1.0, 2.0], amax=[4.0, 8.0], dt=1e-3)
    k = np.argmin(np.abs(tr.t - tr.via_times[1]))
    np.testing.assert_allclose(tr.q[k], [1.0, 2.0], atol=1e-2)
    np.testing.assert_allclose(tr.q[k] + tr.qd[k] * (tr.via_times[1] - tr.t[k]), [1.0, 2.0], atol=1e-12)
    # One point: at rest, one sample.
    still = traj.via_points([[0.5, 0.5]], vmax=1.0, amax=1.0)
    assert len(still) == 1 and np.array_equal(still.q[0], [0.5, 0.5])


def test_via_points_short_segments_are_lengthened_not_overlapped():
    # A tiny middle segment between two reversals: the blends would overlap at the velocity limit.
    points = np.array([[0.0], [1.0], [1.001], [0.0]])
    tr = traj.via_points(points, vmax=1.0, amax=0.5, dt=1e-3)
    assert np.all(np.abs(tr.qd) <= 1 + 1e-12) and np.all(np.abs(tr.qdd) <= 0.5 * (1 + 1e-12))
    steps = np.abs(np.diff(tr.q[:, 0]))
    assert np.all(steps <= 1.0 * np.diff(tr.t) * (1 + 1e-9) + 1e-15)  # continuous: no jump
    assert tr.q[-1, 0] == 0.0


# --- Cartesian ---------------------------------------------------------------------------------

def test_cartesian_about_one_axis_interpolates_the_angle_linearly():
    T0 = pose.from_rpy([0.0, 0.0, 0.3], position=[0.1, 0.2, 0.3])
    T1 = pose.from_rpy([0.0, 0.0, 1.5], position=[0.5, -0.2, 0.3])
    t = np.linspace(0, 2, 401)
    ct = traj.cartesian(T0, T1, t)
    s = t / 2
    shape = 10 * s**3 - 15 * s**4 + 6 * s**5
    yaw = pose.rpy(ct.poses)[:, 2]
    np.testing.assert_allclose(yaw, 0.3 + 1.2 * shape, atol=1e-13)
    np.testing.assert_allclose(ct.poses[:, :3, 3], T0[:3, 3] + np.outer(shape, T1[:3, 3] - T0[:3, 3]), atol=1e-15)
    shaped = (30 * s**2 - 60 * s**3 + 30 * s**4) / 2
    np.testing.assert_allclose(ct.velocity[:, 5], 1.2 * shaped, atol=1e-13)
    np.testing.assert_allclose(ct.velocity[:, 3:5], 0, atol=1e-15)
    assert np.array_equal(ct.poses[0], T0) and np.array_equal(ct.poses[-1], T1)


def test_cartesian_takes_the_shorter_arc():
    T0, T1 = pose.from_rpy([0, 0, 0.0]), pose.from_rpy([0, 0, 1.5 * math.pi])  # -pi/2 the short way
    ct = traj.cartesian(T0, T1, np.linspace(0, 1, 11))
    np.testing.assert_allclose(pose.rpy(ct.poses[5])[2], -math.pi / 4, atol=1e-14)


def slerp_reference(qa, qb, s):
    """The textbook SLERP of unit quaternions (the shorter arc), written independently."""
    if np.dot(qa, qb) < 0:
        qb = -qb
    omega = math.acos(min(1.0, np.dot(qa, qb)))
    return (math.sin((1 - s) * omega) * qa + math.sin(s * omega) * qb) / math.sin(omega)


def test_cartesian_slerp_against_the_quaternion_formula_and_finite_differences():
    for _ in range(20):
        T0 = pose.from_axis_angle(RNG.normal(size=3), RNG.uniform(-3, 3), position=RNG.normal(size=3))
        T1 = pose.from_axis_angle(RNG.normal(size=3), RNG.uniform(-3, 3), position=RNG.normal(size=3))
        t = np.linspace(0.0, 1.0, 2001)
        ct = traj.cartesian(T0, T1, t)
        qa, qb = pose.quaternion(T0), pose.quaternion(T1)
        for k in (250, 1000, 1700):
            s = 10 * t[k] ** 3 - 15 * t[k] ** 4 + 6 * t[k] ** 5
            ref = slerp_reference(qa, qb, s)
            got = pose.quaternion(ct.poses[k])
            assert min(np.abs(got - ref).max(), np.abs(got + ref).max()) < 1e-12
        # Angular velocity: the rotation vector of R_{k+1} R_{k-1}^T over 2 h; linear: positions.
        # A central difference of x0 + s(t) D errs by at most h^2 / 6 max|x'''| = 10 h^2 |D|
        # (|s'''| <= 60), its velocity's by h^2 / 6 max|x''''| = 60 h^2 |D| (|s''''| <= 360); D is
        # the largest move, a coordinate's or the turn's angle (at most pi); rounding adds ~1e-12.
        h = t[1] - t[0]
        move = max(np.abs(T1[:3, 3] - T0[:3, 3]).max(), math.pi)
        w = pose.error(ct.poses[2:], ct.poses[:-2])[:, 3:] / (2 * h)
        np.testing.assert_allclose(w, ct.velocity[1:-1, 3:], atol=10 * h**2 * move + 1e-9)
        v = (ct.poses[2:, :3, 3] - ct.poses[:-2, :3, 3]) / (2 * h)
        np.testing.assert_allclose(v, ct.velocity[1:-1, :3], atol=10 * h**2 * move + 1e-9)
        a = (ct.velocity[2:] - ct.velocity[:-2]) / (2 * h)
        np.testing.assert_allclose(a, ct.acceleration[1:-1], atol=60 * h**2 * move + 1e-9)
        assert np.array_equal(ct.poses[-1], T1)


def test_cartesian_trapezoid_keeps_linear_and_angular_limits():
    T0 = pose.from_rpy([0.2, -0.3, 0.1], position=[0.0, 0.0, 0.0])
    T1 = pose.from_rpy([1.0, 0.4, -0.5], position=[0.3, 0.4, 0.0])  # 0.5 m
    ct = traj.cartesian(T0, T1, law="trapezoidal", vmax=(0.2, 1.0), amax=(0.5, 2.0), dt=1e-3)
    speed = np.linalg.norm(ct.velocity[:, :3], axis=1)
    spin = np.linalg.norm(ct.velocity[:, 3:], axis=1)
    assert speed.max() == pytest.approx(0.2, rel=1e-12)  # the linear motion is the slower one
    assert spin.max() <= 1.0 + 1e-12
    assert np.linalg.norm(ct.acceleration[:, :3], axis=1).max() <= 0.5 * (1 + 1e-12)
    assert np.linalg.norm(ct.acceleration[:, 3:], axis=1).max() <= 2.0 * (1 + 1e-12)
    assert ct.duration == pytest.approx(0.5 / 0.2 + 0.2 / 0.5, abs=1e-12)
    assert np.array_equal(ct.poses[0], T0) and np.array_equal(ct.poses[-1], T1)
    # The path is the straight segment: every position on the line through p0 and p1.
    d = ct.poses[:, :3, 3] - T0[:3, 3]
    np.testing.assert_allclose(np.cross(d, [0.6, 0.8, 0.0]), 0, atol=1e-15)


def test_cartesian_accepts_objects_with_A_and___array__():
    class SE3Like:
        def __init__(self, m):
            self.A = m

    class ArrayLike:
        def __init__(self, m):
            self.m = m

        def __array__(self, dtype=None, copy=None):
            return self.m

    T0, T1 = pose.from_rpy([0, 0, 0]), pose.from_rpy([0, 0, 1], position=[1, 0, 0])
    ref = traj.cartesian(T0, T1, [0, 1, 2])
    for a, b in ((SE3Like(T0), SE3Like(T1)), (ArrayLike(T0), ArrayLike(T1))):
        np.testing.assert_array_equal(traj.cartesian(a, b, [0, 1, 2]).poses, ref.poses)


def test_cartesian_rejects_bad_input():
    T = np.eye(4)
    with pytest.raises(ValueError, match="law"):
        traj.cartesian(T, T, [0, 1], law="cubic")
    with pytest.raises(ValueError, match="vmax, amax"):
        traj.cartesian(T, T, law="trapezoidal")
    with pytest.raises(ValueError, match="t: the trapezoidal law"):
        traj.cartesian(T, T, [0, 1], law="trapezoidal", vmax=(1, 1), amax=(1, 1))
    with pytest.raises(ValueError, match="vmax, amax: limits are for the trapezoidal law"):
        traj.cartesian(T, T, [0, 1], vmax=(1, 1), amax=(1, 1))
    with pytest.raises(ValueError, match="T1: not a rigid transform"):
        traj.cartesian(T, 2 * T, [0, 1])
