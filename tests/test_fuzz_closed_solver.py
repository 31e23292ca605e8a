"""Property tests of rk.closed.ClosedSolver, rk.closed.family and rk.closed.solve: any arguments give a result or a ValueError /
TypeError naming one; every solution it returns reaches its pose (the chain's forward model) and,
off singularities, the joints a pose was made from are among them."""

import math

import numpy as np
from fuzz import arrays, assert_finite, check_call, finite_arrays, small_ints, wild_floats
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk

COVERS = {"ClosedSolver.__init__", "ClosedSolver.solve", "ClosedSolver.solve_batch", "ClosedSolver.chain",
          "ClosedSolver.limits", "ClosedSolver.family", "ClosedSolver.locked", "ClosedSolver.find", "closed.family", "closed.solve"}

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


dh_rows = st.lists(st.tuples(st.floats(-1, 1), st.sampled_from([0.0, P / 2, -P / 2, 0.7]), st.floats(-1, 1),
                             st.floats(-P, P), st.sampled_from(["R", "R", "R", "P"])), min_size=1, max_size=7)


@settings(max_examples=80)
@given(dh_rows, st.one_of(st.just(1e-6), wild_floats), joints)
def test_family_and_solve_any_chain(rows, tol, q):
    """Any chain: a Family or a ValueError naming tol; solve answers with solutions that reach the
    pose, or a ValueError naming the chain (no closed form) or tol."""
    chain = rk.Chain.from_dh(rows)
    f = check_call(lambda: rk.closed.family(chain, tol=tol), "tol")
    if f is None:
        return
    assert f.solvable == (f.reason == "") and (f.name == "none") != f.solvable
    assert f.tol_distance >= 0
    if chain.dof != 6:
        return
    T = chain.fk(q[:chain.dof])
    s = check_call(lambda: rk.closed.solve(T, chain, None, tol=tol), "chain", "tol")
    if s is not None:
        assert_finite(s.q)
        if len(s):
            size = sum(abs(r[0]) + abs(r[2]) for r in rows)
            assert np.all(np.abs(chain.fk(s.q)[:, :3, 3] - T[:3, 3]) <= 1e-9 * size + 1e-12)
        assert rk.closed.ClosedSolver(chain, None, tol=tol).family == f.name


dh7_rows = st.lists(st.tuples(st.sampled_from([0.0, 0.0, 0.3, -0.1]), st.sampled_from([0.0, P / 2, -P / 2, 0.7]),
                              st.sampled_from([0.0, 0.0, 0.4, 0.2]), st.floats(-P, P), st.just("R")),
                    min_size=7, max_size=7)
locks = st.one_of(st.none(), st.dictionaries(st.one_of(small_ints, st.floats(0, 6), st.booleans(), st.text(max_size=2)),
                                             st.one_of(wild_floats, st.text(max_size=2), st.none()), max_size=2),
                  st.lists(small_ints, max_size=2), wild_floats)


@settings(max_examples=150)
@given(dh7_rows, locks, finite_arrays((7,), -2 * P, 2 * P))
def test_locked_any_chain_any_lock(rows, locked, q):
    """Any lock on 7-joint chains (offsets and twists drawn to meet the families): a family, a
    result or an error naming locked; every solution keeps the held value and reaches the pose."""
    chain = rk.Chain.from_dh(rows)
    f = check_call(lambda: rk.closed.family(chain, locked=locked), "locked")
    if f is None:
        return
    assert f.solvable == (f.reason == "")
    if locked:
        (j, v), = locked.items()
        q = q.copy()
        q[j] = v
    T = chain.fk(q)
    solver = check_call(lambda: rk.closed.ClosedSolver(chain, None, locked), "locked")
    if solver is None:
        assert not f.solvable
        return
    assert solver.family == f.name and solver.locked == (locked and {j: float(v)})
    s = solver.solve(T)
    assert_finite(s.q)
    if len(s):
        assert s.q.shape[1] == 7 and np.all(s.q[:, j] == v)
        size = sum(abs(r[0]) + abs(r[2]) for r in rows)
        assert np.all(np.abs(chain.fk(s.q)[:, :3, 3] - T[:3, 3]) <= 1e-9 * size + 1e-12)
    q8 = solver.solve_batch(T[None])[0]
    assert q8.shape == (1, 8, 7) and int(np.sum(~np.isnan(q8[0, :, 0]))) == len(s)


@settings(max_examples=80)
@given(dh_rows, st.one_of(st.just(1e-6), wild_floats), st.one_of(st.none(), st.just("default"), st.just("x"), arrays()))
def test_find_any_chain(rows, tol, limits):
    """Any chain: ClosedSolver.find gives a solver exactly where family finds a closed form (the same
    family), None where it finds none, or a ValueError / TypeError naming tol or limits."""
    chain = rk.Chain.from_dh(rows)
    f = check_call(lambda: rk.closed.family(chain, tol=tol), "tol")
    try:
        found = rk.closed.ClosedSolver.find(chain, limits, tol=tol)
    except (ValueError, TypeError) as e:
        assert "tol" in str(e) or "limits" in str(e), str(e)
        return
    assert f is not None  # find took tol: so does family
    assert (found is not None) == f.solvable
    if found is not None:
        assert found.family == f.name and found.chain is chain
