"""Shared pieces of the property tests (test_fuzz_*.py): arbitrary arrays and numbers, and the one
rule every public call must keep, checked by :func:`check_call`.

The rule: a call returns finite, correctly shaped results, or raises ``ValueError`` / ``TypeError``
whose message names one of the arguments the test varied. Anything else (another exception, a NaN
in a result, a crash of the process) fails the test.
"""

import numpy as np
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
# Every size from empty to large, with NaN, inf, subnormals and huge values mixed in.
wild_floats = st.one_of(floats, st.sampled_from([0.0, -0.0, 1e-308, 5e-324, 1e308, -1e308, 1e15, 1e-15]))
ints = st.integers(-(2**63), 2**63 - 1)
small_ints = st.integers(-3, 12)
shapes = hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=7)


def _layouts(a: np.ndarray):
    """The same values as a C array, a Fortran array, a strided view, a read-only or byte-swapped
    array, or a plain list: the layouts a caller may hand in."""
    return st.sampled_from(["c", "f", "strided", "readonly", "swapped", "list"]).map(lambda how: _layout(a, how))


def _layout(a: np.ndarray, how: str):
    if how == "f":
        return np.asfortranarray(a)
    if how == "strided":
        wide = np.repeat(a[..., None], 2, axis=-1) if a.ndim else a
        return wide[..., 0] if a.ndim else wide
    if how == "readonly":
        b = a.copy()
        b.setflags(write=False)
        return b
    if how == "swapped" and a.dtype.kind == "f":
        return a.astype(a.dtype.newbyteorder(">" if a.dtype.byteorder in "=<" else "<"))
    if how == "list":
        return a.tolist()
    return a


def arrays(shape=shapes, elements=None):
    """Arrays of any dtype (float64, float32, int, bool, complex, object) and layout. ``shape`` may
    be a fixed shape, a strategy, or a list of shapes to pick from (the right one among wrong ones)."""
    if isinstance(shape, list):
        shape = st.sampled_from(shape)
    f64 = hnp.arrays(np.float64, shape, elements=elements if elements is not None else wild_floats)
    other = st.one_of(
        hnp.arrays(np.float32, shape, elements=st.floats(width=32)),
        hnp.arrays(np.int64, shape, elements=st.integers(-5, 5)),
        hnp.arrays(np.bool_, shape),
        hnp.arrays(np.complex128, shape, elements=st.complex_numbers(max_magnitude=10)),
    )
    base = st.one_of(f64, f64, f64, other)
    return st.one_of(base.flatmap(_layouts), st.sampled_from([None, "abc", 1.5, [], [[1.0], [1.0, 2.0]]]))


def finite_arrays(shape, lo=-10.0, hi=10.0):
    """Well-formed float64 arrays of a given shape with values in [lo, hi]."""
    return hnp.arrays(np.float64, shape, elements=st.floats(lo, hi))


def check_call(call, *argnames):
    """Runs ``call()``; returns its result, or None when it raised ValueError/TypeError naming one of
    ``argnames``. Fails on any other exception or on a ValueError that names none of them."""
    try:
        return call()
    except (ValueError, TypeError) as e:
        message = str(e)
        assert any(name in message for name in argnames), f"{type(e).__name__} names none of {argnames}: {message}"
        return None


def assert_finite(*values):
    """Every number in ``values`` (arrays, floats, nested tuples) is finite."""
    for v in values:
        if isinstance(v, (tuple, list)):
            assert_finite(*v)
        elif isinstance(v, dict):
            assert_finite(*v.values())
        elif v is not None:
            a = np.asarray(v)
            if a.dtype.kind in "fc":
                assert np.all(np.isfinite(a)), f"non-finite value in a result: {a}"
