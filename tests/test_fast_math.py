"""The batch paths' sin, cos and atan2 (SLEEF's 1.0-ulp routines, cpp/src/kernel/fast_math.hpp) against
libm's (math.sin, math.cos, math.atan2: correctly rounded in practice, under 1 ulp): at most
2 ulp apart (1 ulp each side of the exact value), any argument, NaN in -> NaN out; a value gives
the same bits alone and inside a batch (single calls and batches agree)."""

import math

import numpy as np
import pytest

import robokin as rk
from robokin import _testing

ULP = 2.0


def ulps(ours, ref):
    """|ours - ref| in units of the spacing of ref (of the smallest normal near 0)."""
    ref = np.asarray(ref, float)
    return np.abs(np.asarray(ours) - ref) / np.spacing(np.maximum(np.abs(ref), np.finfo(float).tiny))


def angles(n, seed):
    rng = np.random.default_rng(seed)
    return np.concatenate([
        rng.uniform(-4 * math.pi, 4 * math.pi, n),
        rng.uniform(-1e6, 1e6, n // 4),
        10.0 ** rng.uniform(6, 300, n // 4) * rng.choice([-1, 1], n // 4),  # huge: full range reduction
        np.arange(-64, 65) * (math.pi / 4),  # at and near the zeros and extrema
        np.nextafter(np.arange(-8, 9) * (math.pi / 2), np.inf),
        [0.0, -0.0, 1e-300, -5e-324, math.pi, 2 * math.pi, 1e22, 2.0**1000],
    ])


def test_sincos_within_2_ulp_of_libm():
    x = angles(20000, 0)
    s, c = _testing.vmath_sincos(x)
    assert ulps(s, [math.sin(v) for v in x]).max() <= ULP
    assert ulps(c, [math.cos(v) for v in x]).max() <= ULP


def test_atan2_within_2_ulp_of_libm():
    rng = np.random.default_rng(1)
    y = np.concatenate([rng.normal(size=20000), 10.0 ** rng.uniform(-300, 300, 2000), [0.0, -0.0, 1.0, -1.0, 0.0, 3.0]])
    x = np.concatenate([rng.normal(size=20000), -(10.0 ** rng.uniform(-300, 300, 2000)), [1.0, -1.0, 0.0, 0.0, -0.0, -3.0]])
    out = _testing.vmath_atan2(y, x)
    assert ulps(out, [math.atan2(a, b) for a, b in zip(y, x)]).max() <= ULP
    for a, b, o in zip(y[-6:], x[-6:], out[-6:]):  # signed zeros: atan2(+-0, x) and the axes
        assert math.copysign(1.0, o) == math.copysign(1.0, math.atan2(a, b)) and o == math.atan2(a, b), (a, b, o)


def test_nan_in_nan_out():
    s, c = _testing.vmath_sincos(np.array([math.nan, math.inf, -math.inf, 1.0]))
    assert np.isnan(s[:3]).all() and np.isnan(c[:3]).all() and np.isfinite([s[3], c[3]]).all()
    assert np.isnan(_testing.vmath_atan2(np.array([math.nan, 1.0]), np.array([1.0, math.nan]))).all()


@pytest.mark.parametrize("n", [1, 2, 3, 5, 8, 33])
def test_same_bits_alone_and_in_a_batch(n):
    x = angles(64, n)
    s, c = _testing.vmath_sincos(x)
    for k in range(0, len(x), 37):
        alone = _testing.vmath_sincos(x[k:k + 1])
        assert (alone[0][0], alone[1][0]) == (s[k], c[k])
        part = _testing.vmath_sincos(x[k:k + n])
        np.testing.assert_array_equal(part[0], s[k:k + n])


def test_long_and_short_arrays_give_the_same_bits():
    """Arrays of 32 values or more take AVX-512 where the CPU has it, shorter ones AVX2 (both
    SLEEF's deterministic routines): 100,000 angles and atan2 arguments of every range, whole
    against 31 at a time, bit for bit."""
    x = angles(80000, 3)
    s, c = _testing.vmath_sincos(x)
    rng = np.random.default_rng(4)
    y2 = np.concatenate([rng.normal(size=80000), 10.0 ** rng.uniform(-300, 300, 20000) * rng.choice([-1, 1], 20000)])
    x2 = np.concatenate([rng.normal(size=80000), 10.0 ** rng.uniform(-300, 300, 20000) * rng.choice([-1, 1], 20000)])
    a = _testing.vmath_atan2(y2, x2)
    short_s, short_c, short_a = [], [], []
    for k in range(0, len(x), 31):
        part = _testing.vmath_sincos(x[k:k + 31])
        short_s.append(part[0]), short_c.append(part[1])
    for k in range(0, len(y2), 31):
        short_a.append(_testing.vmath_atan2(y2[k:k + 31], x2[k:k + 31]))
    for whole, parts in ((s, short_s), (c, short_c), (a, short_a)):
        assert np.array_equal(whole.view(np.int64), np.concatenate(parts).view(np.int64))


def test_a_revolute_joint_is_the_sincos():
    """A one-joint chain about z gives (cos q, sin q) in its first column: the same routine as the
    direct call, in single FK, in a block of the batch and in its tail."""
    chain = rk.Chain.from_dh([(0.0, 0.0, 0.0, 0.0, "R")])
    q = angles(300, 2)
    T = chain.fk(q[:, None])
    s, c = _testing.vmath_sincos(q)
    np.testing.assert_array_equal(T[:, 0, 0], c)
    np.testing.assert_array_equal(T[:, 1, 0], s)
    np.testing.assert_array_equal(chain.fk(q[:1])[:, 0], [c[0], s[0], 0.0, 0.0])
