"""The Reach loop (the RPR study, Algorithm 1), path tracking, null-space joint-limit avoidance and the
RPR's self-motion set, against the seed's algorithm written literally in numpy."""

import inspect
import math
import pickle
import warnings

import numpy as np
import pytest

import robokin as rk

L1, L3 = 1.5, 1.0
Q_MIN = np.array([0.0, 0.0, 0.0])
Q_MAX = np.array([math.pi / 2, 1.5, math.pi])


def forward_kinematic(t):
    """Seed 000, eq. (1)."""
    return np.array([(L1 + t[1]) * np.cos(t[0]) + L3 * np.cos(t[0] + t[2]), (L1 + t[1]) * np.sin(t[0]) + L3 * np.sin(t[0] + t[2])])


def jacobian(t):
    """Seed 000, eq. (9)."""
    s1, c1, s13, c13 = np.sin(t[0]), np.cos(t[0]), np.sin(t[0] + t[2]), np.cos(t[0] + t[2])
    return np.array([[-(L1 + t[1]) * s1 - L3 * s13, c1, -L3 * s13], [(L1 + t[1]) * c1 + L3 * c13, s1, L3 * c13]])


def seed_reach(p_target, theta, weights=None):
    """The Reach algorithm, line by line; with `weights`, the homogeneous term of eqs. (5)-(7),
    dq_H = (1 - J^+ J) W (qbar - q), added to the first iteration's step (robokin.reach's rule:
    the following iterations are the minimum-norm corrections that remove its second-order
    residual)."""
    n, delta = 25, 1e-5
    d, dt = 0.75, 0.025
    p = forward_kinematic(theta)
    iterations = 0
    while True:
        dp = d * (p_target - p) / dt
        J = jacobian(theta)
        Jp = J.T @ np.linalg.inv(J @ J.T)
        dq_m = Jp @ dp
        if weights is not None and iterations == 0:
            dq_m = dq_m + (np.eye(3) - Jp @ J) @ (weights * ((Q_MAX + Q_MIN) / 2 - theta))
        theta = np.clip(theta + dt * dq_m, Q_MIN, Q_MAX)
        p = forward_kinematic(theta)
        n -= 1
        iterations += 1
        if n == 0 or np.linalg.norm(p_target - p) < delta:
            return theta, iterations


def joint_limit_cost(Q):
    """Seed 000, eq. (6)-(7): z = 1/2 |W (qbar - q)|^2."""
    qbar, w = (Q_MAX + Q_MIN) / 2, 1 / (Q_MAX - Q_MIN)
    return 0.5 * np.sum((w * (qbar - Q)) ** 2, axis=-1)


# Figure 2: from point 1 on the workspace boundary (t1 = pi/2) to point 2.
Q1 = np.array([math.pi / 2, 0.75, math.pi / 2])
P1, P2 = forward_kinematic(Q1), np.array([1.5, 1.0])


def test_reach_equals_the_literal_seed_algorithm(rng):
    chain = rk.robots.rpr()
    for _ in range(200):
        q = rng.uniform(Q_MIN, Q_MAX)
        target = forward_kinematic(q) + rng.normal(scale=0.01, size=2)
        expected, iterations = seed_reach(target, q)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", rk.PrecisionWarning)
            r = rk.reach(chain, target, q)
        np.testing.assert_allclose(r.q, expected, atol=1e-9)
        assert r.iterations == iterations
        assert r.converged == (np.linalg.norm(target - forward_kinematic(r.q)) < 1e-5)
        assert r.error == pytest.approx(np.linalg.norm(target - forward_kinematic(r.q)), abs=1e-12)


@pytest.mark.parametrize("gain", [1.0, 5.0])
def test_reach_with_the_nullspace_term_equals_the_literal_seed_algorithm(rng, gain):
    chain = rk.robots.rpr()
    # h = g (qbar - q); the "joint_limits" preset is g = W^T W, W = diag(1 / (q_max - q_min)), which
    # makes h minus the gradient of the study's cost z.
    weights = gain / (Q_MAX - Q_MIN) ** 2
    changed = 0
    for _ in range(200):
        q = rng.uniform(Q_MIN, Q_MAX)
        target = forward_kinematic(q) + rng.normal(scale=0.01, size=2)
        expected, iterations = seed_reach(target, q, weights)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", rk.PrecisionWarning)
            r = rk.reach(chain, target, q, nullspace="joint_limits" if gain == 1.0 else weights)
        np.testing.assert_allclose(r.q, expected, atol=1e-9)
        assert r.iterations == iterations
        changed += not np.allclose(expected, seed_reach(target, q)[0], atol=1e-6)
    assert changed > 150  # the term does move the joints


def test_track_a_2000_point_line_within_tolerance_and_limits():
    chain = rk.robots.rpr()
    points = P1 + np.linspace(0, 1, 2000)[:, None] * (P2 - P1)
    for nullspace in (None, "joint_limits"):
        tr = rk.track(chain, points, Q1, nullspace=nullspace)
        assert tr.q.shape == (2000, 3) and tr.converged.all()
        reached = np.array([forward_kinematic(q) for q in tr.q])
        assert np.max(np.linalg.norm(reached - points, axis=1)) < 1e-5
        assert np.all(tr.q >= Q_MIN) and np.all(tr.q <= Q_MAX)


def test_nullspace_lowers_the_joint_limit_cost_at_the_same_accuracy():
    chain = rk.robots.rpr()
    points = P1 + np.linspace(0, 1, 2000)[:, None] * (P2 - P1)
    plain = rk.track(chain, points, Q1)
    avoid = rk.track(chain, points, Q1, nullspace="joint_limits")
    assert avoid.converged.all() and plain.converged.all()
    assert joint_limit_cost(avoid.q).mean() < 0.95 * joint_limit_cost(plain.q).mean()
    assert avoid.error.max() < 1e-5
    # "joint_limits" is the gains W^T W (h = -grad z); zero gains are the plain minimum-norm path.
    W = 1 / (Q_MAX - Q_MIN)
    np.testing.assert_array_equal(rk.track(chain, points, Q1, nullspace=W**2).q, avoid.q)
    np.testing.assert_array_equal(rk.track(chain, points, Q1, nullspace=np.zeros(3)).q, plain.q)


def best_costs(points):
    """The least z of each point's self-motion set (the best posture the null space can reach),
    from a fine sampling of the set in closed form."""
    best = []
    for p in points:
        S = rk.robots.rpr_self_motion(p, num=20001).reshape(-1, 3)
        best.append(joint_limit_cost(S[~np.isnan(S[:, 0])]).min())
    return np.array(best)


def test_larger_nullspace_gains_lower_the_seeds_cost_toward_the_best_postures():
    """k x the joint-limit gains: every point still reached within tol, and the mean z falls with
    k toward the mean of each point's least z. The seed's literal h = W (qbar - q) (gains W, the
    gradient of another cost) levels off above it however strong."""
    chain = rk.robots.rpr()
    points = P1 + np.linspace(0, 1, 2000)[:, None] * (P2 - P1)
    floor = best_costs(points).mean()
    W = 1 / (Q_MAX - Q_MIN)
    means = []
    for k in (1, 2, 4, 8):
        tr = rk.track(chain, points, Q1, nullspace=k * W**2)
        assert tr.converged.all() and tr.error.max() < 1e-5
        reached = np.array([forward_kinematic(q) for q in tr.q])
        assert np.max(np.linalg.norm(reached - points, axis=1)) < 1e-5
        means.append(joint_limit_cost(tr.q).mean())
    assert all(b < a for a, b in zip(means, means[1:])), means
    gaps = np.array(means) - floor
    assert 0 < gaps[0] < 2e-3 * floor and abs(gaps[-1]) < 0.05 * gaps[0], (means, floor)
    literal = [joint_limit_cost(rk.track(chain, points, Q1, nullspace=k * W).q).mean() for k in (1, 8)]
    assert min(literal) > floor + 0.03 * floor and abs(literal[1] - literal[0]) < 1e-3 * floor, (literal, floor)


def test_joint_limit_cost_is_the_seeds_z(rng):
    chain = rk.robots.rpr()
    Q = rng.uniform(Q_MIN, Q_MAX, size=(50, 3))
    np.testing.assert_allclose(rk.joint_limit_cost(chain, Q), joint_limit_cost(Q), rtol=1e-14)
    assert rk.joint_limit_cost(chain, Q[0]) == pytest.approx(joint_limit_cost(Q[0]), rel=1e-14)
    # Unlimited and fixed-range joints do not count (no NaN from a zero range).
    c = rk.Chain.from_dh([(1, 0, 0, 0, "R")] * 3, limits=([0, -np.inf, 0.5], [2, np.inf, 0.5]))
    assert rk.joint_limit_cost(c, [2.0, 7.0, 0.5]) == pytest.approx(0.5 * (0.5 * 1.0) ** 2)
    with pytest.raises(ValueError, match=r"q: expected shape \(3,\) or \(N, 3\)"):
        rk.joint_limit_cost(chain, [0.0, 0.0])


def test_track_equals_reach_point_by_point(rng):
    chain = rk.robots.planar_3r(0.5, 0.4, 0.3)
    q = np.array([0.3, 0.6, -0.4])
    points = rk.paths.circle(50, radius=0.05, center=chain.fk(q)[:2, 3] - (0.05, 0))
    tr = rk.track(chain, points, q, task="xy")
    for k, p in enumerate(points):
        r = rk.reach(chain, p, q, task="xy")
        np.testing.assert_array_equal(r.q, tr.q[k])
        assert (r.iterations, r.converged, r.error) == (tr.iterations[k], tr.converged[k], tr.error[k])
        q = r.q


@pytest.mark.parametrize("task", ["pose", "position", "xyphi"])
def test_reach_other_tasks(task, rng):
    chain = rk.robots.ur5() if task != "xyphi" else rk.robots.planar_3r(0.5, 0.4, 0.3)
    q = rng.uniform(-1, 1, chain.dof)
    goal_q = q + rng.normal(scale=0.02, size=chain.dof)
    T = chain.fk(goal_q)
    target = {"pose": T, "position": T[:3, 3], "xyphi": [T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])]}[task]
    r = rk.reach(chain, target, q, task=task, max_iter=100, tol=1e-10)
    assert r.converged
    reached = chain.fk(r.q)
    np.testing.assert_allclose(reached[:3, 3] if task != "xyphi" else reached[:2, 3], np.asarray(target if task != "pose" else T[:3, 3])[: 3 if task != "xyphi" else 2], atol=1e-9)
    if task in ("pose", "xyphi"):
        np.testing.assert_allclose(reached[:2, :2] if task == "xyphi" else reached[:3, :3], T[:2, :2] if task == "xyphi" else T[:3, :3], atol=1e-9)


def test_planar_angle_error_is_wrapped():
    chain = rk.robots.planar_3r(0.5, 0.4, 0.3)
    q = np.array([0.3, 0.8, math.pi - 1.1 - 0.01])  # tool angle pi - 0.01, elbow bent
    T = chain.fk(q + [0, 0, 0.02])  # the tool angle crosses +pi
    r = rk.reach(chain, [T[0, 3], T[1, 3], -math.pi + 0.01], q, task="xyphi", max_iter=50, tol=1e-10)
    assert r.converged
    np.testing.assert_allclose(r.q, q + [0, 0, 0.02], atol=1e-9)


def test_precision_not_reached_warns():
    chain = rk.robots.rpr()
    with pytest.warns(rk.PrecisionWarning, match="precision not reached"):
        r = rk.reach(chain, [0.5, 0.5], Q1, max_iter=2)
    assert not r.converged and r.iterations == 2 and r.error > 1e-5
    # Out of reach: saturation holds the joints at their limits and the loop says so.
    with pytest.warns(rk.PrecisionWarning):
        r = rk.reach(chain, [10.0, 10.0], Q1)
    assert not r.converged and np.all(r.q <= Q_MAX) and np.all(r.q >= Q_MIN)
    with pytest.warns(rk.PrecisionWarning, match="on 1 of 2 path points"):
        rk.track(chain, [P1, [10.0, 10.0]], Q1)


def test_damping_near_a_singularity():
    chain = rk.robots.planar_3r(1.0, 1.0, 1.0)
    q = np.array([0.0, 1e-9, 0.0])  # stretched: J J^T is singular in xy
    target = [2.9, 0.05]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        plain = rk.reach(chain, target, q, max_iter=200, task="xy")
    damped = rk.reach(chain, target, q, max_iter=200, damping=0.05, task="xy")
    assert damped.converged and np.all(np.isfinite(plain.q))


def test_saturate_false_lets_joints_leave_their_limits():
    chain = rk.robots.rpr()
    target = forward_kinematic(Q1) + [0.0, 0.05]  # pushes t1 past pi/2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        free = rk.reach(chain, target, Q1, saturate=False)
    assert free.converged


def test_rpr_self_motion_closed_form(rng):
    for _ in range(20):
        p = forward_kinematic(rng.uniform(Q_MIN, Q_MAX))
        S = rk.robots.rpr_self_motion(p, num=361)
        assert S.shape == (2, 361, 3)
        valid = S[np.isfinite(S[..., 0])]
        assert len(valid) > 0
        for q in valid:
            np.testing.assert_allclose(forward_kinematic(q), p, atol=1e-12)
        assert np.all(valid >= Q_MIN - 1e-12) and np.all(valid <= Q_MAX + 1e-12)
    # Point 1 of Figure 2 lies on the workspace boundary: only t1 = pi/2 reaches it.
    S = rk.robots.rpr_self_motion(P1, t1=np.linspace(0, math.pi / 2, 1001))
    t1_ok = S[..., 0][np.isfinite(S[..., 0])]
    assert t1_ok.min() > math.pi / 2 - 0.05
    np.testing.assert_allclose(S[1, -1], Q1, atol=1e-12)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(task="joint"), "task: expected one of"),
        (dict(tol=-1), "tol: must be a positive finite number"),
        (dict(gain=np.nan), "gain: must be a positive finite number"),
        (dict(dt=0), "dt: must be a positive finite number"),
        (dict(max_iter=0), r"max_iter: must be in \[1, 100000\], got 0"),
        (dict(max_iter=100_001), r"max_iter: must be in \[1, 100000\]"),  # one Reach holds the GIL
        (dict(damping=-0.1), "damping: must be a finite number >= 0"),
        (dict(nullspace="limits"), "nullspace: expected None, 'joint_limits' or an array of gains"),
        (dict(nullspace=[1.0, 2.0]), r"nullspace: expected shape \(3,\)"),
        (dict(nullspace=[1.0, np.nan, 2.0]), "nullspace: contains NaN or inf"),
    ],
)
def test_reach_rejects_bad_options(kwargs, match):
    with pytest.raises(ValueError, match=match):
        rk.reach(rk.robots.rpr(), P1, Q1, **kwargs)


def test_reach_rejects_bad_targets_and_joints():
    chain = rk.robots.rpr()
    with pytest.raises(ValueError, match=r"target: expected shape \(2,\)"):
        rk.reach(chain, [1.0, 2.0, 3.0, 4.0], Q1)
    with pytest.raises(ValueError, match="target: expected a \\(4, 4\\) homogeneous matrix"):
        rk.reach(chain, [1.0, 2.0, 3.0, 4.0], Q1, task="pose")
    with pytest.raises(ValueError, match="q: contains NaN or inf"):
        rk.reach(chain, P1, [np.nan, 0, 0])
    with pytest.raises(ValueError, match=r"points: expected shape \(K, 2\)"):
        rk.track(chain, np.zeros((4, 5)), Q1)
    with pytest.raises(ValueError, match="points: contains NaN or inf"):
        rk.track(chain, [[0, np.inf]], Q1)
    with pytest.raises(ValueError, match="nullspace: joint 0 has no finite limits"):
        rk.reach(rk.robots.planar_3r(), [1, 1], [0, 0.5, 0.5], task="xy", nullspace=[1, 0, 0])
    with pytest.raises(TypeError, match="task: expected None or a string"):
        rk.reach(chain, P1, Q1, task=3)
    empty = rk.track(chain, np.zeros((0, 2)), Q1)
    assert empty.q.shape == (0, 3)


def test_reach_options_defaults_are_the_seeds():
    """Seed 000, Algorithm 1: n = 25 iterations, delta = 1e-5 m, d = 0.75, dt = 0.025 s; saturated."""
    o = rk.ReachOptions()
    assert (o.max_iter, o.tol, o.gain, o.dt, o.saturate, o.damping) == (25, 1e-5, 0.75, 0.025, True, 0.0)
    assert rk.ReachOptions.fields == ("max_iter", "tol", "gain", "dt", "saturate", "damping")
    assert repr(o) == "ReachOptions(max_iter=25, tol=1e-05, gain=0.75, dt=0.025, saturate=True, damping=0.0)"
    assert pickle.loads(pickle.dumps(rk.ReachOptions(tol=2e-3))) == rk.ReachOptions(tol=2e-3)
    assert rk.ReachOptions(tol=2e-3) != o


@pytest.mark.parametrize("call", [rk.reach, rk.track])
def test_reach_signature_is_the_options_struct(call):
    """help() shows every option keyword-only with the core struct's default (written once, in C++)."""
    params = inspect.signature(call).parameters
    for name in rk.ReachOptions.fields:
        assert params[name].kind is inspect.Parameter.KEYWORD_ONLY
        assert params[name].default == getattr(rk.ReachOptions(), name)
    assert params["nullspace"].kind is inspect.Parameter.KEYWORD_ONLY


def test_reach_options_are_keyword_only_and_named():
    chain = rk.robots.rpr()
    with pytest.raises(TypeError, match="positional arguments"):
        rk.reach(chain, P1, Q1, "xy", 25)
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'iterations' \(options: max_iter, tol"):
        rk.reach(chain, P1, Q1, iterations=3)
    with pytest.raises(TypeError, match="tol: expected float, got str"):
        rk.track(chain, [P1], Q1, tol="small")
    with pytest.raises(TypeError, match="max_iter: expected int, got float"):
        rk.reach(chain, P1, Q1, max_iter=2.5)
    with pytest.raises(ValueError, match="max_iter: out of range"):
        rk.reach(chain, P1, Q1, max_iter=2**64)


def test_track_result_arrays_are_read_only_views():
    chain = rk.robots.rpr()
    tr = rk.track(chain, rk.paths.line(P1, [-0.9, 2.2], 0.01), Q1)
    assert not tr.q.flags.writeable and not tr.error.flags.writeable
    with pytest.raises(ValueError):
        tr.q[0, 0] = 1.0
    q = tr.q
    del tr  # the view keeps the result alive
    assert np.all(np.isfinite(q))
    assert "TrackResult(q=<array (" in repr(rk.track(chain, rk.paths.line(P1, [-0.9, 2.2], 0.001), Q1))
