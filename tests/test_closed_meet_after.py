"""rk.closed: the spherical wrist with axes 2, 3 meeting after axis 1 (FamilyKind::WristMeetAfter),
and the same read from the tool (a spherical shoulder with the two axes after it meeting: the Panda
with its elbow held).

Truth: the chain's own forward model (every solution reaches the pose), the configuration each pose
was made from (among the solutions), a damped Newton iteration from many random starts
(closed_helpers.newton_held: no solution it finds is missing), the labels' definitions computed
here from chain.frames, and EAIK (the Panda with joint 4 held: the same solutions; skipped when
eaik is not installed)."""

import math

import numpy as np
import pytest

import robokin as rk
from closed_helpers import (angle_distance, arm_size, check_poses, eaik_robot, eaik_solutions, family_solves,
                            labels_agree, newton_agrees, newton_held, newton_steps, random_q, random_rows, zero_along)

P = math.pi
WRIST = "spherical wrist, axes 2, 3 meet after axis 1"
SHOULDER = "spherical shoulder, axes 4, 5 meet before axis 6"


def random_arm(rng, reversed_=False):
    """Axes 2, 3 meeting (a2 = 0) and axes 4, 5, 6 meeting (a4 = a5 = d5 = 0); reversed, axes 1, 2,
    3 meeting (a1 = a2 = d2 = 0) and axes 4, 5 (a4 = 0)."""
    zero = [(0, 0), (1, 0), (1, 2), (3, 0)] if reversed_ else [(1, 0), (3, 0), (4, 0), (4, 2)]
    return rk.Chain.from_dh([tuple(r) for r in random_rows(rng, zero)])


@pytest.mark.parametrize("reversed_", [False, True])
def test_random_arms(reversed_):
    rng = np.random.default_rng(31 + reversed_)
    counts = family_solves([random_arm(rng, reversed_) for _ in range(30)], SHOULDER if reversed_ else WRIST, rng)
    assert max(counts) == 8 and np.mean(counts) > 3


@pytest.mark.parametrize("reversed_", [False, True])
def test_newton_finds_no_solution_the_closed_form_misses(reversed_):
    rng = np.random.default_rng(41 + reversed_)
    arms = [random_arm(rng, reversed_) for _ in range(4)]
    assert newton_agrees(arms, rng) >= 100  # the starts do converge: the check compares something


def label_parts(chain, q):
    """The labels' definitions (closed_solve.hpp), computed from the frames of the forward arm
    (standard DH: joint k's axis is z of frame k - 1; s, where axes 2, 3 meet, the origin of frame
    2; the wrist centre c the origin of frame 4)."""
    F = chain.frames(q)
    a = [F[k][:3, 2] for k in range(6)]
    p1, s, c = F[0][:3, 3], F[2][:3, 3], F[4][:3, 3]
    shoulder = "shoulder left" if a[0] @ np.cross(s - p1, c - p1) > 0 else "shoulder right"
    elbow = "elbow up" if a[2] @ np.cross(a[1], c - s) > 0 else "elbow down"
    wrist = "wrist no flip" if np.cross(a[3], a[5]) @ a[4] >= 0 else "wrist flip"
    return f"{shoulder}, {elbow}, {wrist}"


def test_labels_are_the_geometric_definitions():
    rng = np.random.default_rng(5)
    assert len(labels_agree([random_arm(rng) for _ in range(10)], rng, label_parts)) == 8


def singular_q(chain, rng, which):
    """A configuration on the shoulder's singularity (s, c and axis 1 coplanar: the two q1
    coincide; found along q2) or the elbow's (c - s in the plane of axes 2 and 3: the two (q2, q3)
    coincide; found along q3)."""
    def condition(q):
        F = chain.frames(q)
        a1, a2, a3 = F[0][:3, 2], F[1][:3, 2], F[2][:3, 2]
        p1, s, c = F[0][:3, 3], F[2][:3, 3], F[4][:3, 3]
        return a1 @ np.cross(s - p1, c - p1) if which == "shoulder" else a3 @ np.cross(a2, c - s)

    return zero_along(condition, 1 if which == "shoulder" else 2, rng)


@pytest.mark.parametrize("which", ["shoulder", "elbow"])
@pytest.mark.parametrize("offset", [0.0, 1e-9, 1e-7, 1e-5])
def test_near_singular_poses(which, offset):
    """At the singularity (to rounding) and near it (offset rad along the joint that crosses it): a
    solution is found, each reaches the pose, the generating q is among them (1e-5 at the
    singularity, where the two coinciding solutions are ~1e-6 apart), and the exact ones are flagged."""
    rng = np.random.default_rng(7)
    for _ in range(10):
        chain = random_arm(rng)
        q = singular_q(chain, rng, which)
        q[1 if which == "shoulder" else 2] += offset
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, limits=None)
        assert len(s) >= 1
        assert np.abs(chain.fk(s.q)[:, :3, 3] - T[:3, 3]).max() <= 1e-9 * arm_size(chain)
        assert np.abs(chain.fk(s.q)[:, :3, :3] - T[:3, :3]).max() <= 1e-8
        assert angle_distance(s.q, q).min() < (1e-5 if offset < 1e-6 else 1e-6)
        if offset == 0.0:
            labels = ("shoulder singular",) if which == "shoulder" else ("elbow straight", "elbow folded")
            assert s.singular and any(label in p for p in s.postures for label in labels)


def test_wrist_singular_poses():
    # A PUMA-like wrist (twists +-pi/2): axes 4 and 6 line up at q5 = 0.
    rng = np.random.default_rng(8)
    rows = random_rows(rng, [(1, 0), (3, 0), (4, 0), (4, 2)])
    rows[3][1], rows[4][1], rows[4][3] = P / 2, -P / 2, 0.0
    chain = rk.Chain.from_dh([tuple(r) for r in rows])
    assert rk.closed.family(chain).name == WRIST
    for q in rng.uniform(-P, P, (30, 6)):
        q[4] = 0.0
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, limits=None)
        # The generating posture's wrist is singular (the others have other axes 1 to 3: not theirs).
        assert len(s) >= 1 and s.singular and any(p.endswith("wrist singular") for p in s.postures)
        assert np.abs(chain.fk(s.q) - T).max() <= 1e-9


def test_the_reasons():
    rng = np.random.default_rng(9)
    base = random_rows(rng, [(1, 0), (3, 0), (4, 0), (4, 2)])
    # Axes 2, 3 a known distance apart.
    rows = [list(r) for r in base]
    rows[1][0] = 0.0123
    f = rk.closed.family(rk.Chain.from_dh([tuple(r) for r in rows]))
    assert not f.solvable and "axes 2, 3 do not meet: 12.3 mm apart" in f.reason
    # Axis 1 through the point where axes 2, 3 meet: axes 1, 2, 3 meet in a point, a continuum.
    rows = [list(r) for r in base]
    rows[0][0], rows[1][2] = 0.0, 0.0
    f = rk.closed.family(rk.Chain.from_dh([tuple(r) for r in rows]))
    forward = f.reason.split("; from the tool")[0]
    assert not f.solvable and forward.count("the distance between the two points is the same for every posture") == 1
    # Axis 3 through the wrist centre (a3 = d4 = 0): the wrist centre moves with joints 1, 2 only.
    rows = [list(r) for r in base]
    rows[2][0], rows[3][2] = 0.0, 0.0
    f = rk.closed.family(rk.Chain.from_dh([tuple(r) for r in rows]))
    assert not f.solvable and "axis 3 passes through the wrist centre" in f.reason
    # Axes 2, 3 parallel (alpha2 = 0) and a2 != 0: the PUMA's family, its name unchanged.
    rows = [list(r) for r in base]
    rows[1][0], rows[1][1] = 0.3, 0.0
    assert rk.closed.family(rk.Chain.from_dh([tuple(r) for r in rows])).name == "spherical wrist, axes 2, 3 parallel"


def test_the_names_cannot_be_confused():
    # WristMeet on a held arm's numbering reads "axes 2, 3 meet" too; this family names its lone axis.
    iiwa, panda = rk.robots.iiwa14(), rk.robots.panda()
    assert rk.closed.family(iiwa, locked={0: 0.3}).name == "spherical wrist, axes 2, 3 meet"
    assert rk.closed.family(panda, locked={6: 0.3}).name == "spherical shoulder, axes 5, 6 meet"
    assert rk.closed.family(panda, locked={3: -1.2}).name == "spherical shoulder, axes 5, 6 meet before axis 7"
    assert rk.closed.family(rk.robots.gen3(), locked={1: 0.3}).name == "spherical wrist, axes 3, 4 meet after axis 1"


PANDA = rk.robots.panda()


def test_the_panda_with_its_elbow_held():
    rng = np.random.default_rng(11)
    Q = random_q(PANDA, rng, 300)
    sols = check_poses(PANDA, Q, locked=3)
    assert all(np.all(s.q[:, 3] == q[3]) for s, q in zip(sols, Q))
    found = 0
    for q in Q[:6]:
        T = PANDA.fk(q)
        starts = random_q(PANDA, rng, 96)
        starts[:, 3] = q[3]
        ends, errors = newton_held(PANDA, T, starts, 3, iterations=newton_steps("panda", 3))
        s = rk.closed.solve(T, PANDA, limits=None, locked={3: q[3]})
        for qn in ends[errors < 1e-11]:
            found += 1
            assert angle_distance(s.q, qn).min() < 1e-6
    assert found >= 100


def test_the_panda_against_eaik():
    rng = np.random.default_rng(12)
    for value in (-0.4, -1.2, -2.6):
        robot = eaik_robot(PANDA, {3: value})
        assert robot.has_known_decomposition() and robot.get_kinematic_family().endswith("SECOND_TWO_INTERSECTING")
        Q = random_q(PANDA, rng, 60)
        Q[:, 3] = value
        for q in Q:
            T = PANDA.fk(q)
            s = rk.closed.solve(T, PANDA, limits=None, locked={3: value})
            exact = eaik_solutions(robot, T)
            assert len(exact) == len(s)
            gap = angle_distance(exact[:, None, :], s.q[None, :, :])
            assert gap.min(axis=1).max() < 1e-6 and gap.min(axis=0).max() < 1e-6
