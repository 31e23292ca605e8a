"""Argument checks shared by the pure-Python modules (paths, plots): each error names the argument.
(Arguments of the core's calls are checked in the bindings, cpp/bindings/arrays.hpp.)"""

from __future__ import annotations

import numpy as np


def real_array(value, name: str) -> np.ndarray:
    """``value`` as a float array; complex numbers, strings, None and ragged lists are refused by name."""
    try:
        a = np.asarray(value)
        if value is None or a.dtype.kind not in "biuf":  # no None, strings, complex or objects
            raise TypeError(f"a {a.dtype} array")
        return a.astype(float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name}: expected real numbers, got {value!r} ({exc})") from None


def planar_points(value, name: str) -> np.ndarray:
    """``value`` as a finite (K, 2) float array, K >= 1."""
    p = real_array(value, name)
    if p.ndim != 2 or p.shape[0] < 1 or p.shape[1] != 2:
        raise ValueError(f"{name}: expected a (K, 2) array of real numbers, K >= 1, got shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{name}: contains NaN or inf")
    return p


def frame_like(value):
    """A 4x4 frame (or a batch of them) as given, or the matrix an object holds in ``.A`` (the
    spatialmath ``SE3`` convention: one (4, 4) array, or a list of them for several poses); numpy
    arrays, lists and objects with ``__array__`` pass unchanged (the core converts them)."""
    if isinstance(value, np.ndarray) or value is None or isinstance(value, (list, tuple, str, bytes)):
        return value
    matrix = getattr(value, "A", None)
    if matrix is None:
        return value
    return np.asarray(matrix) if isinstance(matrix, (list, tuple)) else matrix
