"""The layouts with a closed form of their own, read from the chain's geometry whatever describes
it: the UR layout (ik_ur) and the ortho-parallel spherical wrist (ik_spherical: the PUMA, the ABB
IRB 120, the KUKA KR 16 with its shoulder offset a1). ClosedSolver solves such an arm by that form;
truth is the subproblems' closed form on the same chain (robokin._testing.closed_solve_subproblems,
which reads only the joint axes): the same solutions under the same labels off singularities, each
reaching the pose (the chain's own forward model), and solve_batch's slots as solve's."""

import math

import numpy as np
import pytest
from closed_helpers import angle_distance
from kr16_urdf import KR16_URDF
from ur_urdf import UR5_URDF

import robokin as rk
from robokin import _testing

P = math.pi


def random_frame(rng):
    T = np.eye(4)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    T[:3, :3] = q * np.sign(np.linalg.det(q))
    T[:3, 3] = rng.uniform(-0.3, 0.3, 3)
    return T


def dh_matrix(a, alpha, d, theta):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])


def random_ortho_parallel(rng):
    """A spherical-wrist arm of the ortho-parallel layout in random DH terms: a shoulder offset a1,
    an offset d3 along the parallel axes 2 and 3, a forearm a3, d4, twists of +-pi/2 of either sign,
    any theta offsets, joints turning about -z as well as z, a random base and tool."""
    u = lambda lo, hi: rng.uniform(lo, hi)  # noqa: E731
    s = lambda: rng.choice([-1.0, 1.0])  # noqa: E731
    rows = [(u(-0.4, 0.4), s() * P / 2, u(-0.5, 0.5)), (u(0.2, 0.8), 0.0, 0.0), (u(-0.3, 0.3), s() * P / 2, u(-0.3, 0.3)),
            (0.0, s() * P / 2, u(0.2, 0.8)), (0.0, s() * P / 2, 0.0), (0.0, 0.0, u(0.0, 0.2))]
    segments = [("F", (0, 0, 1), random_frame(rng))]
    segments += [("R", (0, 0, s()), dh_matrix(a, alpha, d, u(-P, P))) for a, alpha, d in rows]
    return rk.Chain.from_segments(segments, tool=random_frame(rng))


ARMS = {  # name: (chain, its layout)
    "puma560": (rk.robots.puma560(), "spherical"),
    "irb120": (rk.robots.irb120(), "spherical"),
    "ur5": (rk.robots.ur5(), "ur"),
    "ur10e": (rk.robots.ur10e(), "ur"),
    "kr16 urdf": (rk.Chain.from_urdf(KR16_URDF), "spherical"),
    "ur5 urdf": (rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), "ur"),
}


def compare(chain, rng, poses=300):
    """ClosedSolver against the subproblems on random poses; returns how many were compared."""
    solver = rk.closed.ClosedSolver(chain, limits=None)
    Q = rng.uniform(-P, P, (poses, chain.dof))
    T = chain.fk(Q)
    compared = 0
    for q, t in zip(Q, T):
        a, b = solver.solve(t), _testing.closed_solve_subproblems(chain, t)
        assert len(a) >= 1 and np.max(np.abs(chain.fk(a.q) - t)) < 1e-9
        assert angle_distance(a.q, q).min() < 1e-6 or a.singular
        if a.singular or b.singular:
            continue
        assert sorted(a.postures) == sorted(b.postures)
        for label, row in zip(a.postures, a.q):
            assert angle_distance(row, b.q[b.postures.index(label)]) < 1e-8, label
        compared += 1
    q8, singular, _ = solver.solve_batch(T[:50])
    for k in range(50):
        s = solver.solve(T[k])
        slots = [rk.closed.UR_POSTURES.index(p) for p in s.postures] if not s.singular else None
        assert (~np.isnan(q8[k, :, 0])).sum() == len(s) and singular[k] == s.singular
        if slots is not None:
            assert np.array_equal(q8[k, slots], s.q)
    return compared


@pytest.mark.parametrize("name", ARMS)
def test_the_layouts_closed_form_is_the_subproblems(name, rng):
    chain, layout = ARMS[name]
    assert _testing.closed_layout(chain) == layout
    assert compare(chain, rng) > 250


def test_random_ortho_parallel_arms(rng):
    for _ in range(12):
        chain = random_ortho_parallel(rng)
        assert rk.closed.family(chain).name == "spherical wrist, axes 2, 3 parallel"
        assert _testing.closed_layout(chain) == "spherical"
        assert compare(chain, rng, poses=60) > 40


def test_other_twists_are_solved_by_the_subproblems(rng):
    """A spherical wrist with axes 2, 3 parallel at other twists (0.6 rad between axes 1 and 2) is
    not the ortho-parallel layout: the subproblems solve it, ClosedSolver alike."""
    rows = [(0.1, 0.6, 0.4, 0.0, "R"), (0.5, 0.0, 0.0, 0.3, "R"), (0.05, P / 2, 0.1, 0.0, "R"),
            (0.0, -P / 2, 0.45, 0.0, "R"), (0.0, P / 2, 0.0, 0.0, "R"), (0.0, 0.0, 0.1, 0.0, "R")]
    chain = rk.Chain.from_dh(rows)
    assert rk.closed.family(chain).solvable and _testing.closed_layout(chain) is None
    assert compare(chain, rng, poses=60) > 40
