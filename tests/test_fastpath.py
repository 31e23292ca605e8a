"""The specialised evaluation paths (single fk / jacobian, batch fk, the binding's fast path for
float64 C-contiguous arrays) against KDL's solvers, and the binding's argument checks on every
input route. Nothing here times anything: speed is measured in benchmarks/."""

import math
import warnings

import numpy as np
import pytest

import robokin as rk

CHAINS = {
    "rpr": rk.robots.rpr,
    "ur5": rk.robots.ur5,
    "puma560": rk.robots.puma560,
    "prr": rk.robots.prr,
    "planar_3r": rk.robots.planar_3r,
    "rp": rk.robots.rp,
}


def random_q(chain, rng, size=None):
    lower, upper = chain.limits
    lo = np.where(np.isfinite(lower), lower, -math.pi)
    hi = np.where(np.isfinite(upper), upper, math.pi)
    return rng.uniform(lo, hi, size=None if size is None else (size, chain.dof))


@pytest.mark.parametrize("name", sorted(CHAINS))
def test_single_fk_and_jacobian_equal_kdl(name):
    chain, rng = CHAINS[name](), np.random.default_rng(1)
    for _ in range(50):
        q = random_q(chain, rng)
        np.testing.assert_allclose(chain.fk(q), chain._fk_kdl(q), rtol=0, atol=1e-12)
        np.testing.assert_allclose(chain.jacobian(q), chain._jacobian_kdl(q), rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", sorted(CHAINS))
def test_batch_fk_equals_kdl_and_single(name):
    chain, rng = CHAINS[name](), np.random.default_rng(2)
    Q = random_q(chain, rng, 257)  # not a multiple of any block size
    batch = chain.fk(Q)
    assert batch.shape == (257, 4, 4)
    for k in range(len(Q)):
        np.testing.assert_allclose(batch[k], chain._fk_kdl(Q[k]), rtol=0, atol=1e-12)
        np.testing.assert_array_equal(batch[k], chain.fk(Q[k]))


@pytest.mark.parametrize("name", sorted(CHAINS))
def test_fk_few_gives_single_fk_bits(name):
    """Chain::fk_few (the closed forms' check of up to 8 candidates in one pass of the lane kernel,
    its AVX2 build here) gives each row the bits fk gives it, for every count of rows."""
    from robokin import _testing

    chain, rng = CHAINS[name](), np.random.default_rng(7)
    Q = random_q(chain, rng, 8) * 10.0 ** rng.integers(-2, 3, (8, chain.dof))
    for count in range(1, 9):
        few = _testing.fk_few(chain, Q[:count])
        assert few.shape == (count, 4, 4)
        for k in range(count):
            np.testing.assert_array_equal(few[k], chain.fk(Q[k]))
            np.testing.assert_allclose(few[k], chain._fk_kdl(Q[k]), rtol=0, atol=1e-9)
    with pytest.raises(ValueError, match=r"Q: expected shape \(k, dof\) with k <= 8"):
        _testing.fk_few(chain, random_q(chain, rng, 9))


@pytest.mark.parametrize("name", sorted(CHAINS))
def test_fk_few_turns_reads_the_turns_of_revolute_chains(name):
    """Chain::fk_few_turns (the closed forms' check of candidates held as cosines and sines) gives
    fk of the turns' angles on a chain of revolute joints, and fk of the rows of Q (the turns not
    read) on one with a prismatic joint: given the turns of Q + 0.1, the first gives fk(Q + 0.1)."""
    from robokin import _testing

    chain, rng = CHAINS[name](), np.random.default_rng(9)
    revolute = name in ("ur5", "puma560", "planar_3r")
    Q = random_q(chain, rng, 8)
    for count in range(1, 9):
        turned = Q[:count] + 0.1
        few = _testing.fk_few_turns(chain, Q[:count], np.cos(turned), np.sin(turned))
        assert few.shape == (count, 4, 4)
        for k in range(count):
            np.testing.assert_allclose(few[k], chain.fk(turned[k] if revolute else Q[k]), rtol=0, atol=1e-14)


@pytest.mark.parametrize("threads", ["1", "2"])
@pytest.mark.parametrize("name", ["rpr", "ur5"])
def test_large_frame_batch_gives_the_bits_of_small_batches(name, threads, monkeypatch):
    """A batch of frames large enough to be faulted in ahead of its stores (9 MB: several 2 MB
    pages, prefetched lines, the AVX-512 or AVX2 block stores) gives the bits of the same
    configurations evaluated in batches too small for that, on one thread or split between two."""
    chain, rng = CHAINS[name](), np.random.default_rng(8)
    Q = random_q(chain, rng, 70_001)
    monkeypatch.setenv("ROBOKIN_NUM_THREADS", threads)
    large = chain.fk(Q)
    small = np.concatenate([chain.fk(Q[k:k + 257]) for k in range(0, len(Q), 257)])
    np.testing.assert_array_equal(large, small)
    for k in rng.integers(0, len(Q), 20):
        np.testing.assert_allclose(large[k], chain._fk_kdl(Q[k]), rtol=0, atol=1e-12)
    positions = chain.fk(Q, part="position")
    np.testing.assert_array_equal(positions, large[:, :3, 3])


def test_large_joint_values_equal_kdl():
    chain, rng = rk.robots.ur5(), np.random.default_rng(3)
    for scale in (10.0, 1e3, 1e6):
        q = rng.uniform(-scale, scale, 6)
        np.testing.assert_allclose(chain.fk(q), chain._fk_kdl(q), rtol=0, atol=1e-9)
        np.testing.assert_allclose(chain.fk(q[None])[0], chain._fk_kdl(q), rtol=0, atol=1e-9)


def test_batch_blocks_equal_single_calls_at_any_joint_value():
    chain, rng = rk.robots.ur5(), np.random.default_rng(6)
    Q = rng.uniform(-1.0, 1.0, (200, 6)) * 10.0 ** rng.integers(-3, 8, (200, 6))  # beyond 1e5: std::sin
    batch = chain.fk(Q)
    for k in range(len(Q)):
        np.testing.assert_array_equal(batch[k], chain.fk(Q[k]))
        np.testing.assert_allclose(batch[k], chain._fk_kdl(Q[k]), rtol=0, atol=1e-9)


def test_every_input_route_gives_the_same_result():
    chain = rk.robots.ur5()
    q = np.random.default_rng(4).uniform(-3, 3, 6)
    expected, jac = chain.fk(q), chain.jacobian(q)
    routes = [q.tolist(), tuple(q), q.astype(">f8"), np.asfortranarray(q), np.repeat(q, 2)[::2],
              q.astype(np.longdouble)]
    for route in routes:
        np.testing.assert_array_equal(chain.fk(route), expected)
        np.testing.assert_array_equal(chain.jacobian(route), jac)
    np.testing.assert_array_equal(chain.fk(np.zeros(6, dtype=np.int64)), chain.fk(np.zeros(6)))


def test_results_are_fresh_arrays():
    chain = rk.robots.ur5()
    q = np.zeros(6)
    a, b = chain.fk(q), chain.fk(q)
    assert a is not b and not np.shares_memory(a, b)
    a[0, 0] = 42.0
    assert chain.fk(q)[0, 0] != 42.0
    assert a.dtype == np.float64 and a.flags.c_contiguous and a.flags.writeable


@pytest.mark.parametrize("method", ["fk", "jacobian"])
@pytest.mark.parametrize(
    "bad",
    [np.zeros(5), np.zeros((2, 5)), np.zeros((2, 2, 6)), np.array([0, 0, 0, 0, 0, np.nan]),
     np.array([0, 0, 0, 0, np.inf, 0]), np.zeros(0)],
)
def test_bad_q_raises_value_error_naming_q(method, bad):
    chain = rk.robots.ur5()
    with pytest.raises(ValueError, match="q"):
        getattr(chain, method)(bad)


@pytest.mark.parametrize("method", ["fk", "jacobian"])
@pytest.mark.parametrize("bad", [np.zeros(6, dtype=complex), None, "abcdef"])
def test_q_of_the_wrong_kind_raises_type_error_naming_q(method, bad):
    with pytest.raises(TypeError, match="q: expected"):
        getattr(rk.robots.ur5(), method)(bad)


def test_complex_numbers_in_a_list_are_refused_not_cast():
    """A list of complex scalars makes a complex array: casting it to float64 would drop the
    imaginary parts with only numpy's warning, and compute a wrong answer."""
    chain = rk.robots.rpr()
    for bad in ([np.complex128(0.5 + 1j), 0.0, 0.0], [0.5 + 0j, 0, 0], [[0.1j, 0, 0]]):
        with pytest.raises(TypeError, match="q: expected real numbers, got a complex array"):
            chain.fk(bad)
    with pytest.raises(TypeError, match="target: expected real numbers, got a complex array"):
        rk.reach(chain, [np.complex128(0.5 + 1j), 0.5], np.zeros(3))
    # Refused without numpy's ComplexWarning first (the shape hint reads the shape only).
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(TypeError, match="target: expected real numbers, got a complex array"):
            rk.reach(chain, np.array([0.5 + 1j, 0.5]), np.zeros(3))


def test_nan_in_batch_is_rejected():
    chain = rk.robots.rpr()
    Q = np.zeros((1000, 3))
    Q[777, 1] = np.nan
    with pytest.raises(ValueError, match="q"):
        chain.fk(Q)


# --------------------------------------------------------------------------- the Reach loop
L1, L3 = rk.robots.RPR_L1, rk.robots.RPR_L3


def _reach_literal(p_target, theta, lower, upper):
    """Seed 000, Algorithm 1, line by line, with eqs. (1) and (9)."""
    n, delta, d, dt = 25, 1e-5, 0.75, 0.025

    def fk(t):
        return np.array([(L1 + t[1]) * np.cos(t[0]) + L3 * np.cos(t[0] + t[2]),
                         (L1 + t[1]) * np.sin(t[0]) + L3 * np.sin(t[0] + t[2])])

    def jac(t):
        s1, c1, s13, c13 = np.sin(t[0]), np.cos(t[0]), np.sin(t[0] + t[2]), np.cos(t[0] + t[2])
        return np.array([[-(L1 + t[1]) * s1 - L3 * s13, c1, -L3 * s13],
                         [(L1 + t[1]) * c1 + L3 * c13, s1, L3 * c13]])

    p = fk(theta)
    while True:
        J = jac(theta)
        theta = np.clip(theta + dt * (J.T @ np.linalg.inv(J @ J.T) @ (d * (p_target - p) / dt)), lower, upper)
        p = fk(theta)
        n -= 1
        if n == 0 or np.linalg.norm(p_target - p) < delta:
            return theta, 25 - n


def test_track_equals_the_literal_seed_algorithm_point_by_point():
    chain = rk.robots.rpr()
    lower, upper = chain.limits
    q0 = np.array([math.pi / 2, 0.5, math.pi / 2])
    points = rk.paths.line(chain.fk(q0)[:2, 3], (1.5, 1.0), 0.002)
    tr = rk.track(chain, points, q0)
    q = q0
    for k, p in enumerate(points):
        q, iterations = _reach_literal(p, q, lower, upper)
        np.testing.assert_allclose(tr.q[k], q, rtol=0, atol=1e-9)
        assert tr.iterations[k] == iterations
    assert tr.converged.all()


def test_reach_and_track_agree_on_every_task():
    rng = np.random.default_rng(5)
    cases = [(rk.robots.ur5(), "pose"), (rk.robots.ur5(), "position"), (rk.robots.puma560(), "pose"),
             (rk.robots.planar_3r(), "xyphi"), (rk.robots.rpr(), "xy"), (rk.robots.prr(), "position"),
             (rk.robots.rp(), "xy"),  # 2 joints, 7 joints: the loop's dynamic-size build
             (rk.Chain.from_dh([(0.3, math.pi / 2 * (i % 2), 0.1, 0.0, "R") for i in range(7)]), "pose")]
    for chain, task in cases:
        q0 = random_q(chain, rng) * 0.5
        q1 = q0 + rng.uniform(-0.02, 0.02, chain.dof)
        T = chain._fk_kdl(q1)
        target = {"pose": T, "position": T[:3, 3], "xy": T[:2, 3],
                  "xyphi": np.array([T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])])}[task]
        res = rk.reach(chain, target, q0, task=task, saturate=False)
        assert res.converged, (chain, task, res)
        tr = rk.track(chain, np.asarray(target)[None], q0, task=task, saturate=False)
        np.testing.assert_array_equal(tr.q[0], res.q)
        assert tr.iterations[0] == res.iterations and tr.error[0] == res.error


def test_track_with_nullspace_and_damping_stays_within_tolerance():
    chain = rk.robots.rpr()
    lower, upper = chain.limits
    q0 = np.array([math.pi / 2, 0.5, math.pi / 2])
    points = rk.paths.line(chain.fk(q0)[:2, 3], (1.5, 1.0), 0.005)
    for options in ({"nullspace": "joint_limits"}, {"damping": 1e-3}, {"nullspace": np.array([0.5, 0.0, 0.2])}):
        tr = rk.track(chain, points, q0, **options)
        assert tr.converged.all(), options
        assert np.all(tr.q >= lower - 1e-15) and np.all(tr.q <= upper + 1e-15)
        for k in range(0, len(points), 97):
            np.testing.assert_allclose(chain._fk_kdl(tr.q[k])[:2, 3], points[k], rtol=0, atol=1e-5)


def unaligned(a):
    """A copy of ``a`` (float64) whose buffer starts one byte off an 8-byte boundary, as an array
    unpickled from a byte stream can (a Dask worker's)."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    raw = np.zeros(a.nbytes + 1, dtype=np.uint8)
    out = raw[1:].view(np.float64).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned
    return out


def test_unaligned_buffers_give_the_same_results():
    """The core reads doubles; an unaligned buffer is copied first (UBSan, in make test-asan, reports
    a misaligned load otherwise)."""
    chain = rk.robots.ur5()
    Q = np.random.default_rng(3).uniform(-3, 3, (50, 6))
    np.testing.assert_array_equal(chain.fk(unaligned(Q)), chain.fk(Q))
    np.testing.assert_array_equal(chain.fk(unaligned(Q), part="position"), chain.fk(Q, part="position"))
    T = chain.fk(Q[:5])
    a = rk.ik_batch(chain, unaligned(T), unaligned(Q[0]), restarts=2, seed=1)
    b = rk.ik_batch(chain, T, Q[0], restarts=2, seed=1)
    np.testing.assert_array_equal(a.q, b.q)
    np.testing.assert_array_equal(rk.RRR3().ik_batch(unaligned(np.zeros((3, 3)))), rk.RRR3().ik_batch(np.zeros((3, 3))))


def test_results_unpickled_from_unaligned_state_arrays():
    """A result's state arrays may arrive at any address (pickle protocol 5 buffers): the copy is exact."""
    import pickle

    chain = rk.robots.ur5()
    T = chain.fk(np.random.default_rng(4).uniform(-3, 3, (4, 6)))
    res = rk.ik_batch(chain, T, np.zeros(6), restarts=2, seed=1)
    version, *arrays = res.__getstate__()
    moved = type(res).__new__(type(res))
    moved.__setstate__((version, *(unaligned(a) if a.dtype == np.float64 else a for a in arrays)))
    np.testing.assert_array_equal(moved.q, res.q)
    np.testing.assert_array_equal(moved.error_p, res.error_p)
    assert pickle.loads(pickle.dumps(res, protocol=5)).q.tobytes() == res.q.tobytes()


# Chain.fk, Chain.jacobian and Chain.manipulability are bound without pybind11's dispatcher
# (cpp/bindings/internals.hpp, the table in chain.cpp): the argument handling Python users expect, written
# out there; ik's checks of its own arguments are here too.
UR5 = rk.robots.ur5()
Q5 = np.zeros(6)
FAST_CALL_ERRORS = [
    (lambda: UR5.fk(), TypeError, "fk() missing required argument 'q'"),
    (lambda: UR5.fk(Q5, "frame", np.empty((4, 4))), TypeError, "fk() takes at most 2 positional arguments (3 given)"),
    (lambda: UR5.fk(Q5, bogus=1), TypeError, "fk() got an unexpected keyword argument 'bogus'"),
    (lambda: UR5.fk(Q5, "frame", part="frame"), TypeError, "fk() got multiple values for argument 'part'"),
    (lambda: UR5.fk(Q5, part="nope"), ValueError, "part: expected 'frame' or 'position', got 'nope'"),
    (lambda: UR5.fk(Q5, out="frame"), TypeError, "out: expected a numpy array or None, got str"),
    (lambda: UR5.jacobian(q=Q5, task="nope"), ValueError, "task"),
    (lambda: UR5.jacobian(Q5, 3), TypeError, "task: expected None or a string"),
    (lambda: rk._core.Chain.fk(1, Q5), TypeError, "doesn't apply to a 'int' object"),
    (lambda: rk.ik(1, np.eye(4), Q5), TypeError, "chain: expected a robokin.Chain, got int"),
    (lambda: rk.ik_batch(1, np.eye(4)[None], Q5), TypeError, "chain: expected a robokin.Chain, got int"),
    (lambda: rk._core.ik(UR5, np.eye(4), Q5, seed="x"), TypeError, "seed: expected None or an int"),
    (lambda: rk._core.ik(UR5, np.eye(4), Q5, tol_p=-1.0), ValueError, "tol_p: must be a positive number"),
    (lambda: rk._core.ik(UR5, np.eye(4), Q5, bogus=1), TypeError, "bogus"),
    (lambda: UR5.manipulability(), TypeError, "manipulability() missing required argument 'q'"),
    (lambda: UR5.manipulability(Q5, "yoshikawa", "pose", 1), TypeError, "takes at most 3 positional arguments"),
    (lambda: UR5.manipulability(Q5, measure="nope"), ValueError, "measure"),
    (lambda: UR5.manipulability(Q5, task=1), TypeError, "task: expected None or a string"),
    (lambda: rk.closed.ClosedSolver(UR5).solve(np.eye(3)), ValueError, "target"),
]


@pytest.mark.parametrize("call, error, message", FAST_CALL_ERRORS)
def test_fast_calls_report_argument_mistakes_like_python(call, error, message):
    with pytest.raises(error) as info:
        call()
    assert message in str(info.value)


def test_fast_calls_take_keywords_positions_and_defaults_alike():
    q = np.array([0.1, -0.8, 1.1, 0.2, 0.5, -0.3])
    T = UR5.fk(q)
    assert np.array_equal(UR5.fk(q=q), T) and np.array_equal(UR5.fk(q, "frame"), T)
    assert np.array_equal(UR5.fk(q, part="position"), T[:3, 3])
    J = UR5.jacobian(q)
    assert np.array_equal(UR5.jacobian(q, "pose"), J) and np.array_equal(UR5.jacobian(task="position", q=q), J[:3])
    by_position = rk._core.ik(UR5, T, q + 0.05, seed=1, tol_p=1e-10)
    by_keyword = rk._core.ik(q0=q + 0.05, target=T, chain=UR5, tol_p=1e-10, seed=1)
    assert by_position.success and np.array_equal(by_position.q, by_keyword.q)
    ur = rk.closed.ClosedSolver(UR5)
    assert np.array_equal(ur.solve(T).q, ur.solve(target=T).q) and np.array_equal(ur.solve(T).q, rk.closed.ur(T, UR5).q)
    w = UR5.manipulability(q)
    assert w == UR5.manipulability(q, "yoshikawa", "pose") == UR5.manipulability(task="pose", q=q)
    assert UR5.manipulability(q, task="position") == UR5.manipulability(q, "yoshikawa", task="position")
    assert UR5.manipulability(np.stack([q, q])).tolist() == [w, w]
    solver = rk.IKSolver(UR5, seed=1)
    assert np.array_equal(solver.solve(T, q + 0.05).q, rk.IKSolver(UR5, seed=1).solve(q0=q + 0.05, target=T).q)
    for f in (UR5.fk, UR5.jacobian, UR5.manipulability, rk._core.ik, solver.solve):  # the signature line help() and the stubs read
        assert f.__doc__.startswith(f.__name__ + "(")
