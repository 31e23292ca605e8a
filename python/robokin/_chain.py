"""The Chain methods written in Python (ergonomics around the core's model; robokin/__init__.py
attaches them to Chain): chains from DH rows and KDL-style segments (their records read and
checked here, the frames and limits by the core), a configuration from and to a mapping
{joint name: value}."""

from __future__ import annotations

import collections.abc
import math

import numpy as np
import numpy.typing

from . import _checks, _core
from ._core import Chain
from ._signature import written

LISTED_NAMES = 20  # an error message lists this many names, then says how many more


def _listed(items: list) -> str:
    """'a', 'b' and 'c' (the repr of each item); past LISTED_NAMES, "... and N more"."""
    shown = [repr(item) for item in items[:LISTED_NAMES]]
    if 1 < len(items) <= LISTED_NAMES:
        return ", ".join(shown[:-1]) + " and " + shown[-1]
    more = len(items) - LISTED_NAMES
    return ", ".join(shown) + (f" and {more} more" if more > 0 else "")


def _records(value, name: str, size: int, what: str) -> list:
    """The records of a chain to build (DH rows, segments): a non-empty sequence of sequences of
    ``size`` items (``what`` says which)."""
    if not _checks.is_sequence(value):
        raise TypeError(f"{name}: expected a sequence, got {type(value).__name__}")
    if len(value) == 0:
        raise ValueError(f"{name}: a chain needs at least one joint")
    for i, record in enumerate(value):
        if not _checks.is_sequence(record):
            raise TypeError(f"{name}[{i}]: expected {what}")
        if len(record) != size:
            raise ValueError(f"{name}[{i}]: expected {what}")
    return list(value)


def _joint_type(value, name: str, allowed: str) -> str:
    """One of the letters ``allowed``, in either case."""
    if not isinstance(value, str):
        raise TypeError(f"{name}: joint type must be a string, one of {allowed}")
    if len(value) != 1 or value.upper() not in allowed:
        raise ValueError(f"{name}: joint type must be one of {allowed}, got '{value}'")
    return value.upper()


def _stacked(records: list, k: int, shape: tuple) -> np.ndarray | None:
    """Item k of every record as one float array (n, *shape), or None when one of them is not real
    numbers of that shape (the caller then finds it with _shaped, and names it)."""
    try:
        a = np.array([record[k] for record in records])
    except (TypeError, ValueError):  # ragged
        return None
    return a.astype(float) if a.dtype.kind in "biuf" and a.shape == (len(records),) + shape else None


def from_dh(rows: collections.abc.Sequence, modified: bool = False, tool: numpy.typing.ArrayLike | None = None,
            limits: tuple[numpy.typing.ArrayLike, numpy.typing.ArrayLike] | None = None) -> Chain:
    """Builds a chain from Denavit-Hartenberg rows.

    rows: one (a, alpha, d, theta, joint) per joint: a and d in metres, alpha and theta in radians,
    joint 'R' (revolute) or 'P' (prismatic). theta and d are offsets: a revolute joint turns by
    theta + q_i, a prismatic one slides to d + q_i (q = 0 is the table as written).
    modified: False for standard DH, A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha); True for Craig's
    modified DH, A_i = Rx(alpha) Tx(a) Rz(theta) Tz(d).
    tool: (4, 4) frame of the tool point in the last joint's frame, applied after the last row
    (fk, frames and the Jacobian are at the tool); None for the identity.
    limits: (lower, upper), each dof numbers (rad or m, -inf / inf for none), or None: unlimited.
    print(chain) shows the table (Chain.table).
    """
    table, joints = [], ""
    for i, row in enumerate(_records(rows, "rows", 5, "(a, alpha, d, theta, 'R' or 'P')")):
        table.append([_checks.finite_float(row[k], f"rows[{i}] {field}")
                      for k, field in enumerate(("a", "alpha", "d", "theta"))])
        joints += _joint_type(row[4], f"rows[{i}]", "RP")
    return _core.chain_from_dh(np.array(table), joints, modified, tool, limits)


def from_segments(segments: collections.abc.Sequence, tool: numpy.typing.ArrayLike | None = None,
                  limits: tuple[numpy.typing.ArrayLike, numpy.typing.ArrayLike] | None = None) -> Chain:
    """Builds a chain from KDL-style segments, as KDL::Segment(Joint(axis), tip) does.

    segments: one (joint, axis, tip) per segment: joint 'R' (revolute), 'P' (prismatic) or 'F'
    (fixed); axis (3,), not zero, in the segment's starting frame (the joint turns about / slides
    along it through that frame's origin); tip the (4, 4) frame that follows the joint. A segment's
    frame at q is Rot(axis, q) tip (or Trans(axis * q) tip), so fixed segments only add frames.
    tool: (4, 4) frame appended after the last segment; None for the identity.
    limits: (lower, upper), each dof numbers (rad or m, -inf / inf for none), or None: unlimited.
    """
    records = _records(segments, "segments", 3, "(joint type 'R'|'P'|'F', axis (3,), tip (4, 4))")
    axes, tips = _stacked(records, 1, (3,)), _stacked(records, 2, (4, 4))
    types = ""
    for i, (joint, axis, tip) in enumerate(records):
        types += _joint_type(joint, f"segments[{i}]", "RPF")
        if axes is None or tips is None:  # one of them is not an array of its shape: named in order
            _checks.shaped(axis, f"segments[{i}] axis", (3,))
            _checks.shaped(tip, f"segments[{i}] tip", (4, 4))
    # The values of all segments at once: numpy calls per segment would cost more than the chain.
    peak = np.abs(axes).max(axis=1)
    finite_axes, finite_tips = np.isfinite(peak), np.isfinite(tips).all(axis=(1, 2))
    scale = np.where(finite_axes & (peak > 0), peak, 1.0)[:, None]  # scaled first, norms cannot overflow
    axes = axes / scale
    bad = ~(finite_axes & finite_tips & (np.linalg.norm(axes, axis=1) * scale[:, 0] >= 1e-12))
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"segments[{i}] " + ("axis: contains NaN or inf" if not finite_axes[i] else
                                              "tip: contains NaN or inf" if not finite_tips[i] else
                                              "axis: must not be zero"))
    return _core.chain_from_segments(types, axes, tips, tool, limits)


def _default_q(chain: Chain, default) -> list:
    """q (dof,) filled from default: a number for every joint, or a (dof,) array; NaN marks "no
    default" (None)."""
    if default is None:
        return [math.nan] * chain.dof
    if type(default) is float and math.isfinite(default):
        return [default] * chain.dof
    return _checks.per_joint(default, "default", chain.dof).tolist()


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
    given = [False] * self.dof
    unknown = []
    for key, value in mapping.items():
        found = places.get(key) if isinstance(key, str) else None
        if found is None:
            unknown.append(key)
            continue
        v = _checks.finite_float(value, f"mapping[{key!r}]")
        for i in found:
            q[i], given[i] = v, True
    if unknown:
        raise ValueError(f"mapping: unknown joint name{'s' if len(unknown) > 1 else ''} {_listed(unknown)}; "
                         f"the chain's joints are {_listed(list(names))}")
    missing = [names[i] for i in range(self.dof) if not given[i] and math.isnan(q[i])]
    if missing:
        raise ValueError(f"mapping: no value for joint{'s' if len(missing) > 1 else ''} {_listed(missing)} "
                         "(pass default= for the joints left out)")
    return np.array(q)


def q_dict(self: Chain, q: numpy.typing.ArrayLike) -> dict[str, float]:
    """{joint name: value} of q (dof,), in the chain's joint order (the inverse of q_from)."""
    values = q.tolist() if type(q) is np.ndarray and q.dtype == np.float64 and q.shape == (self.dof,) else None
    if values is None or not all(map(math.isfinite, values)):
        values = _checks.joints(self, q, "q").tolist()  # any other q read, or refused naming it, as everywhere
    return dict(zip(self.joint_names, values))


# Named and documented as the core's methods are (help(), the stubs and the reference read them).
for _method in (from_dh, from_segments, q_from, q_dict):
    written(_method, "Chain." + _method.__name__, Chain.__module__)
