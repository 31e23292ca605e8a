"""Property tests of the Reach loop and path tracking: every keyword arbitrary, arrays of any shape
and dtype; a result is finite and shaped, or a ValueError / TypeError names the argument. And the
reported verdict is the verified one: ``converged`` is True exactly when the independently computed
task error of the returned q is below ``tol``, over reachable, unreachable and singular targets."""

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk
from fuzz import arrays, assert_finite, check_call, floats, wild_floats
from fuzz_chains import dh_chains, q_within, reference_fk, task_errors, task_target

COVERS = {"reach", "track", "ReachResult.q", "ReachResult.converged", "ReachResult.iterations", "ReachResult.error",
          "TrackResult.q", "TrackResult.error", "TrackResult.converged", "TrackResult.iterations", "ReachOptions"}

PI = math.pi
CHAINS = [rk.robots.rpr(), rk.robots.planar_3r(), rk.robots.ur5(), rk.robots.rp(),
          rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True)]
ARGNAMES = ("target", "points", "q", "q0", "task", "max_iter", "tol", "gain", "dt", "saturate", "nullspace", "damping")
tasks = st.one_of(st.sampled_from(["xy", "xyphi", "position", "pose", "bad"]), st.sampled_from([None, 3]))
target_shapes = [(2,), (3,), (4, 4), (6,), (0,), (1, 2)]
point_shapes = [(0, 2), (3, 2), (2, 3), (1, 4, 4), (0, 4, 4), (2,), (5, 3)]
q_shapes = [(2,), (3,), (6,), (7,), (1, 3)]
# max_iter: small valid values, <= 0, and ints past C int (pybind11's TypeError)
iters = st.one_of(st.integers(-2, 30), st.sampled_from([2**31, -(2**31) - 1, 2**63]), st.sampled_from([2.5, None, "5"]))
numbers = st.one_of(wild_floats, st.floats(1e-6, 2.0), st.sampled_from([None, "1", [1.0]]))
nullspaces = st.one_of(st.sampled_from([None, "joint_limits", "bad", ""]), arrays([(3,), (6,), (7,), (2,), (0,)]))
saturates = st.one_of(st.booleans(), st.sampled_from([None, 0, "yes"]))
# finite but huge: errors whose squares (or whose value) overflow
huge = st.sampled_from([1e308, -1e308, 1.7e308, 1e200, -1e160, 0.5, 0.0])
targets = st.one_of(arrays(target_shapes), arrays(target_shapes, elements=huge))
paths = st.one_of(arrays(point_shapes), arrays(point_shapes, elements=huge))


def expect_result_shapes(chain, q, error, converged, iterations, max_iter, tol):
    assert q.shape[-1] == chain.dof and q.dtype == np.float64
    assert_finite(q, error)
    assert np.all(np.asarray(error) >= 0)
    assert np.all(np.asarray(converged) == (np.asarray(error) < tol))
    assert np.all((np.asarray(iterations) >= 0) & (np.asarray(iterations) <= max_iter))


@given(chain=st.sampled_from(CHAINS), target=targets, q=arrays(q_shapes), task=tasks, max_iter=iters,
       tol=numbers, gain=numbers, dt=numbers, saturate=saturates, nullspace=nullspaces, damping=numbers)
def test_reach_with_arbitrary_arguments(chain, target, q, task, max_iter, tol, gain, dt, saturate, nullspace, damping):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = check_call(lambda: rk.reach(chain, target, q, task=task, max_iter=max_iter, tol=tol, gain=gain, dt=dt,
                                        saturate=saturate, nullspace=nullspace, damping=damping), *ARGNAMES)
    if r is None:
        return
    assert r.q.shape == (chain.dof,) and isinstance(r.converged, bool) and isinstance(r.iterations, int)
    expect_result_shapes(chain, r.q, r.error, r.converged, r.iterations, max_iter, tol)
    if saturate:
        lo, hi = chain.limits
        assert np.all(r.q >= lo) and np.all(r.q <= hi)


@given(chain=st.sampled_from(CHAINS), points=paths, q0=arrays(q_shapes), task=tasks, max_iter=iters,
       tol=numbers, gain=numbers, dt=numbers, saturate=saturates, nullspace=nullspaces, damping=numbers)
def test_track_with_arbitrary_arguments(chain, points, q0, task, max_iter, tol, gain, dt, saturate, nullspace, damping):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = check_call(lambda: rk.track(chain, points, q0, task=task, max_iter=max_iter, tol=tol, gain=gain, dt=dt,
                                        saturate=saturate, nullspace=nullspace, damping=damping), *ARGNAMES)
    if r is None:
        return
    k = len(points)
    assert r.q.shape == (k, chain.dof) and r.error.shape == r.converged.shape == r.iterations.shape == (k,)
    assert r.converged.dtype == np.bool_ and r.iterations.dtype == np.int32
    expect_result_shapes(chain, r.q, r.error, r.converged, r.iterations, max_iter, tol)


@given(options=st.dictionaries(st.sampled_from(["max_iter", "tol", "gain", "dt", "saturate", "damping", "bogus"]),
                               st.one_of(iters, numbers, saturates), max_size=4))
def test_reach_options_from_arbitrary_keywords(options):
    """Arbitrary keywords: an options struct holding exactly what was given, or a ValueError /
    TypeError naming the keyword (unknown names and kinds at construction, ranges at validation)."""
    o = check_call(lambda: rk.ReachOptions(**options), *options)
    if o is None:
        return
    for name, value in options.items():
        got = getattr(o, name)
        if isinstance(got, bool):
            assert got is bool(value)  # pybind11's bool caster: truth value (None is False, as before)
        elif isinstance(value, float) and math.isnan(value):
            assert math.isnan(got)
        else:
            assert got == value
    if not any(isinstance(v, float) and math.isnan(v) for v in options.values()):
        assert rk.ReachOptions(**{n: getattr(o, n) for n in rk.ReachOptions.fields}) == o


# --- reported convergence equals verified convergence ----------------------------------------


def reach_error(F, target, task):
    """The Reach task error |e| of the tool pose F: position and orientation rows together."""
    ep, er = task_errors(F, target, task)
    return math.hypot(ep, er)


def assert_verdict(chain, q, converged, error, target, task, tol, fk=None):
    """``converged`` and ``error`` agree with FK of q computed independently (numpy DH product, or
    KDL's recursive FK for chains that are not DH tables)."""
    # Beyond |q| ~ 1e3 (a runaway without limits) the rounding of huge angles and of cancelling
    # prismatic offsets depends on the order of the operations: the public FK is the reference there.
    if np.abs(q).max() >= 1e3:
        F = chain.fk(q)
    else:
        F = fk(q) if fk is not None else chain._fk_kdl(q)
    truth = reach_error(F, target, task)
    rounding = 1e-9 * (1 + truth)
    if task == "xyphi":
        # The planar angle atan2(R10, R00) is only as precise as the tool x axis' projection on the
        # plane is long: two FKs agreeing to 1e-16 give angles 1e-16 / projection apart.
        rounding += 1e-14 / max(math.hypot(F[0, 0], F[1, 0]), 1e-300)
    assert abs(error - truth) <= rounding, (error, truth)
    if abs(truth - tol) > rounding:  # no verdict within the rounding of FK
        assert converged == (truth < tol), (converged, truth, tol)


# Fixed robots with their task, and the special joints that make them singular (stretched or folded).
NAMED = {
    "planar_3r": (rk.robots.planar_3r(), ["xy", "xyphi"], [0.0, 0.0, 0.0]),
    "rpr": (rk.robots.rpr(), ["xy"], [0.0, 1.5, 0.0]),
    "ur5": (rk.robots.ur5(), ["position"], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
}
kinds = st.sampled_from(["near", "far", "singular", "axis"])


def make_target(chain, q_goal, task, kind, offset, fk):
    """Reachable ("near": the tool at q_goal, moved a little), unreachable ("far": 100 times out),
    at a stretched configuration pushed outwards ("singular"), or on the base axis ("axis")."""
    T = fk(q_goal)
    if kind == "far":
        T[:3, 3] = T[:3, 3] * 100 + 50
    elif kind == "singular":
        T[:3, 3] = T[:3, 3] * (1 + abs(offset[0]))
    elif kind == "axis":
        T[:2, 3] = 0.0
    else:
        T[:3, 3] += offset
    return task_target(T, task)


@given(name=st.sampled_from(sorted(NAMED)), kind=kinds, values=st.lists(st.floats(-PI, PI), min_size=6, max_size=6),
       start=st.lists(st.floats(-0.3, 0.3), min_size=6, max_size=6), offset=st.tuples(*[st.floats(-0.05, 0.05)] * 3),
       tol=st.sampled_from([1e-9, 1e-5, 1e-3]), max_iter=st.integers(1, 40), damping=st.sampled_from([0.0, 1e-3, 0.1]),
       nullspace=st.sampled_from([None, "joint_limits"]), data=st.data())
def test_reach_verdict_equals_verified_error(name, kind, values, start, offset, tol, max_iter, damping, nullspace, data):
    chain, task_list, singular_q = NAMED[name]
    task = data.draw(st.sampled_from(task_list))
    lo, hi = chain.limits
    n = chain.dof
    q_goal = np.clip(singular_q if kind == "singular" else values[:n], lo, hi)
    q = np.clip(q_goal + np.array(start[:n]), lo, hi)
    target = make_target(chain, q_goal, task, kind, offset, chain.fk)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = rk.reach(chain, target, q, task=task, tol=tol, max_iter=max_iter, damping=damping, nullspace=nullspace)
    assert r.q.shape == (n,) and 1 <= r.iterations <= max_iter
    assert_verdict(chain, r.q, r.converged, r.error, target, task, tol)


@given(case=dh_chains(max_dof=6), kind=kinds, task=st.sampled_from(["xy", "xyphi", "position", "pose"]),
       values=st.lists(st.floats(-PI, PI), min_size=7, max_size=7),
       start=st.lists(st.floats(-0.2, 0.2), min_size=7, max_size=7), offset=st.tuples(*[st.floats(-0.05, 0.05)] * 3),
       tol=st.sampled_from([1e-9, 1e-5, 1e-3]), max_iter=st.integers(1, 30), damping=st.sampled_from([0.0, 1e-2]),
       saturate=st.booleans())
def test_reach_verdict_on_random_chains(case, kind, task, values, start, offset, tol, max_iter, damping, saturate):
    chain = case["chain"]
    n = chain.dof
    q_goal = q_within(case, np.zeros(7) if kind == "singular" else values)
    q = q_within(case, q_goal + np.array(start[:n]))
    fk = lambda q: reference_fk(case, q)  # noqa: E731
    target = make_target(chain, q_goal, task, kind, offset, fk)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = rk.reach(chain, target, q, task=task, tol=tol, max_iter=max_iter, damping=damping, saturate=saturate)
    assert r.q.shape == (n,)
    assert_verdict(chain, r.q, r.converged, r.error, target, task, tol, fk=fk)


@given(name=st.sampled_from(sorted(NAMED)), kinds_=st.lists(kinds, min_size=1, max_size=5),
       values=st.lists(st.floats(-PI, PI), min_size=6, max_size=6), step=st.floats(-0.05, 0.05),
       tol=st.sampled_from([1e-9, 1e-5, 1e-3]), max_iter=st.integers(1, 30), data=st.data())
def test_track_verdict_equals_verified_error_at_every_point(name, kinds_, values, step, tol, max_iter, data):
    chain, task_list, singular_q = NAMED[name]
    task = data.draw(st.sampled_from(task_list))
    lo, hi = chain.limits
    n = chain.dof
    q0 = np.clip(values[:n], lo, hi)
    points = np.array([make_target(chain, np.clip(singular_q if kind == "singular" else q0 + k * step, lo, hi), task,
                                   kind, (step, step, 0.0), chain.fk) for k, kind in enumerate(kinds_)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = rk.track(chain, points, q0, task=task, tol=tol, max_iter=max_iter)
    assert r.q.shape == (len(points), n)
    for k, target in enumerate(points):
        assert_verdict(chain, r.q[k], r.converged[k], r.error[k], target, task, tol)


# --- moved from test_bad_input_fuzz.py -------------------------------------------------------


@pytest.mark.parametrize("q", [np.arange(6.0)[::2], np.zeros((3, 6))[:, 0:3].T.copy(), np.zeros(3)])
def test_non_contiguous_and_read_only_arrays(q):
    chain = rk.robots.rpr()
    q = np.asarray(q)[: chain.dof] if q.ndim == 1 else q
    q.setflags(write=False)
    np.testing.assert_allclose(chain.fk(q), chain.fk(np.ascontiguousarray(q)))
    start = np.zeros((3, 6))[:, ::2][0]  # non-contiguous, within the limits
    start.setflags(write=False)
    r = rk.reach(chain, chain.fk(np.array([0.1, 0.1, 0.1]))[:2, 3], start)
    assert r.converged and not r.q.flags.writeable and r.q is r.q and not start.any()  # made once, read-only


# --- regressions ------------------------------------------------------------------------------


def test_far_targets_give_a_finite_error_or_a_value_error():
    """A target beyond ~1e154 made |e| overflow: error=inf was returned (reach and track)."""
    chain = rk.robots.planar_3r()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = rk.reach(chain, [1e200, 1e200], np.zeros(3), task="xy")
        assert math.isfinite(r.error) and r.error == pytest.approx(math.sqrt(2) * 1e200) and not r.converged
        assert rk.track(chain, [[1e160, 0.0]], np.zeros(3), task="xy").error[0] == pytest.approx(1e160)
        with pytest.raises(ValueError, match="target: the task error is not finite"):
            rk.reach(chain, [1.7e308, 1.7e308], np.zeros(3), task="xy")
        with pytest.raises(ValueError, match="points: the task error is not finite"):
            rk.track(chain, [[0.0, 0.0], [1.7e308, -1.7e308]], np.zeros(3), task="xy")


def test_a_step_that_overflows_q_stops_at_finite_joints():
    """An overshooting gain on an unlimited prismatic joint drove q + dq past 1e308 (q = inf)."""
    chain = rk.Chain.from_dh([(0.0, 0.0, 0.0, 0.0, "P")])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        r = rk.reach(chain, [0.0, 0.0, 1.5e308], [1e308], task="position", gain=3.0, dt=1.0, max_iter=5)
    assert r.q[0] == 1e308 and r.error == pytest.approx(5e307) and r.iterations == 0
