"""rk.resolved_rate and rk.servo against independent truth: numpy's pseudoinverse and damped least
squares, the null-space projector (1 - J^+ J), a Cartesian line followed with a tracking error
recomputed by robokin.pose.error on the reported joints."""

import numpy as np
import pytest

import robokin as rk
from robokin import pose, traj

RNG_SEED = 3  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)
UR5 = rk.robots.ur5()
ARM7 = rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True,
                        limits=(np.full(7, -2.5), np.full(7, 2.5)))


def test_resolved_rate_is_the_pseudoinverse_and_damped_least_squares():
    q = np.array([0.3, -1.0, 1.2, 0.4, 0.5, 0.6])
    J = UR5.jacobian(q)
    twist = RNG.normal(size=6)
    np.testing.assert_allclose(rk.resolved_rate(UR5, q, twist), np.linalg.solve(J, twist), rtol=1e-9, atol=1e-12)
    lam = 0.1
    dls = J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(6), twist)
    np.testing.assert_allclose(rk.resolved_rate(UR5, q, twist, damping=lam), dls, rtol=1e-9, atol=1e-12)
    Jp = UR5.jacobian(q, task="position")
    qd = rk.resolved_rate(UR5, q, twist[:3], task="position")
    np.testing.assert_allclose(qd, np.linalg.pinv(Jp) @ twist[:3], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("nullspace", ["joint_limits", "gains"])
def test_nullspace_term_moves_joints_without_moving_the_tool(nullspace):
    q = RNG.uniform(-2, 2, 7)
    twist = RNG.normal(size=6)
    J = ARM7.jacobian(q)
    Jp = np.linalg.pinv(J)
    # "joint_limits": h = -grad z = W^T W (qbar - q), W = diag(1 / (q_max - q_min)); gains g: g (qbar - q).
    gains = (1 / (2.5 - -2.5)) ** 2 * np.ones(7) if nullspace == "joint_limits" else RNG.uniform(0, 3, 7)
    arg = "joint_limits" if nullspace == "joint_limits" else gains
    h = gains * (0.0 - q)  # qbar = 0 for limits (-2.5, 2.5)
    qd = rk.resolved_rate(ARM7, q, twist, nullspace=arg)
    np.testing.assert_allclose(qd, Jp @ twist + (np.eye(7) - Jp @ J) @ h, rtol=1e-8, atol=1e-10)
    np.testing.assert_allclose(J @ qd, twist, rtol=1e-9, atol=1e-10)


def test_joint_limit_term_descends_the_seeds_cost():
    """nullspace="joint_limits" is h = -grad z for z = rk.joint_limit_cost (here by central
    differences), projected on the null space: with no twist the joints lower z to first order."""
    q = RNG.uniform(-2, 2, 7)
    J = ARM7.jacobian(q)
    eps = 1e-6
    grad = np.array([(rk.joint_limit_cost(ARM7, q + eps * e) - rk.joint_limit_cost(ARM7, q - eps * e)) / (2 * eps)
                     for e in np.eye(7)])
    qd = rk.resolved_rate(ARM7, q, np.zeros(6), nullspace="joint_limits")
    np.testing.assert_allclose(qd, (np.eye(7) - np.linalg.pinv(J) @ J) @ -grad, rtol=1e-6, atol=1e-9)
    assert grad @ qd < 0


def test_nullspace_needs_limits():
    free = rk.Chain.from_dh([(0.3, 0, 0, 0, "R")] * 3)  # no limits
    with pytest.raises(ValueError, match="nullspace: joint 0 has no finite limits"):
        rk.resolved_rate(free, np.zeros(3), np.zeros(2), nullspace=np.ones(3), task="xy")
    with pytest.raises(ValueError, match="nullspace"):
        rk.resolved_rate(UR5, np.zeros(6), np.zeros(6), nullspace="bad")


def test_servo_follows_a_cartesian_line():
    q0 = np.array([0.3, -1.0, 1.2, 0.4, 0.5, 0.6])
    T0 = UR5.fk(q0)
    T1 = pose.from_rpy(pose.rpy(T0) + [0.2, -0.1, 0.3], position=T0[:3, 3] + [0.1, -0.1, 0.05])
    dt = 0.002
    line = traj.cartesian(T0, T1, law="trapezoidal", vmax=(0.2, 0.5), amax=(1.0, 2.0), dt=dt)
    res = rk.servo(UR5, line, q0, dt)
    k = len(line)
    assert res.q.shape == (k, 6) and res.qd.shape == (k, 6) and res.error_p.shape == (k,)
    # The reported errors are the true ones: recomputed from the joints by an independent FK.
    e = pose.error(line.poses, UR5.fk(res.q))
    np.testing.assert_allclose(res.error_p, np.linalg.norm(e[:, :3], axis=1), rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(res.error_r, np.linalg.norm(e[:, 3:], axis=1), rtol=1e-9, atol=1e-15)
    assert res.error_p.max() < 1e-4 and res.error_r.max() < 1e-3
    np.testing.assert_allclose(res.t, np.arange(k) * dt)
    # The joints move as commanded: q_{k+1} = q_k + dt qd_k (no limit reached here).
    np.testing.assert_allclose(res.q[1:], res.q[:-1] + dt * res.qd[:-1], atol=1e-14)


def test_servo_feedback_removes_an_initial_offset():
    q0 = np.array([0.3, -1.0, 1.2, 0.4, 0.5, 0.6])
    T = UR5.fk(q0)
    poses = np.repeat(T[None], 40, axis=0)
    res = rk.servo(UR5, poses, q0 + 0.01, dt=0.01, gain=0.5)
    assert res.error_p[0] > 1e-3
    assert res.error_p[-1] < 1e-9 and res.error_r[-1] < 1e-9
    # Without feedback nothing corrects it.
    still = rk.servo(UR5, poses, q0 + 0.01, dt=0.01, gain=0.0)
    np.testing.assert_allclose(still.error_p, still.error_p[0])


def test_servo_planar_task_on_the_rpr():
    rpr = rk.robots.rpr()
    q0 = np.array([np.pi / 2, 0.75, np.pi / 2])
    start = rpr.fk(q0)[:2, 3]
    points = start + np.linspace(0, 1, 200)[:, None] * np.array([0.2, -0.1])
    res = rk.servo(rpr, points, q0, dt=0.01, task="xy", nullspace="joint_limits")
    tip = rpr.fk(res.q)[:, :2, 3]
    np.testing.assert_allclose(res.error_p, np.linalg.norm(points - tip, axis=1), rtol=1e-9, atol=1e-15)
    assert res.error_p.max() < 1e-4 and not res.error_r.any()


def test_bad_arguments_name_themselves():
    with pytest.raises(ValueError, match="twist"):
        rk.resolved_rate(UR5, np.zeros(6), np.zeros(3))
    with pytest.raises(ValueError, match="damping"):
        rk.resolved_rate(UR5, np.zeros(6), np.zeros(6), damping=-1.0)
    with pytest.raises(ValueError, match="dt"):
        rk.servo(UR5, np.eye(4)[None], np.zeros(6), dt=0.0)
    with pytest.raises(ValueError, match="poses"):
        rk.servo(UR5, np.eye(4), np.zeros(6), dt=0.01)
    with pytest.raises(ValueError, match="gain"):
        rk.servo(UR5, np.eye(4)[None], np.zeros(6), dt=0.01, gain=-1.0)
