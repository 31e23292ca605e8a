"""The simulator's view of ``robokin.RRR3``: the few calls the 3-RRR scene makes, in one file.

No kinematics are computed here; each function calls the core and turns its answer into what the
scene needs (plain floats, a state name, None instead of an exception).
"""

from __future__ import annotations

import math
from typing import NamedTuple, Optional, Tuple

import numpy as np
import robokin as rk

#: Distance to a parallel singularity (the core's inverse condition number of A, in [0, 1])
#: below which a pose is "near" (orange): the margin the core's avoidance planner keeps, and the
#: clearance of every approach (``RRR3.connect``).
NEAR_DISTANCE = rk.RRR3_DEFAULTS["near_distance"]
#: Grid step of the approach search (m; 0.1 rad in phi): coarse enough that a search that finds
#: nothing gives up in a tenth of a second, and the shortcuts straighten what it finds.
ROUTE_RESOLUTION = 0.01


class Evaluation(NamedTuple):
    """The model at one pose."""

    alpha: np.ndarray
    det_a: float
    det_b: float
    distance: float
    state: str
    det_a_norm: float
    det_b_norm: float


def evaluate(robot, pose, mode) -> Optional[Evaluation]:
    """Inverse model and singularity state at ``pose``.

    Returns:
        The :class:`Evaluation`, state ``none``, ``near``, ``parallel`` or ``serial``; None when a
        leg cannot reach the pose (or the pose is not finite).
    """
    pose = np.asarray(pose, dtype=float)
    if not np.all(np.isfinite(pose)):
        return None
    try:
        alpha = np.asarray(robot.ik(pose, mode=mode), dtype=float)
        sing = robot.singularity(pose, mode)
    except ValueError:  # rk.UnreachableError is a ValueError
        return None
    det_a, det_b, distance = float(sing.det_a), float(sing.det_b), float(sing.distance)
    det_a_norm, det_b_norm = float(sing.det_a_norm), float(sing.det_b_norm)
    if not (np.all(np.isfinite(alpha)) and all(map(math.isfinite, (det_a, det_b, distance, det_a_norm, det_b_norm)))):
        return None
    state = str(sing.kind)
    if state == "none" and distance < NEAR_DISTANCE:
        state = "near"
    return Evaluation(alpha, det_a, det_b, distance, state, det_a_norm, det_b_norm)


def points(robot, pose, mode) -> dict:
    """Joint positions ``{"O", "A", "B"}`` (3, 2) each, for drawing."""
    return {k: np.asarray(v, dtype=float) for k, v in robot.points(np.asarray(pose, dtype=float), mode).items()}


class Workspace(NamedTuple):
    """The core's constant-orientation map: ``cells`` (n, n) codes 0 unreachable, 1 regular,
    2 parallel singular, 3 serial; row j at y[j], column i at x[i]; ``extent`` (x0, x1, y0, y1)."""

    cells: np.ndarray
    extent: Tuple[float, float, float, float]


def workspace(robot, phi: float, mode) -> Optional[Workspace]:
    """The workspace at orientation ``phi`` (``RRR3.workspace``, its default grid and tolerance), or
    None if the core declines."""
    try:
        ws = robot.workspace(phi=phi, mode=mode)
    except ValueError:
        return None
    return Workspace(np.asarray(ws.cells), tuple(float(v) for v in ws.extent))


def route(robot, start, goal, mode, move_step: float, turn_step: float) -> np.ndarray:
    """Poses (K, 3) from ``start`` (excluded) to ``goal`` (included), at most ``move_step`` metres
    and ``turn_step`` radians apart, along which det A keeps its sign and the distance to parallel
    singularities stays at least :data:`NEAR_DISTANCE` (the core's ``RRR3.connect``); empty when
    already there.

    Raises:
        rk.NoRouteError: No such motion (``reason`` says why: the goal is in another
            singularity-free region, or an end is unusable).
    """
    start, goal = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)
    if np.array_equal(start, goal):
        return np.empty((0, 3))
    plan = robot.connect(start, goal, mode=mode, clearance=NEAR_DISTANCE, max_step=move_step, max_turn=turn_step,
                         resolution=ROUTE_RESOLUTION)
    return np.asarray(plan.poses, dtype=float)[1:]


def path_orientations(robot, path: np.ndarray, mode, sign: int, avoid: bool):
    """Orientations (K,) for the closed ``path`` that keep det A of ``sign`` all along, and the
    nominal orientation they were planned about (the core's ``RRR3.plan_loop`` over its default
    nominal orientations, 0 first); None when none gives one.

    With ``avoid``: the closed avoidance plan about the first nominal orientation whose plan is
    clear of parallel singularities with det A of ``sign`` everywhere. Without: a constant
    orientation, 0 when the path's start is of ``sign`` there (the path may then cross
    singularities, which is what turning avoidance off shows).
    """
    loop = robot.plan_loop(np.asarray(path, dtype=float), sign=sign, mode=mode, avoid=avoid)
    if not loop.found:
        return None
    return np.asarray(loop.plan.poses, dtype=float)[:, 2].copy(), float(loop.nominal)
