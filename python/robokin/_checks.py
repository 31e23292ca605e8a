"""Argument checks of what Python reads itself (robots, paths, plots, the 3-RRR design study, the
Chain constructors' rows and q_from's mapping): each error names the argument; a value of the wrong
kind is a TypeError, a value out of range a ValueError. (Arrays passed on to the core are converted
in the bindings, cpp/bindings/arrays.hpp, and the core validates its own options.)"""

from __future__ import annotations

import collections.abc
import math
import numbers
import os

from typing import Optional

import numpy as np

from ._core import Chain


def number(value, name: str, *, minimum: float = -math.inf, maximum: float = math.inf,
           positive: bool = False) -> float:
    """A real scalar (a Python or numpy number, or a 0-d array of one; not a bool) as a float.

    Raises:
        TypeError: not a real number.
        ValueError: not finite, not positive (``positive``), below ``minimum`` or above ``maximum``.
    """
    scalar = isinstance(value, numbers.Real) or (isinstance(value, np.ndarray) and value.ndim == 0
                                                 and value.dtype.kind in "iuf")
    if isinstance(value, (bool, np.bool_)) or not scalar:
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
    v = float(value)
    if positive and not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name}: must be a positive finite number, got {value!r}")
    if not (math.isfinite(v) and minimum <= v <= maximum):
        bounds = (f" in [{minimum:g}, {maximum:g}]" if maximum < math.inf and minimum > -math.inf
                  else f" >= {minimum:g}" if minimum > -math.inf else f" <= {maximum:g}" if maximum < math.inf else "")
        raise ValueError(f"{name}: must be a finite number{bounds}, got {value!r}")
    return v


def instance(value, name: str, kind, what: str, *, optional: bool = False):
    """``value`` as given when it is a ``kind`` (or None, with ``optional``); ``what`` names the
    kind in the message ("a robokin.Chain").

    Raises:
        TypeError: anything else.
    """
    if isinstance(value, kind) or (optional and value is None):
        return value
    raise TypeError(f"{name}: expected {what}{' or None' if optional else ''}, got {type(value).__name__}")


def chain(value, name: str = "chain"):
    """A robokin.Chain, as given."""
    return instance(value, name, Chain, "a robokin.Chain")


def finite_float(value, name: str) -> float:
    """A number as Python's float() takes one (ints and bools, numpy scalars, objects with
    __float__ or __index__; not text), finite: what the core's double arguments take, with its
    messages. (number() is the stricter check of Python's own arguments: no bools.)"""
    if type(value) is not float:  # the checks below cost more than a DH row's other work
        if isinstance(value, (str, bytes, bytearray)) or not (hasattr(value, "__float__") or hasattr(value, "__index__")):
            raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
        try:
            value = float(value)
        except OverflowError:
            raise ValueError(f"{name}: must be finite, got an int too large for a float") from None
        except (TypeError, ValueError):
            raise TypeError(f"{name}: expected a number, got {type(value).__name__}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name}: must be finite, got {value!r}")
    return value


def is_sequence(value) -> bool:
    """A sequence of items (a list, a tuple, a numpy array of rank 1 or more, ...), not text."""
    return type(value) in (list, tuple) or (not isinstance(value, (str, bytes)) and (
        isinstance(value, collections.abc.Sequence) or (isinstance(value, np.ndarray) and value.ndim > 0)))


def whole(value, name: str, lo: int, hi: int, what: str = "") -> int:
    """An integer (a Python or numpy int; not a bool) in ``[lo, hi]`` as an int; ``what`` says in
    the message what it counts.

    Raises:
        TypeError: not an integer.
        ValueError: outside ``[lo, hi]``.
    """
    unit = f" ({what})" if what else ""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected an int{unit}, got {value!r}")
    if not lo <= int(value) <= hi:
        raise ValueError(f"{name}: expected an int in [{lo}, {hi}]{unit}, got {value}")
    return int(value)


def seed(value, name: str = "seed") -> int:
    """A random seed: an int in ``[0, 2**64)``, the range of the core's generators."""
    return whole(value, name, 0, 2**64 - 1, "a random seed")


def real_array(value, name: str) -> np.ndarray:
    """``value`` as a float array; complex numbers, strings, None and ragged lists are refused by name."""
    try:
        a = np.asarray(value)
        if value is None or a.dtype.kind not in "biuf":  # no None, strings, complex or objects
            raise TypeError(f"a {a.dtype} array")
        return a.astype(float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name}: expected real numbers, got {value!r} ({exc})") from None


def finite(a: np.ndarray, name: str) -> np.ndarray:
    """``a`` (a float array, shape checked) when every entry is finite."""
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: contains NaN or inf")
    return a


def positive(a: np.ndarray, name: str) -> np.ndarray:
    """``a`` (a finite float array) when every entry is positive."""
    if not np.all(a > 0):
        raise ValueError(f"{name}: must be positive, got {float(np.min(a))!r}")
    return a


def shaped(value, name: str, shape: tuple) -> np.ndarray:
    """``value`` as a float array of ``shape`` (its values not checked)."""
    a = real_array(value, name)
    if a.shape != shape:
        raise ValueError(f"{name}: expected shape {shape}, got {a.shape}")
    return a


def vector(value, name: str, n: int) -> np.ndarray:
    """``(n,)`` finite real numbers."""
    return finite(shaped(value, name, (n,)), name)


def per_joint(value, name: str, n: int) -> np.ndarray:
    """A value for each of ``n`` joints: a real scalar (repeated) or ``(n,)``, finite."""
    a = real_array(value, name)
    return vector(np.full(n, a) if a.ndim == 0 else a, name, n)


def joints(chain_, value, name: str = "q") -> np.ndarray:
    """One configuration of ``chain_``: ``(dof,)`` finite real numbers."""
    return vector(value, name, chain_.dof)


def flag(value, name: str) -> bool:
    """True or False (numpy's bool too); anything else, even 0 or 1, is refused by name."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected True or False, got {type(value).__name__}")
    return bool(value)


def rows(value, name: str, row: tuple = (), most: Optional[int] = None) -> np.ndarray:
    """``value`` as a finite float array of K >= 1 rows (at most ``most``) of shape ``row``; a None
    in ``row`` takes any size (shown as n): ``rows(poses, "poses", (4, 4))`` for a (K, 4, 4) batch."""
    a = real_array(value, name)
    fits = a.ndim == 1 + len(row) and all(r is None or r == d for r, d in zip(row, a.shape[1:]))
    if not fits or len(a) < 1 or (most is not None and len(a) > most):
        shape = "(K" + "".join(f", {'n' if r is None else r}" for r in row) + ("," if not row else "") + ")"
        count = "K >= 1" if most is None else f"1 <= K <= {most}"
        raise ValueError(f"{name}: expected a {shape} array, {count}, got shape {a.shape}")
    return finite(a, name)


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


def choice(value, name: str, options):
    """One of ``options`` (strings), as given.

    Raises:
        TypeError: not a string.
        ValueError: a string that is not one of ``options``.
    """
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected one of {tuple(options)}, got {type(value).__name__}")
    if value not in options:
        raise ValueError(f"{name}: expected one of {tuple(options)}, got {value!r}")
    return value


def pixels(value, name: str, lo: int, hi: int) -> tuple:
    """A picture's (width, height): two ints, each in ``[lo, hi]``.

    Raises:
        TypeError: a side is not an int.
        ValueError: not a pair, or a side out of range.
    """
    if not is_sequence(value) or len(value) != 2:
        raise ValueError(f"{name}: expected (width, height), got {value!r}")
    return tuple(whole(v, name, lo, hi, "pixels") for v in value)


def file_name(value, name: str, suffixes: tuple) -> str:
    """The suffix (lower case, one of ``suffixes``: ".gif", ...) of a file name (a str or
    os.PathLike).

    Raises:
        TypeError: not a file name.
        ValueError: another suffix.
    """
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name}: expected a file name (str or os.PathLike), got {type(value).__name__}")
    kind = os.path.splitext(os.fspath(value))[1].lower()
    if kind not in suffixes:
        raise ValueError(f"{name}: must end in {' or '.join(suffixes)}, got {os.fspath(value)!r}")
    return kind
