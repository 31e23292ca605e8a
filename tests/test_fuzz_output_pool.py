"""Property test of the memory kept from freed outputs (cpp/bindings/output_pool.cpp): any sequence
of batch calls whose outputs lie around the pool's sizes (4 MB, reuse up to a fifth smaller), some
kept alive and some freed (poisoned with NaN first), with rk.release_output_memory() between them,
gives every output the values of small batches, never two live outputs in one memory, and releases
what was kept, once."""

import resource

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk

COVERS = {"release_output_memory"}

MB = 1 << 20
CHAIN = rk.robots.rpr()
Q = np.random.default_rng(11).uniform(-3.0, 3.0, (200_000, 3))
CALLS = {  # bytes per configuration of each output
    "frame": (128, lambda Qn: CHAIN.fk(Qn)),
    "position": (24, lambda Qn: CHAIN.fk(Qn, out="position")),
    "jacobian": (144, lambda Qn: CHAIN.jacobian(Qn)),
}
_reference = {}


def reference(kind):
    """The whole of Q's outputs, computed in batches of 1 MB or less (numpy's own memory)."""
    if kind not in _reference:
        call = CALLS[kind][1]
        _reference[kind] = np.concatenate([call(Q[k:k + 4096]) for k in range(0, len(Q), 4096)])
    return _reference[kind]


# Output sizes in MB around the pool's threshold and its reuse range (a block serves outputs of
# its size down to a fifth smaller).
SIZES_MB = [3.99, 4.0, 4.01, 4.8, 5.0, 5.99, 6.0, 6.4, 7.9, 8.0, 10.0]
ops = st.lists(st.tuples(st.sampled_from(sorted(CALLS)), st.sampled_from(SIZES_MB), st.booleans(), st.booleans()),
               min_size=1, max_size=8)


@settings(max_examples=max(10, settings.default.max_examples // 3))
@given(ops)
def test_any_sequence_of_outputs_gets_its_values_in_memory_of_its_own(sequence):
    rk.release_output_memory()
    live = []
    for kind, size_mb, keep, release in sequence:
        per, call = CALLS[kind]
        n = int(size_mb * MB) // per
        out = call(Q[:n])
        np.testing.assert_array_equal(out, reference(kind)[:n])
        assert not any(np.shares_memory(out, other) for _, other in live)
        if keep:
            live.append((kind, out))
        else:
            out[...] = np.nan  # what its memory holds if a later output is written into it
        del out
        if release:
            released = rk.release_output_memory()
            assert 0 <= released <= 256 * MB and released % resource.getpagesize() == 0
            assert rk.release_output_memory() == 0
    for kind, out in live:  # still theirs
        np.testing.assert_array_equal(out, reference(kind)[:len(out)])
