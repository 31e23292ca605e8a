"""The simulator's view of ``robokin.RRR3``: the few calls the 3-RRR scene makes, in one file.

No kinematics are computed here; each function calls the core and turns its answer into what the
scene needs (plain floats, a state name, None instead of an exception).
"""

from __future__ import annotations

import math
from typing import NamedTuple, Optional, Tuple

import numpy as np
import robokin as rk

#: The seed's tolerance, on the core's normalised determinants (det A / R_e, det B / l1^3).
SINGULAR_TOL = 1e-3
#: Distance to a parallel singularity (the core's inverse condition number of A, in [0, 1])
#: below which a pose is "near" (orange): the margin the core's avoidance planner keeps, and the
#: clearance of every approach (``RRR3.connect``).
NEAR_DISTANCE = 0.05
#: Grid step of the approach search (m; 0.1 rad in phi): coarse enough that a search that finds
#: nothing gives up in a tenth of a second, and the shortcuts straighten what it finds.
ROUTE_RESOLUTION = 0.01
#: Nominal orientations tried for a path whose orientation-0 plan is in another singularity-free
#: region than the robot: 0, then +-0.05, +-0.1, ... +-1.5 rad (nearest to 0 first).
NOMINALS = tuple(round(s * k * 0.05, 10) for k in range(31) for s in ((1,) if k == 0 else (1, -1)))


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
        sing = robot.singularity(pose, mode, tol=SINGULAR_TOL)
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


def avoidance_plan(robot, path: np.ndarray, mode, phi: float = 0.0) -> np.ndarray:
    """Orientation (K,) for each point of the closed ``path`` (K, 2) from the core's avoidance
    planner (``RRR3.plan``): ``phi`` except where the path comes near a parallel singularity.

    The simulator loops over the path, so the plan must join up with itself: the core plans an
    open path, so the loop is cut where it is clearest of parallel singularities (there the
    planned orientation is back at ``phi`` at both ends) and the plan is rolled back.
    """
    path = np.asarray(path, dtype=float)
    direct = robot.plan(path, phi=phi, mode=mode, avoid=True)
    best = np.asarray(direct.poses, dtype=float)[:, 2]
    nominal = robot.plan(path, phi=phi, mode=mode, avoid=False)
    det, distance = np.asarray(nominal.det_a_norm), np.asarray(nominal.distance)
    same_side = np.isfinite(distance) & (np.sign(det) == np.sign(det[0]))
    if np.any(same_side):
        cut = int(np.argmax(np.where(same_side, distance, -1.0)))
        rolled = robot.plan(np.roll(path, -cut, axis=0), phi=phi, mode=mode, avoid=True)
        orientation = np.roll(np.asarray(rolled.poses, dtype=float)[:, 2], cut)
        closed = np.append(orientation, orientation[0])
        if rolled.feasible and np.all(np.isfinite(orientation)) and np.abs(np.diff(closed)).max() <= 0.01 + 1e-9:
            best = orientation
    return np.where(np.isfinite(best), best, phi)


class Workspace(NamedTuple):
    """The core's constant-orientation map: ``cells`` (n, n) codes 0 unreachable, 1 regular,
    2 parallel singular, 3 serial; row j at y[j], column i at x[i]; ``extent`` (x0, x1, y0, y1)."""

    cells: np.ndarray
    extent: Tuple[float, float, float, float]


def workspace(robot, phi: float, mode, n: int = 200) -> Optional[Workspace]:
    """The workspace at orientation ``phi`` (``RRR3.workspace``), or None if the core declines."""
    try:
        ws = robot.workspace(phi, mode=mode, n=n, tol=SINGULAR_TOL)
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


def path_determinants(robot, poses, mode) -> Tuple[np.ndarray, np.ndarray]:
    """det A / R_e and the distance to parallel singularities at each pose (K, 3); NaN where a
    leg cannot reach."""
    poses = np.asarray(poses, dtype=float)
    det = np.full(len(poses), np.nan)
    distance = np.full(len(poses), np.nan)
    for k, pose in enumerate(poses):
        try:
            sing = robot.singularity(pose, mode)
        except ValueError:
            continue
        det[k], distance[k] = sing.det_a_norm, sing.distance
    return det, distance


def path_orientations(robot, path: np.ndarray, mode, sign: int, avoid: bool):
    """Orientations (K,) for the closed ``path`` that keep det A of ``sign`` all along, and the
    nominal orientation they were planned about; None when no nominal orientation of
    :data:`NOMINALS` gives one.

    With ``avoid``: the avoidance plan about the first nominal orientation (nearest to 0) whose
    plan is clear of parallel singularities with det A of ``sign`` everywhere. Without: the
    constant orientation 0 when the path's start is of ``sign`` there (the path may then cross
    singularities, which is what turning avoidance off shows), else the nearest nominal
    orientation whose whole path keeps ``sign``, else the nearest whose start does.
    """
    path = np.asarray(path, dtype=float)
    fallback = None
    for phi0 in NOMINALS:
        nominal = robot.plan(path, phi=phi0, mode=mode, avoid=False)
        det = np.asarray(nominal.det_a_norm)
        if not np.isfinite(det[0]) or np.sign(det[0]) != sign:
            continue
        if not avoid:
            constant = np.full(len(path), phi0)
            if phi0 == 0.0 or np.all(np.sign(det) == sign):
                return constant, phi0
            fallback = fallback if fallback is not None else (constant, phi0)
            continue
        orientation = avoidance_plan(robot, path, mode, phi=phi0)
        poses = np.column_stack((path, orientation))
        det, distance = path_determinants(robot, poses, mode)
        closed = np.append(orientation, orientation[0])
        if (np.all(np.sign(det) == sign) and np.all(distance >= NEAR_DISTANCE)
                and np.abs(np.diff(closed)).max() <= 0.01 + 1e-9):
            return orientation, phi0
    return fallback
