"""Numerical IK, checked against independent truth: forward kinematics of the returned q (success
must mean the pose is reached), the joint limits, and finite differences of the Jacobian."""

import math
import re
import threading
import time

import numpy as np
import pytest

import robokin as rk
from robokin import _testing

METHODS = ["lm", "gn", "nr", "halley"]


def rotation_angle(R):
    """Angle of a rotation matrix, accurate near 0 (acos of the trace is not)."""
    s = np.linalg.norm([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2.0
    return math.atan2(s, (np.trace(R) - 1.0) / 2.0)


def verified(chain, q, T, tol_p=1e-9, tol_r=1e-9):
    F = chain._fk_kdl(q)  # KDL's recursive FK: independent of the solver's fast path
    return np.linalg.norm(F[:3, 3] - T[:3, 3]) < tol_p and rotation_angle(F[:3, :3].T @ T[:3, :3]) < tol_r


def bent_ur5():
    """The UR5 with axes 2 and 3 a microradian from parallel: the same reach, but no closed form, so
    IK's restarts are the stored and random starts (the UR5's own start from its closed form's
    solutions, which solve at once and hide the random ones and the tolerances' edges)."""
    p = math.pi / 2
    rows = [(0, p, 0.089159, 0, "R"), (-0.425, 1e-6, 0, 0, "R"), (-0.39225, 0, 0, 0, "R"),
            (0, p, 0.10915, 0, "R"), (0, -p, 0.09465, 0, "R"), (0, 0, 0.0823, 0, "R")]
    chain = rk.Chain.from_dh(rows, limits=rk.robots.ur5().limits)
    assert not rk.closed.family(chain).solvable
    return chain


def random_targets(chain, count, seed):
    lo, hi = chain.limits
    q = np.random.default_rng(seed).uniform(lo, hi, (count, chain.dof))
    return q, chain.fk(q)


@pytest.mark.parametrize("robot", ["ur5", "puma560"])
@pytest.mark.parametrize("method", METHODS)
def test_reported_success_equals_verified_success(robot, method):
    chain = getattr(rk.robots, robot)()
    lo, hi = chain.limits
    _, targets = random_targets(chain, 150, seed=7)
    q0 = np.clip(np.zeros(6), lo, hi)
    for restarts in (0, 30):
        res = rk.ik_batch(chain, targets, q0, method=method, restarts=restarts, seed=3)
        for k in range(len(targets)):
            assert res.success[k] == verified(chain, res.q[k], targets[k])
            assert np.all(res.q[k] >= lo) and np.all(res.q[k] <= hi)
        if restarts:
            assert res.success.mean() >= 0.98, (robot, method, res)
    # the default method solves every target with restarts
    if method == "lm":
        assert res.success.all()


def verified_errors(chain, q, T):
    """(position error, rotation angle) of q for the target T, by KDL's FK."""
    F = chain._fk_kdl(q)
    return np.linalg.norm(F[:3, 3] - T[:3, 3]), rotation_angle(F[:3, :3].T @ T[:3, :3])


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("tol_p, tol_r", [(1e-2, 1e-12), (1e-12, 1e-2), (1e-3, 1e-7), (1e-7, 1e-3)])
def test_success_meets_each_tolerance_on_its_own(method, tol_p, tol_r):
    """Position and rotation tolerances far apart: success means both verified errors are within
    their own tolerance (a test with tol_p == tol_r cannot tell which error is compared with which
    tolerance, nor whether the rotation is compared at all)."""
    chain = bent_ur5()
    _, targets = random_targets(chain, 40, seed=17)
    res = rk.ik_batch(chain, targets, np.zeros(6), method=method, tol_p=tol_p, tol_r=tol_r, restarts=2, seed=5,
                      max_iter=60)
    for k in range(len(targets)):
        ep, er = verified_errors(chain, res.q[k], targets[k])
        assert res.error_p[k] == pytest.approx(ep, rel=1e-6, abs=1e-13)
        assert res.error_r[k] == pytest.approx(er, rel=1e-6, abs=1e-13)
        if res.success[k]:
            assert ep < tol_p * (1 + 1e-6) and er < tol_r * (1 + 1e-6), (k, ep, er)
        else:
            assert ep > tol_p * (1 - 1e-6) or er > tol_r * (1 - 1e-6), (k, ep, er)
    # Not a test of nothing: some answers succeed, and on the arm without a closed form some end
    # within one tolerance only (in 15 of the 16 cases; the UR5's closed-form restarts left none).
    assert res.success.any()


def test_single_solve_matches_batch_and_repr():
    chain = rk.robots.ur5()
    q, T = random_targets(chain, 1, seed=11)
    r = rk.ik(chain, T[0], np.zeros(6), restarts=10, seed=5)
    assert r.success and bool(r)
    assert verified(chain, r.q, T[0])
    assert "IKResult(success=True" in repr(r) and "error_p" in repr(r)
    b = rk.ik_batch(chain, T, np.zeros(6), restarts=10, seed=5)
    assert np.allclose(b.q[0], r.q) and b.success[0]
    assert repr(b).startswith("IKBatchResult(q=array([[") and "success=array([ True])" in repr(b)


def test_same_seed_same_answer():
    chain = rk.robots.puma560()
    _, T = random_targets(chain, 20, seed=12)
    a = rk.ik_batch(chain, T, np.zeros(6), method="nr", restarts=5, seed=42)
    b = rk.ik_batch(chain, T, np.zeros(6), method="nr", restarts=5, seed=42)
    assert np.array_equal(a.q, b.q) and np.array_equal(a.attempts, b.attempts)


def test_unreachable_target_is_never_a_success():
    chain = rk.robots.ur5()
    T = np.eye(4)
    T[:3, 3] = (2.0, 0.0, 0.5)  # the UR5 reaches about 0.95 m
    for method in METHODS:
        r = rk.ik(chain, T, np.zeros(6), method=method, restarts=3, seed=1, max_iter=50)
        assert not r.success and r.error_p > 0.5
        assert np.all(np.isfinite(r.q))


@pytest.mark.parametrize(
    "goal, start",
    [
        ([0.01, -1.921, 0.617], [0.166, 0.565, 2.086]),
        ([0.22, 0.661, 1.551], [-0.095, 0.218, -1.519]),
        ([0.052, 1.698, 1.132], [-0.081, -0.258, -0.662]),
    ],
)
def test_joint_limits_do_not_stick(goal, start):
    # A planar 3R with a tight first joint: from these starts KDL's NR_JL (which clamps each
    # iteration's step) stalls on a limit; the active set lets the other joints finish the step.
    lim = (np.array([-0.3, -2.5, -2.5]), np.array([0.3, 2.5, 2.5]))
    chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 3, limits=lim)
    target = chain.fk(np.array(goal))
    for method in METHODS:
        r = rk.ik(chain, target, np.array(start), method=method, task="pose", max_iter=200, restarts=0)  # one attempt
        assert r.success, (method, r)
        assert verified(chain, r.q, target)
        assert np.all(r.q >= lim[0]) and np.all(r.q <= lim[1])


def test_solution_at_a_limit_is_reached():
    lim = (np.array([-1.0, 0.0, -1.0]), np.array([1.0, 2.0, 1.0]))
    chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 3, limits=lim)
    q_goal = np.array([1.0, 0.0, 0.5])  # two joints exactly on a limit
    target = chain.fk(q_goal)
    r = rk.ik(chain, target, np.array([-0.5, 1.5, -0.5]), task="pose", restarts=10, seed=0)
    assert r.success and verified(chain, r.q, target)


def test_tasks_position_xy_xyphi():
    chain = rk.robots.planar_3r(1.0, 0.8, 0.5)
    q = np.array([0.3, 0.7, -0.4])
    T = chain.fk(q)
    phi = math.atan2(T[1, 0], T[0, 0])
    for method in METHODS:
        r = rk.ik(chain, (T[0, 3], T[1, 3], phi), np.zeros(3), method=method, task="xyphi", restarts=5, seed=0)
        F = chain.fk(r.q)
        assert r.success and np.hypot(*(F[:2, 3] - T[:2, 3])) < 1e-9
        assert abs(math.remainder(math.atan2(F[1, 0], F[0, 0]) - phi, 2 * math.pi)) < 1e-9
        r = rk.ik(chain, T[:2, 3], np.zeros(3), method=method, task="xy", restarts=5, seed=0)
        assert r.success and np.hypot(*(chain.fk(r.q)[:2, 3] - T[:2, 3])) < 1e-9 and r.error_r == 0
    ur5 = rk.robots.ur5()
    p = ur5.fk(np.array([0.1, -1.0, 1.2, 0.3, 0.4, 0.5]))[:3, 3]
    r = rk.ik(ur5, p, np.zeros(6), task="position", restarts=5, seed=0)
    assert r.success and np.linalg.norm(ur5.fk(r.q)[:3, 3] - p) < 1e-9


def test_path_warm_start_has_no_branch_jumps():
    chain = rk.robots.puma560()
    q_start = np.array([0.2, 0.6, -0.5, 0.3, 0.8, 0.1])
    T0 = chain.fk(q_start)
    steps = 100
    targets = np.repeat(T0[None], steps, axis=0)
    targets[:, 2, 3] += np.linspace(0.0, 0.05, steps)  # a vertical line of 5 cm
    assert len(rk.closed.puma560(targets[-1])) > 0  # reachable
    res = rk.ik_batch(chain, targets, q_start, path=True)
    assert res.success.all()
    jumps = np.abs(np.diff(np.vstack([q_start, res.q]), axis=0)).max()
    assert jumps < 0.05
    for k in range(0, steps, 10):
        assert verified(chain, res.q[k], targets[k])
    # Each target is solved from the answer to the one before (one attempt, no restart).
    for k in range(1, steps, 9):
        assert np.array_equal(rk.ik(chain, targets[k], res.q[k - 1], restarts=0).q, res.q[k])
    # From the other postures of the first target the path stays in that posture too.
    for start in rk.closed.puma560(targets[0]).only_within_limits().q:
        res = rk.ik_batch(chain, targets[:30], start, path=True)
        assert res.success.all() and np.abs(np.diff(np.vstack([start, res.q]), axis=0)).max() < 0.05


def test_hessian_term_matches_finite_differences():
    rng = np.random.default_rng(0)
    chains = [rk.robots.ur5(), rk.robots.puma560(), rk.robots.rpr(), rk.robots.prr()]
    for chain in chains:
        for _ in range(5):
            q = rng.uniform(-1, 1, chain.dof)
            a = rng.normal(size=chain.dof)
            h = 1e-6
            fd = (chain.jacobian(q + h * a) - chain.jacobian(q - h * a)) / (2 * h)
            assert np.allclose(_testing.hessian_times(chain, q, a), fd, atol=1e-7)


def rotation_vector(R):
    """angle * axis of R (angle < pi), from its skew part and trace."""
    v = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    s = np.linalg.norm(v)
    return v * (math.atan2(s, (np.trace(R) - 1) / 2) / s) if s > 0 else v


def wrapped_difference(a, b):
    return np.remainder(np.asarray(a) - np.asarray(b) + math.pi, 2 * math.pi) - math.pi


@pytest.mark.parametrize("method", ["nr", "halley"])
def test_one_step_is_the_methods_formula(method, rng):
    """One iteration from a start near the target (it lowers the error, so it is the answer), against
    the method written here: pose error e = (p* - p, rotation vector of R* R^T), the damped Newton
    step a = J^T (J J^T + l^2 I)^-1 e (l = 1e-6 for NR), and Halley's correction solving
    (J + 1/2 sum_j a_j dJ/dq_j) dq = e with the Hessian term by central differences of KDL's Jacobian."""
    chain = rk.robots.ur5()
    for _ in range(10):
        q_goal = rng.uniform(-2.5, 2.5, 6)
        q0 = q_goal + rng.normal(scale=0.05, size=6)
        T, F = chain._fk_kdl(q_goal), chain._fk_kdl(q0)
        e = np.concatenate([T[:3, 3] - F[:3, 3], rotation_vector(T[:3, :3] @ F[:3, :3].T)])
        J = chain._jacobian_kdl(q0)
        if method == "nr":
            dq = J.T @ np.linalg.solve(J @ J.T + 1e-12 * np.eye(6), e)
        else:
            a = np.linalg.solve(J, e)
            h = 1e-6
            HA = (chain._jacobian_kdl(q0 + h * a) - chain._jacobian_kdl(q0 - h * a)) / (2 * h)
            dq = np.linalg.solve(J + 0.5 * HA, e)
            assert np.linalg.norm(dq) <= 2 * np.linalg.norm(a)  # Halley's own step, not the Newton fallback
        r = rk.ik(chain, T, q0, method=method, max_iter=1, restarts=0)
        assert r.iterations == 1 and r.error_p < np.linalg.norm(e[:3])
        np.testing.assert_allclose(wrapped_difference(r.q, q0 + dq), 0, atol=1e-7)


def test_timeout_bounds_the_restarts():
    chain = rk.robots.ur5()
    T = np.eye(4)
    T[:3, 3] = (2.0, 0.0, 0.5)
    r = rk.ik(chain, T, np.zeros(6), restarts=1_000_000, timeout=0.02, seed=0)
    assert not r.success and r.attempts < 1_000_000


def test_bad_input_names_the_argument():
    chain = rk.robots.ur5()
    T = chain.fk(np.zeros(6))
    with pytest.raises(ValueError, match="method"):
        rk.ik(chain, T, np.zeros(6), method="bfgs")
    with pytest.raises(ValueError, match="task"):
        rk.ik(chain, T, np.zeros(6), task="orientation")
    with pytest.raises(ValueError, match="q0"):
        rk.ik(chain, T, np.zeros(5))
    with pytest.raises(ValueError, match="q0"):
        rk.ik(chain, T, [np.nan] * 6)
    with pytest.raises(ValueError, match="target"):
        rk.ik(chain, np.ones((4, 4)), np.zeros(6))
    with pytest.raises(ValueError, match="tol_p"):
        rk.ik(chain, T, np.zeros(6), tol_p=-1.0)
    with pytest.raises(ValueError, match="restarts"):
        rk.ik(chain, T, np.zeros(6), restarts=-1)
    with pytest.raises(ValueError, match="max_iter"):
        rk.ik(chain, T, np.zeros(6), max_iter=0)
    with pytest.raises(TypeError, match="seed"):  # the wrong kind
        rk.ik(chain, T, np.zeros(6), seed="abc")
    with pytest.raises(ValueError, match="targets"):
        rk.ik_batch(chain, np.zeros((3, 4)), np.zeros(6))
    with pytest.raises(ValueError, match="q0"):
        rk.ik_batch(chain, np.stack([T, T]), np.zeros((3, 6)))
    with pytest.raises(ValueError, match="q0"):
        rk.ik_batch(chain, np.stack([T, T]), np.zeros((2, 6)), path=True)


def test_bound_solver_matches_ik():
    chain = rk.robots.puma560()
    _, T = random_targets(chain, 5, seed=21)
    solver = rk.IKSolver(chain, method="halley", restarts=20, seed=9)
    assert "IKSolver(method='halley'" in repr(solver) and solver.task == "pose"
    for k in range(5):
        a = solver.solve(T[k], np.zeros(6))
        b = rk.ik(chain, T[k], np.zeros(6), method="halley", restarts=20, seed=9 + k)
        assert np.array_equal(a.q, b.q) and a.success == b.success
        assert a.success == verified(chain, a.q, T[k])
    with pytest.raises(ValueError, match="q0"):
        solver.solve(T[0], np.zeros(3))
    with pytest.raises(ValueError, match="method"):
        rk.IKSolver(chain, method="x")


def test_batch_in_parallel_equals_one_by_one():
    # Few iterations an attempt: many targets reach the random restarts (seed + k for target k).
    chain = bent_ur5()
    _, T = random_targets(chain, 40, seed=31)
    batch = rk.ik_batch(chain, T, np.zeros(6), method="lm", restarts=20, max_iter=6, seed=100)
    for k in range(40):
        r = rk.ik(chain, T[k], np.zeros(6), method="lm", restarts=20, max_iter=6, seed=100 + k)
        assert np.array_equal(batch.q[k], r.q) and batch.success[k] == r.success
    assert 0 < batch.success.sum() < 40 and np.any(batch.attempts > 9)  # random restarts were taken


@pytest.mark.parametrize("method", METHODS)
def test_redundant_seven_joint_arm(method):
    # A 7R arm (KUKA LBR iiwa-like DH: d = 0.34, 0.4, 0.4, 0.126 m): more joints than task rows.
    p = math.pi / 2
    rows = [(0, -p, 0.34, 0, "R"), (0, p, 0, 0, "R"), (0, p, 0.4, 0, "R"), (0, -p, 0, 0, "R"),
            (0, -p, 0.4, 0, "R"), (0, p, 0, 0, "R"), (0, 0, 0.126, 0, "R")]
    lim = np.radians([170, 120, 170, 120, 170, 120, 175])
    chain = rk.Chain.from_dh(rows, limits=(-lim, lim))
    _, T = random_targets(chain, 60, seed=41)
    res = rk.ik_batch(chain, T, np.zeros(7), method=method, restarts=30, seed=0)
    for k in range(len(T)):
        assert res.success[k] == verified(chain, res.q[k], T[k])
    assert res.success.mean() >= 0.95


def test_half_infinite_limits_give_a_finite_solution():
    # lower = -inf, upper finite: wrapping by 2 pi must shift from the upper limit, never to -inf.
    chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 2, limits=([-np.inf, -np.inf], [1.0, np.inf]))
    # The start is 2 rad, above the upper limit 1, with the elbow bent: from the exactly
    # stretched arm (q1 = 0, a singular Jacobian) Halley's first step depends on the last bit of cos.
    for method in METHODS:
        r = rk.ik(chain, [1.0, 1.0], [2.0, 0.5], method=method, task="xy", restarts=0)
        assert np.all(np.isfinite(r.q)) and np.isfinite(r.error_p), (method, r)
        assert r.q[0] <= 1.0 and r.success, (method, r)
        assert np.hypot(*(chain.fk(r.q)[:2, 3] - [1.0, 1.0])) < 1e-9
    # one joint, the solution angle pi/2 above the upper limit: reached at pi/2 - 2 pi
    for lim, target, q_expected in [(([-np.inf], [1.0]), [0.0, 1.0], -1.5 * math.pi),
                                    (([-1.0], [np.inf]), [0.0, -1.0], 1.5 * math.pi)]:
        chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")], limits=lim)
        for method in METHODS:
            r = rk.ik(chain, target, [0.0], method=method, task="xy", restarts=0)
            assert r.success and np.all(np.isfinite(r.q)), (method, lim, r)
            assert abs(r.q[0] - q_expected) < 1e-6, (method, lim, r)


@pytest.mark.parametrize("method", METHODS)
def test_the_best_point_is_returned(method):
    # Out of reach: nr and halley overshoot and climb; the answer is the lowest-error point seen,
    # so more iterations never return a worse point, and never worse than the start.
    chain = rk.robots.planar_3r()
    q0 = np.array([0.3, 0.2, 0.1])
    start = np.hypot(*(chain.fk(q0)[:2, 3] - [5.0, 0.0]))
    previous = start
    for max_iter in range(1, 40):
        r = rk.ik(chain, [5.0, 0.0], q0, method=method, task="xy", max_iter=max_iter, restarts=0)
        assert r.error_p <= previous + 1e-12, (max_iter, r, previous)
        previous = r.error_p
    # towards the 2 m that are out of reach; Halley stalls at 2.44 m from here (its best point at
    # the 39th iteration hung on the last bits of sin and cos: a start 1e-4 away stalls as well)
    assert previous < start - (0.25 if method == "halley" else 0.4)
    for seed in range(5):  # across attempts too: random restarts never lose the first attempt's best
        r = rk.ik(chain, [5.0, 0.0], q0, method=method, task="xy", max_iter=7, restarts=3, seed=seed)
        assert r.error_p <= start and np.all(np.isfinite(r.q))


@pytest.mark.parametrize("method", ["lm", "gn"])
def test_descent_methods_never_return_a_worse_point_with_more_iterations(method):
    """LM and GN accept a step only when it lowers the error at a point within the limits, so the
    answer after k + 1 iterations is never worse than after k (one attempt, no restart). Planar arms
    whose limits span less than a turn: a line search through the wrap at +-pi must stop on the
    limit, not evaluate a point beyond it that the answer is clamped back from."""
    rng = np.random.default_rng(0)
    worse = []
    for trial in range(300):
        n = int(rng.integers(2, 4))
        lim = rng.uniform(2.6, 3.1, n)
        chain = rk.Chain.from_dh([(float(a), 0, 0, 0, "R") for a in rng.uniform(0.5, 1.5, n)], limits=(-lim, lim))
        q_goal, q0 = rng.uniform(-lim, lim), rng.uniform(-lim, lim)
        target = chain.fk(q_goal)[:2, 3]
        previous = np.hypot(*(chain.fk(q0)[:2, 3] - target))
        for k in range(1, 9):
            r = rk.ik(chain, target, q0, method=method, task="xy", restarts=0, max_iter=k)
            assert np.all(r.q >= -lim) and np.all(r.q <= lim)
            if r.error_p > previous * (1 + 1e-12) + 1e-15:
                worse.append((trial, k, previous, r.error_p))
            previous = r.error_p
    assert not worse, worse[:5]


def test_default_damping_is_the_documented_one():
    doc = " ".join(rk.ik.__doc__.split())
    patterns = {
        "lm": r"lm: initial damping relative to max diag\(J\^T J\) \(default ([^)]+)\)",
        "nr": r"nr: lambda of the damped pseudoinverse \(default ([^)]+)\)",
        "halley": r"halley: the same lambda \(default ([^)]+)\)",
    }
    chain = rk.robots.ur5()
    _, T = random_targets(chain, 3, seed=5)
    for method, pattern in patterns.items():
        m = re.search(pattern, doc)
        assert m, method
        documented = float(m.group(1))
        solver = rk.IKSolver(chain, method=method, max_iter=3, restarts=0)  # one attempt: no random restarts
        for k in range(3):
            default = rk.ik(chain, T[k], np.zeros(6), method=method, max_iter=3, restarts=0)
            explicit = rk.ik(chain, T[k], np.zeros(6), method=method, max_iter=3, restarts=0, damping=documented)
            other = rk.ik(chain, T[k], np.zeros(6), method=method, max_iter=3, restarts=0, damping=documented * 1e3)
            assert np.array_equal(default.q, explicit.q), method
            assert np.array_equal(solver.solve(T[k], np.zeros(6)).q, explicit.q), method
            assert not np.array_equal(other.q, explicit.q), method  # the damping does matter here


def test_bound_solver_releases_the_gil():
    chain = rk.robots.ur5()
    T = np.eye(4)
    T[:3, 3] = (2.0, 0.0, 0.5)  # out of reach: every restart runs until the timeout
    solver = rk.IKSolver(chain, restarts=1_000_000, timeout=0.3, seed=0)
    results = []
    worker = threading.Thread(target=lambda: results.append(solver.solve(T, np.zeros(6))))
    t0 = time.perf_counter()
    worker.start()
    turns = 0  # main-thread turns while the solver works: about 1 if it held the GIL, ~300 if not
    while worker.is_alive():
        turns += 1
        time.sleep(0.001)
    worker.join()
    assert results and not results[0].success and np.all(np.isfinite(results[0].q))
    assert time.perf_counter() - t0 >= 0.25
    assert turns >= 20, turns
    # one solver used by two threads at once: serialised, both answers valid
    solver = rk.IKSolver(chain, restarts=1_000_000, timeout=0.05, seed=0)
    out = []
    threads = [threading.Thread(target=lambda: out.append(solver.solve(T, np.zeros(6)))) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(out) == 2 and all(np.all(np.isfinite(r.q)) and not r.success for r in out)


def test_seed_is_any_64_bit_unsigned_int():
    chain = rk.robots.ur5()
    _, T = random_targets(chain, 2, seed=8)
    top = 2**64 - 1
    a = rk.ik(chain, T[0], np.zeros(6), restarts=3, seed=top)
    b = rk.ik(chain, T[0], np.zeros(6), restarts=3, seed=np.uint64(top))
    assert np.array_equal(a.q, b.q)
    assert rk.IKSolver(chain, seed=top).solve(T[0], np.zeros(6)).q.shape == (6,)
    assert len(rk.ik_batch(chain, T, np.zeros(6), seed=top)) == 2  # target 1: seed 2**64 wraps to 0
    for bad in (2**64, -1, 2**100):
        with pytest.raises(ValueError, match="seed"):
            rk.ik(chain, T[0], np.zeros(6), seed=bad)
        with pytest.raises(ValueError, match="seed"):
            rk.IKSolver(chain, seed=bad)


def test_restarts_are_capped():
    chain = rk.robots.ur5()
    T = chain.fk(np.zeros(6))
    assert rk.ik(chain, T, np.zeros(6), restarts=1_000_000).success
    assert rk.ik(chain, T, np.zeros(6), restarts=np.int64(3)).success
    with pytest.raises(ValueError, match=r"restarts: must be at most 1000000 \(use timeout to bound the time\)"):
        rk.ik(chain, T, np.zeros(6), restarts=1_000_001)
    for bad in (1_000_001, 2**31, 2**70, -1, -(2**70)):
        for call in (lambda: rk.ik(chain, T, np.zeros(6), restarts=bad),
                     lambda: rk.ik_batch(chain, T[None], np.zeros(6), restarts=bad),
                     lambda: rk.IKSolver(chain, restarts=bad)):
            with pytest.raises(ValueError, match="^restarts: (must be|out of range)"):
                call()
    for bad, kind in ((2.5, "float"), ("3", "str"), (True, "bool")):  # a wrong kind of object
        with pytest.raises(TypeError, match=f"^restarts: expected None or int, got {kind}$"):
            rk.ik(chain, T, np.zeros(6), restarts=bad)


def test_stall_window_drops_crawling_attempts_only_while_restarts_are_left():
    # A planar 2R told to reach (3, 0.5), 1 m beyond its reach: NR takes every step and never
    # succeeds, so each attempt runs until the stall rule drops it or max_iter ends it. The last
    # attempt has no restart left and is never dropped.
    chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 2)

    def iterations(window):
        r = rk.ik(chain, [3.0, 0.5], np.zeros(2), task="xy", method="nr", restarts=3, max_iter=50, seed=1,
                  stall_window=window)
        assert not r.success and r.attempts == 4
        return r.iterations

    assert iterations(0) == 4 * 50  # never dropped
    assert iterations(50) == 4 * 50  # the window is never complete within max_iter
    assert iterations(1) == 3 * 1 + 50  # no attempt halves its cost in one step beyond reach
    assert 3 * 6 + 50 <= iterations(6) < 4 * 50
    assert iterations(None) == iterations(6)  # the default without a closed form
    assert rk.IKOptions().stall_window is rk.IK_DEFAULTS["stall_window"] is None
    with pytest.raises(ValueError, match=r"stall_window: must be None or >= 0 \(0: never drop an attempt\)"):
        rk.ik(chain, [1.0, 0.5], np.zeros(2), task="xy", stall_window=-1)
    with pytest.raises(TypeError, match="stall_window: expected None or int, got float"):
        rk.IKOptions(stall_window=2.5)


def test_the_default_stall_window_is_shorter_before_a_closed_form_restart():
    # A pose 1 m beyond the UR5's reach: no closed-form solution, so every attempt runs until the
    # stall rule drops it; the default window is 3 for a pose target on an arm with a closed form,
    # 6 for a position target (no closed-form restart).
    chain = rk.robots.ur5()
    T = chain.fk(np.zeros(6))
    T[:3, 3] += [0.0, 0.0, 1.0]

    def iterations(window, task):
        target = T if task == "pose" else T[:3, 3]
        r = rk.ik(chain, target, np.full(6, 0.3), task=task, method="nr", restarts=4, max_iter=60, seed=2,
                  stall_window=window)
        assert not r.success and r.attempts == 5
        return r.iterations

    for task, window in (("pose", 3), ("position", 6)):
        assert iterations(3, task) != iterations(6, task)
        assert iterations(None, task) == iterations(window, task)
