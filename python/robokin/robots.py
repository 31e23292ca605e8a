"""A catalogue of robots with their published parameters (SI units, radians).

Every function returns a new :class:`robokin.Chain`; ``names()`` lists them and ``get(name)``
builds one by name. The real arms (UR3/5/10 and their e-Series, UR16e, Franka Emika Panda, KUKA LBR
iiwa 14 R820, ABB IRB 120, Kinova Gen3 7-DoF, PUMA 560) come from their makers' published
kinematic parameters and joint ranges, each named in its docstring; the tool frame is the flange
(no gripper).
"""

from __future__ import annotations

import math

import numpy as np

from ._core import Chain
from ._checks import instance, number, whole
from ._ur_dh import ur_dh_rows

__all__ = ["RPR_L1", "RPR_STROKE", "RPR_L3", "RPR_LIMITS", "RPR_LINE_Q1", "RPR_LINE_P2", "rpr", "prr",
           "planar_3r", "rp", "ur3", "ur5", "ur10", "ur3e", "ur5e", "ur10e", "ur16e", "panda", "iiwa14",
           "irb120", "gen3", "puma560", "PUMA560_A", "PUMA560_D", "PUMA560_ALPHA", "PUMA560_LIMITS", "names", "get",
           "configurations", "rpr_self_motion"]

#: Seed 000's planar RPR: link 1, the prismatic stroke, link 3 (metres).
RPR_L1, RPR_STROKE, RPR_L3 = 1.5, 1.5, 1.0
#: Seed 000's joint limits [t1, t2, t3].
RPR_LIMITS = (np.array([0.0, 0.0, 0.0]), np.array([math.pi / 2, RPR_STROKE, math.pi]))
#: Seed 000's Figure 2: the straight line starts at point 1, on the workspace boundary, reached only
#: with t1 = pi/2 (these joints), and ends at point 2 (x, y).
RPR_LINE_Q1 = np.array([math.pi / 2, 0.75, math.pi / 2])
RPR_LINE_P2 = np.array([1.5, 1.0])


def _translate_x(length: float) -> np.ndarray:
    m = np.eye(4)
    m[0, 3] = length
    return m


def rpr() -> Chain:
    """The planar RPR arm of the RPR study (L. Baron, "Modélisation et commande d'un robot RPR planaire").

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
    """The 3-DoF PRR arm of the DH exercise (F. Morbidi, "Modèle géométrique direct", 2019).

    DH table ``(a, alpha, d, theta)``: ``(0, pi/2, d1, 0)``, ``(a2, 0, 0, theta2)``,
    ``(a3, 0, 0, theta3)``; ``q = (d1, theta2, theta3)``; frame 3 is the tool (the seed omits T_e^3).
    """
    a2, a3 = number(a2, "a2"), number(a3, "a3")
    return Chain.from_dh([(0.0, math.pi / 2, 0.0, 0.0, "P"), (a2, 0.0, 0.0, 0.0, "R"), (a3, 0.0, 0.0, 0.0, "R")])


def planar_3r(a1: float = 1.0, a2: float = 1.0, a3: float = 1.0) -> Chain:
    """A planar 3R arm (the IK course, example 2): three revolute joints about z, links a1, a2, a3."""
    a1, a2, a3 = number(a1, "a1"), number(a2, "a2"), number(a3, "a3")
    return Chain.from_dh([(a, 0.0, 0.0, 0.0, "R") for a in (a1, a2, a3)])


def rp(stroke: float = 1.0) -> Chain:
    """The planar RP arm of the IK course, example 1: a revolute joint, then a prismatic one along the arm.

    The tip is at ``d2 (cos theta1, sin theta1)``; ``d2`` is limited to ``[0, stroke]``.
    """
    stroke = number(stroke, "stroke", minimum=0.0)
    return Chain.from_dh(
        [(0.0, math.pi / 2, 0.0, math.pi / 2, "R"), (0.0, 0.0, 0.0, 0.0, "P")],
        limits=([-math.inf, 0.0], [math.inf, stroke]),
    )


_UR_SOURCE = ("Universal Robots, \"DH Parameters for calculations of kinematics and dynamics\" "
              "(universal-robots.com, support article)")


def _ur(d1: float, a2: float, a3: float, d4: float, d5: float, d6: float, wrist3_unlimited: bool = False) -> Chain:
    """A UR arm: standard DH a = (0, a2, a3, 0, 0, 0), d = (d1, 0, 0, d4, d5, d6),
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0); every joint +-360 deg (wrist 3 unlimited when asked)."""
    lower, upper = np.full(6, -2 * math.pi), np.full(6, 2 * math.pi)
    if wrist3_unlimited:
        lower[5], upper[5] = -math.inf, math.inf
    return Chain.from_dh(ur_dh_rows(d1, a2, a3, d4, d5, d6), limits=(lower, upper))


def ur3() -> Chain:
    """Universal Robots UR3 (CB3), standard DH from Universal Robots' published table
    ("DH Parameters for calculations of kinematics and dynamics"): d1 = 0.1519, a2 = -0.24365,
    a3 = -0.21325, d4 = 0.11235, d5 = 0.08535, d6 = 0.0819, alpha = (pi/2, 0, 0, pi/2, -pi/2, 0).
    Joint ranges from UR's technical specifications: +-360 deg, wrist 3 infinite (unlimited here).
    """
    return _ur(0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819, wrist3_unlimited=True)


def ur5() -> Chain:
    """Universal Robots UR5, standard DH from Universal Robots' published table
    ("DH parameters for calculations of kinematics and dynamics"):
    d1 = 0.089159, a2 = -0.425, a3 = -0.39225, d4 = 0.10915, d5 = 0.09465, d6 = 0.0823,
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0); every joint limited to +-2 pi.
    """
    return _ur(0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823)


def ur10() -> Chain:
    """Universal Robots UR10 (CB3), standard DH from Universal Robots' published table
    ("DH Parameters for calculations of kinematics and dynamics"): d1 = 0.1273, a2 = -0.612,
    a3 = -0.5723, d4 = 0.163941, d5 = 0.1157, d6 = 0.0922, alpha = (pi/2, 0, 0, pi/2, -pi/2, 0);
    every joint +-360 deg (UR's technical specifications).
    """
    return _ur(0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922)


def ur3e() -> Chain:
    """Universal Robots UR3e, standard DH from Universal Robots' published table
    ("DH Parameters for calculations of kinematics and dynamics", e-Series): d1 = 0.15185,
    a2 = -0.24355, a3 = -0.2132, d4 = 0.13105, d5 = 0.08535, d6 = 0.0921,
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0). Joint ranges from UR's technical specifications:
    +-360 deg, wrist 3 infinite (unlimited here).
    """
    return _ur(0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921, wrist3_unlimited=True)


def ur5e() -> Chain:
    """Universal Robots UR5e, standard DH from Universal Robots' published table
    ("DH Parameters for calculations of kinematics and dynamics", e-Series): d1 = 0.1625,
    a2 = -0.425, a3 = -0.3922, d4 = 0.1333, d5 = 0.0997, d6 = 0.0996,
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0); every joint +-360 deg (UR's technical specifications).
    """
    return _ur(0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996)


def ur10e() -> Chain:
    """Universal Robots UR10e, standard DH from Universal Robots' published table
    ("DH Parameters for calculations of kinematics and dynamics", e-Series): d1 = 0.1807,
    a2 = -0.6127, a3 = -0.57155, d4 = 0.17415, d5 = 0.11985, d6 = 0.11655,
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0); every joint +-360 deg (UR's technical specifications).
    """
    return _ur(0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655)


def ur16e() -> Chain:
    """Universal Robots UR16e, standard DH from Universal Robots' published table
    ("DH Parameters for calculations of kinematics and dynamics", e-Series): d1 = 0.1807,
    a2 = -0.4784, a3 = -0.36, d4 = 0.17415, d5 = 0.11985, d6 = 0.11655,
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0); every joint +-360 deg (UR's technical specifications).
    """
    return _ur(0.1807, -0.4784, -0.36, 0.17415, 0.11985, 0.11655)


def panda() -> Chain:
    """Franka Emika Panda (7 joints), modified DH (Craig) as Franka Emika publishes it (FCI
    documentation, "Robot and interface specifications", frankaemika.github.io/docs/
    control_parameters.html): rows (a, d, alpha) = (0, 0.333, 0), (0, 0, -pi/2), (0, 0.316, pi/2),
    (0.0825, 0, pi/2), (-0.0825, 0.384, -pi/2), (0, 0, pi/2), (0.088, 0, pi/2), then the flange
    d = 0.107 (the tool frame here; no hand). Joint limits (same page), rad:
    lower (-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973),
    upper (2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973).
    """
    p = math.pi
    rows = [
        (0.0, 0.0, 0.333, 0.0, "R"),
        (0.0, -p / 2, 0.0, 0.0, "R"),
        (0.0, p / 2, 0.316, 0.0, "R"),
        (0.0825, p / 2, 0.0, 0.0, "R"),
        (-0.0825, -p / 2, 0.384, 0.0, "R"),
        (0.0, p / 2, 0.0, 0.0, "R"),
        (0.088, p / 2, 0.0, 0.0, "R"),
    ]
    flange = np.eye(4)
    flange[2, 3] = 0.107
    lower = np.array([-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973])
    upper = np.array([2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973])
    return Chain.from_dh(rows, modified=True, tool=flange, limits=(lower, upper))


def iiwa14() -> Chain:
    """KUKA LBR iiwa 14 R820 (7 joints), standard DH from KUKA's published dimensions (LBR iiwa
    specification / operating instructions: base to axis 2 360 mm, axis 2 to axis 4 420 mm,
    axis 4 to axis 6 400 mm, axis 6 to the flange 126 mm): d = (0.36, 0, 0.42, 0, 0.4, 0, 0.126),
    a = 0, alpha = (-pi/2, pi/2, pi/2, -pi/2, -pi/2, pi/2, 0) (the arm straight up at q = 0).
    Axis ranges (same specification): +-170, +-120, +-170, +-120, +-170, +-120, +-175 deg.
    """
    p = math.pi
    d = (0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.126)
    alpha = (-p / 2, p / 2, p / 2, -p / 2, -p / 2, p / 2, 0.0)
    limit = np.radians([170, 120, 170, 120, 170, 120, 175])
    return Chain.from_dh([(0.0, alpha[i], d[i], 0.0, "R") for i in range(7)], limits=(-limit, limit))


def irb120() -> Chain:
    """ABB IRB 120-3/0.6, standard DH from ABB's product specification (IRB 120, 3HAC035960-001:
    dimensions 290 mm base to axis 2, 270 mm axis 2 to axis 3, 70 mm axis 3 offset, 302 mm to the
    wrist centre, 72 mm wrist centre to the flange): (a, alpha, d, theta) = (0, -pi/2, 0.29, 0),
    (0.27, 0, 0, -pi/2), (0.07, -pi/2, 0, 0), (0, pi/2, 0.302, 0), (0, -pi/2, 0, 0),
    (0, 0, 0.072, pi), so that q = 0 is ABB's calibration position (upper arm vertical, forearm
    horizontal, flange at x = 0.374 m, z = 0.63 m, facing +x) and each joint turns the way ABB's
    axis does. Working range (same specification): axis 1 +-165, axis 2 +-110, axis 3 -110 / +70,
    axis 4 +-160, axis 5 +-120, axis 6 +-400 deg.
    """
    p = math.pi
    rows = [
        (0.0, -p / 2, 0.29, 0.0, "R"),
        (0.27, 0.0, 0.0, -p / 2, "R"),
        (0.07, -p / 2, 0.0, 0.0, "R"),
        (0.0, p / 2, 0.302, 0.0, "R"),
        (0.0, -p / 2, 0.0, 0.0, "R"),
        (0.0, 0.0, 0.072, p, "R"),
    ]
    lower = np.radians([-165, -110, -110, -160, -120, -400])
    upper = np.radians([165, 110, 70, 160, 120, 400])
    return Chain.from_dh(rows, limits=(lower, upper))


def _rx(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def _dh_tip(a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    """Rz(theta) Tz(d) Tx(a) Rx(alpha): a standard DH row's constant part after its joint."""
    c, s = math.cos(theta), math.sin(theta)
    rz = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1]])
    tz, tx = np.eye(4), np.eye(4)
    tz[2, 3], tx[0, 3] = d, a
    return rz @ tz @ tx @ _rx(alpha)


def gen3() -> Chain:
    """Kinova Gen3 7-DOF (without gripper), classic DH from Kinova's Gen3 User Guide ("Classic DH
    parameters", 7 DoF): a base frame Rx(pi), then (alpha, a, d, theta) = (pi/2, 0, -0.2848, q1),
    (pi/2, 0, -0.0118, q2 + pi), (pi/2, 0, -0.4208, q3 + pi), (pi/2, 0, -0.0128, q4 + pi),
    (pi/2, 0, -0.3143, q5 + pi), (pi/2, 0, 0, q6 + pi), (pi, 0, -0.1674, q7 + pi) (the guide
    writes the lengths as sums: 0.1564 + 0.1284, 0.0054 + 0.0064, 0.2104 + 0.2104, 0.0064 + 0.0064,
    0.2084 + 0.1059, 0.1059 + 0.0615). Joint ranges (same guide): joints 1, 3, 5, 7 infinite
    (unlimited here), joint 2 +-128.9, joint 4 +-147.8, joint 6 +-120.3 deg.
    """
    p = math.pi
    z = (0.0, 0.0, 1.0)
    d = (-(0.1564 + 0.1284), -(0.0054 + 0.0064), -(0.2104 + 0.2104), -(0.0064 + 0.0064),
         -(0.2084 + 0.1059), 0.0, -(0.1059 + 0.0615))
    alpha = (p / 2,) * 6 + (p,)
    theta = (0.0,) + (p,) * 6
    segments = [("F", z, _rx(p))]
    segments += [("R", z, _dh_tip(0.0, alpha[i], d[i], theta[i])) for i in range(7)]
    inf = math.inf
    upper = np.array([inf, math.radians(128.9), inf, math.radians(147.8), inf, math.radians(120.3), inf])
    lower = -upper
    return Chain.from_segments(segments, limits=(lower, upper))
#: The PUMA 560's standard DH lengths (m) and twists, and its joint limits (rad): the one statement
#: of its geometry (robokin.closed.PUMA560 and its closed form read them).
PUMA560_A = (0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0)
PUMA560_D = (0.0, 0.0, 0.15005, 0.4318, 0.0, 0.0)
PUMA560_ALPHA = (math.pi / 2, 0.0, -math.pi / 2, math.pi / 2, -math.pi / 2, 0.0)
PUMA560_LIMITS = (np.radians([-160, -45, -225, -110, -100, -266]), np.radians([160, 225, 45, 170, 100, 266]))


def puma560() -> Chain:
    """Unimation PUMA 560, standard DH as in P. Corke's Robotics Toolbox (``Puma560``, after
    Corke and Armstrong-Helouvry, 1994): a = (0, 0.4318, 0.0203, 0, 0, 0),
    d = (0, 0, 0.15005, 0.4318, 0, 0), alpha = (pi/2, 0, -pi/2, pi/2, -pi/2, 0); limits in degrees
    (-160, 160), (-45, 225), (-225, 45), (-110, 170), (-100, 100), (-266, 266).
    """
    a, d, alpha = PUMA560_A, PUMA560_D, PUMA560_ALPHA
    return Chain.from_dh([(a[i], alpha[i], d[i], 0.0, "R") for i in range(6)], limits=PUMA560_LIMITS)


# The catalogue by name: every builder above, each callable without arguments (the seeds' robots
# with their default dimensions).
_CATALOGUE = {
    "gen3": gen3,
    "iiwa14": iiwa14,
    "irb120": irb120,
    "panda": panda,
    "planar_3r": planar_3r,
    "prr": prr,
    "puma560": puma560,
    "rp": rp,
    "rpr": rpr,
    "ur3": ur3,
    "ur3e": ur3e,
    "ur5": ur5,
    "ur5e": ur5e,
    "ur10": ur10,
    "ur10e": ur10e,
    "ur16e": ur16e,
}


def names() -> list:
    """The names of every robot in the catalogue, sorted; ``get(name)`` builds one."""
    return sorted(_CATALOGUE)


def get(name: str) -> Chain:
    """Builds the catalogue's robot called ``name`` (one of :func:`names`, e.g. ``"panda"``);
    the seeds' parametrised robots (``prr``, ``planar_3r``, ``rp``) with their default dimensions.

    Raises:
        ValueError: ``name`` is not in the catalogue (the message lists the valid names).
        TypeError: ``name`` is not a string.
    """
    instance(name, "name", str, "a str")
    builder = _CATALOGUE.get(name)
    if builder is None:
        raise ValueError(f"name: no robot named {name!r} in the catalogue; valid names: {', '.join(names())}")
    return builder()


# Named postures of the real arms (radians; sources in configurations' docstring). The UR family
# shares its maker's postures (one controller convention for all its sizes).
_PI = math.pi
_UR_POSTURES = {
    "home": (0.0, -_PI / 2, 0.0, 0.0, 0.0, 0.0),
    "up": (0.0, -_PI / 2, 0.0, -_PI / 2, 0.0, 0.0),
    "ready": (1.54, -1.62, 1.4, -1.2, -1.6, -0.11),
}
_GEN3_HOME = tuple(math.radians(a) for a in (0.0, 15.0, 180.0, -130.0, 0.0, 55.0, 90.0))
_POSTURES = {
    **{name: _UR_POSTURES for name in ("ur3", "ur3e", "ur5", "ur5e", "ur10", "ur10e", "ur16e")},
    "panda": {"home": (0.0, -_PI / 4, 0.0, -3 * _PI / 4, 0.0, _PI / 2, _PI / 4),
              "ready": (0.0, -0.3, 0.0, -2.2, 0.0, 2.0, _PI / 4)},
    "iiwa14": {"home": (0.0,) * 7, "ready": (0.0, -0.3, 0.0, -1.9, 0.0, 1.5, _PI / 4)},
    "gen3": {"home": _GEN3_HOME, "ready": _GEN3_HOME},
    "puma560": {"home": (0.0, _PI / 2, -_PI / 2, 0.0, 0.0, 0.0), "ready": (0.0, _PI / 4, -_PI, 0.0, _PI / 4, 0.0)},
    "irb120": {"home": (0.0,) * 6},
}


def configurations(name: str) -> dict:
    """Named joint configurations of the catalogue's robot ``name``, like the Robotics Toolbox's
    ``qz`` / ``qr``: ``{configuration name: q (dof,)}`` (radians; metres for prismatic joints), new
    arrays at each call. Every one lies within the arm's joint limits.

    - ``zero`` (every robot): all joints at 0, clipped into the limits (the Panda's joint 4 stops at
      -0.0698). Arms stretched out at zero are singular there (UR, iiwa, Gen3, PUMA 560, IRB 120).
    - ``home`` (the real arms): the rest posture the maker (or the Robotics Toolbox, RTB) documents;
      singular where the maker's is (UR, iiwa, PUMA 560, IRB 120: an upright or stretched arm, or a
      wrist with joint 5 at 0).
    - ``ready`` (the real arms but the IRB 120): a working posture from a published source, away
      from every singularity: the posture to start inverse kinematics or a simulation from.
    - ``up`` (UR arms): the maker's upright posture.

    Sources:

    - UR3 / UR5 / UR10 and the e-Series: Universal Robots' MoveIt configuration (ur_moveit_config,
      Universal_Robots_ROS2_Driver, ``srdf/ur_macro.srdf.xacro``): ``home`` = (0, -pi/2, 0, 0, 0, 0)
      and ``up`` = (0, -pi/2, 0, -pi/2, 0, 0) (the file writes -1.5707 for -pi/2), ``ready`` = its
      ``test_configuration`` (1.54, -1.62, 1.4, -1.2, -1.6, -0.11). RTB's UR ``qr``
      (pi, 0, 0, 0, pi/2, 0) has the elbow straight (singular) and is not used.
    - Panda: ``home`` = franka_ros's start pose (``move_to_start``, also panda_moveit_config's
      ``ready``) (0, -pi/4, 0, -3 pi/4, 0, pi/2, pi/4); ``ready`` = RTB's ``qr``
      (0, -0.3, 0, -2.2, 0, 2.0, pi/4).
    - LBR iiwa 14: ``home`` = 0 (the arm straight up, KUKA's zero); ``ready`` = RTB's LBR ``qr``
      (0, -0.3, 0, -1.9, 0, 1.5, pi/4).
    - Gen3: ``home`` = ``ready`` = Kinova's Home position (0, 15, 180, 230, 0, 55, 90) deg, which
      is also RTB's ``qr``; joint 4 written -130 deg, the same angle within its +-147.8 deg range.
    - PUMA 560: ``home`` = RTB's ``qr``, the arm upright (0, pi/2, -pi/2, 0, 0, 0); ``ready`` =
      RTB's ``qn``, its nominal table-top picking posture (0, pi/4, pi, 0, pi/4, 0) with joint 3
      written -pi, the same angle within this model's -225 .. 45 deg range.
    - IRB 120: ``home`` = 0, ABB's calibration position (see :func:`irb120`).

    Raises:
        ValueError: ``name`` is not in the catalogue (the message lists the valid names).
        TypeError: ``name`` is not a string.
    """
    chain = get(name)
    lower, upper = chain.limits
    named = {"zero": np.clip(np.zeros(chain.dof), lower, upper)}
    named.update({key: np.array(q, dtype=float) for key, q in _POSTURES.get(name, {}).items()})
    return named


_MAX_SAMPLES = 10_000_000


def rpr_self_motion(point, t1=None, num: int = 721) -> np.ndarray:
    """Every joint vector of the RPR study's arm that puts the tip at ``point``, within its limits.

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
        t1 = np.linspace(lower[0], upper[0], whole(num, "num", 0, _MAX_SAMPLES, "samples"))
    return _core.rpr_self_motion(point, t1, RPR_L1, RPR_L3, lower, upper)
