"""rk.closed: three parallel axes 1, 2, 3 with axes 5, 6 meeting (FamilyKind::ParallelFirst), and
the same read from the tool (axes 4, 5, 6 parallel, axes 1, 2 meeting: the Unitree Z1 with its
first joint held is the one; its URDF is not a test dependency).

Truth: the chain's own forward model (every solution reaches the pose), the configuration each pose
was made from (among the solutions), a damped Newton iteration from many random starts
(closed_helpers.newton_held: no solution it finds is missing), the labels' definitions computed
here from chain.frames, and EAIK (random arms: the same solutions; skipped without eaik)."""

import math

import numpy as np
import pytest

import robokin as rk
from closed_helpers import (angle_distance, arm_size, eaik_robot, eaik_solutions, family_solves, labels_agree,
                            newton_agrees, random_rows, zero_along)

P = math.pi
FIRST = "three parallel axes 1, 2, 3 first, axes 5, 6 meet"
LAST = "three parallel axes 4, 5, 6 last, axes 1, 2 meet"


def random_arm(rng, reversed_=False):
    """Axes 1, 2, 3 parallel (alpha1 = alpha2 = 0) and axes 5, 6 meeting (a5 = 0); reversed, axes
    4, 5, 6 parallel (alpha4 = alpha5 = 0) and axes 1, 2 meeting (a1 = 0)."""
    rows = random_rows(rng, [(0, 0)], (3, 4)) if reversed_ else random_rows(rng, [(4, 0)], (0, 1))
    return rk.Chain.from_dh([tuple(r) for r in rows])


@pytest.mark.parametrize("reversed_", [False, True])
def test_random_arms(reversed_):
    rng = np.random.default_rng(51 + reversed_)
    counts = family_solves([random_arm(rng, reversed_) for _ in range(30)], LAST if reversed_ else FIRST, rng)
    assert max(counts) == 8 and np.mean(counts) > 3


@pytest.mark.parametrize("reversed_", [False, True])
def test_newton_finds_no_solution_the_closed_form_misses(reversed_):
    rng = np.random.default_rng(61 + reversed_)
    arms = [random_arm(rng, reversed_) for _ in range(4)]
    assert newton_agrees(arms, rng) >= 100  # the starts do converge: the check compares something


def parts(chain, q):
    """What the labels measure (closed_solve.hpp), from the frames of the forward arm (standard
    DH: joint k turns about z of frame k - 1, through its origin; c, where axes 5, 6 meet, the
    origin of frame 5; w, axis 3's point, the origin of frame 2, o2 axis 2's, frame 1's): the
    shoulder's, the elbow's and the wrist's signed quantities."""
    F = chain.frames(q)
    a = [F[k][:3, 2] for k in range(6)]
    o1, o2, w, o4, c = F[0][:3, 3], F[1][:3, 3], F[2][:3, 3], F[3][:3, 3], F[5][:3, 3]
    return a[3] @ np.cross(a[0], c - o4), a[0] @ np.cross(o2 - o1, w - o2), np.cross(a[4], a[5]) @ a[0]


def label(chain, q):
    shoulder, elbow, wrist = parts(chain, q)
    return (f"shoulder {'left' if shoulder > 0 else 'right'}, elbow {'up' if elbow > 0 else 'down'}, "
            f"wrist {'no flip' if wrist >= 0 else 'flip'}")


def test_labels_are_the_geometric_definitions():
    rng = np.random.default_rng(5)
    assert len(labels_agree([random_arm(rng) for _ in range(10)], rng, label)) == 8


def singular_q(chain, rng, which):
    """A configuration where two of the closed form's solutions coincide, found by bisection along
    the joint that crosses it: the shoulder's (c on the plane of axis 4 and a1: along q4), the
    elbow's (the planar arm straight or folded: along q2), the wrist's (a5, a6 and a1 coplanar:
    along q5)."""
    index, joint = {"shoulder": (0, 3), "elbow": (1, 1), "wrist": (2, 4)}[which]
    return zero_along(lambda q: parts(chain, q)[index], joint, rng), joint


@pytest.mark.parametrize("which", ["shoulder", "elbow", "wrist"])
@pytest.mark.parametrize("offset", [0.0, 1e-9, 1e-7, 1e-5])
def test_near_singular_poses(which, offset):
    """At the singularity (to rounding) and near it: a solution is found, each reaches the pose, the
    generating q is among them (1e-5 at the singularity, where the two coinciding solutions are
    ~1e-6 apart), and the exact ones are flagged."""
    rng = np.random.default_rng(7)
    for _ in range(10):
        chain = random_arm(rng)
        q, joint = singular_q(chain, rng, which)
        q[joint] += offset
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, limits=None)
        assert len(s) >= 1
        assert np.abs(chain.fk(s.q)[:, :3, 3] - T[:3, 3]).max() <= 1e-9 * arm_size(chain)
        assert np.abs(chain.fk(s.q)[:, :3, :3] - T[:3, :3]).max() <= 1e-8
        assert angle_distance(s.q, q).min() < (1e-5 if offset < 1e-6 else 1e-6)
        if offset == 0.0:
            labels = {"shoulder": ("shoulder singular",), "elbow": ("elbow straight", "elbow folded"),
                      "wrist": ("wrist singular",)}[which]
            assert s.singular and any(word in p for p in s.postures for word in labels)


def test_the_reasons():
    rng = np.random.default_rng(9)
    base = random_rows(rng, [(4, 0)], (0, 1))

    def reason(change):
        rows = [list(r) for r in base]
        change(rows)
        f = rk.closed.family(rk.Chain.from_dh([tuple(r) for r in rows]))
        assert not f.solvable
        return f.reason

    assert "axes 1, 2, 3 are parallel, but two of them are one line" in reason(lambda r: r[0].__setitem__(0, 0.0))
    assert "axes 1, 2, 3 are parallel, but so is axis 4" in reason(lambda r: r[2].__setitem__(1, 0.0))
    assert "axes 1, 2, 3 are parallel, but axes 5, 6 do not meet" in reason(lambda r: r[4].__setitem__(0, 0.0123))
    # Axis 4 through the point where axes 5, 6 meet (a4 = 0 and d5 = 0: axes 4, 5, 6 meet in it, a
    # spherical wrist whose axes 2, 3 are parallel: the PUMA's family but for axes 1, 2 parallel).
    why = reason(lambda r: (r[3].__setitem__(0, 0.0), r[4].__setitem__(2, 0.0)))
    assert "axis 4 passes through the point where axes 5, 6 meet" in why
    assert "axes 2, 3 are not parallel" not in why and "axes 1, 2 are parallel" in why


def test_the_names_cannot_be_confused():
    # The UR family's parallel axes are 2, 3, 4 after axis 1; these are the first three.
    assert rk.closed.family(rk.robots.ur5()).name == "three parallel axes 2, 3, 4"
    rng = np.random.default_rng(3)
    assert rk.closed.family(random_arm(rng)).name == FIRST


def test_random_arms_against_eaik():
    rng = np.random.default_rng(13)
    for reversed_ in (False, True):
        for _ in range(5):
            chain = random_arm(rng, reversed_)
            robot = eaik_robot(chain)
            assert robot.has_known_decomposition(), robot.get_kinematic_family()
            for q in rng.uniform(-P, P, (20, 6)):
                T = chain.fk(q)
                s = rk.closed.solve(T, chain, limits=None)
                exact = eaik_solutions(robot, T)
                assert len(exact) == len(s)
                gap = angle_distance(exact[:, None, :], s.q[None, :, :])
                assert gap.min(axis=1).max() < 1e-6 and gap.min(axis=0).max() < 1e-6
