"""Outputs of 4 MB or more reuse the memory of freed ones (cpp/bindings/output_pool.cpp): the
values are those of a fresh output, the reused memory is a freed output's (no page faults), an
output still referenced is never reused, the freed outputs kept add up to at most 256 MB, and
rk.release_output_memory() gives them back."""

import gc
import resource
import sys

import numpy as np
import pytest

import robokin as rk

pytestmark = pytest.mark.skipif(sys.platform != "linux", reason="the pool exists on Linux only")

MB = 1 << 20
N = 300_000  # RPR frames: 38.4 MB
CALLS = {
    "fk frames": (rk.robots.rpr, N, lambda c, Q: c.fk(Q)),
    "fk positions": (rk.robots.rpr, 1_000_000, lambda c, Q: c.fk(Q, out="position")),  # 24 MB
    "jacobian": (rk.robots.ur5, 20_000, lambda c, Q: c.jacobian(Q)),  # 5.8 MB
}


def configurations(chain, n, seed):
    return np.random.default_rng(seed).uniform(-3.0, 3.0, (n, chain.dof))


def in_small_batches(call, chain, Q):
    return np.concatenate([call(chain, Q[k:k + 4096]) for k in range(0, len(Q), 4096)])


def page_faults(f):
    before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    out = f()
    return out, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()


@pytest.mark.parametrize("name", sorted(CALLS))
def test_a_freed_output_is_written_into_by_the_next_call_of_its_size(name):
    make, n, call = CALLS[name]
    chain = make()
    Q = configurations(chain, n, 2)
    rk.release_output_memory()
    first, fresh_faults = page_faults(lambda: call(chain, configurations(chain, n, 1)))
    address = first.ctypes.data
    first[...] = np.nan  # what the reused output holds before the call writes it
    del first
    out, faults = page_faults(lambda: call(chain, Q))
    assert out.ctypes.data == address
    assert out.flags.writeable and out.flags.c_contiguous and out.dtype == np.float64
    np.testing.assert_array_equal(out, in_small_batches(call, chain, Q))  # outputs below the pool's size
    for k in np.random.default_rng(3).integers(0, n, 5):  # and KDL's values, independently of both
        reference = chain._jacobian_kdl(Q[k]) if name == "jacobian" else chain._fk_kdl(Q[k])
        if name == "fk positions":
            reference = reference[:3, 3]
        np.testing.assert_allclose(out[k], reference, rtol=0, atol=1e-12)
    # A fresh output faults in every page (2 MB or 4 KB ones) of its 5.8-38 MB; the reused one none.
    assert fresh_faults >= 3
    assert faults <= fresh_faults // 3, (faults, fresh_faults)


def test_an_output_still_referenced_is_not_reused():
    chain = rk.robots.rpr()
    Q = configurations(chain, N, 4)
    first = chain.fk(Q)
    view = first[10:]  # keeps the memory alive
    expected = view.copy()
    del first
    second = chain.fk(configurations(chain, N, 5))
    assert not np.shares_memory(second, view)
    np.testing.assert_array_equal(view, expected)
    del view
    third = chain.fk(Q)  # now the first output's memory is free again
    np.testing.assert_array_equal(third[10:], expected)


def test_the_freed_outputs_kept_add_up_to_at_most_256_mb_and_are_released_on_request():
    chain = rk.robots.rpr()
    rk.release_output_memory()
    sizes = [N + 25_000 * k for k in range(12)]  # 38-74 MB each, 670 MB in all, none reusing another
    Q = configurations(chain, sizes[-1], 7)  # made first: no other memory comes and goes below
    gc.collect()
    before = resident_bytes()
    for n in sizes:
        chain.fk(Q[:n])  # freed at once
    kept = resident_bytes() - before
    assert 128 * MB < kept < 256 * MB + 16 * MB, kept / MB  # the newest ones (their pages still held)
    released = rk.release_output_memory()
    assert 128 * MB < released <= 256 * MB, released / MB
    assert resident_bytes() < before + 16 * MB
    assert rk.release_output_memory() == 0


def test_an_output_larger_than_the_budget_is_kept_alone():
    chain = rk.robots.rpr()
    rk.release_output_memory()
    chain.fk(configurations(chain, N, 8))
    big = 2_200_000  # 282 MB of frames, in whole pages
    chain.fk(configurations(chain, big, 9))  # the 38 MB one kept before is given back
    page = resource.getpagesize()
    assert rk.release_output_memory() == -(-big * 128 // page) * page
