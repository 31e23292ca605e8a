"""The Chain methods written in Python (ergonomics around the core's model; robokin/__init__.py
attaches them to Chain): a configuration from and to a mapping {joint name: value}."""

from __future__ import annotations

import collections.abc
import inspect

import numpy as np
import numpy.typing

from . import _checks
from ._core import Chain

LISTED_NAMES = 20  # an error message lists this many names, then says how many more


def _listed(items: list) -> str:
    """'a', 'b' and 'c' (the repr of each item); past LISTED_NAMES, "... and N more"."""
    shown = [repr(item) for item in items[:LISTED_NAMES]]
    if 1 < len(items) <= LISTED_NAMES:
        return ", ".join(shown[:-1]) + " and " + shown[-1]
    more = len(items) - LISTED_NAMES
    return ", ".join(shown) + (f" and {more} more" if more > 0 else "")


def _joint_value(value, key: str) -> float:
    """A joint's value as Python's float() takes a number (ints, numpy scalars, __float__ or
    __index__), finite; text is not a number here."""
    number = not isinstance(value, (str, bytes, bytearray)) and (
        hasattr(value, "__float__") or hasattr(value, "__index__"))
    try:
        v = float(value) if number else None
    except OverflowError:
        raise ValueError(f"mapping[{key}]: must be finite, got an int too large for a float") from None
    except TypeError:
        v = None
    if v is None:
        raise TypeError(f"mapping[{key}]: expected a number, got {type(value).__name__}")
    if not np.isfinite(v):
        raise ValueError(f"mapping[{key}]: must be finite, got {v!r}")
    return v


def _default_q(chain: Chain, default) -> np.ndarray:
    """q (dof,) filled from default: a number for every joint, or a (dof,) array; NaN marks "no
    default" (None)."""
    if default is None:
        return np.full(chain.dof, np.nan)
    a = _checks.real_array(default, "default")
    return _checks.joints(chain, np.full(chain.dof, a) if a.ndim == 0 else a, "default")


def q_from(self: Chain, mapping: collections.abc.Mapping[str, float],
           default: float | numpy.typing.ArrayLike | None = None) -> numpy.typing.NDArray[numpy.float64]:
    """q (dof,) from a mapping {joint name: value} (names as joint_names gives them).

    default: the value of the joints the mapping leaves out: a number, or a (dof,) array read at
      their places; None: every joint must be given. Raises ValueError for a name the chain has
      not (listing its joints), for joints left out without a default (listing them) and for
      values that are not finite; TypeError for a mapping or value of the wrong kind.
    """
    if not isinstance(mapping, collections.abc.Mapping):
        raise TypeError(f"mapping: expected a mapping {{joint name: value}}, got {type(mapping).__name__}")
    names = self.joint_names
    places: dict[str, list[int]] = {}  # a name may be given to several joints
    for i, name in enumerate(names):
        places.setdefault(name, []).append(i)
    q = _default_q(self, default)
    given = np.zeros(self.dof, bool)
    unknown = []
    for key, value in mapping.items():
        found = places.get(key) if isinstance(key, str) else None
        if found is None:
            unknown.append(key)
            continue
        q[found] = _joint_value(value, repr(key))
        given[found] = True
    if unknown:
        raise ValueError(f"mapping: unknown joint name{'s' if len(unknown) > 1 else ''} {_listed(unknown)}; "
                         f"the chain's joints are {_listed(list(names))}")
    missing = [names[i] for i in range(self.dof) if not given[i] and np.isnan(q[i])]
    if missing:
        raise ValueError(f"mapping: no value for joint{'s' if len(missing) > 1 else ''} {_listed(missing)} "
                         "(pass default= for the joints left out)")
    return q


def q_dict(self: Chain, q: numpy.typing.ArrayLike) -> dict[str, float]:
    """{joint name: value} of q (dof,), in the chain's joint order (the inverse of q_from)."""
    values = _checks.joints(self, q, "q")
    return {name: float(v) for name, v in zip(self.joint_names, values)}


# Named and documented as the core's methods are (help(), the stubs and the reference read them).
for _method in (q_from, q_dict):
    _method.__qualname__ = "Chain." + _method.__name__
    _method.__doc__ = inspect.cleandoc(_method.__doc__)
