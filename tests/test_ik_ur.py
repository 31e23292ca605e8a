"""rk.closed.ur: the UR family's closed form.

Truth: the textbook DH product of tests/dh_reference.py (not the core's forward model), the joints
each target was made from, and the numerical IK (rk.ik_batch, Levenberg-Marquardt from many random
starts): every distinct solution it finds must be one of the closed form's.
The DH tables are Universal Robots' published ones ("DH parameters for calculations of
kinematics and dynamics of UR robots", universal-robots.com support article).
"""

import math
import pickle
import re

import numpy as np
import pytest

import robokin as rk
from dh_reference import fk_dh

P = math.pi
#: d1, a2, a3, d4, d5, d6 (UR's published tables).
UR_TABLES = {
    "ur3": (0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819),
    "ur5": (0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823),
    "ur10": (0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922),
    "ur3e": (0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921),
    "ur5e": (0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996),
    "ur10e": (0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655),
}


def rows_of(t):
    d1, a2, a3, d4, d5, d6 = t
    return [(0.0, P / 2, d1, 0.0, "R"), (a2, 0.0, 0.0, 0.0, "R"), (a3, 0.0, 0.0, 0.0, "R"),
            (0.0, P / 2, d4, 0.0, "R"), (0.0, -P / 2, d5, 0.0, "R"), (0.0, 0.0, d6, 0.0, "R")]


def fk_ref(t, q):
    return fk_dh(rows_of(t), q)


def as_dict(t):
    return dict(zip(("d1", "a2", "a3", "d4", "d5", "d6"), t))


def angle_dist(q1, q2):
    return np.max(np.abs(np.remainder(np.asarray(q1) - np.asarray(q2) + P, 2 * P) - P), axis=-1)


def assert_all_reach(t, sols, T, tol=1e-10):
    for q in sols.q:
        F = fk_ref(t, q)
        assert np.linalg.norm(F[:3, 3] - T[:3, 3]) < tol
        assert np.max(np.abs(F[:3, :3] - T[:3, :3])) < tol


@pytest.mark.parametrize("name", sorted(UR_TABLES))
def test_eight_solutions_each_verified_and_the_source_among_them(name, rng):
    """Up to 8: a pose may have 2, 4 or 6 (the wrist flip moves origin 4, which may leave the
    reach of the 2R arm of joints 2, 3; the numerical IK test below shows none is missed)."""
    t = UR_TABLES[name]
    counts = []
    for _ in range(60):
        q0 = rng.uniform(-P, P, 6)
        T = fk_ref(t, q0)
        s = rk.closed.ur(T, as_dict(t))
        assert not s.singular
        assert len(s) in (2, 4, 6, 8)
        counts.append(len(s))
        assert len(set(s.postures)) == len(s) and set(s.postures) <= set(rk.closed.UR_POSTURES)
        assert_all_reach(t, s, T)
        assert np.min(angle_dist(s.q, q0)) < 1e-8
        # distinct joint vectors
        d = angle_dist(s.q[:, None, :], s.q[None, :, :])
        assert np.all(d[~np.eye(len(s), dtype=bool)] > 1e-6)
    assert counts.count(8) > 30


def test_catalogue_ur5_chain_and_its_limits(rng):
    chain = rk.robots.ur5()
    t = UR_TABLES["ur5"]
    for _ in range(30):
        q0 = rng.uniform(-P, P, 6)
        T = chain.fk(q0)
        s = rk.closed.ur(T, chain)
        assert len(s) in (2, 4, 6, 8)
        assert np.min(angle_dist(s.q, q0)) < 1e-8
        assert_all_reach(t, s, T)
        lo, hi = chain.limits
        assert np.all(s.q >= lo) and np.all(s.q <= hi)


def test_labels_match_the_geometry(rng):
    """shoulder left: wrist centre on the -x1 side; elbow up: elbow above the shoulder-wrist line;
    wrist no flip: q5 in [0, pi] -- recomputed here from the frames of the reference DH."""
    t = UR_TABLES["ur5"]
    rows = rows_of(t)
    for _ in range(20):
        T = fk_ref(t, rng.uniform(-P, P, 6))
        s = rk.closed.ur(T, as_dict(t), limits=None)
        assert len(s) >= 2
        for q, label in zip(s.q, s.postures):
            A = [np.eye(4)]
            for r, qi in zip(rows, q):
                A.append(A[-1] @ fk_dh([r], [qi]))
            F1, F2, F3, F4, F5 = A[1], A[2], A[3], A[4], A[5]
            x1 = F1[:3, 0]
            wrist = F5[:3, 3] - F1[:3, 3]
            assert ("shoulder left" in label) == (np.dot(wrist, x1) < 0)
            # In frame 1 (y1 is the vertical): shoulder (0,0), elbow E, origin 4 W.
            E = (F1[:3, :3].T @ (F2[:3, 3] - F1[:3, 3]))[:2]  # the elbow: origin of frame 2
            W = (F1[:3, :3].T @ (F4[:3, 3] - F1[:3, 3]))[:2]
            above = E[1] > W[1] * E[0] / W[0] if W[0] != 0 else E[0] < 0
            assert ("elbow up" in label) == above
            assert ("wrist no flip" in label) == (np.sin(q[4]) >= 0)


def test_complete_against_numerical_ik_with_restarts(rng):
    """Every distinct solution that LM finds from 48 random starts is in the closed-form set; a few
    hundred poses here (10,000 were run by hand once, see the issue's report)."""
    t = UR_TABLES["ur5"]
    chain = rk.Chain.from_dh(rows_of(t))
    poses, starts = 200, 48
    Q = rng.uniform(-P, P, (poses, 6))
    targets = chain.fk(Q)
    rep = np.repeat(targets, starts, axis=0)
    q0 = rng.uniform(-P, P, (poses * starts, 6))
    res = rk.ik_batch(chain, rep, q0, max_iter=200)
    found_total = 0
    for i in range(poses):
        s = rk.closed.ur(targets[i], chain, limits=None)
        assert len(s) >= 2
        sols = res.q[i * starts:(i + 1) * starts][res.success[i * starts:(i + 1) * starts]]
        distinct = []
        for q in sols:
            # LM stops at 1e-9 in the pose: near-singular solutions are only that close in joints
            assert np.min(angle_dist(s.q, q)) < 1e-4, (i, q, s)
            if not distinct or np.min(angle_dist(np.array(distinct), q)) > 1e-4:
                distinct.append(q)
        found_total += len(distinct)
    # the restarts do find several postures per pose (the check above has teeth)
    assert found_total > 4 * poses


def test_theta_offsets_tool_and_reversed_joint(rng):
    t = UR_TABLES["ur10"]
    d1, a2, a3, d4, d5, d6 = t
    offs = rng.uniform(-1, 1, 6)
    tool = np.eye(4)
    tool[:3, :3] = fk_dh([(0, 0.3, 0, 0.7, "R")], [0.0])[:3, :3]
    tool[:3, 3] = (0.01, -0.02, 0.05)
    rows = [(0.0, P / 2, d1, offs[0], "R"), (a2, 0.0, 0.0, offs[1], "R"), (a3, 0.0, 0.0, offs[2], "R"),
            (0.0, P / 2, d4, offs[3], "R"), (0.0, -P / 2, d5, offs[4], "R"), (0.0, 0.0, d6, offs[5], "R")]
    chain = rk.Chain.from_dh(rows, tool=tool)
    for _ in range(20):
        q0 = rng.uniform(-P, P, 6)
        T = chain.fk(q0)
        s = rk.closed.ur(T, chain)
        assert len(s) in (2, 4, 6, 8)
        assert np.min(angle_dist(s.q, q0)) < 1e-8
        for q in s.q:
            F = fk_dh(rows, q) @ tool
            assert np.allclose(F, T, atol=1e-10, rtol=0)


def test_singular_cases_are_flagged_and_verified():
    t = UR_TABLES["ur5"]
    d = as_dict(t)
    # wrist singular: q5 = 0 (axes 2, 3, 4, 6 parallel): one representative per elbow on that
    # shoulder (the other shoulder's axis 2 is not parallel to axis 6: its wrist is regular)
    q = np.array([0.3, -1.0, 1.2, 0.4, 0.0, 0.5])
    T = fk_ref(t, q)
    s = rk.closed.ur(T, d)
    singular = [p for p in s.postures if "wrist singular" in p]
    assert s.singular and 1 <= len(singular) <= 2 and len(s) <= 6
    assert all(p.startswith(singular[0].split(",")[0]) for p in singular)
    assert_all_reach(t, s, T, 1e-9)
    # the continuum: q2 + q3 + q4 + q6 fixed; the representative is another point of it
    rep = s.q[s.postures.index(singular[0])]
    assert abs(rep[4]) < 1e-9 or abs(abs(rep[4]) - P) < 1e-9
    # shoulder singular: a2 c2 + a3 c23 + d5 s234 = 0 (the wrist centre |d4| from axis 1)
    d1_, a2, a3, d4, d5, d6 = t
    q2, q3 = P / 2, 0.2
    q4 = math.asin(-(a2 * math.cos(q2) + a3 * math.cos(q2 + q3)) / d5) - q2 - q3
    q = np.array([0.2, q2, q3, q4, 0.7, 0.1])
    T = fk_ref(t, q)
    s = rk.closed.ur(T, d)
    assert s.singular and len(s) in (2, 4)  # the two shoulders coincide: half the postures
    assert all("shoulder singular" in p for p in s.postures)
    assert_all_reach(t, s, T, 1e-9)
    # elbow straight: q3 = 0
    q = np.array([0.2, -0.8, 0.0, 0.3, 0.7, 0.1])
    T = fk_ref(t, q)
    s = rk.closed.ur(T, d)
    assert s.singular and 2 <= len(s) < 8
    assert any("elbow straight" in p for p in s.postures)
    assert_all_reach(t, s, T, 1e-9)
    assert np.min(angle_dist(s.q, q)) < 1e-6


@pytest.mark.parametrize("a1", [0.0, 0.9e-9])
def test_every_solution_is_verified_by_the_chains_forward_model(a1, rng):
    """A UR3 scaled to 1/100 with a1 = 0.9e-9 m: the UR reading admits it (its layout tolerance is
    1e-9 m for arms under 1 m) but its closed form ignores a1, so its candidates miss by ~9e-10 m,
    75 times the verified tolerance (1e-9 x the arm's size): the forward-model check must drop them
    all. With a1 = 0 every target is solved, each solution within that tolerance."""
    t = tuple(0.01 * v for v in UR_TABLES["ur3"])
    rows = rows_of(t)
    rows[0] = (a1,) + rows[0][1:]
    chain = rk.Chain.from_dh(rows)
    size = a1 + sum(abs(v) for v in t)
    count = 0
    for _ in range(20):
        q = rng.uniform(-P, P, 6)
        T = fk_dh(rows, q)
        s = rk.closed.ur(T, chain, limits=None)
        for row in s.q:
            F = fk_dh(rows, row)
            assert np.linalg.norm(F[:3, 3] - T[:3, 3]) <= 1.01e-9 * size
            assert np.max(np.abs(F[:3, :3] - T[:3, :3])) <= 1e-8
        count += len(s)
    if a1 == 0:
        assert count >= 20 * 2


def test_out_of_reach_is_empty():
    T = np.eye(4)
    T[:3, 3] = (2.0, 0.0, 0.1)
    s = rk.closed.ur(T, rk.robots.ur5())
    assert len(s) == 0 and s.q.shape == (0, 6)


def test_limits_mark_the_solutions(rng):
    chain = rk.robots.ur5()
    T = chain.fk(rng.uniform(-P, P, 6))
    full = rk.closed.ur(T, chain, limits=None)
    assert full.within_limits.all()
    lo, hi = np.full(6, -P), np.full(6, P)
    lo[1], hi[1] = -P, 0.0
    marked = rk.closed.ur(T, chain, limits=(lo, hi))
    assert marked.postures == full.postures and np.all(angle_dist(marked.q, full.q) < 1e-12)
    part = marked.only_within_limits()
    assert 0 < len(part) < len(full)
    assert np.all(part.q[:, 1] <= 0.0) and np.all(marked.q[~marked.within_limits, 1] > 0.0)


def test_batch_equals_single_calls(rng):
    chain = rk.robots.ur5()
    Q = rng.uniform(-P, P, (300, 6))
    Q[:3, 4] = 0.0  # a few wrist-singular poses
    targets = chain.fk(Q)
    targets[5, 0, 3] = 5.0  # unreachable
    q, singular, within = rk.closed.ur_batch(targets, chain)
    assert q.shape == (300, 8, 6) and singular.shape == (300,) and within.shape == (300, 8)
    assert np.array_equal(within, ~np.isnan(q[:, :, 0]))  # the UR5's limits (+-2 pi) hold every solution
    names = list(rk.closed.UR_POSTURES)
    for i in range(300):
        s = rk.closed.ur(targets[i], chain)
        assert singular[i] == s.singular
        rows = q[i][~np.isnan(q[i, :, 0])]
        assert len(rows) == len(s)
        if not s.singular:
            for sq, p in zip(s.q, s.postures):
                np.testing.assert_array_equal(q[i, names.index(p)], sq)
    assert np.all(np.isnan(q[5]))


def test_not_a_ur_arm_and_bad_arguments():
    with pytest.raises(ValueError, match="robot"):
        rk.closed.ur(np.eye(4), rk.robots.puma560())
    with pytest.raises(ValueError, match="robot"):
        rk.closed.ur(np.eye(4), {"d1": 1.0})
    with pytest.raises(ValueError, match="robot"):
        rk.closed.ur(np.eye(4), dict(as_dict(UR_TABLES["ur5"]), a2=math.nan))
    with pytest.raises(ValueError, match="target"):
        rk.closed.ur(np.zeros((3, 3)), rk.robots.ur5())
    with pytest.raises(ValueError, match="targets"):
        rk.closed.ur_batch(np.zeros((2, 3, 3)), rk.robots.ur5())
    with pytest.raises(ValueError, match="limits"):
        rk.closed.ur(np.eye(4), rk.robots.ur5(), limits="abc")


@pytest.mark.parametrize("v", [1.1920929e-07, -1.1920929e-07, 3e-8])
def test_ur_a_hair_off_the_wrist_and_elbow_singularities_finds_its_source(v):
    """Every joint a hair off 0 (wrist and elbow nearly singular at once): the closed form's
    rotations take the DH rows' cos(pi/2) (6e-17) as the chain has it. With an exact 0 there, q234
    (from two entries of size ~1e-7) moved by ~1e-9, and the nearly stretched elbow came out of
    reach: no solution at all for -1.2e-7."""
    ur5 = rk.robots.ur5()
    q = np.full(6, v)
    T = ur5.fk(q)
    s = rk.closed.ur(T, ur5, limits=None)
    assert len(s) >= 1
    for row in s.q:
        assert np.abs(ur5.fk(row) - T).max() < 1e-9
    d = np.remainder(s.q - q + np.pi, 2 * np.pi) - np.pi
    assert np.min(np.max(np.abs(d), axis=1)) < 1e-6


@pytest.mark.parametrize("v", [1.1920929e-07, -1.1920929e-07, 3e-8])
def test_puma560_a_hair_off_the_wrist_singularity_finds_its_source(v):
    """The PUMA's twin of the test above (its R03 takes the rows' cos(+-pi/2) as well)."""
    puma = rk.robots.puma560()
    q = np.array([0.3, 0.2, -0.4, 0.5, v, 0.7])
    T = puma.fk(q)
    s = rk.closed.puma560(T, limits=None)
    assert len(s) >= 1
    for row in s.q:
        assert np.abs(puma.fk(row) - T).max() < 1e-9
    d = np.remainder(s.q - q + np.pi, 2 * np.pi) - np.pi
    assert np.min(np.max(np.abs(d[:, :3]), axis=1)) < 1e-6


@pytest.mark.parametrize("q5", [1e-9, -1e-8, 1e-7, 1e-6])
@pytest.mark.parametrize("q3", [0.0, P])
@pytest.mark.parametrize("name", ["ur5", "ur10e"])
def test_elbow_straight_or_folded_near_the_wrist_singularity_finds_its_source(name, q3, q5):
    """Elbow straight (q3 = 0) or folded (pi) and joint 5 within 1e-6 of 0: q234, from two rotation
    entries of size |sin q5|, is known only to ~1e-16 / |sin q5|, and the origin 4 it gave fell a
    hair out of the planar 2R's reach, or a hair inside it. The pose's own solution was lost (UR5 at
    q = (0, 2, 0, 0, 1e-6, 0): only the other shoulder's two came back) or came back with the elbow
    bent by ~1e-4; now q234 is moved onto the reach's edge within that uncertainty, and the solution
    is checked like every other."""
    t = UR_TABLES[name]
    for q in ([0.0, 2.0, q3, 0.0, q5, 0.0], [0.4, -1.1, q3, 0.7, q5, -0.3], [-2.0, 0.5, q3, -1.4, q5, 2.5]):
        q = np.array(q)
        T = fk_ref(t, q)
        s = rk.closed.ur(T, as_dict(t))
        assert_all_reach(t, s, T, 1e-9)
        assert np.min(angle_dist(s.q, q)) < 1e-6, (q, s.postures)


def test_random_poses_near_the_wrist_and_elbow_singularities_find_their_source():
    """500 random UR5 poses with the elbow straight or folded and |q5| from 1e-9.9 (just above the
    wrist's singular threshold, 1e-10) to 1e-3: each finds its source within 1e-6 (before, 74 %
    did not: 28 % lost their posture, the others came back bent by up to 1e-2)."""
    t, rng = UR_TABLES["ur5"], np.random.default_rng(11)
    for _ in range(500):
        q = rng.uniform(-P, P, 6)
        q[2] = rng.choice([0.0, P])
        q[4] = rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-9.9, -3.0)
        T = fk_ref(t, q)
        s = rk.closed.ur(T, as_dict(t))
        assert_all_reach(t, s, T, 1e-9)
        assert np.min(angle_dist(s.q, q)) < 1e-6, q


def test_the_layout_is_read_from_the_geometry(rng):
    """The UR5 as its URDF describes it (joints about y, rotated frames), and with its elbow and
    first wrist joint turning the other way (axes 3 and 4 against axis 2: the reading's scale -1),
    are solved by the UR closed form itself (rk._core.ik_ur, no fallback): the same solutions and
    labels as the DH table's, q3 and q4 negated for the reversed arm."""
    from ur_urdf import UR5_URDF

    dh = rk.robots.ur5()
    urdf = rk.Chain.from_urdf(UR5_URDF, "base", "tool0")
    reversed_xml = UR5_URDF
    for name in ("elbow_joint", "wrist_1_joint"):
        head, tail = reversed_xml.split(f'<joint name="{name}"', 1)
        reversed_xml = head + f'<joint name="{name}"' + tail.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 -1 0"/>', 1)
    flipped = rk.Chain.from_urdf(reversed_xml, "base", "tool0")
    sign = np.array([1, 1, -1, -1, 1, 1])
    for q in rng.uniform(-P, P, (50, 6)):
        T = dh.fk(q)
        want = rk._core.ik_ur(T, dh, None)
        for chain, s in ((urdf, 1), (flipped, sign)):
            got = rk._core.ik_ur(T, chain, None)
            assert got.postures == want.postures
            assert np.max(angle_dist(got.q * s, want.q)) < 1e-9
            assert np.max(np.abs(chain.fk(got.q) - T)) < 1e-9


@pytest.mark.parametrize("rows, why", [
    ("puma", "axes 2, 3, 4 are not parallel"),
    ([(0.01, P / 2, 0.1, 0, "R")], "axes 1 and 2 do not meet"),
    ([(0.0, 1.2, 0.1, 0, "R")], "axes 1 and 2 are not perpendicular"),
    ([None, None, None, (0.02, P / 2, 0.1, 0, "R")], "axes 4 and 5 do not meet"),
    ([None, None, None, None, (0.0, -1.0, 0.1, 0, "R")], "axes 5 and 6 are not perpendicular"),
    ([None, (0.4, 0.0, 0.0, 0, "R"), (0.0, 0.0, 0.0, 0, "R")], "axes 2, 3, 4 do not stand apart"),
    ([None, None, (0.4, 0.0, 0.0, 0, "P")], "joint 3 is prismatic"),
    ("5 joints", "it has 5 joints, not 6"),
])
def test_not_the_ur_layout_says_what_differs(rows, why):
    table = rows_of(UR_TABLES["ur5"])
    if rows == "puma":
        chain = rk.robots.puma560()
    elif rows == "5 joints":
        chain = rk.Chain.from_dh(table[:5])
    else:
        chain = rk.Chain.from_dh([r if r is not None else table[i] for i, r in enumerate(rows)] + table[len(rows):])
    with pytest.raises(ValueError, match=re.escape(f"robot: not an arm of the UR layout ({why}")):
        rk._core.ik_ur(np.eye(4), chain, None)


def test_batch_and_path_results_are_named_and_read_as_their_tuples():
    """ur_batch's ClosedBatch and puma560_path's ClosedPath: fields by name, the same arrays when
    unpacked or indexed (the tuples they replaced), pickled whole."""
    ur5 = rk.robots.ur5()
    T = ur5.fk(np.array([[0.3, -1.0, 1.2, 0.4, 0.5, 0.6]] * 4))
    b = rk.closed.ur_batch(T, ur5)
    q, singular, within = b
    assert q is b.q and singular is b.singular and within is b.within_limits and len(b) == 3
    assert b[0] is b.q and b[-1] is b.within_limits
    assert b.q.shape == (4, 8, 6) and b.singular.shape == (4,) and b.within_limits.shape == (4, 8)
    again = pickle.loads(pickle.dumps(b))
    assert np.array_equal(again.q, b.q, equal_nan=True) and np.array_equal(again.within_limits, b.within_limits)
    puma = rk.robots.puma560()
    p = rk.closed.puma560_path(puma.fk(np.linspace(0.1, 0.3, 5)[:, None] * np.ones(6)), np.zeros(6))
    q, ok, reachable = p
    assert (q, ok, reachable) == (p.q, p.ok, p.reachable) and p[1] is p.ok and p.ok.all() and p.reachable.all()
    assert np.abs(puma.fk(p.q) - puma.fk(np.linspace(0.1, 0.3, 5)[:, None] * np.ones(6))).max() < 1e-9
    assert type(pickle.loads(pickle.dumps(p))) is rk.closed.ClosedPath
