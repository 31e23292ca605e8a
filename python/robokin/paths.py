"""Sampled Cartesian paths: a straight line, and the seed program's circle and four-leaf clover."""

from __future__ import annotations

import math

import numpy as np

from ._checks import finite, number, real_array, vector, whole

__all__ = ["MAX_POINTS", "line", "circle", "clover"]


#: Most points a path may have (a typo such as ``step=1e-12`` must not allocate terabytes).
MAX_POINTS = 10_000_000


def _point(value, name: str) -> np.ndarray:
    p = real_array(value, name)
    if p.ndim != 1 or p.shape[0] not in (2, 3):
        raise ValueError(f"{name}: expected a 2-D or 3-D point, got shape {p.shape}")
    return finite(p, name)


def _count(n, name: str = "n") -> int:
    return whole(n, name, 1, MAX_POINTS, "points")


def line(p1, p2, step: float) -> np.ndarray:
    """Points from ``p1`` to ``p2`` (both included), evenly spaced at most ``step`` apart.

    Returns:
        (K, 2) or (K, 3) array, K = max(2, ceil(|p2 - p1| / step) + 1) (two equal points when
        p1 == p2).

    Raises:
        ValueError: naming ``step`` when K would exceed :data:`MAX_POINTS`.
    """
    a, b = _point(p1, "p1"), _point(p2, "p2")
    if a.shape != b.shape:
        raise ValueError(f"p2: expected the dimension of p1 ({a.shape[0]}), got {b.shape[0]}")
    step = number(step, "step", positive=True)
    with np.errstate(over="ignore"):  # an overflow is reported below, by name
        d = b - a
    length = math.hypot(*d)  # no overflow in the squares
    if not math.isfinite(length):
        raise ValueError("p1, p2: too far apart (their distance overflows)")
    # Count in floating point first: length / step may be far beyond any integer size.
    k = math.ceil(length / step) + 1 if length / step < MAX_POINTS else MAX_POINTS + 1
    if k > MAX_POINTS:
        raise ValueError(f"step: {step!r} over a length of {length:g} gives more than {MAX_POINTS} points")
    return a + np.linspace(0.0, 1.0, max(k, 2))[:, None] * d


def _center(center) -> np.ndarray:
    return vector(center, "center", 2)


def circle(n: int, radius: float = 0.1, center=(0.0, 0.0)) -> np.ndarray:
    """``n`` points of a circle of ``radius`` about ``center``, counter-clockwise from angle 0,
    ``t_k = 2 pi k / n`` (no repeat).

    The seed program's circle has radius 0.1 m about the origin.
    """
    n, radius, c = _count(n), number(radius, "radius", positive=True), _center(center)
    t = 2.0 * np.pi * np.arange(n) / n
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is reported by _finite, by name
        return _finite(c + radius * np.column_stack((np.cos(t), np.sin(t))), "radius, center")


def clover(n: int, k: float = 0.02, center=(0.0, 0.0)) -> np.ndarray:
    """``n`` points of the seed program's four-leaf clover ``r(t) = k (1 + cos 4t + 2 sin^2 4t)``.

    Polar about ``center``, ``t_k = 2 pi k / n`` (no repeat).
    """
    n, k, c = _count(n), number(k, "k", positive=True), _center(center)
    t = 2.0 * np.pi * np.arange(n) / n
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is reported by _finite, by name
        r = k * (1.0 + np.cos(4 * t) + 2.0 * np.sin(4 * t) ** 2)
        return _finite(c + r[:, None] * np.column_stack((np.cos(t), np.sin(t))), "k, center")


def _finite(points, names: str) -> np.ndarray:
    if not np.all(np.isfinite(points)):
        raise ValueError(f"{names}: the points overflow (values too large)")
    return points
