"""Chain.fk and Chain.jacobian write into the caller's array with ``out=`` (numpy's idiom: the
caller reuses memory across calls): the result is the same as a new array's, bit for bit, for single
configurations and batches, frames and positions; ``out`` is returned; nothing else of it is
touched; and an array of the wrong kind, shape or layout, or one sharing memory with q, is refused
by name before anything is written."""

import math

import numpy as np
import pytest

import robokin as rk

RNG_SEED = 8  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)
UR5 = rk.robots.ur5()
RPR = rk.robots.rpr()


@pytest.mark.parametrize("chain", [UR5, RPR], ids=["ur5", "rpr"])
@pytest.mark.parametrize("count", [None, 1, 33, 40000])  # one configuration, the tail, blocks, streamed frames
@pytest.mark.parametrize("call", ["frame", "position", "jacobian", "jacobian position"])
def test_out_receives_the_new_arrays_result(chain, count, call):
    Q = RNG.uniform(-math.pi, math.pi, (chain.dof,) if count is None else (count, chain.dof))
    if call.startswith("jacobian"):
        task = "position" if call.endswith("position") else "pose"
        compute = lambda **kw: chain.jacobian(Q, task, **kw)  # noqa: E731
    else:
        compute = lambda **kw: chain.fk(Q, call, **kw)  # noqa: E731
    fresh = compute()
    out = np.full(fresh.shape, np.nan)  # anything left unwritten would stay NaN
    assert compute(out=out) is out
    assert out.tobytes() == fresh.tobytes()
    out.fill(7.0)  # reused: every value written again
    compute(out=out)
    assert out.tobytes() == fresh.tobytes()


def test_out_of_an_empty_batch():
    out = np.empty((0, 4, 4))
    assert UR5.fk(np.zeros((0, 6)), out=out) is out


def test_out_can_be_a_view_into_a_larger_array():
    Q = RNG.uniform(-1, 1, (50, 6))
    big = np.zeros((60, 4, 4))
    UR5.fk(Q, out=big[5:55])
    assert np.array_equal(big[5:55], UR5.fk(Q))
    assert not big[:5].any() and not big[55:].any()


BAD_OUTS = [
    ([[0.0] * 4] * 4, TypeError, "out: expected a numpy array or None, got list"),
    ("frame", TypeError, "out: expected a numpy array or None, got str"),
    (np.empty((4, 4), dtype=np.float32), TypeError, "out: expected a float64 array, got float32"),
    (np.empty((4, 4), dtype=">f8"), TypeError, "out: expected a float64 array, got >f8"),
    (np.empty((4, 4), dtype=np.int64), TypeError, "out: expected a float64 array, got int64"),
    (np.empty((4, 3)), ValueError, r"out: expected shape \(4, 4\), got \(4, 3\)"),
    (np.empty((1, 4, 4)), ValueError, r"out: expected shape \(4, 4\), got \(1, 4, 4\)"),
    (np.empty((4, 8))[:, ::2], ValueError, "out: expected a writable, aligned, C-contiguous array"),
    (np.empty((4, 4)).T, ValueError, "out: expected a writable, aligned, C-contiguous array"),
]


@pytest.mark.parametrize("bad, error, message", BAD_OUTS)
def test_a_bad_out_is_refused_by_name(bad, error, message):
    with pytest.raises(error, match=message):
        UR5.fk(np.zeros(6), out=bad)


def test_a_read_only_or_unaligned_out_is_refused():
    ro = np.empty((4, 4))
    ro.setflags(write=False)
    with pytest.raises(ValueError, match="out: expected a writable"):
        UR5.fk(np.zeros(6), out=ro)
    raw = np.empty(16 * 8 + 1, dtype=np.uint8)
    odd = raw[1:].view(np.float64).reshape(4, 4)
    assert not odd.flags.aligned
    with pytest.raises(ValueError, match="out: expected a writable, aligned"):
        UR5.fk(np.zeros(6), out=odd)


def test_out_sharing_memory_with_q_is_refused_untouched():
    buf = np.zeros(100 * 16)
    Q = buf[:600].reshape(100, 6)
    Q[:] = RNG.uniform(-1, 1, Q.shape)
    before = buf.copy()
    with pytest.raises(ValueError, match="out: shares memory with q"):
        UR5.fk(Q, out=buf.reshape(100, 4, 4))
    with pytest.raises(ValueError, match="out: shares memory with q"):
        UR5.jacobian(Q[:10], out=buf[30:390].reshape(10, 6, 6))
    assert buf.tobytes() == before.tobytes()
    apart = np.zeros((100, 4, 4))  # q converted (a list): a copy, so any out is apart from it
    UR5.fk(Q.tolist(), out=apart)
    assert np.array_equal(apart, UR5.fk(Q))


def test_a_wrong_shape_for_the_batch_names_the_expected_one():
    with pytest.raises(ValueError, match=r"out: expected shape \(3, 3\), got \(3, 4, 4\)"):
        RPR.fk(np.zeros((3, 3)), "position", out=np.empty((3, 4, 4)))
    with pytest.raises(ValueError, match=r"out: expected shape \(2, 2, 3\)"):
        RPR.jacobian(np.zeros((2, 3)), "xy", out=np.empty((2, 6, 3)))
