"""Arbitrary arrays into the chain and Reach calls: a result of the right shape, or a ValueError;
never a crash or a NaN."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import robokin as rk

CHAINS = [rk.robots.rpr(), rk.robots.ur5()]
floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
shapes = hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=7)
arrays = st.one_of(
    hnp.arrays(np.float64, shapes, elements=floats),
    hnp.arrays(np.float32, shapes, elements=st.floats(width=32)),
    hnp.arrays(np.int64, shapes, elements=st.integers(-5, 5)),
    hnp.arrays(np.bool_, shapes),
)


@settings(max_examples=300, deadline=None)
@given(chain=st.sampled_from(CHAINS), q=arrays, task=st.sampled_from(["pose", "position", "xy", "xyphi", "bad"]))
def test_fk_and_jacobian_return_finite_or_raise(chain, q, task):
    for call in (lambda: chain.fk(q), lambda: chain.jacobian(q, task=task), lambda: chain.frames(q)):
        try:
            out = call()
        except ValueError:
            continue
        assert np.all(np.isfinite(out))


@settings(max_examples=200, deadline=None)
@given(chain=st.sampled_from([rk.robots.rpr(), rk.robots.planar_3r()]), target=arrays, q=arrays, tol=floats, gain=floats)
def test_reach_returns_or_raises(chain, target, q, tol, gain):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        try:
            r = rk.reach(chain, target, q, tol=tol, gain=gain)
        except ValueError:
            return
    assert np.all(np.isfinite(r.q)) and np.isfinite(r.error)
    assert r.converged == (r.error < tol)


@pytest.mark.parametrize("q", [np.arange(6.0)[::2], np.zeros((3, 6))[:, 0:3].T.copy(), np.zeros(3)])
def test_non_contiguous_and_read_only_arrays(q):
    chain = rk.robots.rpr()
    q = np.asarray(q)[: chain.dof] if q.ndim == 1 else q
    q.setflags(write=False)
    np.testing.assert_allclose(chain.fk(q), chain.fk(np.ascontiguousarray(q)))
