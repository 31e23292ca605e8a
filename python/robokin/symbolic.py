"""Symbolic models of a DH chain (sympy: the optional extra ``symbolic``): the tool pose ``T(q)``
and the geometric Jacobian as simplified sympy matrices, read from the chain's own DH table.

The table's numbers become exact: an angle within 1e-12 of a multiple of pi/12 is that multiple of
``pi``, any other number the decimal fraction Python prints for it (``0.4318`` is ``2159/5000``),
so that ``sin(pi/2)`` is 1 and not 1.0000000000000000. The joints are the symbols ``q1 ... qn``
unless given. With ``lengths="symbols"`` each non-zero ``a`` and ``d`` of the table that is not a
joint variable is the symbol ``a<i>`` / ``d<i>`` instead (``i`` the row, from 1), as a course writes
the model; its value is ``table(chain)``'s.

Only chains built from a DH table (:meth:`robokin.Chain.from_dh` and the arms of
:mod:`robokin.robots` made that way) have one: a chain from a URDF file or from joints and frames
is refused with a ``ValueError``.
"""

from __future__ import annotations

import sympy as sp

from ._checks import chain as _chain, choice as _choice
from ._core import Chain

__all__ = ["fk", "jacobian", "table"]

_LENGTHS = ("values", "symbols")
_TASK_ROWS = {"pose": [0, 1, 2, 3, 4, 5], "position": [0, 1, 2], "xy": [0, 1], "xyphi": [0, 1, 5]}
# A cosine or sine of a multiple of pi/12 within this of its exact value is taken for it; far
# below any physical length, far above the rounding of a float angle (1e-16).
_EXACT_TOL = 1e-12


def _exact(x: float):
    """The exact number a float of the table stands for (the module's docstring says how)."""
    k = x / (sp.pi.evalf() / 12)
    if x != 0 and abs(float(k) - round(float(k))) < _EXACT_TOL:
        return sp.pi * sp.Rational(round(float(k)), 12)
    return sp.Rational(repr(float(x)))


def _exact_entry(x: float):
    """A rotation or position entry of the tool transform: sines and cosines of multiples of pi/12
    exactly (``sqrt(2)/2`` ...), any other number as :func:`_exact` gives it."""
    for k in range(13):
        for value in (sp.cos(sp.pi * k / 12), -sp.cos(sp.pi * k / 12)):
            if abs(float(value) - x) < _EXACT_TOL:
                return value
    return sp.Rational(repr(float(x)))


def _dh_state(chain: Chain):
    state = _chain(chain).__getstate__()
    if state[2] != "dh":
        raise ValueError("chain: has no DH table (built from a URDF file or from joints and frames); "
                         "rk.symbolic needs a chain made by Chain.from_dh")
    rows, modified, tool = state[3], bool(state[4]), state[5]
    return rows, modified, sp.Matrix(4, 4, [_exact_entry(float(v)) for v in tool])  # row-major


def table(chain: Chain, lengths: str = "values") -> sp.Matrix:
    """The chain's DH table as an exact sympy matrix, one row ``(a, alpha, d, theta)`` per joint,
    the joint variable ``q<i>`` added to ``theta`` (revolute) or ``d`` (prismatic).

    Args:
        chain: A chain built from a DH table (``Chain.from_dh``).
        lengths: ``"values"`` (the table's numbers, exact) or ``"symbols"`` (each non-zero ``a`` and
            ``d`` that is not a joint variable as the symbol ``a<i>`` / ``d<i>``).

    Returns:
        sympy.Matrix of shape (dof, 4); standard or modified DH as the chain was built.

    Raises:
        TypeError: ``chain`` is not a Chain; ``lengths`` is not a string.
        ValueError: the chain has no DH table; ``lengths`` is not one of the two.

    Example:
        >>> import robokin as rk
        >>> from robokin import symbolic
        >>> symbolic.table(rk.robots.prr(), lengths="symbols")
        Matrix([
        [ 0, pi/2, q1,      0],
        [a2,    0,  0,     q2],
        [a3,    0,  0,     q3]])
    """
    rows, _, _ = _dh_state(chain)
    return _table(rows, _choice(lengths, "lengths", _LENGTHS), sp.symbols(f"q1:{len(rows) + 1}", real=True))


def _table(rows, lengths, q):
    out = []
    for i, (a, alpha, d, theta, joint) in enumerate(rows, start=1):
        a, alpha, d, theta = _exact(a), _exact(alpha), _exact(d), _exact(theta)
        if lengths == "symbols":
            a = sp.Symbol(f"a{i}", real=True) if a != 0 else a
            d = sp.Symbol(f"d{i}", real=True) if d != 0 and joint == "R" else d
        if joint == "P":
            d = d + q[i - 1]
        else:
            theta = theta + q[i - 1]
        out.append([a, alpha, d, theta])
    return sp.Matrix(out)


def _rot_z(t):
    return sp.Matrix([[sp.cos(t), -sp.sin(t), 0, 0], [sp.sin(t), sp.cos(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def _rot_x(t):
    return sp.Matrix([[1, 0, 0, 0], [0, sp.cos(t), -sp.sin(t), 0], [0, sp.sin(t), sp.cos(t), 0], [0, 0, 0, 1]])


def _shift(x=0, z=0):
    return sp.Matrix([[1, 0, 0, x], [0, 1, 0, 0], [0, 0, 1, z], [0, 0, 0, 1]])


def _joints(chain, q):
    n = chain.dof
    if q is None:
        return sp.symbols(f"q1:{n + 1}", real=True)
    if isinstance(q, (str, bytes)) or not hasattr(q, "__len__"):
        raise TypeError(f"q: expected a sequence of {n} sympy expressions or numbers, got {type(q).__name__}")
    if len(q) != n:
        raise ValueError(f"q: expected {n} entries (the chain's dof), got {len(q)}")
    try:
        values = tuple(sp.sympify(v, strict=True) for v in q)
    except sp.SympifyError as exc:
        raise TypeError(f"q: expected sympy expressions or numbers, got {exc.expr!r}") from None
    for v in values:
        if not isinstance(v, sp.Expr) or v.is_real is False:
            raise TypeError(f"q: expected real sympy expressions or numbers, got {v!r}")
        if v.has(sp.nan, sp.oo, -sp.oo, sp.zoo):
            raise ValueError(f"q: contains NaN or inf ({v!r})")
    return values


def _frames(chain, q, lengths):
    """The joint axes' frames (in the base frame) and the tool pose, unsimplified: for each joint the
    frame whose z is its axis and whose origin is on it, then ``T(q)`` with the tool applied."""
    rows, modified, tool = _dh_state(chain)
    dh = _table(rows, _choice(lengths, "lengths", _LENGTHS), q)
    T, axes = sp.eye(4), []
    for a, alpha, d, theta in (dh.row(i) for i in range(dh.rows)):
        if modified:  # Craig: A_i = Rx(alpha) Tx(a) Rz(theta) Tz(d); joint i turns about this z
            T = T * _rot_x(alpha) * _shift(x=a)
            axes.append(T)
            T = T * _rot_z(theta) * _shift(z=d)
        else:  # A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha); joint i turns about the previous frame's z
            axes.append(T)
            T = T * _rot_z(theta) * _shift(z=d) * _shift(x=a) * _rot_x(alpha)
    return axes, T * tool


def _simplified(m: sp.Matrix, simplify: bool) -> sp.Matrix:
    return m.applyfunc(sp.simplify) if simplify else m


def fk(chain: Chain, q=None, lengths: str = "values", simplify: bool = True) -> sp.Matrix:
    """The tool pose ``T(q) = A_1(q_1) ... A_n(q_n) tool`` as a 4 x 4 sympy matrix.

    Args:
        chain: A chain built from a DH table (``Chain.from_dh``), standard or modified.
        q: The joint values: a sequence of ``dof`` sympy expressions or numbers; ``None`` for the
            symbols ``q1 ... qn``.
        lengths: ``"values"`` or ``"symbols"``, as :func:`table`.
        simplify: Simplify each entry (``sympy.simplify``; slow for a 6-joint arm: ``False`` skips it).

    Returns:
        sympy.Matrix (4, 4): the same matrix as ``chain.fk(q)`` for any numeric ``q``.

    Raises:
        TypeError: ``chain`` is not a Chain; ``q`` holds what sympy cannot read.
        ValueError: the chain has no DH table; ``q`` has not ``dof`` entries; ``lengths`` unknown.

    Example:
        >>> import robokin as rk
        >>> from robokin import symbolic
        >>> symbolic.fk(rk.robots.prr(), lengths="symbols")[:3, 3].T
        Matrix([[a2*cos(q2) + a3*cos(q2 + q3), 0, a2*sin(q2) + a3*sin(q2 + q3) + q1]])
    """
    _, T = _frames(_chain(chain), _joints(chain, q), lengths)
    return _simplified(T, bool(simplify))


def jacobian(chain: Chain, q=None, task: str | None = None, lengths: str = "values",
             simplify: bool = True) -> sp.Matrix:
    """The geometric Jacobian at the tool point, in the base frame, as a sympy matrix.

    Column ``i``: for a revolute joint ``(z_i x (p - o_i), z_i)``, for a prismatic one ``(z_i, 0)``,
    with ``z_i`` the joint's axis, ``o_i`` a point on it and ``p`` the tool point; rows
    ``[v_x, v_y, v_z, w_x, w_y, w_z]`` as ``chain.jacobian``.

    Args:
        chain: A chain built from a DH table (``Chain.from_dh``), standard or modified.
        q: As :func:`fk`.
        task: The rows: ``"pose"`` (6), ``"position"`` (0-2), ``"xy"`` (0, 1), ``"xyphi"`` (0, 1, 5);
            ``None`` for the chain's ``natural_task``.
        lengths: ``"values"`` or ``"symbols"``, as :func:`table`.
        simplify: As :func:`fk`.

    Returns:
        sympy.Matrix (rows, dof): the same matrix as ``chain.jacobian(q, task)`` for a numeric ``q``.

    Raises:
        TypeError: ``chain`` is not a Chain; ``q`` holds what sympy cannot read; ``task`` not a string.
        ValueError: the chain has no DH table; ``q`` has not ``dof`` entries; ``task`` or ``lengths``
            unknown.

    Example:
        >>> import robokin as rk
        >>> from robokin import symbolic
        >>> symbolic.jacobian(rk.robots.planar_3r(), task="xy")[:, 2].T
        Matrix([[-sin(q1 + q2 + q3), cos(q1 + q2 + q3)]])
    """
    task = _chain(chain).natural_task if task is None else _choice(task, "task", tuple(_TASK_ROWS))
    axes, T = _frames(chain, _joints(chain, q), lengths)
    p = T[:3, 3]
    columns = []
    for frame, joint in zip(axes, chain.joint_types):
        z, o = frame[:3, 2], frame[:3, 3]
        columns.append(z.col_join(sp.zeros(3, 1)) if joint == "P" else z.cross(p - o).col_join(z))
    J = sp.Matrix.hstack(*columns)
    return _simplified(J.extract(_TASK_ROWS[task], list(range(J.cols))), bool(simplify))

