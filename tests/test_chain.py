"""Serial chains: FK and Jacobians against the seeds' closed forms, numpy DH products, finite
differences and KDL's own solvers."""

import math

import numpy as np
import pytest

import robokin as rk
from dh_reference import fk_dh, numeric_jacobian, rot_x, rot_z, trans

PI = math.pi
L1, L3 = 1.5, 1.0

# Published tables, written here independently of rk.robots.
UR5_ROWS = [
    (0, PI / 2, 0.089159, 0, "R"),
    (-0.425, 0, 0, 0, "R"),
    (-0.39225, 0, 0, 0, "R"),
    (0, PI / 2, 0.10915, 0, "R"),
    (0, -PI / 2, 0.09465, 0, "R"),
    (0, 0, 0.0823, 0, "R"),
]
PUMA_ROWS = [
    (0, PI / 2, 0, 0, "R"),
    (0.4318, 0, 0, 0, "R"),
    (0.0203, -PI / 2, 0.15005, 0, "R"),
    (0, PI / 2, 0.4318, 0, "R"),
    (0, -PI / 2, 0, 0, "R"),
    (0, 0, 0, 0, "R"),
]


def rpr_tip(q):
    """Seed 000, eq. (1)."""
    t1, t2, t3 = q[..., 0], q[..., 1], q[..., 2]
    return np.stack(
        [(L1 + t2) * np.cos(t1) + L3 * np.cos(t1 + t3), (L1 + t2) * np.sin(t1) + L3 * np.sin(t1 + t3)], axis=-1
    )


def rpr_jacobian(q):
    """Seed 000, annex eq. (9)."""
    t1, t2, t3 = q
    return np.array(
        [
            [-(L1 + t2) * np.sin(t1) - L3 * np.sin(t1 + t3), np.cos(t1), -L3 * np.sin(t1 + t3)],
            [(L1 + t2) * np.cos(t1) + L3 * np.cos(t1 + t3), np.sin(t1), L3 * np.cos(t1 + t3)],
        ]
    )


def random_q(rng, chain, n=None):
    lo, hi = chain.limits
    lo, hi = np.maximum(lo, -PI), np.minimum(hi, PI)
    size = (chain.dof,) if n is None else (n, chain.dof)
    return rng.uniform(lo, hi, size=size)


# --- the RPR study's arm ---------------------------------------------------------------------


def test_rpr_fk_equals_seed_eq1(rng):
    chain = rk.robots.rpr()
    Q = random_q(rng, chain, 500)
    for q in Q[:50]:
        T = chain.fk(q)
        np.testing.assert_allclose(T[:2, 3], rpr_tip(q), atol=1e-12)
        phi = q[0] + q[2]
        np.testing.assert_allclose(T[:2, :2], [[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]], atol=1e-12)
    batch = chain.fk(Q)
    assert batch.shape == (500, 4, 4)
    np.testing.assert_allclose(batch[:, :2, 3], rpr_tip(Q), atol=1e-12)
    np.testing.assert_array_equal(batch[:, 3], np.tile([0, 0, 0, 1.0], (500, 1)))


def test_rpr_jacobian_equals_seed_annex_and_finite_differences(rng):
    chain = rk.robots.rpr()
    for q in random_q(rng, chain, 30):
        J = chain.jacobian(q, task="xy")
        np.testing.assert_allclose(J, rpr_jacobian(q), atol=1e-12)
        np.testing.assert_allclose(chain.jacobian(q), numeric_jacobian(chain.fk, q), atol=1e-7)


# --- the DH exercise's PRR ----------------------------------------------------------------------


def prr_T30(q, a2, a3):
    """Seed 004's T_3^0(q), q = (d1, theta2, theta3)."""
    d1, t2, t3 = q
    c23, s23 = np.cos(t2 + t3), np.sin(t2 + t3)
    return np.array(
        [
            [c23, -s23, 0, a3 * c23 + a2 * np.cos(t2)],
            [0, 0, -1, 0],
            [s23, c23, 0, a3 * s23 + d1 + a2 * np.sin(t2)],
            [0, 0, 0, 1],
        ]
    )


def test_prr_fk_equals_seed_T30(rng):
    a2, a3 = 0.7, 0.45
    chain = rk.robots.prr(a2, a3)
    assert chain.joint_types == "PRR"
    for q in rng.uniform(-2, 2, size=(30, 3)):
        np.testing.assert_allclose(chain.fk(q), prr_T30(q, a2, a3), atol=1e-12)


def test_prr_point_in_frames_1_and_2_equals_seed_question_3(rng):
    a2, a3 = 0.7, 0.45
    chain = rk.robots.prr(a2, a3)
    p3 = [0.0, -1.0, 0.0]
    for q in rng.uniform(-2, 2, size=(10, 3)):
        _, t2, t3 = q
        p1 = [np.sin(t2 + t3) + a3 * np.cos(t2 + t3) + a2 * np.cos(t2), -np.cos(t2 + t3) + a3 * np.sin(t2 + t3) + a2 * np.sin(t2), 0]
        p2 = [np.sin(t3) + a3 * np.cos(t3), -np.cos(t3) + a3 * np.sin(t3), 0]
        np.testing.assert_allclose(chain.point_in_frame(q, p3, frame=3, in_frame=1), p1, atol=1e-12)
        np.testing.assert_allclose(chain.point_in_frame(q, p3, frame=3, in_frame=2), p2, atol=1e-12)
        # In the base frame it is T_3^0 p^3.
        np.testing.assert_allclose(chain.point_in_frame(q, p3, frame=3), (prr_T30(q, a2, a3) @ [0, -1, 0, 1])[:3], atol=1e-12)


def test_prr_with_the_seeds_tool_frame(rng):
    Te3 = np.array([[0, 0, 1, 0], [-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, 0, 1.0]])
    rows = [(0, PI / 2, 0, 0, "P"), (0.7, 0, 0, 0, "R"), (0.45, 0, 0, 0, "R")]
    chain = rk.Chain.from_dh(rows, tool=Te3)
    q = rng.uniform(-1, 1, 3)
    np.testing.assert_allclose(chain.fk(q), prr_T30(q, 0.7, 0.45) @ Te3, atol=1e-12)
    np.testing.assert_allclose(chain.frames(q)[-1], chain.fk(q), atol=1e-15)


# --- published arms against an independent numpy product -----------------------------------


@pytest.mark.parametrize("robot,rows", [(rk.robots.ur5, UR5_ROWS), (rk.robots.puma560, PUMA_ROWS)])
def test_arm_fk_and_jacobian(robot, rows, rng):
    chain = robot()
    Q = random_q(rng, chain, 40)
    batch = chain.fk(Q)
    for q, T in zip(Q, batch):
        expected = fk_dh(rows, q)
        np.testing.assert_allclose(chain.fk(q), expected, atol=1e-12)
        np.testing.assert_allclose(T, expected, atol=1e-12)
    for q in Q[:10]:
        np.testing.assert_allclose(chain.jacobian(q), numeric_jacobian(chain.fk, q), atol=1e-7)


def test_frames_are_the_partial_products(rng):
    chain = rk.robots.puma560()
    q = random_q(rng, chain)
    F = chain.frames(q)
    assert F.shape == (7, 4, 4)
    np.testing.assert_array_equal(F[0], np.eye(4))
    for i in range(1, 7):
        np.testing.assert_allclose(F[i], fk_dh(PUMA_ROWS[:i], q[:i]), atol=1e-12)


def test_modified_dh_equals_craig_product(rng):
    rows = [(0.0, 0.0, 0.3, 0.1, "R"), (0.2, -PI / 2, 0.0, 0.0, "R"), (0.5, 0.3, 0.0, 0.2, "P"), (0.1, PI / 2, 0.4, 0.0, "R")]
    chain = rk.Chain.from_dh(rows, modified=True)
    for q in rng.uniform(-2, 2, size=(20, 4)):
        np.testing.assert_allclose(chain.fk(q), fk_dh(rows, q, modified=True), atol=1e-12)
        np.testing.assert_allclose(chain.jacobian(q), numeric_jacobian(chain.fk, q), atol=1e-7)
    F = chain.frames(q)
    for i in range(1, 5):
        np.testing.assert_allclose(F[i], fk_dh(rows[:i], q[:i], modified=True), atol=1e-12)


def random_rigid(rng):
    A = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    if np.linalg.det(A) < 0:
        A[:, 0] *= -1
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = A, rng.normal(size=3)
    return T


def test_fast_path_equals_kdl_on_random_chains(rng):
    """The specialised evaluation path against KDL's recursive solvers, on chains with arbitrary
    axes, fixed segments, prismatic joints, tools and DH offsets."""
    for _ in range(20):
        segments = []
        for _ in range(rng.integers(1, 8)):
            kind = rng.choice(["R", "P", "F"])
            segments.append((kind, rng.normal(size=3), random_rigid(rng)))
        if not any(s[0] != "F" for s in segments):
            segments.append(("R", rng.normal(size=3), random_rigid(rng)))
        chain = rk.Chain.from_segments(segments, tool=random_rigid(rng))
        for q in rng.uniform(-3, 3, size=(5, chain.dof)):
            np.testing.assert_allclose(chain.fk(q), chain._fk_kdl(q), atol=1e-12)
            np.testing.assert_allclose(chain.jacobian(q), chain._jacobian_kdl(q), atol=1e-12)
        rows = [(*rng.uniform(-1, 1, 4), rng.choice(["R", "P"])) for _ in range(rng.integers(1, 8))]
        for modified in (False, True):
            chain = rk.Chain.from_dh(rows, modified=modified, tool=random_rigid(rng))
            q = rng.uniform(-3, 3, chain.dof)
            np.testing.assert_allclose(chain.fk(q), chain._fk_kdl(q), atol=1e-12)
            np.testing.assert_allclose(chain.jacobian(q), chain._jacobian_kdl(q), atol=1e-12)


def test_tasks_select_jacobian_rows(rng):
    chain = rk.robots.ur5()
    q = random_q(rng, chain)
    J = chain.jacobian(q)
    np.testing.assert_array_equal(chain.jacobian(q, task="position"), J[:3])
    np.testing.assert_array_equal(chain.jacobian(q, task="xy"), J[:2])
    np.testing.assert_array_equal(chain.jacobian(q, task="xyphi"), J[[0, 1, 5]])
    Q = random_q(rng, chain, 4)
    Jb = chain.jacobian(Q, task="xyphi")
    assert Jb.shape == (4, 3, 6)
    np.testing.assert_array_equal(Jb[2], chain.jacobian(Q[2], task="xyphi"))


def test_limits():
    chain = rk.robots.rpr()
    lo, hi = chain.limits
    np.testing.assert_array_equal(lo, [0, 0, 0])
    np.testing.assert_array_equal(hi, [PI / 2, 1.5, PI])
    lo, hi = rk.robots.planar_3r().limits
    assert np.all(np.isneginf(lo)) and np.all(np.isposinf(hi))
    assert repr(chain) == "Chain(dof=3, joints='RPR')"


# --- bad input: a clear ValueError naming the argument ---------------------------------------


@pytest.mark.parametrize(
    "q, match",
    [
        ([0.1, 0.2], r"q: expected shape \(3,\) or \(N, 3\)"),
        (np.zeros((2, 4)), r"q: expected shape"),
        (np.zeros((2, 3, 1)), r"q: expected shape"),
        ([0.1, np.nan, 0.2], "q: contains NaN or inf"),
        ([0.1, np.inf, 0.2], "q: contains NaN or inf"),
    ],
)
def test_fk_rejects_bad_q(q, match):
    with pytest.raises(ValueError, match=match):
        rk.robots.rpr().fk(q)


@pytest.mark.parametrize(
    "q, match",
    [
        ("abc", "q: expected an array of numbers, got a string"),
        (None, "q: expected an array of numbers, got None"),
        (np.array([1 + 2j, 0, 0]), "q: expected real numbers, got a complex array"),
        ([object(), 0, 0], "q: expected an array of numbers"),
    ],
)
def test_fk_rejects_q_of_the_wrong_kind_with_a_type_error(q, match):
    with pytest.raises(TypeError, match=match):
        rk.robots.rpr().fk(q)


def test_bad_chain_definitions():
    with pytest.raises(ValueError, match="task: expected one of"):
        rk.robots.rpr().jacobian([0, 0, 0], task="orientation")
    with pytest.raises(ValueError, match=r"rows\[1\]: joint type must be one of RP, got 'X'"):
        rk.Chain.from_dh([(0, 0, 0, 0, "R"), (0, 0, 0, 0, "X")])
    with pytest.raises(ValueError, match=r"rows\[0\]: expected \(a, alpha, d, theta"):
        rk.Chain.from_dh([(0, 0, 0, "R")])
    with pytest.raises(ValueError, match=r"rows\[0\] a: must be finite"):
        rk.Chain.from_dh([(np.nan, 0, 0, 0, "R")])
    with pytest.raises(ValueError, match="rows: a chain needs at least one joint"):
        rk.Chain.from_dh([])
    with pytest.raises(ValueError, match="limits: joint 1 has its lower limit above its upper limit"):
        rk.Chain.from_dh([(1, 0, 0, 0, "R")] * 2, limits=([0, 1], [1, 0]))
    with pytest.raises(ValueError, match="limits: joint 0 has a NaN limit"):
        rk.Chain.from_dh([(1, 0, 0, 0, "R")], limits=([np.nan], [1]))
    with pytest.raises(ValueError, match="limits: expected"):
        rk.Chain.from_dh([(1, 0, 0, 0, "R")], limits=([0, 0], [1, 1]))
    with pytest.raises(ValueError, match="tool: not a rigid transform"):
        rk.Chain.from_dh([(1, 0, 0, 0, "R")], tool=2 * np.eye(4))
    with pytest.raises(ValueError, match=r"segments\[0\] axis: must not be zero"):
        rk.Chain.from_segments([("R", (0, 0, 0), np.eye(4))])
    # A value of the wrong kind is a TypeError, one out of range a ValueError; the first bad one is named.
    with pytest.raises(TypeError, match=r"^rows\[1\] alpha: expected a number, got str$"):
        rk.Chain.from_dh([(1, 0, 0, 0, "R"), (1, "0", 0, 0, "R"), (np.nan, 0, 0, 0, "R")])
    with pytest.raises(TypeError, match=r"^rows\[0\]: joint type must be a string, one of RP$"):
        rk.Chain.from_dh([(1, 0, 0, 0, 1)])
    with pytest.raises(TypeError, match=r"^rows: expected a sequence, got int$"):
        rk.Chain.from_dh(3)
    with pytest.raises(ValueError, match=r"^segments\[1\] tip: contains NaN or inf$"):
        rk.Chain.from_segments([("R", (0, 0, 1), np.eye(4)), ("R", (0, 0, 1), np.full((4, 4), np.nan))])
    with pytest.raises(ValueError, match=r"^segments\[0\] tip: not a rigid transform"):
        rk.Chain.from_segments([("R", (0, 0, 1), 2 * np.eye(4))])
    with pytest.raises(ValueError, match="chain needs at least one joint"):
        rk.Chain.from_segments([("F", (0, 0, 1), np.eye(4))])
    with pytest.raises(ValueError, match="in_frame: expected 0..3"):
        rk.robots.rpr().point_in_frame([0, 0, 0], [0, 0, 0], frame=3, in_frame=7)


def test_limits_must_admit_a_value():
    for lower, upper in (([np.inf], [np.inf]), ([-np.inf], [-np.inf])):
        with pytest.raises(ValueError, match="limits: joint 0 has no admissible value"):
            rk.Chain.from_dh([(1, 0, 0, 0, "R")], limits=(lower, upper))


def test_segment_axes_of_any_length_are_the_same_axis():
    """A segment's axis is a direction: any length gives the unit axis's chain (1e300 included, whose
    norm would overflow unscaled)."""
    def chain(scale):
        return rk.Chain.from_segments([("R", scale * np.array([0, 0.6, 0.8]), np.eye(4)),
                                       ("P", scale * np.array([1.0, 0, 0]), np.eye(4))])
    unit = chain(1.0)
    # Rodrigues' rotation about k by 0.7, then the slide of 0.2 along x in the turned frame.
    k, th = np.array([0, 0.6, 0.8]), 0.7
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    R = np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K
    np.testing.assert_allclose(unit.fk([th, 0.2])[:3, :3], R, rtol=0, atol=1e-15)
    np.testing.assert_allclose(unit.fk([th, 0.2])[:3, 3], R @ [0.2, 0, 0], rtol=0, atol=1e-15)
    for scale in (1e-9, 3.0, 1e300):
        np.testing.assert_allclose(chain(scale).fk([0.7, 0.2]), unit.fk([0.7, 0.2]), rtol=0, atol=1e-15)


def test_the_cores_chain_constructors_refuse_letters_that_do_not_fit_their_arrays():
    """robokin._chain checks what the user gives; the core's own constructors are reachable from Python
    too, and read no further than their arrays."""
    from robokin import _core

    with pytest.raises(ValueError, match=r"^joints: expected one of RP per row \(2\)$"):
        _core.chain_from_dh(np.zeros((2, 4)), "RRRRR", False, None, None)
    with pytest.raises(ValueError, match=r"^joints: expected one of RP per row \(1\)$"):
        _core.chain_from_dh(np.zeros((1, 4)), "X", False, None, None)
    with pytest.raises(ValueError, match=r"^types: expected one of RPF per row \(1\)$"):
        _core.chain_from_segments("RR", [[0, 0, 1]], [np.eye(4)], None, None)
    with pytest.raises(ValueError, match=r"^segments\[0\] axis: must not be zero$"):
        _core.chain_from_segments("R", [[0, 0, 0]], [np.eye(4)], None, None)


def test_what_the_docstrings_say_of_segments_frames_and_point_in_frame():
    """from_segments: a segment's frame at q is Rot(axis, q) tip (Trans(axis * q) tip), the axis
    through the starting frame's origin; frames[dof] is fk(q); point_in_frame numbers frames as
    frames does."""
    tip = np.eye(4)
    tip[:3, 3] = (0.3, 0.1, 0.2)
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    chain = rk.Chain.from_segments([("R", axis, tip), ("P", (0, 0, 1), tip)], tool=trans(0, 0, 0.05))
    q = np.array([0.7, 0.25])
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    R = np.eye(3) + math.sin(0.7) * K + (1 - math.cos(0.7)) * K @ K  # Rodrigues
    first = np.eye(4)
    first[:3, :3] = R
    first = first @ tip
    slide = np.eye(4)
    slide[2, 3] = 0.25
    frames = chain.frames(q)
    np.testing.assert_allclose(frames[1], first, atol=1e-12)
    np.testing.assert_allclose(frames[2], first @ slide @ tip @ trans(0, 0, 0.05), atol=1e-12)
    np.testing.assert_allclose(frames[2], chain.fk(q), atol=1e-12)
    p = np.array([0.1, -0.2, 0.3])
    np.testing.assert_allclose(chain.point_in_frame(q, p, 2), (frames[2] @ np.r_[p, 1])[:3], atol=1e-12)
    np.testing.assert_allclose(chain.point_in_frame(q, p, 2, 1), (np.linalg.inv(frames[1]) @ frames[2] @ np.r_[p, 1])[:3],
                               atol=1e-12)
