"""Property tests of rk.closed.ClosedSolver: any arguments give a result or a ValueError /
TypeError naming one; every solution it returns reaches its pose (the chain's forward model) and,
off singularities, the joints a pose was made from are among them."""

import math

import numpy as np
from fuzz import arrays, assert_finite, check_call, finite_arrays, wild_floats
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk

COVERS = {"ClosedSolver.__init__", "ClosedSolver.solve", "ClosedSolver.solve_batch", "ClosedSolver.chain",
          "ClosedSolver.limits"}

P = math.pi
UR5 = rk.robots.ur5()
joints = finite_arrays((6,), -2 * P, 2 * P)


@settings(max_examples=60)
@given(st.one_of(st.none(), st.just("default"), st.just("x"), st.tuples(joints, joints), wild_floats, arrays()),
       st.one_of(arrays(), st.just(np.eye(4))))
def test_closed_solver_any_arguments(limits, target):
    solver = check_call(lambda: rk.closed.ClosedSolver(UR5, limits), "limits")
    if solver is None:
        return
    assert solver.chain is UR5
    s = check_call(lambda: solver.solve(target), "target")
    if s is not None:
        assert_finite(s.q)
    b = check_call(lambda: solver.solve_batch(target), "targets")
    if b is not None:
        assert b[0].shape[1:] == (8, 6)


@settings(max_examples=100)
@given(joints)
def test_closed_solver_reaches_and_finds_the_source(q):
    solver = rk.closed.ClosedSolver(UR5, None)
    T = UR5.fk(q)
    s = solver.solve(T)
    assert len(s) >= 1
    assert np.allclose(UR5.fk(s.q), T, atol=1e-9)
    if not s.singular:
        d = np.remainder(s.q - q + P, 2 * P) - P
        assert np.min(np.max(np.abs(d), axis=1)) < 1e-6
    q8, singular, within = solver.solve_batch(T[None])
    rows = q8[0][~np.isnan(q8[0, :, 0])]
    assert len(rows) == len(s) and bool(singular[0]) == s.singular
