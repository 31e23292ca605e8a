"""One rule for joint limits across the core (cpp/include/robokin/limits.hpp): the same check of a
(lower, upper) pair for chains and closed forms, and one way a revolute solution is brought within
its limits: its angle wrapped to [-pi, pi] when that is within, else the nearest value 2 pi k away
that is (none: no solution). Checked against the forward model and against the rule written here."""

import math

import numpy as np
import pytest

import robokin as rk


def settled(v, lo, hi):
    """The rule, written independently: wrapped when within, else the nearest 2 pi shift within."""
    w = math.remainder(v, 2 * math.pi)
    if lo <= w <= hi:
        return w
    shifts = [v + 2 * math.pi * k for k in range(-10, 11) if lo <= v + 2 * math.pi * k <= hi]
    return min(shifts, key=lambda x: abs(x - v)) if shifts else None


def tip(q, a=(1.0, 1.0)):
    t1, t2 = q
    return np.array([a[0] * math.cos(t1) + a[1] * math.cos(t1 + t2), a[0] * math.sin(t1) + a[1] * math.sin(t1 + t2)])


def test_closed_form_solutions_follow_the_rule():
    free = rk.closed.planar_2r([1.2, 0.8])
    lower, upper = np.array([1.0, -10.0]), np.array([6.2, 10.0])  # joint 2 spans more than 2 pi
    s = rk.closed.planar_2r([1.2, 0.8], limits=(lower, upper))
    assert len(s) == 2
    for q_free, q in zip(free.q, s.q):
        expected = [settled(v, lo, hi) for v, lo, hi in zip(q_free, lower, upper)]
        np.testing.assert_allclose(q, expected, rtol=0, atol=1e-12)
        np.testing.assert_allclose(tip(q), [1.2, 0.8], atol=1e-12)
    assert s.q[0][0] > math.pi  # -0.18 rad is below joint 1's lower limit: shifted up by 2 pi
    assert np.all(np.abs(s.q[:, 1]) <= math.pi)  # within joint 2's wide limits: wrapped


def test_a_solution_no_shift_brings_within_is_marked_outside():
    # Joint 1 limited to [3, 6]: neither -0.18 + 2 pi = 6.11 nor 1.35 (+ 2 pi) is within. Both are
    # returned, wrapped to [-pi, pi] (as without limits), marked outside.
    s = rk.closed.planar_2r([1.2, 0.8], limits=([3.0, -10.0], [6.0, 10.0]))
    free = rk.closed.planar_2r([1.2, 0.8])
    assert len(s) == 2 and not s.within_limits.any() and np.array_equal(s.q, free.q)


def test_numerical_ik_reports_its_solution_by_the_same_rule():
    lim = (np.array([-10.0, -10.0]), np.array([10.0, 10.0]))
    chain = rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 2, limits=lim)
    r = rk.ik(chain, [1.2, 0.8], np.array([6.0, 7.0]), task="xy", restarts=0)  # starts beyond pi
    assert r.success and np.all(np.abs(r.q) <= math.pi)
    np.testing.assert_allclose(tip(r.q), [1.2, 0.8], atol=1e-9)
    closed = rk.closed.planar_2r([1.2, 0.8], limits=lim)
    assert min(np.abs(closed.q - r.q).max(axis=1)) < 1e-7  # one of the closed forms' solutions


@pytest.mark.parametrize(
    "lower, upper, message",
    [
        ([0.0, np.nan], [1.0, 1.0], "limits: joint 1 has a NaN limit"),
        ([0.0, 2.0], [1.0, 1.0], "limits: joint 1 has its lower limit above its upper limit"),
        ([np.inf, 0.0], [np.inf, 1.0], "limits: joint 0 has no admissible value"),
    ],
)
def test_chains_and_closed_forms_check_limits_alike(lower, upper, message):
    with pytest.raises(ValueError, match=message):
        rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 2, limits=(lower, upper))
    with pytest.raises(ValueError, match=message):
        rk.closed.planar_2r([1.2, 0.8], limits=(lower, upper))
    with pytest.raises(ValueError, match=message):
        rk.closed.general_3r([1.0, 0.5, 0.2], rk.robots.get("planar_3r"), limits=(lower + [0.0], upper + [1.0]))


def test_wrap_angle_has_the_bits_of_ieee_remainder_by_two_pi():
    # angles.hpp's wrap_angle skips std::remainder for |a| < 3 pi: the same bits as math.remainder
    # (IEEE 754 remainder) everywhere, the signed zeros and the edges at pi, 2 pi, 3 pi included.
    from robokin import _testing

    rng = np.random.default_rng(7)
    edges = np.array([k * math.pi for k in range(-4, 5)] + [k * 2 * math.pi for k in (-2, -1, 1, 2)])
    near = np.concatenate([edges, np.nextafter(edges, np.inf), np.nextafter(edges, -np.inf)])
    a = np.concatenate([near, [0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300],
                        rng.uniform(-12, 12, 200_000), rng.normal(0, 1e4, 1000)])
    got = _testing.wrap_angle(a)
    want = np.array([math.remainder(x, 2 * math.pi) for x in a])
    assert np.array_equal(got.view(np.uint64), want.view(np.uint64))  # bit for bit, zeros' signs too
    assert np.isnan(_testing.wrap_angle(np.array([np.nan, np.inf, -np.inf]))).all()
