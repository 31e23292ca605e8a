"""The serial scene's view of a chain: its start posture, its task, its closed form, its size.

Nothing numerical is computed here beyond choosing: each function asks the core (frames,
Jacobians, manipulability, closed forms) and turns the answer into what the scene needs.
"""

from __future__ import annotations

import math
from typing import Callable, Optional

import numpy as np
import robokin as rk

#: Start postures of the catalogue's arms (degrees for revolute joints, metres for prismatic
#: ones): away from singularities, with every closed-form posture within the limits where the arm
#: has a closed form (all 8 for the PUMA 560 and the UR arms).
START = {
    "puma560": (0, 50, -150, -20, 60, 0),
    "panda": (0, -45, 0, -135, 0, 90, 45),
    "iiwa14": (0, 35, 0, -80, 0, 55, 0),
    "gen3": (0, 15, 180, -130, 0, -35, 90),
    "irb120": (0, 10, 10, 0, 40, 0),
    "planar_3r": (20, 100, 40),
    "prr": (0.5, 30, 60),
    "rp": (45, 0.6),
}
UR_START = (0, -110, 100, -80, -90, 0)

#: Manipulability (Yoshikawa, pose rows) relative to the best of a sample of postures, below which
#: a posture is "near" a singularity (orange) and "singular" (red).
NEAR_RATIO, SINGULAR_RATIO = 0.1, 0.01
#: Postures sampled (within the limits, seeded) for that reference.
REFERENCE_SAMPLES = 512


def start_posture(name: str, chain: rk.Chain) -> np.ndarray:
    """The posture a scene starts in: the table above for the catalogue's arms; for others (URDF)
    0.3 rad on every revolute joint, alternating in sign, 0 on prismatic ones, clamped into the
    limits."""
    values = START.get(name) or (UR_START if name.startswith("ur") else None)
    lower, upper = (np.asarray(v, dtype=float) for v in chain.limits)
    types = chain.joint_types
    if values is not None and len(values) == chain.dof:
        q = np.array([math.radians(v) if t == "R" else float(v) for v, t in zip(values, types)])
    else:
        q = np.array([(0.3 if i % 2 == 0 else -0.3) if t == "R" else 0.0 for i, t in enumerate(types)])
    return np.clip(q, lower, upper)


def is_planar(chain: rk.Chain, seed: int = 0) -> bool:
    """Whether the tool moves in the base xy plane only (rows v_z, w_x, w_y of the Jacobian zero
    at a few random postures) with the base at z = 0 (a planar arm, drawn from above)."""
    q = sample(chain, 4, seed)
    jac = chain.jacobian(q)
    origins = chain.frames(q[0])[:, 2, 3]
    return bool(np.max(np.abs(jac[:, 2:5, :])) < 1e-12 and np.max(np.abs(origins)) < 1e-12)


def task_of(chain: rk.Chain, planar: bool) -> str:
    """The rows the jog and the paths control: the whole pose for 6 joints or more; x, y (and phi
    with 3 joints) for planar arms; the position otherwise."""
    if chain.dof >= 6:
        return "pose"
    if planar:
        return "xyphi" if chain.dof >= 3 else "xy"
    return "position"


def sample(chain: rk.Chain, n: int, seed: int = 0) -> np.ndarray:
    """(n, dof) postures drawn uniformly within the limits (unlimited: [-pi, pi] or [-1, 1] m)."""
    lower, upper = (np.asarray(v, dtype=float) for v in chain.limits)
    span = np.array([math.pi if t == "R" else 1.0 for t in chain.joint_types])
    lo = np.where(np.isfinite(lower), lower, -span)
    hi = np.where(np.isfinite(upper), upper, span)
    return np.random.default_rng(seed).uniform(lo, hi, (n, chain.dof))


def reference_manipulability(chain: rk.Chain) -> float:
    """The best Yoshikawa manipulability (pose rows) of a seeded sample of postures: the
    reference of the scene's near / singular colours."""
    w = chain.manipulability(sample(chain, REFERENCE_SAMPLES, seed=1))
    best = float(np.max(w)) if np.all(np.isfinite(w)) else 0.0
    return best if best > 0 else 1.0


def size_of(chain: rk.Chain, q) -> float:
    """The arm's size (m): the summed lengths between its frames' origins at q, the prismatic
    strokes' finite upper limits added (at least 0.1 m)."""
    origins = chain.frames(q)[:, :3, 3]
    length = float(np.sum(np.linalg.norm(np.diff(origins, axis=0), axis=1)))
    _, upper = chain.limits
    stroke = sum(float(u) for u, t in zip(upper, chain.joint_types) if t == "P" and math.isfinite(u))
    return max(length + stroke, 0.1)


def posture_solver(name: str, chain: rk.Chain, q) -> Optional[Callable]:
    """``solve(T) -> IKSolutions``: every closed-form posture of the tool frame T within the
    limits (robokin.closed), or None when the arm has no closed form."""
    solve = _closed_form(name, chain, q)
    return None if solve is None else (lambda T: solve(T).only_within_limits())


def _closed_form(name: str, chain: rk.Chain, q) -> Optional[Callable]:
    """``solve(T) -> IKSolutions``: every closed-form posture of T (robokin.closed, each marked
    within the limits or not), or None when the arm has no closed form."""
    if name == "puma560":
        return rk.closed.puma560
    if name == "planar_3r":
        def planar(T):
            return rk.closed.planar_3r((T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])), limits=chain)

        return planar
    if name == "rp":
        return lambda T: rk.closed.planar_rp(T[:2, 3], limits=chain)
    if chain.dof == 6:
        try:
            rk.closed.ur(chain.fk(q), chain)
        except ValueError:
            pass
        else:
            return lambda T: rk.closed.ur(T, chain)
    if chain.dof == 3 and chain.joint_types == "RRR":
        return lambda T: rk.closed.general_3r(T[:3, 3], chain)
    return None
