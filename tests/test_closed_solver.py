"""rk.closed.ClosedSolver: a closed form read from its chain once and held.

Truth: rk.closed.ur (the arm read at each call) on the same poses, bit for bit; the chain's own
forward model; a pickled copy; one solver shared by eight threads against the calls made alone."""

import pickle
import threading

import numpy as np
import pytest
from closed_helpers import angle_distance

import robokin as rk


def _answer(s):
    return s.q.tobytes(), tuple(s.postures), s.within_limits.tobytes(), bool(s.singular)


@pytest.mark.parametrize("limits", ["default", None])
def test_a_held_solver_answers_as_closed_ur(rng, limits):
    chain = rk.robots.ur10()
    solver = rk.closed.ClosedSolver(chain, limits)
    poses = chain.fk(rng.uniform(-3, 3, (50, 6)))
    for T in poses:
        s = solver.solve(T)
        assert len(s) >= 2 and _answer(s) == _answer(rk.closed.ur(T, chain, limits))
        assert np.allclose(chain.fk(s.q), T, atol=1e-9)
    q, singular, within = solver.solve_batch(poses)
    q2, singular2, within2 = rk.closed.ur_batch(poses, chain, limits)
    assert np.array_equal(q, q2, equal_nan=True) and np.array_equal(within, within2)
    assert np.array_equal(singular, singular2)


def test_limits_are_resolved_once_and_shown():
    chain = rk.robots.ur5()
    lower, upper = rk.robots.ur5().limits
    assert rk.closed.ClosedSolver(chain).chain is chain
    got = rk.closed.ClosedSolver(chain).limits
    assert np.array_equal(got[0], lower) and np.array_equal(got[1], upper)
    assert rk.closed.ClosedSolver(chain, None).limits is None
    narrow = (np.full(6, -1.0), np.full(6, 1.0))
    T = chain.fk(np.full(6, 0.5))
    s = rk.closed.ClosedSolver(chain, narrow).solve(T)
    assert 0 < s.within_limits.sum() < len(s)
    assert np.all(np.abs(s.q[s.within_limits]) <= 1.0)


def test_a_pickled_solver_gives_the_same_answers(rng):
    chain = rk.robots.ur5e()
    solver = rk.closed.ClosedSolver(chain, (np.full(6, -2.0), np.full(6, 2.0)))
    copy = pickle.loads(pickle.dumps(solver))
    assert copy.chain == chain and np.array_equal(copy.limits[0], solver.limits[0])
    for T in chain.fk(rng.uniform(-3, 3, (20, 6))):
        assert _answer(copy.solve(T)) == _answer(solver.solve(T))


def test_arms_without_the_ur_layout_and_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="chain: no closed form for this arm .axes 4, 5, 6 do not meet"):
        rk.closed.ClosedSolver(rk.Chain.from_dh(
            [(0, 1.5708, 0.6, 0, "R"), (0.4, 0, 0, 0, "R"), (0.02, -1.5708, 0.15, 0, "R"), (0, 1.5708, 0.43, 0, "R"),
             (0, -1.5708, 0.0032, 0, "R"), (0, 0, 0.05, 0, "R")]))
    with pytest.raises(TypeError):
        rk.closed.ClosedSolver("ur5")
    with pytest.raises(ValueError, match="limits"):
        rk.closed.ClosedSolver(rk.robots.ur5(), "nope")
    solver = rk.closed.ClosedSolver(rk.robots.ur5())
    with pytest.raises(ValueError, match="target"):
        solver.solve(np.eye(3))
    with pytest.raises(ValueError, match="targets"):
        solver.solve_batch(np.eye(4))
    with pytest.raises(ValueError, match="state"):
        rk.closed.ClosedSolver.__new__(rk.closed.ClosedSolver).__setstate__((99, None, None))


def test_one_solver_shared_by_eight_threads_answers_as_alone(rng):
    chain = rk.robots.ur3()
    solver = rk.closed.ClosedSolver(chain)
    poses = [chain.fk(rng.uniform(-3, 3, (400, 6))) for _ in range(8)]
    alone = [[_answer(solver.solve(T)) for T in p] for p in poses]
    got, errors, start = [None] * 8, [], threading.Barrier(8)

    def work(i):
        try:
            start.wait()
            got[i] = [_answer(solver.solve(T)) for T in poses[i]]
        except Exception as exc:  # noqa: BLE001 - reported below
            errors.append(repr(exc))

    threads = [threading.Thread(target=work, args=(i,)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and got == alone


def _same_solver(a, b, poses):
    assert a.family == b.family and repr(a) == repr(b)
    for T in poses:
        assert _answer(a.solve(T)) == _answer(b.solve(T))


@pytest.mark.parametrize("name, locked", [("ur5", None), ("puma560", None), ("irb120", None), ("panda", {3: -1.5}),
                                          ("iiwa14", {2: 0.3})])
def test_find_gives_the_solver_of_an_arm_with_a_closed_form(rng, name, locked):
    chain = rk.robots.get(name)
    found = rk.closed.ClosedSolver.find(chain, locked=locked)
    assert rk.closed.family(chain, locked=locked).solvable and found.chain is chain
    q = rng.uniform(-1, 1, (20, chain.dof))
    if locked:
        (j, v), = locked.items()
        q[:, j] = v
    _same_solver(found, rk.closed.ClosedSolver(chain, locked=locked), chain.fk(q))


@pytest.mark.parametrize("name, locked", [("rpr", None), ("planar_3r", None), ("panda", None), ("iiwa14", {3: 0.5})])
def test_find_gives_none_exactly_where_family_finds_no_closed_form(name, locked):
    chain = rk.robots.get(name)
    assert not rk.closed.family(chain, locked=locked).solvable
    assert rk.closed.ClosedSolver.find(chain, locked=locked) is None
    with pytest.raises(ValueError, match="no closed form|holding a joint needs"):
        rk.closed.ClosedSolver(chain, locked=locked)


def test_find_refuses_bad_arguments_as_the_constructor_does():
    with pytest.raises(ValueError, match=r"locked: q\[2\] = 3.5 is outside the joint's limits \[-2.9670597283903604, "):
        rk.closed.ClosedSolver.find(rk.robots.iiwa14(), locked={2: 3.5})
    with pytest.raises(ValueError, match="locked: holding a joint needs a chain of 7 joints"):
        rk.closed.ClosedSolver.find(rk.robots.ur5(), locked={2: 0.5})
    with pytest.raises(ValueError, match="limits"):
        rk.closed.ClosedSolver.find(rk.robots.ur5(), "nope")
    with pytest.raises(TypeError, match="unexpected keyword argument 'tolerance'"):
        rk.closed.ClosedSolver.find(rk.robots.ur5(), tolerance=1e-3)


@pytest.mark.parametrize("d6", [1e150, 1.3407807929942597e154, 1e165])
def test_an_arm_whose_squares_overflow_returns_only_what_reaches(d6):
    # The arm's size (the FK check's scale) summed from lengths whose squares reach the largest
    # float: measured as a plain norm it was infinite, and a tool d6 away from its target passed.
    # At 1e165 the check's squared tolerance overflows too: an infinite squared distance passed it.
    alphas = (np.pi / 2, 0, 0, np.pi / 2, -np.pi / 2, 0)  # the UR table's, every length 0 but d6
    chain = rk.Chain.from_dh([(0.0, alpha, d6 if i == 5 else 0.0, 0.0, "R") for i, alpha in enumerate(alphas)])
    # The family's distance tolerance is its options' tol times that size: finite, and d6's.
    tol = rk.closed.ClosedFamilyOptions().tol
    assert rk.closed.family(chain).tol_distance == pytest.approx(tol * d6, rel=1e-12)
    solver = rk.closed.ClosedSolver.find(chain, None)
    assert solver is not None and solver.family == "three parallel axes 2, 3, 4"
    T = rk.robots.ur5().fk(np.zeros(6))  # a metre from the base: out of this arm's reach
    assert len(solver.solve(T)) == 0
    own = chain.fk(np.full(6, 0.4))
    solutions = solver.solve(own)
    assert len(solutions) >= 1
    for q in solutions.q:
        assert np.max(np.abs(chain.fk(q)[:3, 3] - own[:3, 3])) <= 1e-9 * d6


@pytest.mark.parametrize("scale", [1e-150, 1e100])
def test_an_arm_scaled_far_from_a_metre_solves_as_the_unit_arm(rng, scale):
    # Lengths of 1e-150 m: squares of coordinates below the normal range, where the subproblems'
    # directions are measured by hypot instead. Lengths of 1e100 m: fourth powers beyond the
    # largest float, where a subproblem's scale (the root of a product of squares) takes two roots.
    # A uniform scale leaves every angle as it is; the scaled arm's own forward model checks its
    # answers too.
    alphas = (-np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, -np.pi / 2, np.pi / 2, 0.0)
    lengths = (0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.126)  # the iiwa 14's (robots.iiwa14), no limits
    arm, scaled = (rk.Chain.from_dh([(0.0, a, factor * d, 0.0, "R") for a, d in zip(alphas, lengths)])
                  for factor in (1.0, scale))
    unit = rk.closed.ClosedSolver(arm, None, locked={2: 0.3})
    scaled_solver = rk.closed.ClosedSolver(scaled, None, locked={2: 0.3})
    for q in rng.uniform(-2, 2, (50, 7)):
        q[2] = 0.3
        T = arm.fk(q)
        T_scaled = T.copy()
        T_scaled[:3, 3] *= scale
        want, got = unit.solve(T), scaled_solver.solve(T_scaled)
        assert len(want) >= 1 and got.postures == want.postures
        assert np.max(angle_distance(got.q, want.q)) < 1e-9
        reached = scaled.fk(got.q)
        assert np.max(np.abs(reached[:, :3, 3] - T_scaled[:3, 3])) <= 1e-9 * scale
        assert np.max(np.abs(reached[:, :3, :3] - T[:3, :3])) <= 1e-9
