"""The specialised evaluation paths (single fk / jacobian, batch fk, the binding's fast path for
float64 C-contiguous arrays) against KDL's solvers, and the binding's argument checks on every
input route. Nothing here times anything: speed is measured in benchmarks/."""

import math

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


def test_large_joint_values_equal_kdl():
    chain, rng = rk.robots.ur5(), np.random.default_rng(3)
    for scale in (10.0, 1e3, 1e6):
        q = rng.uniform(-scale, scale, 6)
        np.testing.assert_allclose(chain.fk(q), chain._fk_kdl(q), rtol=0, atol=1e-9)
        np.testing.assert_allclose(chain.fk(q[None])[0], chain._fk_kdl(q), rtol=0, atol=1e-9)


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
     np.array([0, 0, 0, 0, np.inf, 0]), np.zeros(6, dtype=complex), None, "abcdef", np.zeros(0)],
)
def test_bad_q_raises_value_error_naming_q(method, bad):
    chain = rk.robots.ur5()
    with pytest.raises(ValueError, match="q"):
        getattr(chain, method)(bad)


def test_nan_in_batch_is_rejected():
    chain = rk.robots.rpr()
    Q = np.zeros((1000, 3))
    Q[777, 1] = np.nan
    with pytest.raises(ValueError, match="q"):
        chain.fk(Q)
