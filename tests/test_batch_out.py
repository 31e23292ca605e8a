"""The batch calls that return one array take ``out=`` as Chain.fk does (test_fk_out.py):
Chain.manipulability of a batch and RRR3.ik_batch write into the caller's array, bit for bit the
new array's values, return it, and refuse a wrong kind, shape or layout, or an array sharing memory
with the input, by name and before anything is written."""

import math

import numpy as np
import pytest

import robokin as rk

RNG_SEED = 31  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)
UR5 = rk.robots.ur5()
ROBOT = rk.RRR3()


def manipulability_batch(count):
    Q = RNG.uniform(-math.pi, math.pi, (count, 6))
    return Q, lambda **kw: UR5.manipulability(Q, "condition", **kw)


def rrr3_batch(count):
    # Poses around the centre, some out of reach (NaN rows, written too).
    P = np.column_stack([RNG.uniform(-0.3, 0.3, count), RNG.uniform(-0.3, 0.3, count), RNG.uniform(-1, 1, count)])
    return P, lambda **kw: ROBOT.ik_batch(P, **kw)


CALLS = {"manipulability": manipulability_batch, "RRR3.ik_batch": rrr3_batch}


@pytest.mark.parametrize("call", CALLS)
@pytest.mark.parametrize("count", [1, 33, 5000])
def test_out_receives_the_new_arrays_result(call, count):
    _, compute = CALLS[call](count)
    fresh = compute()
    out = np.full(fresh.shape, 7.0)
    assert compute(out=out) is out
    assert out.tobytes() == fresh.tobytes()
    if call == "RRR3.ik_batch" and count > 1:
        assert np.isnan(fresh).any() and not np.isnan(fresh).all()  # both kinds of row were written


@pytest.mark.parametrize("call", CALLS)
def test_a_bad_out_is_refused_by_name_and_left_untouched(call):
    data, compute = CALLS[call](10)
    shape = compute().shape
    wrong = (11,) + shape[1:]
    cases = [
        ([0.0] * 10, TypeError, "out: expected a numpy array or None, got list"),
        (np.zeros(shape, dtype=np.float32), TypeError, "out: expected a float64 array, got float32"),
        (np.zeros(wrong), ValueError, rf"out: expected shape \({shape[0]},{' ' + str(shape[1]) if len(shape) > 1 else ''}\)"),
        (np.zeros(shape + (2,))[..., 0], ValueError, "out: expected a writable, aligned, C-contiguous array"),
    ]
    for out, error, message in cases:
        before = np.array(out, copy=True) if isinstance(out, np.ndarray) else None
        with pytest.raises(error, match=message):
            compute(out=out)
        if before is not None:
            assert np.array_equal(out, before)
    # an output in the input's own memory: refused, the input untouched
    kept = data.copy()
    overlap = data.reshape(-1)[:int(np.prod(shape))].reshape(shape)
    name = "poses" if call == "RRR3.ik_batch" else "q"
    with pytest.raises(ValueError, match=f"out: shares memory with {name}"):
        compute(out=overlap)
    assert np.array_equal(data, kept)


def test_out_is_for_a_batch_only():
    with pytest.raises(ValueError, match=r"^out: a single q gives a float; out is for a batch q \(N, dof\)$"):
        UR5.manipulability(np.zeros(6), out=np.zeros(1))
    assert UR5.manipulability(np.zeros(6), out=None) == UR5.manipulability(np.zeros(6))
