"""Closed-form inverse kinematics, checked by forward kinematics (KDL chains from the DH tables),
by the solution counts of the IK course and at the singular configurations."""

import math

import numpy as np
import pytest

import robokin as rk


def wrapped_distance(a, b):
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))).max(axis=-1)


def planar_pose(chain, q):
    T = chain.fk(q)
    return np.array([T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])])


def anthropomorphic_chain(a2, a3, d1=0.0):
    return rk.Chain.from_dh([(0.0, math.pi / 2, d1, 0.0, "R"), (a2, 0.0, 0.0, 0.0, "R"), (a3, 0.0, 0.0, 0.0, "R")])


# --- the IK course, example 1: planar RP -----------------------------------------------------------

def test_rp_matches_the_course_formula_and_fk():
    chain = rk.robots.rp(stroke=2.0)
    s = rk.closed.planar_rp((0.3, -0.4), limits=chain)
    assert s.postures == ["stroke forward", "stroke backward"] and s.within_limits.tolist() == [True, False]
    assert np.allclose(s.q[0], [math.atan2(-0.4, 0.3), 0.5])
    assert np.allclose(s.q[1], [math.atan2(0.4, -0.3), -0.5])  # d2 < 0: outside the stroke [0, 2]
    assert np.allclose(chain.fk(s.q[0])[:2, 3], [0.3, -0.4], atol=1e-14)


def test_rp_backward_stroke_when_limits_allow_it_and_out_of_stroke():
    chain = rk.robots.rp()
    both = rk.closed.planar_rp((0.3, 0.4), limits=([-math.inf, -1.0], [math.inf, 1.0]))
    assert len(both) == 2
    for q in both.q:
        assert np.allclose(chain.fk(q)[:2, 3], [0.3, 0.4], atol=1e-14)
    beyond = rk.closed.planar_rp((3.0, 4.0), limits=chain)  # beyond the stroke: returned, marked outside
    assert len(beyond) == 2 and not beyond.within_limits.any() and len(beyond.only_within_limits()) == 0
    origin = rk.closed.planar_rp((0.0, 0.0))
    assert origin.singular and len(origin) == 1


# --- the IK course, example 2: planar 3R with phi --------------------------------------------------

@pytest.mark.parametrize("method", ["algebraic", "geometric"])
def test_planar_3r_two_postures_reach_the_pose(method):
    a = (1.0, 0.8, 0.5)
    chain = rk.robots.planar_3r(*a)
    rng = np.random.default_rng(1)
    for _ in range(200):
        q = rng.uniform(-math.pi, math.pi, 3)
        pose = planar_pose(chain, q)
        s = rk.closed.planar_3r(pose, *a, method=method)
        assert len(s) == 2 and set(s.postures) == {"elbow up", "elbow down"}
        for qq, label in zip(s.q, s.postures):
            got = planar_pose(chain, qq)
            assert np.allclose(got[:2], pose[:2], atol=1e-12)
            assert abs(math.remainder(got[2] - pose[2], 2 * math.pi)) < 1e-12
            # the IK course: elbow down is theta2 in (0, pi), elbow up theta2 in (-pi, 0)
            assert (qq[1] > 0) == (label == "elbow down")
        assert wrapped_distance(s.q, q).min() < 1e-8  # the configuration we started from is one of them


def test_planar_3r_algebraic_and_geometric_methods_agree():
    a = (1.0, 0.8, 0.5)
    chain = rk.robots.planar_3r(*a)
    rng = np.random.default_rng(2)
    for _ in range(50):
        pose = planar_pose(chain, rng.uniform(-math.pi, math.pi, 3))
        alg = rk.closed.planar_3r(pose, *a)
        geo = rk.closed.planar_3r(pose, *a, method="geometric")
        assert alg.postures == geo.postures
        assert np.all(wrapped_distance(alg.q, geo.q) < 1e-9)


@pytest.mark.parametrize("method", ["algebraic", "geometric"])
def test_planar_3r_singular_and_unreachable(method):
    chain = rk.robots.planar_3r(1.0, 1.0, 1.0)
    # s2 = 0 stretched out: one solution
    s = rk.closed.planar_3r((3.0, 0.0, 0.0), method=method)
    assert len(s) == 1 and s.singular and s.postures == ["elbow straight"]
    assert np.allclose(planar_pose(chain, s.q[0]), (3.0, 0.0, 0.0), atol=1e-12)
    # s2 = 0 folded back on itself with a1 = a2: W at the origin, theta1 free
    s = rk.closed.planar_3r((1.0, 0.0, 0.0), method=method)
    assert len(s) == 1 and s.singular and s.postures == ["elbow folded"]
    assert np.allclose(planar_pose(chain, s.q[0]), (1.0, 0.0, 0.0), atol=1e-12)
    # beyond reach: empty, no exception
    assert len(rk.closed.planar_3r((3.5, 0.0, 0.0), method=method)) == 0
    # inside the inner hole (|a1 - a2| > |p_W|) of an arm with unequal links
    assert len(rk.closed.planar_3r((0.1 + 0.5, 0.0, 0.0), 1.0, 0.5, 0.5, method=method)) == 0


def test_planar_3r_joint_limits_mark_the_postures():
    limits = (np.array([-math.pi, 0.0, -math.pi]), np.array([math.pi, math.pi, math.pi]))
    s = rk.closed.planar_3r((1.5, 0.5, 0.3), limits=limits)
    assert s.postures == ["elbow down", "elbow up"] and s.within_limits.tolist() == [True, False]
    assert s.q[1, 1] < 0  # elbow up: theta2 < 0, below joint 2's lower limit
    assert s.only_within_limits().postures == ["elbow down"]
    chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 3, limits=limits)
    assert rk.closed.planar_3r((1.5, 0.5, 0.3), limits=chain).within_limits.tolist() == [True, False]


def test_planar_2r():
    chain = rk.Chain.from_dh([(0.7, 0, 0, 0, "R"), (0.4, 0, 0, 0, "R")])
    s = rk.closed.planar_2r((0.5, 0.6), 0.7, 0.4)
    assert len(s) == 2
    for q in s.q:
        assert np.allclose(chain.fk(q)[:2, 3], [0.5, 0.6], atol=1e-14)
    assert len(rk.closed.planar_2r((1.2, 0.0), 0.7, 0.4)) == 0
    assert len(rk.closed.planar_2r((0.2, 0.0), 0.7, 0.4)) == 0
    assert len(rk.closed.planar_2r((1.1, 0.0), 0.7, 0.4)) == 1


# --- the anthropomorphic arm: 4 postures ------------------------------------------------------

def test_anthropomorphic_four_postures():
    a2, a3, d1 = 0.5, 0.4, 0.3
    chain = anthropomorphic_chain(a2, a3, d1)
    rng = np.random.default_rng(3)
    for _ in range(100):
        q = rng.uniform(-math.pi, math.pi, 3)
        p = chain.fk(q)[:3, 3]
        s = rk.closed.anthropomorphic(p, a2, a3, d1)
        assert len(s) == 4 and len(set(s.postures)) == 4
        for qq in s.q:
            assert np.allclose(chain.fk(qq)[:3, 3], p, atol=1e-12)
        assert wrapped_distance(s.q, q).min() < 1e-8
    assert len(rk.closed.anthropomorphic((1.0, 0.0, 0.3), a2, a3, d1)) == 0


def test_anthropomorphic_elbow_up_is_above_the_shoulder_wrist_line():
    a2, a3 = 0.5, 0.4
    chain = anthropomorphic_chain(a2, a3)
    s = rk.closed.anthropomorphic((0.6, 0.1, 0.2), a2, a3)
    for q, label in zip(s.q, s.postures):
        elbow = chain.frames(q)[2][:3, 3]
        wrist = np.array([0.6, 0.1, 0.2])
        t = np.dot(elbow, wrist) / np.dot(wrist, wrist)
        above = elbow[2] > t * wrist[2]
        assert above == ("elbow up" in label), label


def test_anthropomorphic_wrist_on_the_shoulder_axis_is_singular():
    chain = anthropomorphic_chain(0.5, 0.4)
    s = rk.closed.anthropomorphic((0.0, 0.0, 0.6), 0.5, 0.4)
    assert s.singular and len(s) == 2
    for q in s.q:
        assert np.allclose(chain.fk(q)[:3, 3], [0, 0, 0.6], atol=1e-12)


# --- 6R with a spherical wrist: the PUMA 560, 8 solutions ----------------------------------------

def test_puma560_eight_solutions_by_fk():
    puma = rk.robots.puma560()
    lo, hi = puma.limits
    rng = np.random.default_rng(4)
    for _ in range(300):
        q = rng.uniform(lo, hi)
        T = puma.fk(q)
        s = rk.closed.puma560(T, limits=None)
        assert len(s) == 8 and len(set(s.postures)) == 8
        for qq in s.q:
            assert np.abs(puma.fk(qq) - T).max() < 1e-10
            assert np.abs(puma._fk_kdl(qq) - T).max() < 1e-10
        assert wrapped_distance(s.q, q).min() < 1e-7
        # with the PUMA's limits: the same 8, those marked within them within them, the start
        # configuration among those
        lim = rk.closed.puma560(T)
        assert lim.postures == s.postures and np.all(wrapped_distance(lim.q, s.q) < 1e-12)
        inside = lim.only_within_limits()
        assert 1 <= len(inside) == lim.within_limits.sum()
        assert np.all(inside.q >= lo) and np.all(inside.q <= hi)
        assert wrapped_distance(inside.q, q).min() < 1e-7  # joint 6 spans more than 2 pi: one representative


def test_puma560_postures_by_geometry():
    """The labels against each solution's geometry: "wrist no flip" has sin q5 > 0 and its flip is
    the same arm with (q4 + pi, -q5, q6 + pi); "elbow up" has the elbow (origin of frame 2) above
    the line from the shoulder to the wrist centre (origin of frame 4), in frame 1, whose y axis is
    the base's z."""
    puma = rk.robots.puma560()
    lo, hi = puma.limits
    rng = np.random.default_rng(11)
    for _ in range(200):
        T = puma.fk(rng.uniform(lo, hi))
        s = rk.closed.puma560(T, limits=None)
        assert len(s) == 8
        by_label = dict(zip(s.postures, s.q))
        for q, label in zip(s.q, s.postures):
            assert (math.sin(q[4]) > 0) == ("wrist no flip" in label), label
            if "wrist no flip" in label:
                flip = by_label[label.replace("wrist no flip", "wrist flip")]
                assert np.array_equal(flip[:3], q[:3])
                assert wrapped_distance(flip[3:], q[3:] * [1, -1, 1] + [math.pi, 0, math.pi]) < 1e-12
            f = puma.frames(q)
            inv = np.linalg.inv(f[1])
            e = (inv @ f[2][:, 3])[:2]
            w = (inv @ f[4][:, 3])[:2]
            above = e[1] - w[1] / w[0] * e[0]
            if abs(above) > 1e-6:
                assert (above > 0) == ("elbow up" in label), label


def test_puma560_wrist_singularity_and_unreachable():
    puma = rk.robots.puma560()
    q = np.array([0.3, 0.2, -0.4, 0.5, 0.0, 0.7])
    T = puma.fk(q)
    s = rk.closed.puma560(T, limits=None)
    assert s.singular and len(s) == 8
    for qq in s.q:
        assert np.abs(puma.fk(qq) - T).max() < 1e-10
    far = np.eye(4)
    far[:3, 3] = (2.0, 0.0, 0.0)
    assert len(rk.closed.puma560(far)) == 0
    # inside the shoulder offset cylinder: sqrt(px^2 + py^2) < d3
    near = np.eye(4)
    near[:3, 3] = (0.05, 0.0, 0.3)
    assert len(rk.closed.puma560(near)) == 0


def test_spherical_wrist_with_tool_offset_and_base_height():
    g = dict(d1=0.3, a2=0.5, a3=0.05, d3=0.1, d4=0.45, d6=0.08)
    rows = [(0, math.pi / 2, g["d1"], 0, "R"), (g["a2"], 0, 0, 0, "R"), (g["a3"], -math.pi / 2, g["d3"], 0, "R"),
            (0, math.pi / 2, g["d4"], 0, "R"), (0, -math.pi / 2, 0, 0, "R"), (0, 0, g["d6"], 0, "R")]
    chain = rk.Chain.from_dh(rows)
    rng = np.random.default_rng(5)
    for _ in range(50):
        T = chain.fk(rng.uniform(-math.pi, math.pi, 6))
        s = rk.closed.spherical_wrist_6r(T, **g)
        assert len(s) == 8
        for qq in s.q:
            assert np.abs(chain.fk(qq) - T).max() < 1e-10


def test_nearest_solution():
    puma = rk.robots.puma560()
    q = np.array([0.1, 0.4, -0.3, 0.2, 0.5, -0.1])
    s = rk.closed.puma560(puma.fk(q))
    k = s.nearest(q + 0.01)
    assert np.allclose(s.q[k], q, atol=1e-9)
    far = np.eye(4)
    far[0, 3] = 5.0
    assert rk.closed.puma560(far).nearest(q) is None


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="target"):
        rk.closed.planar_3r((1.0, 2.0))
    with pytest.raises(ValueError, match="target"):
        rk.closed.planar_2r((np.nan, 0.0))
    with pytest.raises(ValueError, match="a1"):
        rk.closed.planar_2r((0.5, 0.0), a1=-1.0)
    with pytest.raises(ValueError, match="method"):
        rk.closed.planar_3r((1.0, 0.0, 0.0), method="magic")
    with pytest.raises(ValueError, match="limits"):
        rk.closed.planar_3r((1.0, 0.0, 0.0), limits=([0, 0], [1, 1]))
    with pytest.raises(ValueError, match="target"):
        rk.closed.puma560(np.ones((4, 4)))


def test_puma560_path_keeps_its_branch():
    puma = rk.robots.puma560()
    q_start = np.array([0.3, 0.5, -0.8, 2.9, 0.6, 3.0])  # q4, q6 near pi: wrapping must not jump
    T0 = puma.fk(q_start)
    K = 200
    targets = np.repeat(T0[None], K, axis=0)
    targets[:, 1, 3] += np.linspace(0.0, 0.1, K)
    q, ok, reachable = rk.closed.puma560_path(targets, q_start)
    assert ok.all() and reachable.all()
    for k in range(K):
        assert np.abs(puma.fk(q[k]) - targets[k]).max() < 1e-10
    assert np.abs(np.diff(np.vstack([q_start, q]), axis=0)).max() < 0.05
    # From each of the start pose's postures the path stays in that posture (never a jump).
    starts = rk.closed.puma560(T0, limits=None).q
    assert len(starts) == 8
    for start in starts:
        q, ok, _ = rk.closed.puma560_path(targets[:20], start, limits=None)
        assert ok.all() and np.abs(np.diff(np.vstack([start, q]), axis=0)).max() < 0.05, start
    # an unreachable frame keeps the previous joints and says so
    far = targets.copy()
    far[100, 0, 3] = 3.0
    q2, ok2, reachable2 = rk.closed.puma560_path(far, q_start)
    assert not ok2[100] and ok2.sum() == K - 1 and np.array_equal(q2[100], q2[99])
    assert np.array_equal(reachable2, ok2)


def test_puma560_path_shifts_whole_turns_towards_far_previous_joints():
    """Unlimited joints follow the previous joints by whole turns, computed in one step: a far-away
    q0 (1e17 rad) returns at once with finite joints instead of stepping 2 pi at a time. The shift
    stops at 2^20 rad, where a double still holds the angle to 1.2e-10 rad: the joints reach the
    target (at 1e9 a double keeps only 1e-7 rad, at 1e17 nothing of the angle)."""
    puma = rk.robots.puma560()
    q = np.array([0.3, 0.4, -0.5, 0.4, 0.5, 0.6])
    T = puma.fk(q)[None]
    turns = np.array([3, -2, 0, 5, 1, -4])
    path, ok, _ = rk.closed.puma560_path(T, q + 2 * np.pi * turns + 0.01, limits=None)
    assert ok[0]
    np.testing.assert_allclose(path[0], q + 2 * np.pi * turns, atol=1e-9)
    for q0 in (1e9, 1e17):
        path, ok, _ = rk.closed.puma560_path(T, np.full(6, q0), limits=None)
        assert ok[0] and np.all(np.abs(path[0]) <= 2.0**20) and np.all(path[0] > 2.0**20 - 2 * np.pi)
        np.testing.assert_allclose(puma.fk(path[0]), T[0], atol=1e-9)
