"""A catalogue of robots with their published parameters (SI units, radians).

Every function returns a new :class:`robokin.Chain`.
"""

from __future__ import annotations

import math
import numbers
import operator

import numpy as np

from ._core import Chain

#: Seed 000's planar RPR: link 1, the prismatic stroke, link 3 (metres).
RPR_L1, RPR_STROKE, RPR_L3 = 1.5, 1.5, 1.0
#: Seed 000's joint limits [t1, t2, t3].
RPR_LIMITS = (np.array([0.0, 0.0, 0.0]), np.array([math.pi / 2, RPR_STROKE, math.pi]))
#: Seed 000's Figure 2: the straight line starts at point 1, on the workspace boundary, reached only
#: with t1 = pi/2 (these joints), and ends at point 2 (x, y).
RPR_LINE_Q1 = np.array([math.pi / 2, 0.75, math.pi / 2])
RPR_LINE_P2 = np.array([1.5, 1.0])


def _length(value, name: str, minimum: float = -math.inf) -> float:
    """A finite real argument as a float; the error names the argument (not the DH row it goes to)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
    value = float(value)
    if not (math.isfinite(value) and value >= minimum):
        raise ValueError(f"{name}: must be a finite number" + (f" >= {minimum:g}" if minimum > -math.inf else "")
                         + f", got {value!r}")
    return value


def _translate_x(length: float) -> np.ndarray:
    m = np.eye(4)
    m[0, 3] = length
    return m


def rpr() -> Chain:
    """The planar RPR arm of seed 000 (L. Baron, "Modélisation et commande d'un robot RPR planaire").

    Tip ``p = (L1 + t2) (cos t1, sin t1) + L3 (cos(t1 + t3), sin(t1 + t3))`` with ``L1 = 1.5``,
    ``L3 = 1.0`` and a prismatic stroke ``L2 = 1.5`` m; limits ``[0, 0, 0]`` to ``[pi/2, 1.5, pi]``.
    Built from segments (R about z, P along link 1, R about z): it is not a DH chain in this form.
    """
    z, x = (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)
    return Chain.from_segments(
        [("R", z, _translate_x(RPR_L1)), ("P", x, np.eye(4)), ("R", z, _translate_x(RPR_L3))],
        limits=RPR_LIMITS,
    )


def prr(a2: float = 1.0, a3: float = 1.0) -> Chain:
    """The 3-DoF PRR arm of seed 004 (F. Morbidi, "Modèle géométrique direct", 2019).

    DH table ``(a, alpha, d, theta)``: ``(0, pi/2, d1, 0)``, ``(a2, 0, 0, theta2)``,
    ``(a3, 0, 0, theta3)``; ``q = (d1, theta2, theta3)``; frame 3 is the tool (the seed omits T_e^3).
    """
    a2, a3 = _length(a2, "a2"), _length(a3, "a3")
    return Chain.from_dh([(0.0, math.pi / 2, 0.0, 0.0, "P"), (a2, 0.0, 0.0, 0.0, "R"), (a3, 0.0, 0.0, 0.0, "R")])


def planar_3r(a1: float = 1.0, a2: float = 1.0, a3: float = 1.0) -> Chain:
    """A planar 3R arm (seed 003, example 2): three revolute joints about z, links a1, a2, a3."""
    a1, a2, a3 = _length(a1, "a1"), _length(a2, "a2"), _length(a3, "a3")
    return Chain.from_dh([(a, 0.0, 0.0, 0.0, "R") for a in (a1, a2, a3)])


def rp(stroke: float = 1.0) -> Chain:
    """The planar RP arm of seed 003, example 1: a revolute joint, then a prismatic one along the arm.

    The tip is at ``d2 (cos theta1, sin theta1)``; ``d2`` is limited to ``[0, stroke]``.
    """
    stroke = _length(stroke, "stroke", minimum=0.0)
    return Chain.from_dh(
        [(0.0, math.pi / 2, 0.0, math.pi / 2, "R"), (0.0, 0.0, 0.0, 0.0, "P")],
        limits=([-math.inf, 0.0], [math.inf, stroke]),
    )


def ur5() -> Chain:
    """Universal Robots UR5, standard DH from Universal Robots' published table
    ("DH parameters for calculations of kinematics and dynamics"):
    d1 = 0.089159, a2 = -0.425, a3 = -0.39225, d4 = 0.10915, d5 = 0.09465, d6 = 0.0823,
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0); every joint limited to +-2 pi.
    """
    p = math.pi
    rows = [
        (0.0, p / 2, 0.089159, 0.0, "R"),
        (-0.425, 0.0, 0.0, 0.0, "R"),
        (-0.39225, 0.0, 0.0, 0.0, "R"),
        (0.0, p / 2, 0.10915, 0.0, "R"),
        (0.0, -p / 2, 0.09465, 0.0, "R"),
        (0.0, 0.0, 0.0823, 0.0, "R"),
    ]
    return Chain.from_dh(rows, limits=(np.full(6, -2 * p), np.full(6, 2 * p)))


def puma560() -> Chain:
    """Unimation PUMA 560, standard DH as in P. Corke's Robotics Toolbox (``Puma560``, after
    Corke and Armstrong-Helouvry, 1994): a = (0, 0.4318, 0.0203, 0, 0, 0),
    d = (0, 0, 0.15005, 0.4318, 0, 0), alpha = (pi/2, 0, -pi/2, pi/2, -pi/2, 0); limits in degrees
    (-160, 160), (-45, 225), (-225, 45), (-110, 170), (-100, 100), (-266, 266).
    """
    p = math.pi
    a = (0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0)
    d = (0.0, 0.0, 0.15005, 0.4318, 0.0, 0.0)
    alpha = (p / 2, 0.0, -p / 2, p / 2, -p / 2, 0.0)
    lower = np.radians([-160, -45, -225, -110, -100, -266])
    upper = np.radians([160, 225, 45, 170, 100, 266])
    return Chain.from_dh([(a[i], alpha[i], d[i], 0.0, "R") for i in range(6)], limits=(lower, upper))


_MAX_SAMPLES = 10_000_000


def rpr_self_motion(point, t1=None, num: int = 721) -> np.ndarray:
    """Every joint vector of the seed-000 RPR that puts the tip at ``point``, within its limits.

    For each ``t1`` the prismatic extension ``L1 + t2`` solves a quadratic (closed form, in the
    core), so the set is sampled along ``t1``.

    Args:
        point: The tip position (x, y).
        t1: Samples of t1; by default ``num`` values spanning its limits.
        num: Number of default samples.

    Returns:
        (2, K, 3) joints (t1, t2, t3): branch 0 the shorter extension, branch 1 the longer; NaN
        rows where the branch has no solution within the limits.
    """
    from . import _core

    lower, upper = RPR_LIMITS
    if t1 is None:
        # num names itself in the error (numpy's messages do not), and cannot ask for absurd sizes.
        if isinstance(num, bool) or not isinstance(num, numbers.Integral):
            raise TypeError(f"num: expected an int, got {type(num).__name__}")
        if not 0 <= num <= _MAX_SAMPLES:
            raise ValueError(f"num: expected an int in [0, {_MAX_SAMPLES}], got {num}")
        t1 = np.linspace(lower[0], upper[0], operator.index(num))
    return _core.rpr_self_motion(point, t1, RPR_L1, RPR_L3, lower, upper)
