"""Sampled paths: spacing, ends and the seed program's curves."""

import numpy as np
import pytest

import robokin as rk


def test_line_includes_both_ends_with_bounded_spacing():
    pts = rk.paths.line([0, 0], [1, 0.5], 0.01)
    np.testing.assert_array_equal(pts[0], [0, 0])
    np.testing.assert_allclose(pts[-1], [1, 0.5], atol=1e-15)
    gaps = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert gaps.max() <= 0.01 and np.ptp(gaps) < 1e-12
    assert rk.paths.line([0, 0, 0], [0, 0, 1], 0.3).shape == (5, 3)


def test_circle_and_clover_follow_their_formulas():
    c = rk.paths.circle(628, radius=0.1, center=(0.01, -0.02))
    np.testing.assert_allclose(np.linalg.norm(c - (0.01, -0.02), axis=1), 0.1, atol=1e-15)
    k = rk.paths.clover(400, k=0.02)
    t = np.arctan2(k[:, 1], k[:, 0])
    r = np.linalg.norm(k, axis=1)
    np.testing.assert_allclose(r, 0.02 * (1 + np.cos(4 * t) + 2 * np.sin(4 * t) ** 2), atol=1e-15)
    assert r.max() == pytest.approx(0.02 * 3.125, rel=1e-3)  # max of 1 + c + 2 (1 - c^2) at c = 1/4


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: rk.paths.line([0, 0], [1, 1], 0), "step: must be a positive finite number"),
        (lambda: rk.paths.line([0, 0], [1, 1, 1], 0.1), "p2: expected the dimension of p1"),
        (lambda: rk.paths.line([0, np.nan], [1, 1], 0.1), "p1: contains NaN or inf"),
        (lambda: rk.paths.circle(0), r"n: expected an int in \[1, 10000000\] \(points\), got 0"),
        (lambda: rk.paths.circle(10, radius=-1), "radius: must be a positive finite number"),
        (lambda: rk.paths.clover(10, center=(0, 0, 0)), r"center: expected shape \(2,\), got \(3,\)"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
