"""Text for people: a chain's kinematic table (``chain.table()``, ``print(chain)``), a result's
summary (``print(result)``) and the ``repr`` of the core's classes (the short, exact form: numbers
as Python writes them). The bindings call these.

A chain built from a DH table shows that table (a, alpha, d, theta, the joint's type and limits,
the convention said); any other chain (a URDF file, joints and frames) shows one row per segment:
the frame after the joint at q = 0 relative to the frame before it, as xyz and roll, pitch, yaw,
and the joint's axis in that frame (what a URDF joint's <origin> and <axis> say). Lengths in
metres, angles in degrees, ASCII only (a terminal of any encoding prints it).
"""

from __future__ import annotations

import math
from typing import List, Sequence

import numpy as np

from . import pose

# KDL's joint types (KDL::Joint::JointType) of a chain's segment records: rotations, translations.
_ROTATIONS, _TRANSLATIONS = (0, 1, 2, 3), (4, 5, 6, 7)
# Decimals shown, trailing zeros dropped: lengths to 10 micrometres (published DH tables give
# 0.15005 m), angles to 0.0001 degree.
_LENGTH_DIGITS, _ANGLE_DIGITS = 5, 4
# Most numbers of an array shown in full in a result's summary (longer ones by shape and range).
_SHOWN = 8


def _num(value: float, digits: int = _LENGTH_DIGITS) -> str:
    """value to ``digits`` decimals, trailing zeros dropped, -0 as 0; infinities as -inf / inf."""
    if not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    text = f"{value:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _deg(radians: float) -> str:
    return _num(math.degrees(radians), _ANGLE_DIGITS)


def _offset(variable: str, value: str) -> str:
    """'q2', 'q2 + 90', 'q2 - 90' for a joint variable plus a constant shown as value."""
    if value == "0":
        return variable
    return f"{variable} - {value[1:]}" if value.startswith("-") else f"{variable} + {value}"


def _limit(value: float, prismatic: bool) -> str:
    if not math.isfinite(value):
        return _num(value)
    return f"{_num(value)} m" if prismatic else f"{_deg(value)} deg"


def _columns(header: Sequence[str], rows: List[Sequence[str]], right: Sequence[bool]) -> List[str]:
    """Aligned lines: the header, a rule, the rows; column i right-aligned when right[i]."""
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]

    def line(cells):
        return "  ".join(c.rjust(w) if r else c.ljust(w) for c, w, r in zip(cells, widths, right)).rstrip()

    return [line(header), line(["-" * w for w in widths]), *(line(r) for r in rows)]


def _frame_text(T: np.ndarray) -> str:
    xyz = ", ".join(_num(v) for v in T[:3, 3])
    rpy = ", ".join(_deg(v) for v in pose.rpy(T))
    return f"xyz ({xyz}) m, rpy ({rpy}) deg"


def _dh_lines(chain, rows, modified: bool, tool: np.ndarray) -> List[str]:
    lower, upper = chain.limits
    names = chain.joint_names
    convention = ("modified DH (Craig): A_i = Rx(alpha) Tx(a) Rz(theta) Tz(d)" if modified
                  else "standard DH: A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha)")
    body = []
    for i, (a, alpha, d, theta, kind) in enumerate(rows):
        prismatic = kind == "P"
        variable = f"q{i + 1}"
        body.append([names[i], _num(a), _deg(alpha),
                     _offset(variable, _num(d)) if prismatic else _num(d),
                     _deg(theta) if prismatic else _offset(variable, _deg(theta)),
                     kind, _limit(lower[i], prismatic), _limit(upper[i], prismatic)])
    header = ["joint", "a (m)", "alpha (deg)", "d (m)", "theta (deg)", "type", "lower", "upper"]
    lines = [f"Chain: {chain.dof} joints ({chain.joint_types}), {convention}",
             *_columns(header, body, [False, True, True, True, True, False, True, True])]
    if not np.array_equal(tool, np.eye(4)):
        lines.append(f"tool: {_frame_text(tool)}")
    return lines


def _segment_lines(chain, records) -> List[str]:
    lower, upper = chain.limits
    names, links = chain.joint_names, chain.link_names
    body, joint = [], 0
    for _, joint_name, kind, _, axis, tip in records:
        T = np.asarray(tip, dtype=float).reshape(4, 4)
        xyz = "(" + ", ".join(_num(v) for v in T[:3, 3]) + ")"
        rpy = "(" + ", ".join(_deg(v) for v in pose.rpy(T)) + ")"
        if kind in _ROTATIONS or kind in _TRANSLATIONS:
            prismatic = kind in _TRANSLATIONS
            # KDL's axis is given in the frame before the joint; R^T turns it into the frame after.
            direction = T[:3, :3].T @ np.asarray(axis, dtype=float) / np.linalg.norm(axis)
            body.append([names[joint], "P" if prismatic else "R", xyz, rpy,
                         "(" + ", ".join(_num(v) for v in direction) + ")",
                         _limit(lower[joint], prismatic), _limit(upper[joint], prismatic)])
            joint += 1
        else:
            body.append([joint_name if joint_name != "NoName" else "", "fixed", xyz, rpy, "", "", ""])
    header = ["joint", "type", "xyz (m)", "rpy (deg)", "axis", "lower", "upper"]
    return [f"Chain: {chain.dof} joints ({chain.joint_types}), base {links[0]!r}, tip {links[-1]!r}",
            "xyz, rpy: the frame after the joint at q = 0 in the one before (URDF <origin>); axis: in that frame",
            *_columns(header, body, [False, False, False, False, False, True, True])]


def table(chain) -> str:
    """The chain's kinematic table as text (see the module's docstring)."""
    state = chain.__getstate__()
    if state[2] == "dh":
        _, _, _, rows, modified, tool, _, _ = state
        return "\n".join(_dh_lines(chain, rows, modified, np.array(tool, dtype=float).reshape(4, 4)))
    return "\n".join(_segment_lines(chain, state[3]))


def _shape(a: np.ndarray) -> str:
    """numpy's way of writing a shape: (3,), (2, 4)."""
    return "(" + ", ".join(str(s) for s in a.shape) + (",)" if a.ndim == 1 else ")")


def _value_text(value) -> str:
    """One field of a result: numbers to 4 significant digits, short arrays in full, long ones by
    shape and range (booleans by how many are true), lists by length, other objects by type."""
    if isinstance(value, (bool, np.bool_, str)) or value is None:
        return repr(value) if isinstance(value, str) else str(value)
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.4g}"
    if isinstance(value, np.ndarray):
        shape = _shape(value)
        if value.size <= _SHOWN and value.dtype.kind in "biuf":
            return np.array2string(value, precision=4, separator=", ", suppress_small=True).replace("\n", "")
        if value.dtype.kind == "b":
            return f"{shape}, {int(np.count_nonzero(value))} of {value.size} true"
        if value.dtype.kind in "iuf" and value.size:
            finite = value[np.isfinite(value)] if value.dtype.kind == "f" else value
            nan = value.size - finite.size
            span = f"{finite.min():.4g} to {finite.max():.4g}" if finite.size else "no finite value"
            return f"{shape}, {span}" + (f", {nan} NaN" if nan else "")
        return f"{shape} {value.dtype}"
    if isinstance(value, (list, tuple)):
        return f"{type(value).__name__} of {len(value)}"
    return f"<{type(value).__name__}>"


def summary(result, names: Sequence[str]) -> str:
    """A result as text: its class's name, then one line per field ``name: value`` (fields listed
    in ``names``, each shown by :func:`_value_text`)."""
    lines = [f"{type(result).__name__}:"]
    width = max((len(n) for n in names), default=0)
    lines += [f"  {n.ljust(width)}  {_value_text(getattr(result, n))}" for n in names]
    return "\n".join(lines)


def cuspidality_evidence(c) -> str:
    """The sentence of a :class:`robokin.Cuspidality` saying why: its cusps and posture change, or
    why there is none."""
    n = len(c.grid)
    if not c.cuspidal:
        return (f"no cusp point on the singular curves ({n} x {n} grid of the (q2, q3) torus): "
                f"every posture change meets a singularity; {c.aspects} aspect(s)")
    q2, q3, rho, z = c.cusps[0]
    text = (f"{len(c.cusps)} cusp point(s) on the singular curves, e.g. q2 = {q2:.4f}, q3 = {q3:.4f} "
            f"(rho = {rho:.4f}, z = {z:.4f}), where three inverse solutions coincide")
    if c.path is not None:
        text += (f"; a posture change without singularity: two solutions of {np.round(c.point, 4).tolist()} "
                 f"in one aspect, joined by {len(c.path)} configurations")
    return text


# ---- repr: the short, exact form ----------------------------------------------------------------

# A chain's repr lists this many joint names first and this many last (a long list is elided).
_HEAD_NAMES, _TAIL_NAMES = 8, 2
# A URDF tree's repr shows this many joints, each indented by its depth up to this many levels.
_TREE_LINES, _TREE_INDENT = 200, 16


def fields_repr(obj, names: Sequence[str]) -> str:
    """``ClassName(a=1, b=...)`` from the named attributes of obj (options, results); arrays of more
    than 8 numbers by shape and dtype."""
    parts = []
    for name in names:
        value = getattr(obj, name)
        if isinstance(value, np.ndarray) and value.size > _SHOWN:
            text = f"<array {_shape(value)} {value.dtype}>"
        else:
            text = repr(value)
        parts.append(f"{name}={text}")
    return f"{type(obj).__name__}({', '.join(parts)})"


def chain_repr(chain, named: bool) -> str:
    """``Chain(dof=6, joints='RRRRRR', ...)``: the base, tip and joint names of a chain that came with
    names (``named``: a URDF chain's); a DH chain's rows as written (and whether a tool follows)."""
    state = chain.__getstate__()
    text = f"Chain(dof={chain.dof}, joints={chain.joint_types!r}"
    if named:
        links, joints = chain.link_names, chain.joint_names
        if len(joints) > _HEAD_NAMES + _TAIL_NAMES + 1:
            shown = [repr(n) for n in joints[:_HEAD_NAMES]] + ["..."] + [repr(n) for n in joints[-_TAIL_NAMES:]]
        else:
            shown = [repr(n) for n in joints]
        names = ", ".join(shown) + ("," if len(joints) == 1 else "")
        text += f", base={links[0]!r}, tip={links[-1]!r}, joint_names=({names})"
    if state[2] == "dh":
        _, _, _, rows, modified, tool, _, _ = state
        listed = ",\n    ".join(f"({float(a)!r}, {float(alpha)!r}, {float(d)!r}, {float(theta)!r}, {kind!r})"
                                for a, alpha, d, theta, kind in rows)
        text += f", {'modified ' if modified else ''}dh=[\n    {listed}]"
        if not np.array_equal(np.array(tool, dtype=float).reshape(4, 4), np.eye(4)):
            text += ", tool"
    return text + ")"


def urdf_joint_repr(joint) -> str:
    return f"UrdfJoint({joint.name!r}, {joint.type!r}, parent={joint.parent!r}, child={joint.child!r})"


def urdf_tree_repr(tree) -> str:
    """One line for the tree, then one per joint in depth-first order, indented by depth (both
    bounded: a URDF may hold thousands of joints)."""
    text = (f"UrdfTree(name={tree.name!r}, root={tree.root!r}, base={tree.base!r}, tip={tree.tip!r}")
    if tree.tip is None and tree.tips:
        text += f", tips=[{', '.join(repr(t) for t in tree.tips)}]"
    text += f", {len(tree.links)} links, {len(tree.joints)} joints)"
    depth = {tree.root: 0}
    lines = [text]
    for j in tree.joints[:_TREE_LINES]:
        depth[j.child] = depth.get(j.parent, 0) + 1
        lines.append("  " * min(depth[j.child], _TREE_INDENT) + f"{j.parent} -> {j.child} ({j.name}, {j.type})")
    if len(tree.joints) > _TREE_LINES:
        lines.append(f"  ... and {len(tree.joints) - _TREE_LINES} more joints")
    return "\n".join(lines)


def solutions_repr(solutions) -> str:
    """``IKSolutions(k solutions, ...)`` and one line per solution: its posture and joints."""
    within = solutions.within_limits
    count, outside = len(solutions), int(np.count_nonzero(~within))
    text = f"IKSolutions({count} solution{'' if count == 1 else 's'}"
    text += f", {outside} outside the limits" if outside else ""
    text += ", singular" if solutions.singular else ""
    if not count:
        return text + ")"
    lines = [text + ":"]
    for posture, ok, q in zip(solutions.postures, within, solutions.q):
        values = ", ".join("%.6g" % v for v in q)
        lines.append(f"  {posture}{'' if ok else ' (outside the limits)'}: [{values}]")
    return "\n".join(lines) + "\n)"


def rrr3_repr(robot) -> str:
    return (f"RRR3(base_radius={robot.base_radius!r}, platform_radius={robot.platform_radius!r}, "
            f"l1={robot.l1!r}, l2={robot.l2!r})")


def closed_solver_repr(solver) -> str:
    text = f"ClosedSolver({solver.chain!r}, family={solver.family!r}"
    text += ", limits=None" if solver.limits is None else ""
    text += f", locked={solver.locked!r}" if solver.locked is not None else ""
    return text + ")"


def ik_solver_repr(solver) -> str:
    """``IKSolver(method=..., ...)``: the solver's options."""
    return "IKSolver(" + repr(solver.options).partition("(")[2]
