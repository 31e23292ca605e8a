"""Closed-form inverse kinematics (the IK course): every solution of a pose, labelled by its posture.

Each function returns an :class:`IKSolutions` (``q`` of shape ``(k, dof)``, ``postures``,
``within_limits``, ``singular``) holding **every** solution of the pose, and empty (``len(s) == 0``,
never an exception) when the pose is out of reach. The joint limits hide none: ``within_limits[k]``
says whether solution ``k`` is within them (``s.only_within_limits()``, or ``s.q[s.within_limits]``,
keeps those). Revolute angles are wrapped to ``(-pi, pi]`` and shifted by ``2 pi`` into the limits
when that fits; a solution that does not fit keeps its wrapped angles. ``limits`` defaults to the
chain's own where the arm is a chain (:func:`puma560`, :func:`ur`, :func:`general_3r`), to none
where it is given by its lengths (every ``within_limits`` True). The batch and path variants
follow the same rule: :func:`ur_batch` returns a ``within_limits`` mask beside its solutions, and
:func:`puma560_path`, which must stay within the limits, says where a frame was reachable only
outside them.

The solvers run in the C++ core, and every solution is checked against the forward model before it
is returned: the tool within 1e-9 x the arm's size (the sum of its lengths) of the target position,
rotation-matrix entries within 1e-8 (a pose a hair out of reach, where a cosine is clamped to 1, is
therefore returned only when the stretched arm really is that close).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from . import robots as _robots
from ._checks import chain as check_chain
from ._checks import finite_float
from ._core import UR_POSTURES, Chain, ClosedBatch, ClosedFamilyOptions, ClosedPath, ClosedSolver, IKSolutions
from ._options import with_options
from ._ur_dh import ur_dh_rows

__all__ = [
    "ClosedBatch",
    "ClosedFamilyOptions",
    "ClosedPath",
    "ClosedSolver",
    "Family",
    "family",
    "solve",
    "IKSolutions",
    "anthropomorphic",
    "general_3r",
    "planar_2r",
    "planar_3r",
    "planar_rp",
    "puma560",
    "puma560_path",
    "rpr_self_motion",
    "spherical_wrist_6r",
    "ur",
    "ur_batch",
    "UR_POSTURES",
    "PUMA560",
]

#: PUMA 560 standard DH (P. Corke's Robotics Toolbox ``Puma560``, as in :func:`robokin.robots.puma560`).
PUMA560 = {"d1": _robots.PUMA560_D[0], "a2": _robots.PUMA560_A[1], "a3": _robots.PUMA560_A[2],
           "d3": _robots.PUMA560_D[2], "d4": _robots.PUMA560_D[3], "d6": _robots.PUMA560_D[5]}
_PUMA560_LENGTHS = tuple(PUMA560[k] for k in ("a2", "a3", "d3", "d4", "d1", "d6"))  # spherical_wrist_6r's order


def _limits(limits):
    """``None``, a ``(lower, upper)`` pair, or a Chain whose limits are used."""
    if isinstance(limits, Chain):
        return limits.limits
    return limits


def planar_rp(target, limits=None) -> IKSolutions:
    """Planar RP arm (the IK course, example 1): ``theta1 = atan2(p_y, p_x)``, ``d2 = sqrt(p_x^2 + p_y^2)``.

    Args:
        target: Tip position (x, y).
        limits: ``(lower, upper)`` for ``(theta1, d2)``, or a Chain (e.g. :func:`robokin.robots.rp`),
            for ``within_limits``; None: every solution within.

    Returns:
        The forward stroke (``d2 >= 0``) and the backward one (``d2 < 0``, outside limits such as
        :func:`robokin.robots.rp`'s ``0 <= d2``).
    """
    return _core.ik_planar_rp(target, _limits(limits))


def planar_2r(target, a1: float = 1.0, a2: float = 1.0, limits=None) -> IKSolutions:
    """Planar 2R arm: both elbow postures putting the tip at ``target`` (x, y).

    Args:
        target: Tip position (x, y).
        a1: Length of link 1.
        a2: Length of link 2.
        limits: ``(lower, upper)`` or a Chain, for ``within_limits``; None: none.

    Returns:
        "elbow down" (``theta2`` in ``(0, pi)``) and "elbow up"; one solution when ``sin theta2 = 0``.
    """
    return _core.ik_planar_2r(target, a1, a2, _limits(limits))


def planar_3r(target, a1: float = 1.0, a2: float = 1.0, a3: float = 1.0, method: str = "algebraic",
              limits=None) -> IKSolutions:
    """Planar 3R arm with the tool orientation (the IK course, example 2).

    Args:
        target: ``(x, y, phi)``, the tip position and the angle of the last link to the x axis.
        a1: Length of link 1.
        a2: Length of link 2.
        a3: Length of link 3.
        method: ``"algebraic"`` (``c2``, ``s2 = +-sqrt(1 - c2^2)``, then ``s1``, ``c1``) or
            ``"geometric"`` (law of cosines, ``theta1 = alpha -+ beta``).
        limits: ``(lower, upper)`` or a Chain (e.g. :func:`robokin.robots.planar_3r`), for
            ``within_limits``; None: none.

    Returns:
        "elbow down" and "elbow up"; one solution ("elbow straight" / "elbow folded", ``singular``)
        when ``s2 = 0``. Within 1e-12 of that cosine the two elbows are returned once, unless their
        ``theta1`` still differ by more than 1e-5 (a folded elbow of near-equal links with the wrist
        point near the first joint): then both, ``singular`` set.
    """
    return _core.ik_planar_3r(target, a1, a2, a3, method, _limits(limits))


def anthropomorphic(target, a2: float, a3: float, d1: float = 0.0, limits=None) -> IKSolutions:
    """Anthropomorphic arm, standard DH ``(0, pi/2, d1)``, ``(a2, 0, 0)``, ``(a3, 0, 0)``.

    Args:
        target: Tip position (x, y, z).
        a2: Upper arm length.
        a3: Forearm length.
        d1: Shoulder height.
        limits: ``(lower, upper)`` or a Chain, for ``within_limits``; None: none.

    Returns:
        Up to 4 postures: shoulder right / left x elbow up / down.
    """
    return _core.ik_anthropomorphic(target, a2, a3, d1, _limits(limits))


def spherical_wrist_6r(target, a2: float, a3: float, d3: float, d4: float, d1: float = 0.0, d6: float = 0.0,
                       limits=None) -> IKSolutions:
    """6R arm with a spherical wrist in the PUMA layout (standard DH rows
    ``(0, pi/2, d1)``, ``(a2, 0, 0)``, ``(a3, -pi/2, d3)``, ``(0, pi/2, d4)``, ``(0, -pi/2, 0)``, ``(0, 0, d6)``).

    Args:
        target: Tool frame (4, 4).
        a2, a3, d3, d4, d1, d6: The DH lengths above.
        limits: ``(lower, upper)`` or a Chain, for ``within_limits``; None: none.

    Returns:
        Up to 8 solutions: shoulder right / left x elbow up / down x wrist no flip / flip. At the
        wrist singularity (``q5 = 0``) only ``q4 + q6`` is determined: ``q4 = 0`` (and ``pi``).
    """
    return _core.ik_spherical_wrist_6r(target, a2, a3, d3, d4, d1, d6, _limits(limits))


def puma560(target, limits="default") -> IKSolutions:
    """All (up to 8) solutions of :func:`robokin.robots.puma560` for the tool frame ``target``,
    each marked within the joint limits or not (``within_limits``): :func:`spherical_wrist_6r` with
    the PUMA's lengths.

    Args:
        target: Tool frame (4, 4).
        limits: ``"default"`` for the PUMA's joint limits, ``None`` for none, a pair or a Chain.
    """
    if isinstance(limits, str) and limits == "default":
        limits = _robots.PUMA560_LIMITS
    return _core.ik_spherical_wrist_6r(target, *_PUMA560_LENGTHS, _limits(limits))


def puma560_path(targets, q0, limits="default"):
    """Follows a path of tool frames with the closed form: at each frame, the solution within the
    limits nearest to the previous joints (``q0`` for the first), angles shifted by ``2 pi`` towards
    the previous ones within the limits. The posture never jumps to another branch unless the path
    forces it.

    Angles are shifted at most to ``|q| <= 2**20`` rad (about 167,000 turns), where a double still
    holds them to 1.2e-10 rad, so that the joints reach each frame within the verified tolerance;
    from a ``q0`` farther out the path starts as near it as that allows (at 1e9 rad a double keeps
    only 1e-7 rad, at 1e17 nothing of the angle), and a joint turning beyond it steps back by 2 pi.

    Args:
        targets: (K, 4, 4) tool frames.
        q0: (6,) joints before the first frame.
        limits: As :func:`puma560`.

    Returns:
        A :class:`ClosedPath`, which unpacks as ``(q, ok, reachable)``: (K, 6) joints and two (K,)
        boolean arrays. Where a frame has no solution within the limits, ``ok`` is False and the
        row repeats the previous joints; ``reachable`` is True where the frame has a solution,
        within the limits or not (so ``reachable & ~ok`` marks the frames the limits alone exclude).
    """
    if isinstance(limits, str) and limits == "default":
        limits = _robots.PUMA560_LIMITS
    return _core.ik_spherical_wrist_6r_path(targets, *_PUMA560_LENGTHS, q0, _limits(limits))


# The RPR study's arm's self-motion set (redundant: a fixed-shape table of the solutions along t1),
# one function under both names: robokin.robots' arm and the closed forms.
rpr_self_motion = _robots.rpr_self_motion


_UR_KEYS = ("d1", "a2", "a3", "d4", "d5", "d6")


def _ur_chain(robot) -> Chain:
    """``robot`` as a Chain: a Chain as it is, or the UR arm of a mapping ``d1, a2, a3, d4, d5, d6``."""
    if isinstance(robot, Chain):
        return robot
    expected = f"robot: expected a Chain or a dict with the keys {', '.join(_UR_KEYS)}, got {robot!r}"
    if not isinstance(robot, dict):
        raise TypeError(expected)
    if set(robot) != set(_UR_KEYS):
        raise ValueError(expected)
    key = tuple(finite_float(robot[k], f"robot[{k!r}]") for k in _UR_KEYS)
    return Chain.from_dh(ur_dh_rows(*key))


def ur(target, robot, limits="default") -> IKSolutions:
    """All (up to 8) solutions of a Universal Robots arm (UR3/5/10/16 and the e-series: three
    parallel axes 2, 3, 4) for the tool frame ``target``, in closed form.

    The arm is read from ``robot``'s geometry, its joint axes at q = 0 whatever describes them (the
    standard DH ``(0, pi/2, d1)``, ``(a2, 0, 0)``, ``(a3, 0, 0)``, ``(0, pi/2, d4)``, ``(0, -pi/2, d5)``,
    ``(0, 0, d6)`` with any theta offsets, base and tool; a UR URDF,
    ``Chain.from_urdf(path, "base", "tool0")``): axes 1 and 2 meeting at a right angle, 2, 3 and 4
    parallel, 4 and 5, 5 and 6 meeting at right angles. Another arm with three parallel axes 2, 3, 4
    (:func:`family`) is solved as :func:`solve` does, with the same labels; any other chain raises
    ``ValueError``. Each solution is checked by ``robot.fk``. A chain reads its layout at its
    first call and keeps it; a dict builds its chain at each call: a loop over many poses of a
    table holds a :class:`ClosedSolver` (``ClosedSolver(chain, limits).solve(T)``, the same
    answers).

    Args:
        target: Tool frame (4, 4).
        robot: A Chain such as :func:`robokin.robots.ur5`, or a dict ``{"d1", "a2", "a3", "d4",
            "d5", "d6"}`` (the UR table; no limits).
        limits: ``"default"`` for the chain's limits, ``None`` for none, or ``(lower, upper)``: for
            ``within_limits`` (every solution is returned).

    Returns:
        IKSolutions (every solution, ``within_limits`` marking those within the limits) labelled
        ``"shoulder left|right, elbow up|down, wrist no flip|flip"`` (the 8 of :data:`UR_POSTURES`):
        shoulder left puts the wrist centre (origin of frame 5) on the -x side of frame 1, elbow up
        the elbow above the line from the shoulder to the origin of frame 4, and wrist no flip the
        DH angle of joint 5 in ``[0, pi]``. ``singular`` is set, and postures that coincide are
        returned once, at the shoulder singularity (wrist centre ``|d4|`` from
        axis 1: "shoulder singular"), the elbow's (q3 = 0 or pi: "elbow straight" / "elbow
        folded") and the wrist's (joint 5 at 0 or pi: axes 2, 3, 4 and 6 parallel, a continuum of
        solutions of which one representative per shoulder and elbow is returned, "wrist
        singular", chosen with the elbow as near a right angle as the continuum allows). Within
        1e-3 of the wrist's singularity, where q2 + q3 + q4 is known only to ~1e-16 / |sin q5|, an
        elbow within that rounding of straight or folded is returned straight or folded.
    """
    chain = robot if isinstance(robot, Chain) else _ur_chain(robot)  # a Chain as it is, without a call
    try:
        return _core.ik_ur(target, chain, limits)
    except ValueError:
        if robot is not chain or family(chain).name != "three parallel axes 2, 3, 4":
            raise
    return ClosedSolver(chain, limits).solve(target)  # three parallel axes, other angles: the same labels


def ur_batch(targets, robot, limits="default"):
    """:func:`ur` for a batch of frames, on every core with the GIL released.

    Args:
        targets: (N, 4, 4) tool frames.
        robot, limits: As :func:`ur`.

    Returns:
        A :class:`ClosedBatch`, which unpacks as ``(q, singular, within_limits)``: ``q`` (N, 8, 6),
        solution ``k`` in row ``k`` of ``q[i]`` for posture ``UR_POSTURES[k]``; ``singular`` (N,)
        booleans; ``within_limits`` (N, 8) booleans, True where the slot holds a solution within
        the limits. A fixed-shape table:
        a slot without a solution is a NaN row (``within_limits`` False), by design: the pose is
        out of reach, or, at a singularity, its posture coincides with another (the one solution
        is kept in the first slot of the postures that coincide). No row is NaN for its limits.
    """
    chain = _ur_chain(robot)
    solver = ClosedSolver.find(chain, limits)
    if solver is None or solver.family != "three parallel axes 2, 3, 4":
        _core.ik_ur(np.eye(4), chain, limits)  # raises the UR table's ValueError, naming what differs
    return solver.solve_batch(targets)


def general_3r(target, chain: Chain, limits="default") -> IKSolutions:
    """Every position solution (at most 4) of a 3R arm of any geometry (any DH table, revolute
    joints), for the tool point at ``target`` (x, y, z).

    With ``V = Rz(q2) w(q3)`` the point seen from joint 2, the invariants of joint 1 (height along
    its axis, distance to its origin) are two linear equations in ``V``; with ``|V_xy|`` fixed they
    leave a trigonometric polynomial of degree 2 in ``q3`` (a quartic in ``exp(i q3)``, solved as
    the eigenvalues of its companion matrix), of degree 1 when the first two axes are parallel or
    intersect. Each root gives ``q2`` and ``q1`` in closed form, is polished by Newton's method on
    the forward model and kept only when ``chain.fk`` puts the tool within 1e-9 x the arm's size of
    ``target``.

    Args:
        target: Tool point (3,).
        chain: A 3-joint revolute chain (e.g. ``Chain.from_dh`` of three "R" rows).
        limits: ``"default"`` (the chain's), ``None`` or ``(lower, upper)``, for ``within_limits``.

    Returns:
        IKSolutions labelled by the sign of det J ("det J > 0", "det J < 0", "singular");
        ``singular`` is set when a solution is singular or a joint is free (one representative).
    """
    return _core.ik_general_3r(target, chain, limits)


@dataclass(frozen=True)
class Family:
    """The closed-form family of an arm's geometry (:func:`family`).

    Attributes:
        name: ``"spherical wrist, axes 2, 3 parallel"`` (axes 4, 5, 6 meet in a point: the PUMA,
            KUKA KR, ABB IRB, Fanuc and Staubli arms), ``"three parallel axes 2, 3, 4"`` (axes 5
            and 6 meeting: the UR family), ``"spherical wrist, axes 1, 2 meet"`` (the iiwa with
            ``q[2]`` held), ``"spherical wrist, axes 2, 3 meet after axis 1"`` (the Gen3 with
            ``q[1]`` held: ``"axes 3, 4 meet after axis 1"``), ``"three parallel axes 1, 2, 3
            first, axes 5, 6 meet"`` (the Unitree Z1 with ``q[0]`` held: ``"three parallel axes 2,
            3, 4 first, axes 6, 7 meet"``), the same read from the tool
            (``"spherical shoulder, axes 5, 6 meet"``: the Panda with ``q[6]`` held; ``"spherical
            shoulder, axes 5, 6 meet before axis 7"``: the Panda with ``q[3]`` held; ``"spherical
            shoulder, axes 4, 5 parallel"``, ``"three parallel axes 3, 4, 5"``, ``"three parallel
            axes 4, 5, 6 last, axes 1, 2 meet"``), or ``"none"``. Axes are named by their joint
            numbers; where two axes meet beside the wrist (or the shoulder), the lone axis beyond
            them is named too, and three parallel axes at an end of the arm are the first (last).
        solvable: :func:`solve` has a closed form for it.
        reason: Why there is none (``"axes 4, 5, 6 do not meet: 3.2 mm apart; ..."``), else ``""``.
        meet: Consecutive axes (1-based pairs) whose lines meet.
        parallel: Consecutive axes that are parallel.
        tol_distance: The distance (m) within which two lines were taken to meet: ``tol`` times
            the arm's size (the sum of the chain's fixed translations at the zero configuration).
    """

    name: str
    solvable: bool
    reason: str
    meet: tuple
    parallel: tuple
    tol_distance: float


@with_options(ClosedFamilyOptions)
def family(chain: Chain, locked=None, **options) -> Family:
    """The decomposition of ``chain``'s geometry, read from its joint axes at the zero configuration
    (whatever the chain was built from: DH, modified DH, URDF, joints and frames): which
    consecutive axes meet or are parallel, within a tolerance relative to the arm's size, and
    which closed form :func:`solve` applies, or why none does.

    A 7-joint chain has none by itself (a continuum of solutions); with one joint held,
    ``locked={index: value}``, the family is that of the 6 others, whose axes the held joint
    moves (so the value may matter: the iiwa with ``q[2] = 0`` has its axes 2 and 4 parallel).
    Axes are named by their joint numbers in the chain (1-based; the held one skipped); a family
    found from the tool to the base is a ``"spherical shoulder"``. See :func:`solve` for the
    catalogue's 7-joint arms.

    Args:
        chain: A Chain.
        locked: None, or ``{index: value}``: joint ``index`` (0-based, as in ``q``) of a 7-joint
            chain held at ``value``.

    Returns:
        A :class:`Family`.
    """
    check_chain(chain)
    name, solvable, reason, meet, parallel, tol_distance = _core.closed_family(chain, locked, **options)
    return Family(name, solvable, reason, tuple(map(tuple, meet)), tuple(map(tuple, parallel)), tol_distance)


_core_find = ClosedSolver.find


@with_options(ClosedFamilyOptions)
def _find(chain: Chain, limits="default", locked=None, **options) -> Optional[ClosedSolver]:
    """The chain's :class:`ClosedSolver`, or None when the arm has no closed form (:func:`family`
    says why): the arm read once, where ``family(chain).solvable`` and then ``ClosedSolver(chain)``
    read it twice.

    Args:
        chain: The arm.
        limits: As :class:`ClosedSolver`'s (``"default"``, None or ``(lower, upper)``).
        locked: As :class:`ClosedSolver`'s: None, or ``{index: value}`` for a 7-joint chain. A bad
            ``limits`` or ``locked`` raises as :class:`ClosedSolver` does.
    """
    return _core_find(chain, limits, locked, **options)


_find.__name__, _find.__qualname__ = "find", "ClosedSolver.find"
ClosedSolver.find = staticmethod(_find)


@with_options(ClosedFamilyOptions)
def solve(target, chain: Chain, limits="default", locked=None, **options) -> IKSolutions:
    """Every solution (up to 8) of a 6R arm whose geometry has a closed form (:func:`family`), for
    the tool frame ``target``: from the Paden-Kahan subproblems on the chain's joint axes, or, for
    the UR layout and a spherical wrist in the ortho-parallel layout (PUMA, KUKA KR, ABB IRB), read
    from the same axes, those layouts' own closed forms (:func:`ur`, :func:`puma560`), which give the
    same solutions and labels faster. URDF chains are read as they are.

    Each solution is checked by ``chain.fk`` (tool within 1e-9 x the arm's size, rotation entries
    within 1e-8). Labels as :func:`puma560` and :func:`ur`: ``"shoulder left|right"`` (the wrist
    point on the -/+ side of x1 = axis 1 x axis 2 from axis 1; the wrist point is where the
    wrist's axes meet), ``"elbow up|down"`` (the elbow, axis 3, on axis 1's side of the line from
    the shoulder, axis 2, to the wrist: the wrist centre, or axis 4 for the three parallel axes,
    in the plane normal to axis 2), ``"wrist no flip|flip"`` (the axes a4, a5, a6 at the solution
    with (a4 x a6) . a5 >= 0, or < 0); ``"shoulder singular"``, ``"elbow straight|folded"`` and
    ``"wrist singular"`` (a continuum, one representative) at singularities, ``singular`` set.
    For a spherical wrist with axes 1, 2 meeting at s, ``"elbow up"`` means that the arm turns
    positively about axis 3 (a3, at the solution) from the shoulder to the wrist centre c:
    a3 . ((s - e) x (c - e)) > 0, e the point of axis 3 nearest s. For a spherical wrist with
    axes 2, 3 meeting at s after axis 1, ``"shoulder left"`` means that the wrist centre c turns
    positively about axis 1 (a1) from s (at the solution): a1 . ((s - o) x (c - o)) > 0, o on
    axis 1; ``"elbow up"`` that it turns positively about axis 3 from axis 2: a3 . (a2 x (c - s))
    > 0 (where the two elbows coincide, ``"elbow straight"`` when a3 lies between a2 and c - s).
    For three parallel axes 1, 2, 3 (direction a1) first, axes 5, 6 meeting at c: ``"shoulder
    left"`` when c turns positively about axis 4 (a4 through o4, at the solution) from a1:
    a4 . (a1 x (c - o4)) > 0; ``"elbow up"`` when the planar arm of joints 1 to 3 turns positively
    at axis 2: a1 . ((o2 - o1) x (w - o2)) > 0, o1, o2, w on axes 1, 2, 3; ``"wrist no flip"`` when
    (a5 x a6) . a1 >= 0. A family read from the tool (a
    ``"spherical shoulder"``) is solved for the inverse pose, and its labels are those of the arm
    read from the tool: its "shoulder" is at the chain's tool end.
    A loop over many poses holds a :class:`ClosedSolver` (the arm read once).

    **A 7-joint arm with one joint held**, ``locked={index: value}``: the 6 other joints are
    solved, with the held joint's motion folded into the axes after it; every solution is a
    7-vector with ``value`` at ``index``, checked by the 7-joint chain's own ``fk``. Which joint
    (0-based) leaves a closed form, for the catalogue's arms:

    - :func:`robokin.robots.iiwa14` (spherical shoulder and wrist): ``q[0]``, ``q[2]``, ``q[4]``,
      ``q[6]`` at any value; ``q[1]`` and ``q[5]`` away from 0 and pi (there axes 1 and 3, or 5
      and 7, line up); never ``q[3]``, the elbow: the shoulder's and the wrist's points are
      then a fixed distance apart, a continuum of solutions or none.
    - :func:`robokin.robots.panda`: ``q[6]`` (the flange joint: a spherical shoulder, axes 5, 6
      meeting) at any value, ``q[3]`` (the elbow: a spherical shoulder, axes 5, 6 meeting before
      axis 7) at any value within its limits (at 0 axis 5 passes through the shoulder's point),
      ``q[5]`` away from 0 and pi; no other (the 88 mm and 82.5 mm offsets).
    - :func:`robokin.robots.gen3`: ``q[0]``, ``q[2]``, ``q[3]`` (the elbow: only the 11.8 mm
      shoulder offset sets the wrist's distance, so this one is ill-conditioned) and ``q[1]``
      (axes 3, 4 then meet 11.8 mm off axis 1: only that offset lets joint 1 move their point,
      ill-conditioned too); no other.

    A sweep over the held value traces the arm's self-motion through one pose (as
    :func:`rpr_self_motion` does for the RPR arm)::

        iiwa = robokin.robots.iiwa14()
        T = iiwa.fk([0.4, 0.7, -0.2, -1.1, 0.5, 0.9, -0.3])
        for v in np.linspace(-0.8, 0.4, 61):
            s = robokin.closed.solve(T, iiwa, locked={2: v})  # every row reaches T, s.q[:, 2] == v

    Args:
        target: Tool frame (4, 4).
        chain: A 6R Chain with a decomposition; ValueError naming the reason otherwise.
        limits: ``"default"`` (the chain's), ``None`` or ``(lower, upper)``, for ``within_limits``.
        locked: None, or ``{index: value}`` for a 7-joint chain: joint ``index`` (0-based, as in
            ``q``) held at ``value`` (within ``limits`` when there are limits). ValueError for an
            index out of range, a value outside the limits, a chain without 7 joints, or a hold
            that leaves no closed form (the message says why).

    Returns:
        IKSolutions (every solution, ``within_limits`` marking those within the limits).
    """
    check_chain(chain)
    return ClosedSolver(chain, limits, locked, **options).solve(target)
