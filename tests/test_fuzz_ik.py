"""Property tests of the numerical IK: arbitrary arrays, numbers and options into rk.ik, rk.ik_batch
and rk.IKSolver give a result or a ValueError / TypeError naming the argument, never a crash; and a
reported success is always a reached pose, a reported failure an unreached one, checked by an
independent forward model. The solvers are fuzzed with rigid targets (FK of a random q, perturbed,
pushed far out of reach, at stretched and folded configurations, or on the base axis) on the
catalogue's chains and on random DH chains of 1-7 joints (revolute and prismatic, with finite,
half-infinite and no limits), for every method, for single solves and batches (plain and path)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk
from fuzz import arrays, assert_finite, check_call, floats, wild_floats
from fuzz_chains import dh_chains, reference_fk, task_errors, task_target

COVERS = {
    "ik", "ik_batch", "IKSolver.__init__", "IKSolver.solve", "IKSolver.method", "IKSolver.task", "IKSolver.options",
    "IKOptions", "IKOptions.validate",
    "IKResult.q", "IKResult.success", "IKResult.iterations", "IKResult.attempts", "IKResult.error_p",
    "IKResult.error_r", "IKResult.__bool__",
    "IKBatchResult.q", "IKBatchResult.success", "IKBatchResult.iterations", "IKBatchResult.attempts",
    "IKBatchResult.error_p", "IKBatchResult.error_r", "IKBatchResult.__len__",
}

UR5 = rk.robots.ur5()
METHODS = ["lm", "gn", "nr", "halley"]
TASKS = ["pose", "position", "xy", "xyphi"]
ORIENTED = ("pose", "xyphi")
ARGNAMES = ("chain", "target", "targets", "q0", "method", "task", "tol_p", "tol_r", "max_iter", "restarts", "seed",
            "timeout", "damping", "path")
huge = st.sampled_from([1e308, -1e308, 1.7e308, 1e200, -1e160, 0.5, 0.0, 1.0])
target_shapes = [(4, 4), (6,), (3,), (2,), (1, 4, 4), (2, 6), (0,)]
batch_shapes = [(0, 4, 4), (2, 4, 4), (3, 3), (2, 2), (1, 4, 4), (2, 6), (4,), (3, 4, 4, 1)]
targets_any = st.one_of(arrays(target_shapes), arrays(target_shapes, elements=huge),
                        st.sampled_from([np.eye(4), np.eye(4)[None], np.diag([1.0, 1.0, -1.0, 1.0])]))
batches_any = st.one_of(arrays(batch_shapes), arrays(batch_shapes, elements=huge),
                        st.sampled_from([np.eye(4)[None].repeat(2, 0), np.zeros((0, 3))]))
q0_any = arrays([(6,), (3,), (2, 6), (1, 6), (0,), (7,)])
methods_any = st.one_of(st.sampled_from([*METHODS, "?", "LM", ""]), st.sampled_from([None, 1]))
tasks_any = st.one_of(st.sampled_from([*TASKS, "?"]), st.sampled_from([None, 2]))
tols_any = st.one_of(wild_floats, st.sampled_from([1e-9, 1e-3, None, "1e-3"]))
iters_any = st.one_of(st.integers(-2, 30), st.sampled_from([2**31, -(2**31) - 1, 2**70, 2.5, None]))
restarts_any = st.one_of(st.integers(-1, 3), st.sampled_from([1_000_001, 2**63, -(2**70), 1.5, None, True, "2",
                                                              np.int64(2)]))
seeds_any = st.one_of(st.none(), st.integers(-3, 2**64 + 3), st.sampled_from([2**64 - 1, True, 1.5, "3", np.uint64(7)]))
timeouts_any = st.one_of(st.none(), wild_floats, st.sampled_from([1e-300, 5.0, "1", [1.0]]))
dampings_any = st.one_of(st.none(), wild_floats, st.sampled_from([1e-300, 1e300, "x"]))


def budget(restarts, timeout):
    """restarts=None restarts until the timeout (5 ms by default): a fuzzed timeout of hours on an
    unreachable target would take that long, so it is cut to 10 ms (the contract is the same)."""
    if restarts is None and isinstance(timeout, (int, float)) and not isinstance(timeout, bool) \
            and math.isfinite(timeout) and timeout > 0.01:
        return 0.01
    return timeout


def most_restarts(restarts):
    return rk.IK_DEFAULTS["restarts"] if restarts is None else int(restarts)


def expect_ik_result(chain, r, tol_p, tol_r, task, restarts):
    assert r.q.shape == (chain.dof,) and isinstance(r.success, bool) and bool(r) == r.success
    assert_finite(r.q, r.error_p, r.error_r)
    lo, hi = chain.limits
    assert np.all(r.q >= lo) and np.all(r.q <= hi)
    assert r.success == (r.error_p < tol_p and (task not in ORIENTED or r.error_r < tol_r))
    assert 1 <= r.attempts <= restarts + 1 and r.iterations >= 0


@given(chain=st.sampled_from([UR5, rk.robots.rpr(), rk.robots.prr()]), target=targets_any, q0=q0_any,
       method=methods_any, task=tasks_any, tol_p=tols_any, tol_r=tols_any, max_iter=iters_any, restarts=restarts_any,
       seed=seeds_any, timeout=timeouts_any, damping=dampings_any)
def test_ik_with_arbitrary_arguments(chain, target, q0, method, task, tol_p, tol_r, max_iter, restarts, seed, timeout,
                                     damping):
    timeout = budget(restarts, timeout)
    r = check_call(lambda: rk.ik(chain, target, q0, method=method, task=task, tol_p=tol_p, tol_r=tol_r,
                                 max_iter=max_iter, restarts=restarts, seed=seed, timeout=timeout, damping=damping),
                   *ARGNAMES)
    if r is not None:
        expect_ik_result(chain, r, tol_p, tol_r, task, most_restarts(restarts))


@given(chain=st.sampled_from([UR5, rk.robots.rpr()]), targets=batches_any, q0=q0_any, method=methods_any,
       task=tasks_any, tol=tols_any, max_iter=iters_any, restarts=restarts_any, seed=seeds_any, timeout=timeouts_any,
       damping=dampings_any, path=st.one_of(st.booleans(), st.sampled_from([None, 1, "yes"])))
def test_ik_batch_with_arbitrary_arguments(chain, targets, q0, method, task, tol, max_iter, restarts, seed, timeout,
                                           damping, path):
    timeout = budget(restarts, timeout)
    r = check_call(lambda: rk.ik_batch(chain, targets, q0, method=method, task=task, tol_p=tol, tol_r=tol,
                                       max_iter=max_iter, restarts=restarts, seed=seed, timeout=timeout,
                                       damping=damping, path=path), *ARGNAMES)
    if r is None:
        return
    n = len(targets)
    assert len(r) == n and r.q.shape == (n, chain.dof)
    assert r.success.shape == r.iterations.shape == r.attempts.shape == r.error_p.shape == r.error_r.shape == (n,)
    assert r.success.dtype == np.bool_ and r.iterations.dtype == r.attempts.dtype == np.int32
    assert_finite(r.q, r.error_p, r.error_r)
    lo, hi = chain.limits
    assert np.all(r.q >= lo) and np.all(r.q <= hi)
    assert np.all(r.success == ((r.error_p < tol) & ((task not in ORIENTED) | (r.error_r < tol))))
    assert np.all((r.attempts >= 1) & (r.attempts <= most_restarts(restarts) + 1))


@given(chain=st.one_of(st.sampled_from([UR5, rk.robots.rp()]), st.sampled_from([None, "ur5", 1])),
       method=methods_any, task=tasks_any, tol_p=tols_any, tol_r=tols_any, max_iter=iters_any, restarts=restarts_any,
       seed=seeds_any, timeout=timeouts_any, damping=dampings_any,
       calls=st.lists(st.tuples(targets_any, q0_any), max_size=3))
def test_ik_solver_with_arbitrary_arguments(chain, method, task, tol_p, tol_r, max_iter, restarts, seed, timeout,
                                            damping, calls):
    timeout = budget(restarts, timeout)
    solver = check_call(lambda: rk.IKSolver(chain, method=method, task=task, tol_p=tol_p, tol_r=tol_r,
                                            max_iter=max_iter, restarts=restarts, seed=seed, timeout=timeout,
                                            damping=damping), *ARGNAMES)
    if solver is None:
        return
    assert solver.method == method and solver.task == task
    o = solver.options  # what was given, as given (None where the default rule applies)
    assert (o.method, o.task, o.tol_p, o.tol_r, o.max_iter, o.restarts) == (method, task, tol_p, tol_r, max_iter,
                                                                           restarts)
    for target, q0 in calls:
        r = check_call(lambda: solver.solve(target, q0), "target", "q0")
        if r is not None:
            expect_ik_result(chain, r, tol_p, tol_r, task, most_restarts(restarts))


@given(options=st.dictionaries(st.sampled_from(["method", "task", "tol_p", "tol_r", "max_iter", "restarts", "timeout",
                                                "damping", "seed"]),
                               st.one_of(methods_any, tasks_any, tols_any, iters_any, restarts_any, timeouts_any),
                               max_size=4))
def test_ik_options_from_arbitrary_keywords(options):
    """IKOptions holds exactly what it was given, or a TypeError (unknown name, wrong kind) or a
    ValueError (a method or task that does not exist, an int beyond C's) names the keyword;
    validate() then accepts it or names the option out of range."""
    o = check_call(lambda: rk.IKOptions(**options), *options)
    if o is None:
        return
    for name, value in options.items():
        got = getattr(o, name)
        assert got == value or (got != got and value != value), (name, got, value)  # NaN stays NaN
    check_call(o.validate, *options)


# --- reported success equals verified success -----------------------------------------------

INF = math.inf
P2 = math.pi / 2
UR5_ROWS = [(0, P2, 0.089159, 0, "R"), (-0.425, 0, 0, 0, "R"), (-0.39225, 0, 0, 0, "R"),
            (0, P2, 0.10915, 0, "R"), (0, -P2, 0.09465, 0, "R"), (0, 0, 0.0823, 0, "R")]
CHAINS = [
    UR5,
    rk.robots.puma560(),
    # a UR5 geometry with half-infinite and unlimited joints
    rk.Chain.from_dh(UR5_ROWS, limits=([-INF, -1.0, -INF, -INF, 0.5, -INF], [0.5, INF, INF, 1.0, INF, INF])),
    rk.Chain.from_dh(UR5_ROWS),  # no limits at all
    rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 3, limits=([-INF, -1.0, -INF], [1.0, INF, INF])),
    rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 2, limits=([-INF, -INF], [1.0, INF])),
    rk.Chain.from_dh([(1.0, 0, 0, 0, "R")], limits=([-INF], [1.0])),
    # prismatic joints: unlimited, and half-infinite
    rk.robots.prr(),
    rk.Chain.from_dh([(0, P2, 0, 0, "P"), (1.0, 0, 0, 0, "R"), (0.7, 0, 0, 0, "R")],
                     limits=([0.0, -INF, -2.0], [INF, 0.5, INF])),
    rk.robots.rp(),
    rk.robots.rpr(),
]


def rotation(v):
    """Rodrigues: the rotation by |v| about v."""
    angle = np.linalg.norm(v)
    if angle == 0:
        return np.eye(3)
    k = v / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def check(chain, q, success, error_p, error_r, T, task, tol_p, tol_r, fk=None):
    """The result against the forward model ``fk`` (the numpy DH product; KDL's recursive FK for
    chains that are not DH tables): errors equal, and success exactly when each is within its own
    tolerance (tol_p for the position, tol_r for the rotation)."""
    lo, hi = chain.limits
    assert q.shape == (chain.dof,) and np.all(np.isfinite(q)), q
    assert np.isfinite(error_p) and np.isfinite(error_r)
    assert np.all(q >= lo) and np.all(q <= hi), (q, lo, hi)
    # Beyond |q| ~ 1e3 (a runaway unlimited joint) the rounding of huge angles and of cancelling
    # prismatic offsets depends on the order of the operations: the public FK is the reference there.
    if np.abs(q).max() >= 1e3:
        F = chain.fk(q)
    else:
        F = fk(q) if fk is not None else chain._fk_kdl(q)
    ep, er = task_errors(F, task_target(T, task), task)
    margin = 1e-12  # FK rounding: no verdict within it of the tolerance
    if task == "xyphi" and min(math.hypot(F[0, 0], F[1, 0]), math.hypot(T[0, 0], T[1, 0])) < 1e-6:
        # The tool's x axis (nearly) along z: its planar angle is rounding noise, no verdict on it.
        assert abs(ep - error_p) <= 1e-9 * (1 + ep) and (not success or ep < tol_p + margin), (ep, error_p)
        return
    assert abs(ep - error_p) <= 1e-9 * (1 + ep) and abs(er - error_r) <= 1e-9 * (1 + er), (ep, error_p, er, error_r)
    if success:
        assert ep < tol_p + margin and er < tol_r + margin, (ep, er, tol_p, tol_r)
    else:
        assert ep >= tol_p - margin or er >= tol_r - margin, (ep, er, tol_p, tol_r)


coords = st.floats(-7, 7, allow_nan=False)
tolerances = st.sampled_from([1e-10, 1e-6, 1e-3, 1e-2])
special = st.sampled_from([0.0, P2, -P2, math.pi])  # stretched and folded arms
rigid = st.fixed_dictionaries({
    "chain": st.integers(0, len(CHAINS) - 1),
    "q": st.lists(st.one_of(coords, special), min_size=7, max_size=7),
    "kind": st.sampled_from(["exact", "near", "off", "far", "singular", "axis"]),
    "dp": st.tuples(*[st.floats(-0.3, 0.3)] * 3),
    "dr": st.one_of(st.just((0.0, 0.0, 0.0)), st.tuples(*[st.floats(-1, 1)] * 3)),
    "method": st.sampled_from(METHODS),
    "task": st.sampled_from(TASKS),
    # Drawn apart: a success test that compared the wrong error with a tolerance, or left one out,
    # passes whenever the two tolerances are equal.
    "tol_p": tolerances,
    "tol_r": tolerances,
})


def rigid_target(case, chain, fk, q_of=None):
    """A (4, 4) target for the case: the tool at q ("exact"), moved a little ("near") or up to 5 m
    ("off"), 100 times farther than the arm reaches ("far": unreachable), at q with every joint 0
    pushed outwards ("singular": a stretched arm, often unreachable), or with the position on the
    base z axis ("axis")."""
    lo, hi = chain.limits
    q = np.zeros(chain.dof) if case["kind"] == "singular" else np.array(case["q"][: chain.dof])
    T = fk(np.clip(q, lo, hi))
    dp = np.array(case["dp"])
    if case["kind"] == "near":
        T[:3, 3] += dp
    elif case["kind"] == "off":
        T[:3, 3] += dp * 16
    elif case["kind"] == "far":
        T[:3, 3] = 100 * T[:3, 3] + 50 + dp
    elif case["kind"] == "singular":
        T[:3, 3] *= 1 + np.abs(dp).max()
    elif case["kind"] == "axis":
        T[:2, 3] = 0.0
    T[:3, :3] = T[:3, :3] @ rotation(np.array(case["dr"]))
    return T


@given(case=rigid, q0=st.lists(st.floats(-20, 20), min_size=7, max_size=7), max_iter=st.integers(1, 60),
       restarts=st.integers(0, 3), seed=st.integers(0, 2**64 - 1))
def test_ik_success_is_verified_on_the_catalogue(case, q0, max_iter, restarts, seed):
    chain = CHAINS[case["chain"]]
    T = rigid_target(case, chain, chain.fk)
    task, tol_p, tol_r = case["task"], case["tol_p"], case["tol_r"]
    r = rk.ik(chain, task_target(T, task), np.array(q0[: chain.dof]), method=case["method"], task=task,
              tol_p=tol_p, tol_r=tol_r, max_iter=max_iter, restarts=restarts, seed=seed)
    check(chain, r.q, r.success, r.error_p, r.error_r, T, task, tol_p, tol_r)
    assert bool(r) == r.success and 1 <= r.attempts <= restarts + 1


@given(chain_case=dh_chains(), case=rigid, q0=st.lists(st.floats(-7, 7), min_size=7, max_size=7),
       max_iter=st.integers(1, 40), restarts=st.integers(0, 2), seed=st.integers(0, 2**64 - 1),
       damping=st.sampled_from([None, 1e-3, 0.5]))
def test_ik_success_is_verified_on_random_chains(chain_case, case, q0, max_iter, restarts, seed, damping):
    chain = chain_case["chain"]
    fk = lambda q: reference_fk(chain_case, q)  # noqa: E731
    T = rigid_target(case, chain, fk)
    task, tol_p, tol_r = case["task"], case["tol_p"], case["tol_r"]
    r = rk.ik(chain, task_target(T, task), np.array(q0[: chain.dof]), method=case["method"], task=task,
              tol_p=tol_p, tol_r=tol_r, max_iter=max_iter, restarts=restarts, seed=seed, damping=damping)
    check(chain, r.q, r.success, r.error_p, r.error_r, T, task, tol_p, tol_r, fk=fk)
    assert 1 <= r.attempts <= restarts + 1


@given(chain_case=dh_chains(max_dof=6), cases=st.lists(rigid, min_size=1, max_size=4),
       q0=st.lists(st.floats(-7, 7), min_size=7, max_size=7), method=st.sampled_from(METHODS),
       task=st.sampled_from(TASKS), path=st.booleans(), restarts=st.integers(0, 2), solver=st.booleans(),
       tol_p=tolerances, tol_r=tolerances)
def test_ik_batch_and_solver_success_is_verified_on_random_chains(chain_case, cases, q0, method, task, path, restarts,
                                                                  solver, tol_p, tol_r):
    chain = chain_case["chain"]
    fk = lambda q: reference_fk(chain_case, q)  # noqa: E731
    targets = [rigid_target(case, chain, fk) for case in cases]
    values = np.array([task_target(T, task) for T in targets])
    start = np.array(q0[: chain.dof])
    options = dict(method=method, task=task, tol_p=tol_p, tol_r=tol_r, max_iter=30, restarts=restarts, seed=3)
    res = rk.ik_batch(chain, values, start, path=path, **options)
    for k, T in enumerate(targets):
        check(chain, res.q[k], res.success[k], res.error_p[k], res.error_r[k], T, task, tol_p, tol_r, fk=fk)
    if solver:  # the bound solver: the same verdicts, each call re-verified
        s = rk.IKSolver(chain, **options)
        for T, target in zip(targets, values):
            r = s.solve(target, start)
            check(chain, r.q, r.success, r.error_p, r.error_r, T, task, tol_p, tol_r, fk=fk)


@given(cases=st.lists(rigid, min_size=1, max_size=4), q0=st.lists(st.floats(-20, 20), min_size=7, max_size=7),
       chain_index=st.integers(0, len(CHAINS) - 1), method=st.sampled_from(METHODS), task=st.sampled_from(TASKS),
       path=st.booleans(), restarts=st.integers(0, 3), tol_p=tolerances, tol_r=tolerances)
def test_ik_batch_success_is_verified_on_the_catalogue(cases, q0, chain_index, method, task, path, restarts, tol_p,
                                                        tol_r):
    chain = CHAINS[chain_index]
    targets = [rigid_target(case, chain, chain.fk) for case in cases]
    res = rk.ik_batch(chain, np.array([task_target(T, task) for T in targets]), np.array(q0[: chain.dof]),
                      method=method, task=task, tol_p=tol_p, tol_r=tol_r, max_iter=40, restarts=restarts,
                      seed=7, path=path)
    for k, T in enumerate(targets):
        check(chain, res.q[k], res.success[k], res.error_p[k], res.error_r[k], T, task, tol_p, tol_r)


# --- the closed forms (kept from test_ik_fuzz.py; rk.closed is fuzzed in its own file) -----------

closed_targets = st.one_of(arrays(), arrays([(4, 4), (2,), (3,)], elements=st.floats(-3, 3)))


@given(target=closed_targets, a=st.tuples(floats, floats, floats), method=st.sampled_from(["algebraic", "geometric"]))
def test_closed_forms_return_or_raise(target, a, method):
    calls = [
        lambda: rk.closed.planar_rp(target),
        lambda: rk.closed.planar_2r(target, a[0], a[1]),
        lambda: rk.closed.planar_3r(target, *a, method=method),
        lambda: rk.closed.anthropomorphic(target, a[0], a[1], a[2]),
        lambda: rk.closed.puma560(target),
        lambda: rk.closed.spherical_wrist_6r(target, 0.4, 0.02, 0.1, 0.4, d6=a[0]),
    ]
    for call in calls:
        try:
            s = call()
        except (ValueError, TypeError):  # a bad value; a target of the wrong kind (None, a string)
            continue
        assert np.all(np.isfinite(s.q)) and len(s.postures) == len(s)


# --- regressions ------------------------------------------------------------------------------


def test_far_targets_give_a_finite_error_or_a_value_error():
    """A target beyond ~1e154 made error_p overflow to inf (ik, ik_batch, IKSolver.solve)."""
    T = np.eye(4)
    T[:3, 3] = [1e200, 0.0, 0.0]
    for r in (rk.ik(UR5, T, np.zeros(6)), rk.IKSolver(UR5).solve(T, np.zeros(6)),
              rk.ik(UR5, T[:3, 3], np.zeros(6), task="position", method="halley")):
        assert r.error_p == 1e200 and not r.success
    assert rk.ik_batch(UR5, T[None], np.zeros(6)).error_p[0] == 1e200
    T[:3, 3] = [1.7e308, 1.7e308, 0.0]
    for call, name in ((lambda: rk.ik(UR5, T, np.zeros(6)), "target"),
                       (lambda: rk.IKSolver(UR5).solve(T, np.zeros(6)), "target"),
                       (lambda: rk.ik_batch(UR5, T[None], np.zeros(6), path=True), "targets")):
        try:
            call()
            raise AssertionError("no ValueError")
        except ValueError as e:
            assert str(e).startswith(name + ": the error is not finite")


def test_timeout_and_damping_of_the_wrong_type_name_themselves():
    """timeout="1" or damping="x" raised pybind11's RuntimeError "Unable to cast ... to C++ type '?'";
    a wrong kind of object is a TypeError naming the option and what it takes."""
    for kwargs, name in ((dict(timeout="1"), "timeout"), (dict(damping="x"), "damping"), (dict(damping=[1.0]), "damping")):
        for call in (lambda: rk.ik(UR5, np.eye(4), np.zeros(6), **kwargs),
                     lambda: rk.ik_batch(UR5, np.eye(4)[None], np.zeros(6), **kwargs),
                     lambda: rk.IKSolver(UR5, **kwargs)):
            with pytest.raises(TypeError) as e:
                call()
            assert str(e.value) == f"{name}: expected None or float, got {type(next(iter(kwargs.values()))).__name__}"
