"""The 3-RRR models against independent truth: the legs' forward chains, finite differences, the
seed's formulas and an independent dense search, all written here in numpy."""

import math

import numpy as np
import pytest

import robokin as rk

from rrr3_truth import T, U, base, cross, elbows, platform, random_poses, rot, seed_jacobians, u


@pytest.fixture
def robot():
    return rk.RRR3()


@pytest.fixture
def rng():
    return np.random.default_rng(3)


# --- inverse models -------------------------------------------------------------------------------


def test_modes_are_the_eight_sign_triples(robot):
    modes = rk.RRR3.modes
    assert len(modes) == 8 and len(set(modes)) == 8
    assert modes[0] == (1, 1, 1)
    assert all(set(m) <= {1, -1} and len(m) == 3 for m in modes)


def test_ik_leg_chains_reach_the_platform_in_every_mode(robot, rng):
    count = 0
    for _ in range(60):
        pose = np.array([*rng.uniform(-0.08, 0.08, 2), rng.uniform(-1, 1)])
        all_rows = robot.ik_all(pose)
        for k, mode in enumerate(robot.modes):
            try:
                alpha = robot.ik(pose, mode)
            except rk.UnreachableError:
                assert np.isnan(all_rows[k]).all()
                continue
            np.testing.assert_array_equal(all_rows[k], alpha)
            a, b, o = elbows(robot, alpha), platform(robot, pose), base(robot)
            np.testing.assert_allclose(np.linalg.norm(b - a, axis=1), robot.l2, atol=1e-12)
            # Elbow sign: link 2 turns counter-clockwise from link 1 when m_i = +1.
            assert np.all(np.sign(cross(a - o, b - a)) == np.array(mode))
            count += 1
    assert count > 200


def test_ik_matches_design_formula(robot, rng):
    """DESIGN.md: alpha_i = atan2(B_i - O_i) - m_i acos((l1^2 + |OB|^2 - l2^2) / (2 l1 |OB|))."""
    for pose in random_poses(robot, rng, 20):
        for mode in robot.modes:
            d = platform(robot, pose) - base(robot)
            r = np.linalg.norm(d, axis=1)
            expected = np.arctan2(d[:, 1], d[:, 0]) - np.array(mode) * np.arccos(
                (robot.l1**2 + r**2 - robot.l2**2) / (2 * robot.l1 * r))
            diff = np.angle(np.exp(1j * (robot.ik(pose, mode) - expected)))
            np.testing.assert_allclose(diff, 0, atol=1e-12)


def test_ik_batch_equals_ik_row_by_row(robot, rng):
    poses = np.column_stack((rng.uniform(-0.2, 0.2, (3000, 2)), rng.uniform(-np.pi, np.pi, 3000)))
    for mode in [(1, 1, 1), (-1, 1, -1)]:
        out = robot.ik_batch(poses, mode)
        assert out.shape == (3000, 3)
        unreachable = 0
        for p, row in zip(poses, out):
            try:
                np.testing.assert_array_equal(row, robot.ik(p, mode))
            except rk.UnreachableError:
                assert np.isnan(row).all()
                unreachable += 1
        assert 100 < unreachable < 2900
    assert robot.ik_batch(np.zeros((0, 3))).shape == (0, 3)


def test_unreachable_names_the_leg(robot):
    # Far below the base: leg 0 at O_0 = (0, -0.13) is the closest, legs 1 and 2 cannot reach.
    with pytest.raises(rk.UnreachableError, match="leg 1") as info:
        robot.ik([0.0, -0.3, 0.0])
    assert isinstance(info.value, ValueError) and info.value.leg == 1
    # Only leg 0 too far: the pose is pushed away from O_0 along +y.
    pose = np.array([0.0, 0.185, 0.0])
    assert np.linalg.norm(platform(robot, pose)[0] - base(robot)[0]) > 0.24
    assert np.all(np.linalg.norm(platform(robot, pose)[1:] - base(robot)[1:], axis=1) < 0.24)
    with pytest.raises(rk.UnreachableError, match="leg 0"):
        robot.ik(pose)


def test_ik_newton_converges_to_the_analytic_answer(robot, rng):
    for pose in random_poses(robot, rng, 10):
        for mode in [(1, 1, 1), (1, -1, -1), (-1, 1, -1)]:
            alpha = robot.ik(pose, mode)
            a, b = elbows(robot, alpha), platform(robot, pose)
            link1 = a - base(robot)
            beta = np.arctan2(cross(link1, b - a), np.sum(link1 * (b - a), axis=1))
            guess = np.concatenate((alpha + rng.uniform(-0.1, 0.1, 3), beta + rng.uniform(-0.1, 0.1, 3)))
            res = robot.ik_newton(pose, guess)
            assert res.converged and res.error < 1e-12
            # Newton's quadratic convergence: from 0.1 rad off, a handful of iterations (a step
            # shortened on any unknown converges linearly and needs dozens).
            assert res.iterations <= 6, res.iterations
            got_alpha, got_beta = res
            np.testing.assert_allclose(np.angle(np.exp(1j * (got_alpha - alpha))), 0, atol=1e-10)
            np.testing.assert_allclose(np.angle(np.exp(1j * (got_beta - beta))), 0, atol=1e-10)
            assert np.all(np.sign(got_beta) == np.array(mode))
            # The full chain O + l1 u(alpha) + l2 u(alpha + beta) lands on B.
            tip = base(robot) + robot.l1 * np.column_stack((np.cos(got_alpha), np.sin(got_alpha))) + robot.l2 * \
                np.column_stack((np.cos(got_alpha + got_beta), np.sin(got_alpha + got_beta)))
            np.testing.assert_allclose(tip, b, atol=1e-12)


def test_ik_newton_reports_non_convergence(robot):
    pose = np.array([0.01, 0.0, 0.1])
    assert not robot.ik_newton(pose, np.zeros(6), max_iter=1).converged
    res = robot.ik_newton([0.0, -0.3, 0.0], np.ones(6))  # unreachable: no root at all
    assert not res.converged and res.error > 1e-3


# --- forward models -------------------------------------------------------------------------------


def closure(robot, alpha, pose):
    return np.abs(np.linalg.norm(platform(robot, pose) - elbows(robot, alpha), axis=1) - robot.l2)


def independent_fk_phis(robot, alpha, samples=100_000):
    """Roots in phi found by another elimination: E on the intersection of the circles of legs 0 and 1
    (two branches), then the sign of |A_2B_2| - l2 along a dense phi grid."""
    a = elbows(robot, alpha)
    phi = np.linspace(-np.pi, np.pi, samples, endpoint=False)
    c, s = np.cos(phi), np.sin(phi)
    bp = robot.platform_radius * U
    rb = np.stack([np.column_stack((c * bp[i, 0] - s * bp[i, 1], s * bp[i, 0] + c * bp[i, 1])) for i in range(3)])
    p0, p1 = a[0] - rb[0], a[1] - rb[1]  # E lies on circle(p0, l2) and circle(p1, l2)
    d = p1 - p0
    dist = np.linalg.norm(d, axis=1)
    h2 = robot.l2**2 - (dist / 2) ** 2
    valid = (h2 >= 0) & (dist > 0)
    h = np.sqrt(np.where(valid, h2, 0.0))
    mid = p0 + d / 2
    perp = np.column_stack((-d[:, 1], d[:, 0])) / np.where(dist > 0, dist, 1)[:, None]
    found = []
    for sign in (1, -1):
        e = mid + sign * h[:, None] * perp
        g = np.linalg.norm(e + rb[2] - a[2], axis=1) - robot.l2
        ok = valid & np.roll(valid, -1)
        change = ok & (np.sign(g) != np.sign(np.roll(g, -1)))
        found.extend(phi[change])
    return np.array(found)


def test_fk_all_contains_the_pose_and_closes_the_loops(robot, rng):
    for mode in robot.modes:
        for pose in random_poses(robot, rng, 4, mode):
            alpha = robot.ik(pose, mode)
            sols = robot.fk_all(alpha)
            assert 1 <= len(sols) <= 6
            assert np.min(np.linalg.norm(sols - pose, axis=1)) < 1e-9
            for sol in sols:
                assert np.max(closure(robot, alpha, sol)) < 1e-10
                assert -np.pi <= sol[2] < np.pi


def test_fk_all_misses_nothing_an_independent_search_finds(robot, rng):
    total = 0
    for trial in range(25):
        alpha = rng.uniform(-np.pi, np.pi, 3)
        sols = robot.fk_all(alpha)
        for sol in sols:
            assert np.max(closure(robot, alpha, sol)) < 1e-10
        for phi in independent_fk_phis(robot, alpha):
            total += 1
            gap = np.abs(np.angle(np.exp(1j * (sols[:, 2] - phi)))) if len(sols) else np.array([np.inf])
            assert gap.min() < 1e-3, f"alpha={alpha!r}: fk_all missed phi={phi}"
    assert total > 10  # the random actuations did produce assembly modes


def near_singular_poses(robot, rng, count, mode, offsets=(1e-5, 1e-4, 1e-3, 3e-3)):
    """Poses a little off a parallel singularity: a root of det A along phi (bisected on the seed's
    det A in numpy), then moved along phi by a small offset. Their assembly modes come in close pairs."""
    def det(p):
        try:
            return np.linalg.det(seed_jacobians(robot, p, robot.ik(p, mode))[0])
        except rk.UnreachableError:
            return np.nan
    out = []
    while len(out) < count:
        x, y = rng.uniform(-0.08, 0.08, 2)
        phis = rng.uniform(-np.pi, np.pi) + np.linspace(0, 2 * np.pi, 121)
        d = np.array([det(np.array([x, y, p])) for p in phis])
        k = np.nonzero(np.isfinite(d[:-1]) & np.isfinite(d[1:]) & (np.sign(d[:-1]) != np.sign(d[1:])))[0]
        if len(k) == 0:
            continue
        lo, hi = phis[k[0]], phis[k[0] + 1]
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if np.sign(det(np.array([x, y, mid]))) == np.sign(d[k[0]]) else (lo, mid)
        for off in offsets:
            for sign in (1, -1):
                p = np.array([x, y, np.angle(np.exp(1j * (lo + sign * off)))])
                if np.isfinite(det(p)):
                    out.append(p)
    return out


def assert_fk_all_finds(robot, pose, mode, dense=False):
    alpha = robot.ik(pose, mode)
    sols = robot.fk_all(alpha)
    assert len(sols) >= 1, f"pose={pose!r} mode={mode}: fk_all found nothing"
    for sol in sols:
        assert np.max(closure(robot, alpha, sol)) < 1e-10
        assert -np.pi <= sol[2] < np.pi
    gap = np.linalg.norm(np.column_stack((sols[:, :2] - pose[:2], np.angle(np.exp(1j * (sols[:, 2] - pose[2]))))),
                         axis=1)
    assert gap.min() < 1e-6, f"pose={pose!r} mode={mode}: fk_all missed the pose itself"  # ill-conditioned near det A = 0
    if dense:
        for phi in independent_fk_phis(robot, alpha):
            assert np.abs(np.angle(np.exp(1j * (sols[:, 2] - phi)))).min() < 1e-3, f"alpha={alpha!r}: missed {phi}"


def test_fk_all_near_parallel_singularities(robot, rng):
    # Review repro: two roots in phi within one scan step; r.fk closes the pose but fk_all missed it.
    assert_fk_all_finds(robot, np.array([-0.0182793, -0.02691826, 0.80348873]), (-1, -1, 1), dense=True)
    # Poses just off parallel singularities (|det_a_norm| down to ~1e-6) in every working mode.
    local = np.random.default_rng(11)
    count = 0
    for mode in robot.modes:
        for k, pose in enumerate(near_singular_poses(robot, local, 24, mode)):
            assert_fk_all_finds(robot, pose, mode, dense=k % 8 == 0)
            count += 1
    assert count >= 8 * 24


def test_fk_all_over_random_poses_without_a_singularity_filter(robot):
    # Unlike random_poses, no |det| filter: near-singular poses are drawn as they come.
    local = np.random.default_rng(12)
    count = near = 0
    while count < 3000:
        pose = np.array([*local.uniform(-0.1, 0.1, 2), local.uniform(-np.pi, np.pi)])
        mode = robot.modes[local.integers(8)]
        try:
            robot.ik(pose, mode)
        except rk.UnreachableError:
            continue
        near += abs(robot.singularity(pose, mode).det_a_norm) < 0.01
        assert_fk_all_finds(robot, pose, mode, dense=count % 300 == 0)
        count += 1
    assert near >= 10


def test_fk_all_finds_six_modes_on_a_known_case():
    # Over random actuations the seed's robot shows several assembly modes at once.
    robot = rk.RRR3(0.13, 0.07, 0.12, 0.12)
    best = 0
    rng = np.random.default_rng(0)
    for _ in range(300):
        alpha = rng.uniform(-np.pi, np.pi, 3)
        sols = robot.fk_all(alpha)
        best = max(best, len(sols))
    assert best >= 4


def fk_gap(sols, pose):
    """Distance of each row of sols to pose, phi wrapped."""
    d = np.column_stack((sols[:, :2] - pose[:2], np.angle(np.exp(1j * (sols[:, 2] - pose[2])))))
    return np.max(np.abs(d), axis=1)


def test_fk_all_gives_a_double_root_once():
    # Fuzz repro: 8 poses, 4 of them copies of the pose (0, 0, 0) (B_i = O_i, a double root with
    # det A = 0: legs 1 and 2 give the same row of A), each where Newton stopped within some 1e-7 of it.
    robot = rk.RRR3(0.1, 0.1, 0.1, 0.1)
    alpha = np.array([1.0, 0.0, 0.0])
    sols = robot.fk_all(alpha)
    assert len(sols) == 5, sols  # F's six roots: the double one and four simple ones
    assert fk_gap(sols, np.zeros(3)).min() < 1e-6
    assert fk_gap(sols, np.array([0.1 * (1 + math.cos(1)), 0.1 * math.sin(1), 0.0])).min() < 1e-12
    for sol in sols:
        assert np.max(closure(robot, alpha, sol)) < 1e-15
    # Two distinct modes 2.3e-5 rad apart across a parallel singularity stay two; the copy of one
    # of them that Newton left closing the loops only to 5e-11 m is dropped (7 poses before).
    alpha = np.array([2.079234930507397, -2.8658642621553416, 2.1860714805007526])
    sols = robot.fk_all(alpha)
    assert len(sols) == 6, sols
    for pose in ([-0.03006711, -0.02438518, -0.67277114], [-0.03006573, -0.02438528, -0.672748]):
        assert np.sum(fk_gap(sols, np.array(pose)) < 1e-6) == 1, (pose, sols)


def test_fk_all_leaves_out_a_continuum():
    # Elbows on a triangle congruent to the platform's: the platform turns its parallel legs on a
    # circle (phi fixed, |E - centre| = l2), which is no assembly mode of its own; only the isolated
    # ones are returned. With base_radius == platform_radius: any alpha_0 = alpha_1 = alpha_2, the
    # isolated modes at E = l1 u(alpha), phi = +-60 deg.
    robot = rk.RRR3(0.1, 0.1, 0.1, 0.1)
    for a in (0.0, 1.0, -2.5, math.pi):
        alpha = np.full(3, a)
        sols = robot.fk_all(alpha)
        e = 0.1 * u(a)
        np.testing.assert_allclose(sols, [[*e, -math.pi / 3], [*e, math.pi / 3]], rtol=0, atol=1e-12)
    # The seed's robot: elbows A_i = R_e R(theta) u(t_i), |R_b - R_e e^(i theta)| = l1, E on the circle |E| = l2.
    robot = rk.RRR3()
    theta = math.acos((0.13**2 + 0.07**2 - 0.12**2) / (2 * 0.13 * 0.07))
    for th in (theta, -theta):
        d = 0.07 * U @ rot(th).T - 0.13 * U
        alpha = np.arctan2(d[:, 1], d[:, 0])
        assert np.max(closure(robot, alpha, np.array([0.12, 0.0, th]))) < 1e-15  # a pose of the continuum
        sols = robot.fk_all(alpha)
        assert len(sols) == 2 and np.all(np.abs(sols[:, :2]) < 1e-12), sols  # the isolated modes, E = 0
        for sol in sols:
            assert np.max(closure(robot, alpha, sol)) < 1e-15


def test_fk_newton_from_a_guess(robot, rng):
    for pose in random_poses(robot, rng, 10):
        alpha = robot.ik(pose)
        res = robot.fk(alpha, pose + np.array([0.003, -0.002, 0.03]))
        assert res.converged
        np.testing.assert_allclose(res.pose, pose, atol=1e-10)
    assert not robot.fk(np.zeros(3), np.zeros(3), max_iter=0).converged


# --- Jacobians ----------------------------------------------------------------------------------------


def test_jacobians_match_the_seed_formulas(robot, rng):
    for mode in [(1, 1, 1), (-1, 1, -1), (-1, -1, -1)]:
        for pose in random_poses(robot, rng, 5, mode):
            A, B = robot.jacobians(pose, mode)
            A_ref, B_ref = seed_jacobians(robot, pose, robot.ik(pose, mode))
            np.testing.assert_allclose(A, A_ref, atol=1e-12)
            np.testing.assert_allclose(B, B_ref, atol=1e-12)


def test_jacobians_against_finite_differences(robot, rng):
    """A v = B alpha_dot with v = (v_x, v_y, w), the linear velocity in the effector frame."""
    h = 1e-6
    for mode in [(1, 1, 1), (1, -1, 1)]:
        for pose in random_poses(robot, rng, 5, mode):
            A, B = robot.jacobians(pose, mode)
            twist = rng.normal(size=3) * np.array([0.05, 0.05, 0.5])  # base-frame velocity and w
            alpha_dot = (robot.ik(pose + h * twist, mode) - robot.ik(pose - h * twist, mode)) / (2 * h)
            v = np.concatenate((rot(pose[2]).T @ twist[:2], twist[2:]))
            np.testing.assert_allclose(A @ v, B @ alpha_dot, atol=1e-7)


# --- singularities --------------------------------------------------------------------------------


def test_well_conditioned_poses_are_regular(robot):
    s = robot.singularity([0.0, 0.0, 0.0])
    assert s.kind == "none" and s.leg is None and s.lines is None
    assert 0 < s.distance <= 1


def test_stretched_leg_is_serial():
    robot = rk.RRR3()
    for leg in range(3):
        # Leg `leg` fully stretched towards the centre; the platform orientation is free.
        alpha = T[leg] + np.pi + 0.2
        b = base(robot)[leg] + (robot.l1 + robot.l2) * u(alpha)
        phi = 0.1
        pose = np.array([*(b - rot(phi) @ (robot.platform_radius * U[leg])), phi])
        s = robot.singularity(pose, (1, 1, 1))
        assert s.kind == "serial" and s.leg == leg
        assert abs(s.det_b) < 1e-9


def concurrency_defect(robot, pose, mode):
    """Distance from the intersection of lines A_0B_0, A_1B_1 to line A_2B_2 (0 when concurrent)."""
    a, b = elbows(robot, robot.ik(pose, mode)), platform(robot, pose)
    d = b - a
    t = np.linalg.solve(np.column_stack((d[0], -d[1])), a[1] - a[0])
    p = a[0] + t[0] * d[0]
    return abs(cross(d[2], p - a[2])) / np.linalg.norm(d[2])


def test_parallel_singularity_found_along_phi(robot):
    # At (0.05, 0.03) in mode (1, 1, 1), det A changes sign along phi: bisect for the root.
    x, y, mode = 0.05, 0.03, (1, 1, 1)
    phis = np.linspace(-1.0, 1.0, 401)
    dets = np.array([np.linalg.det(seed_jacobians(robot, np.array([x, y, p]), robot.ik([x, y, p], mode))[0])
                     for p in phis])
    k = np.nonzero(np.sign(dets[:-1]) != np.sign(dets[1:]))[0]
    assert len(k) >= 1
    lo, hi = phis[k[0]], phis[k[0] + 1]
    f = lambda p: np.linalg.det(seed_jacobians(robot, np.array([x, y, p]), robot.ik([x, y, p], mode))[0])
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sign(f(mid)) == np.sign(f(lo)) else (lo, mid)
    pose = np.array([x, y, 0.5 * (lo + hi)])
    s = robot.singularity(pose, mode)
    assert s.kind == "parallel" and abs(s.det_a_norm) < 1e-9 and s.distance < 1e-6
    assert s.lines == "concurrent" and concurrency_defect(robot, pose, mode) < 1e-9
    # A little away from it the robot is regular again.
    assert robot.singularity(pose + [0, 0, 0.1], mode).kind == "none"


def test_normalised_determinants_do_not_depend_on_size(robot, rng):
    big = rk.RRR3(13.0, 7.0, 12.0, 12.0)
    for pose in random_poses(robot, rng, 5):
        s, S = robot.singularity(pose), big.singularity(pose * [100, 100, 1])
        assert S.det_a_norm == pytest.approx(s.det_a_norm, rel=1e-9)
        assert S.det_b_norm == pytest.approx(s.det_b_norm, rel=1e-9)
        assert S.distance == pytest.approx(s.distance, rel=1e-7)
        assert S.kind == s.kind


def test_points_for_drawing(robot):
    pose = np.array([0.01, -0.02, 0.2])
    pts = robot.points(pose, (1, -1, 1))
    np.testing.assert_allclose(pts["O"], base(robot))
    np.testing.assert_allclose(pts["B"], platform(robot, pose))
    np.testing.assert_allclose(np.linalg.norm(pts["A"] - pts["O"], axis=1), robot.l1)
    np.testing.assert_allclose(np.linalg.norm(pts["B"] - pts["A"], axis=1), robot.l2)


# --- bad input -------------------------------------------------------------------------------------


@pytest.mark.parametrize("args, name", [
    ((0, 0.07, 0.12, 0.12), "base_radius"), ((0.13, -1, 0.12, 0.12), "platform_radius"),
    ((0.13, 0.07, float("nan"), 0.12), "l1"), ((0.13, 0.07, 0.12, float("inf")), "l2"),
])
def test_invalid_geometry(args, name):
    with pytest.raises(ValueError, match=name):
        rk.RRR3(*args)


def test_bad_input_raises_value_error(robot):
    cases = [
        (lambda: robot.ik([0, 0, float("nan")]), "pose"),
        (lambda: robot.ik([0, 0]), "pose"),
        (lambda: robot.ik([0, 0, 0], (1, 0, 1)), "mode"),
        (lambda: robot.ik([0, 0, 0], (1, 1)), "mode"),
        (lambda: robot.ik([0, 0, 0], (1, 2, -1)), "mode"),
        (lambda: robot.ik_batch(np.zeros((4, 2))), "poses"),
        (lambda: robot.ik_batch(np.full((4, 3), np.inf)), "poses"),
        (lambda: robot.ik_batch(np.zeros(3)), "poses"),
        (lambda: robot.fk_all([0, 0]), "alpha"),
        (lambda: robot.fk_all([0, 0, float("nan")]), "alpha"),
        (lambda: robot.fk([0, 0, 0], [0, 0]), "guess"),
        (lambda: robot.ik_newton([0, 0, 0], np.zeros(5)), "guess"),
        (lambda: robot.jacobians([0, 0, 0], (1, 1, 1, 1)), "mode"),
        (lambda: robot.singularity([0, 0, 0], tol=-1), "tol"),
        (lambda: robot.points(np.zeros((3, 3))), "pose"),
    ]
    for call, name in cases:
        with pytest.raises(ValueError, match=name):
            call()
    with pytest.raises(TypeError, match="pose: expected an array of numbers, got a string"):
        robot.ik("abc")
    with pytest.raises(TypeError, match="pose: expected an array of numbers, got None"):
        robot.ik_all(None)


def test_degenerate_geometry_does_not_crash():
    # Base and platform of the same size with l1 == l2: at the centre every leg is folded (r = 0).
    robot = rk.RRR3(0.1, 0.1, 0.1, 0.1)
    with pytest.raises(rk.UnreachableError):
        robot.ik([0, 0, 0])
    assert np.isnan(robot.ik_batch(np.zeros((2, 3)))).all()
    robot.fk_all([0.0, 2.0, 4.0])  # any answer, but no crash


def test_ik_is_periodic_in_phi_for_any_orientation(robot, rng):
    """The fast sine/cosine and atan2 of the core hold for small and huge orientations alike."""
    poses = np.array(random_poses(robot, rng, 5))
    for turns in [1, -7, 1000, 20_000, 10**6]:
        shifted = poses + [0, 0, 2 * np.pi * turns]
        got = robot.ik_batch(shifted, (1, -1, 1))
        want = robot.ik_batch(poses, (1, -1, 1))
        tol = 1e-14 * max(1.0, 2 * np.pi * abs(turns))  # phi itself is rounded to that
        np.testing.assert_allclose(np.angle(np.exp(1j * (got - want))), 0, atol=tol)
        for p, row in zip(shifted, got):
            np.testing.assert_array_equal(robot.ik(p, (1, -1, 1)), row)


def parallel_lines_pose(robot, theta, signs, start):
    """A pose whose lines A_iB_i are all parallel to u(theta): A_i = B_i - s_i l2 u(theta) on the
    circle (O_i, l1). Newton on the three circle equations in (x, y, phi) from start; None if it fails."""
    o, d = base(robot), robot.l2 * u(theta)
    x = np.array(start, float)
    for _ in range(60):
        b = platform(robot, x)
        r = b - np.outer(signs, d) - o  # O_iA_i
        f = np.sum(r * r, axis=1) - robot.l1**2
        db = (b - x[:2]) @ np.array([[0, 1], [-1, 0]])  # dB_i/dphi = perp(B_i - E)
        jac = 2 * np.column_stack((r[:, 0], r[:, 1], np.sum(r * db, axis=1)))
        try:
            step = np.linalg.solve(jac, f)
        except np.linalg.LinAlgError:
            return None
        x = x - step
        if not np.all(np.isfinite(x)):
            return None
    return np.array([x[0], x[1], np.angle(np.exp(1j * x[2]))]) if np.max(np.abs(f)) < 1e-14 else None


def test_parallel_lines_singularity(robot):
    # With every s_i = 1 there is a closed form: E = l2 u(theta) puts A_i = R(phi) b_i, on the
    # circle (O_i, l1) when |O_i - R(phi) b_i| = l1, i.e. cos phi = (R_b^2 + R_e^2 - l1^2) / (2 R_b R_e)
    # (phi = +-66 deg for the seed's robot). Other sign triples come from a root search.
    phi0 = math.acos((robot.base_radius**2 + robot.platform_radius**2 - robot.l1**2) /
                     (2 * robot.base_radius * robot.platform_radius))
    poses = [(np.array([robot.l2 * math.cos(t), robot.l2 * math.sin(t), sgn * phi0]), t, np.ones(3))
             for t in (0.3, 2.0, -2.5) for sgn in (1, -1)]
    rng = np.random.default_rng(4)
    while len(poses) < 20:
        theta, signs = rng.uniform(-np.pi, np.pi), rng.choice([-1, 1], 3)
        pose = parallel_lines_pose(robot, theta, signs, [*rng.uniform(-0.1, 0.1, 2), rng.uniform(-np.pi, np.pi)])
        if pose is not None:
            poses.append((pose, theta, signs))
    checked = 0
    for pose, theta, signs in poses:
        b = platform(robot, pose)
        a = b - np.outer(signs, robot.l2 * u(theta))
        np.testing.assert_allclose(np.linalg.norm(a - base(robot), axis=1), robot.l1, atol=1e-13)
        mode = tuple(int(v) for v in np.sign(cross(a - base(robot), b - a)))
        np.testing.assert_allclose(elbows(robot, robot.ik(pose, mode)), a, atol=1e-12)
        sa, _ = seed_jacobians(robot, pose, robot.ik(pose, mode))
        assert abs(np.linalg.det(sa)) < 1e-12  # (cos g_i, sin g_i) all collinear: A is singular
        s = robot.singularity(pose, mode)
        if s.kind == "serial":
            continue  # a stretched or folded leg as well
        checked += 1
        assert s.kind == "parallel" and abs(s.det_a_norm) < 1e-12 and s.distance < 1e-6, (pose, mode)
        assert s.lines == "parallel", (pose, mode)
        # Turned away from it the lines are no longer parallel: at most a concurrent singularity.
        t = robot.singularity(pose + [0, 0, 0.05], mode)
        assert t.kind != "parallel" or t.lines == "concurrent"
    assert checked >= 10


@pytest.mark.parametrize("geometry, pose, mode", [
    # Two assembly modes at (nearly) the same phi: c_0, c_1, c_2 collinear, det M = 0, N / D = 0 / 0.
    ((0.15, 0.0866, 0.1, 0.1), [-0.11210236524486471, -0.01674159504742448, 0.32668011224636606], (1, 1, 1)),
    ((0.2, 0.05, 0.15, 0.08), [-0.07603874214982485, 0.02385199211094924, -0.0586967902403992], (1, -1, -1)),
    ((0.13, 0.07, 0.12, 0.12), [-0.11989577701054777, -0.00792209681894901, 1.1516178773222334], (1, 1, -1)),
    # Three roots of F within one scan step (a sign change hiding two more roots).
    ((0.13, 0.07, 0.12, 0.12), [0.06634909065521899, -0.09234243044567052, 1.1103930395561186], (-1, 1, 1)),
    ((0.13, 0.07, 0.12, 0.12), [0.0055549583776657585, -0.07314090889654673, 1.4136550870365436], (1, 1, -1)),
    ((0.15, 0.0866, 0.1, 0.1), [0.04553210246852732, -0.011481287899902493, 0.8765751012293439], (-1, -1, 1)),
    ((0.2, 0.05, 0.15, 0.08), [0.012019405956752577, 0.07088462600119894, 0.46224416209596475], (1, -1, -1)),
    ((0.2, 0.05, 0.15, 0.08), [-0.05101960568996092, -0.056000981990985466, -0.3968591576762872], (1, -1, -1)),
    ((0.1, 0.09, 0.07, 0.14), [-0.09038067992523888, 0.06430037069568303, -0.06692229484557988], (-1, -1, -1)),
    ((13.0, 7.0, 12.0, 12.0), [6.6476266403898165, 11.45175562658715, -1.053853915485965], (-1, -1, 1)),
    # Two tangencies of F within one scan step (the first one found hid the other).
    ((0.2, 0.05, 0.15, 0.08), [0.0259206776139195, 0.07586139422058419, -0.031512351772624125], (-1, -1, 1)),
])
def test_fk_all_hard_cases_from_a_sweep(geometry, pose, mode):
    # Misses of earlier versions in a sweep of 200,000 random (pose, mode) pairs over 5 geometries.
    robot = rk.RRR3(*geometry)
    pose = np.array(pose)
    alpha = robot.ik(pose, mode)
    sols = robot.fk_all(alpha)
    scale = geometry[0] / 0.13
    gap = np.linalg.norm(np.column_stack(((sols[:, :2] - pose[:2]) / scale, np.angle(np.exp(1j * (sols[:, 2] - pose[2]))))),
                         axis=1)
    assert gap.min() < 1e-6
    for sol in sols:
        assert np.max(closure(robot, alpha, sol)) < 1e-10 * scale
