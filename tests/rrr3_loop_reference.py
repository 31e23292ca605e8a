"""The simulator's loop planning as it was written in Python (sim/robokin_sim/rrr3_model.py before
it moved to the core as ``RRR3.plan(closed=True)`` and ``RRR3.plan_loop``), kept verbatim as the
reference the core's results are compared with. It calls only the core's open plan and
``RRR3.singularity``."""

import numpy as np

#: 0, then +-0.05, +-0.1, ... +-1.5 rad (nearest to 0 first).
NOMINALS = tuple(round(s * k * 0.05, 10) for k in range(31) for s in ((1,) if k == 0 else (1, -1)))
NEAR_DISTANCE = 0.05


def avoidance_plan(robot, path, mode, phi=0.0):
    """Orientation (K,) for each point of the closed ``path``: the loop cut where it is clearest of
    parallel singularities, planned open from there and rolled back."""
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


def path_determinants(robot, poses, mode):
    """det A / R_e and the distance to parallel singularities at each pose; NaN where unreachable."""
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


def path_orientations(robot, path, mode, sign, avoid):
    """(orientations (K,), nominal) for the closed ``path`` keeping det A of ``sign``, or None."""
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
