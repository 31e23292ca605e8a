"""robokin.traj.quintic writes into the caller's arrays with ``out=`` (numpy's idiom: the caller
reuses memory across calls): the samples are the same as a new trajectory's, bit for bit (whose
values tests/test_traj.py checks against the closed form); the returned Trajectory holds out's q, qd
and qdd arrays themselves and a copy of t; out.t is neither read nor written; and an out of the wrong
kind, or an array of the wrong kind, shape or layout, or one sharing memory with t or with another
of out's arrays, is refused by name before anything is written."""

import numpy as np
import pytest

from robokin import traj
from robokin.traj import Trajectory

RNG_SEED = 21  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)


def empty_out(k, n, fill=np.nan):
    """A Trajectory of new arrays, filled so that anything left unwritten shows."""
    return Trajectory(np.full(k, fill), np.full((k, n), fill), np.full((k, n), fill), np.full((k, n), fill))


def same_bits(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("k", [2, 33, 20000])  # the ends only, one block, several parallel blocks
@pytest.mark.parametrize("velocities", [False, True])
def test_out_receives_the_samples_of_a_new_trajectory(k, velocities):
    n = 6
    q0, q1 = RNG.uniform(-2, 2, n), RNG.uniform(-2, 2, n)
    ends = dict(qd0=RNG.uniform(-1, 1, n), qd1=RNG.uniform(-1, 1, n)) if velocities else {}
    t = np.sort(RNG.uniform(0.0, 3.0, k))
    fresh = traj.quintic(q0, q1, t, **ends)
    out = empty_out(k, n)
    tr = traj.quintic(q0, q1, t, **ends, out=out)
    assert tr.q is out.q and tr.qd is out.qd and tr.qdd is out.qdd
    for got, want in ((tr.t, fresh.t), (tr.q, fresh.q), (tr.qd, fresh.qd), (tr.qdd, fresh.qdd)):
        assert same_bits(got, want)
    assert not np.shares_memory(tr.t, t) and np.isnan(out.t).all()  # t copied as without out; out.t untouched
    for a in (out.q, out.qd, out.qdd):
        a.fill(7.0)  # reused: every value written again
    again = traj.quintic(q0, q1, t, **ends, out=out)
    assert all(np.shares_memory(a, b) for a, b in ((again.q, out.q), (again.qd, out.qd), (again.qdd, out.qdd)))
    assert same_bits(again.q, fresh.q) and same_bits(again.qd, fresh.qd) and same_bits(again.qdd, fresh.qdd)


def test_a_trajectory_from_an_earlier_call_is_reused_for_the_next():
    t = np.linspace(0.0, 2.0, 101)
    first = traj.quintic(np.zeros(3), np.ones(3), t)
    kept = first.q, first.qd, first.qdd
    q0, q1 = RNG.uniform(-1, 1, 3), RNG.uniform(-1, 1, 3)
    second = traj.quintic(q0, q1, t + 1.0, out=first)
    assert all(a is b for a, b in zip((second.q, second.qd, second.qdd), kept))
    want = traj.quintic(q0, q1, t + 1.0)
    assert same_bits(second.q, want.q) and same_bits(second.qd, want.qd) and same_bits(second.qdd, want.qdd)
    assert same_bits(second.t, t + 1.0) and same_bits(first.t, t)  # each trajectory keeps its own times


def test_out_t_may_be_anything_and_a_none_array_is_made_new():
    t = np.linspace(0.0, 1.0, 11)
    q = np.empty((11, 2))
    tr = traj.quintic([0.0, 1.0], [1.0, 0.0], t, out=Trajectory(None, q, None, None))
    want = traj.quintic([0.0, 1.0], [1.0, 0.0], t)
    assert tr.q is q and same_bits(tr.q, want.q)
    assert same_bits(tr.qd, want.qd) and same_bits(tr.qdd, want.qdd)


def test_times_converted_from_a_list_are_apart_from_any_out():
    out = empty_out(5, 2)
    tr = traj.quintic([0.0, 0.0], [1.0, 2.0], [0.0, 0.1, 0.5, 0.7, 1.0], out=out)
    assert tr.q is out.q and same_bits(tr.q, traj.quintic([0.0, 0.0], [1.0, 2.0], [0.0, 0.1, 0.5, 0.7, 1.0]).q)


def _with(k=5, n=2, **arrays):
    """A Trajectory of good (k, n) arrays, some replaced by ``arrays``."""
    fields = dict(t=None, q=np.empty((k, n)), qd=np.empty((k, n)), qdd=np.empty((k, n)))
    fields.update(arrays)
    return Trajectory(**fields)


def _read_only():
    a = np.empty((5, 2))
    a.setflags(write=False)
    return a


def _unaligned():
    raw = np.empty(10 * 8 + 1, dtype=np.uint8)
    a = raw[1:].view(np.float64).reshape(5, 2)
    assert not a.flags.aligned
    return a


LAYOUT = "expected a writable, aligned, C-contiguous array (np.empty gives one)"
BAD_OUTS = [
    (np.empty((5, 2)), TypeError, "out: expected a robokin.traj.Trajectory or None, got ndarray"),
    ((np.empty((5, 2)),) * 3, TypeError, "out: expected a robokin.traj.Trajectory or None, got tuple"),
    (_with(q=[[0.0, 0.0]] * 5), TypeError, "out.q: expected a numpy array or None, got list"),
    (_with(qd=np.empty((5, 2), dtype=np.float32)), TypeError, "out.qd: expected a float64 array, got float32"),
    (_with(qdd=np.empty((5, 2), dtype=np.int64)), TypeError, "out.qdd: expected a float64 array, got int64"),
    (_with(q=np.empty((5, 2), dtype=">f8")), TypeError, "out.q: expected a float64 array, got >f8"),
    (_with(q=np.empty((5, 3))), ValueError, "out.q: expected shape (5, 2), got (5, 3)"),
    (_with(qd=np.empty((2, 5))), ValueError, "out.qd: expected shape (5, 2), got (2, 5)"),
    (_with(qdd=np.empty(10)), ValueError, "out.qdd: expected shape (5, 2), got (10,)"),
    (_with(q=np.empty((5, 4))[:, ::2]), ValueError, f"out.q: {LAYOUT}"),
    (_with(qd=np.empty((5, 2), order="F")), ValueError, f"out.qd: {LAYOUT}"),
    (_with(qdd=_read_only()), ValueError, f"out.qdd: {LAYOUT}"),
    (_with(q=_unaligned()), ValueError, f"out.q: {LAYOUT}"),
]


@pytest.mark.parametrize("bad, error, message", BAD_OUTS)
def test_a_bad_out_is_refused_by_name(bad, error, message):
    with pytest.raises(error) as caught:
        traj.quintic([0.0, 1.0], [1.0, 0.0], np.linspace(0.0, 1.0, 5), out=bad)
    assert str(caught.value) == message


def test_the_inputs_are_checked_before_outs_arrays():
    with pytest.raises(ValueError) as caught:
        traj.quintic([0.0], [1.0], [1.0, 0.0], out=_with(q=np.empty(3)))
    assert str(caught.value) == "t: times must be strictly increasing"


def _overlaps():
    """(t, out, message) where out's arrays overlap t or each other (all in one buffer)."""
    buf = np.zeros(5 + 4 * 10)
    t, a, b, c, d = buf[:5], *(buf[5 + 10 * i:15 + 10 * i].reshape(5, 2) for i in range(4))
    t[:] = np.linspace(0.0, 1.0, 5)
    over_t = buf[3:13].reshape(5, 2)  # its first two values are t's last two
    return buf, t, [
        (Trajectory(None, over_t, b, c), "out.q: shares memory with t"),
        (Trajectory(None, a, b, buf[:10].reshape(5, 2)), "out.qdd: shares memory with t"),
        (Trajectory(None, a, a, c), "out.qd: shares memory with out.q"),
        (Trajectory(None, a, b, a), "out.qdd: shares memory with out.q"),
        (Trajectory(None, a, b, buf[24:34].reshape(5, 2)), "out.qdd: shares memory with out.qd"),
        (Trajectory(None, d, b, c), None),  # apart: accepted
    ]


@pytest.mark.parametrize("case", range(6))
def test_out_sharing_memory_with_t_or_with_itself_is_refused_untouched(case):
    buf, t, cases = _overlaps()
    out, message = cases[case]
    before = buf.copy()
    if message is None:
        tr = traj.quintic([0.0, 1.0], [1.0, 0.0], t, out=out)
        assert same_bits(tr.q, traj.quintic([0.0, 1.0], [1.0, 0.0], np.linspace(0.0, 1.0, 5)).q)
        return
    with pytest.raises(ValueError) as caught:
        traj.quintic([0.0, 1.0], [1.0, 0.0], t, out=out)
    assert str(caught.value) == message
    assert buf.tobytes() == before.tobytes()
