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
#: below which a pose is "near" (orange): the margin the core's avoidance planner keeps.
NEAR_DISTANCE = 0.05


class Evaluation(NamedTuple):
    """The model at one pose."""

    alpha: np.ndarray
    det_a: float
    det_b: float
    distance: float
    state: str


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
    if not (np.all(np.isfinite(alpha)) and math.isfinite(det_a) and math.isfinite(det_b) and math.isfinite(distance)):
        return None
    state = str(sing.kind)
    if state == "none" and distance < NEAR_DISTANCE:
        state = "near"
    return Evaluation(alpha, det_a, det_b, distance, state)


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


def approach(robot, start, goal, mode, move_step: float, turn_step: float) -> np.ndarray:
    """Poses (K, 3) from ``start`` (excluded) to ``goal`` (included), at most ``move_step`` metres
    and ``turn_step`` radians apart, all reachable; empty when already there.

    Goes straight when every pose on the way is reachable (checked with the core's batch inverse
    model), else through the home pose (0, 0, 0).
    """
    start, goal = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)

    def straight(a, b):
        n = int(max(math.ceil(np.linalg.norm(b[:2] - a[:2]) / move_step), math.ceil(abs(b[2] - a[2]) / turn_step)))
        if n == 0:
            return np.empty((0, 3))
        return a + np.linspace(0.0, 1.0, n + 1)[1:, None] * (b - a)

    def reachable(poses):
        return len(poses) == 0 or bool(np.all(np.isfinite(robot.ik_batch(poses, mode))))

    direct = straight(start, goal)
    if reachable(direct):
        return direct
    home = np.zeros(3)
    via = np.concatenate((straight(start, home), straight(home, goal)))
    return via if reachable(via) else direct
