"""The serial scene's view of a chain: its start posture, its task, its closed form, its size, the
floor it stands on.

Nothing numerical is computed here beyond choosing: each function asks the core (frames,
Jacobians, manipulability, closed forms) and turns the answer into what the scene needs.
"""

from __future__ import annotations

import math
from typing import Callable, Optional

import numpy as np
import robokin as rk

#: Manipulability (Yoshikawa, pose rows) relative to the best of a sample of postures, below which
#: a posture is "near" a singularity (orange) and "singular" (red).
NEAR_RATIO, SINGULAR_RATIO = 0.1, 0.01
#: Postures sampled (within the limits, seeded) for that reference.
REFERENCE_SAMPLES = 512


#: Share of each limited joint's range kept clear of either limit by the start posture.
START_MARGIN = 0.1
#: Offsets (rad) from mid-range tried for the start posture's revolute joints; a prismatic joint
#: moves the same share of its free half-range (offset / (pi / 2)).
START_OFFSETS = (math.pi / 6, math.pi / 3)
#: Manipulability share of the best candidate within which the candidate nearest mid-range wins.
START_TIE = 0.99


def _mid_range(chain: rk.Chain):
    """(centre, room) per joint: the middle of its limits and how far the start posture may move
    from it with :data:`START_MARGIN` kept to each limit. An unlimited revolute joint is centred on
    0 with half a turn of room; one limited on one side only starts a quarter turn (or 0.5 m)
    inside its limit; an unlimited prismatic joint is centred on 0 with 0.5 m of room."""
    lower, upper = (np.asarray(v, dtype=float) for v in chain.limits)
    centre, room = np.zeros(chain.dof), np.zeros(chain.dof)
    for i, kind in enumerate(chain.joint_types):
        unit = math.pi if kind == "R" else 1.0
        lo, hi = lower[i], upper[i]
        if math.isfinite(lo) and math.isfinite(hi):
            centre[i], room[i] = 0.5 * (lo + hi), (0.5 - START_MARGIN) * (hi - lo)
        elif math.isfinite(lo) or math.isfinite(hi):
            inward = 1.0 if math.isfinite(lo) else -1.0
            centre[i], room[i] = (lo if math.isfinite(lo) else hi) + inward * unit / 2, unit / 4
        else:
            centre[i], room[i] = 0.0, unit / 2
    return centre, room


def start_candidates(chain: rk.Chain) -> np.ndarray:
    """(K, dof) postures the start posture is chosen from: mid-range, and mid-range moved by each
    offset of :data:`START_OFFSETS` in a few sign patterns (every joint one way, every joint the
    other, alternating both ways, every second joint bent either way: the elbows); nearest
    mid-range first (distance in shares of each joint's room), mid-range itself first."""
    centre, room = _mid_range(chain)
    n = chain.dof
    alternate = np.array([1.0 if i % 2 == 0 else -1.0 for i in range(n)])
    elbows = np.array([0.0 if i % 2 == 0 else 1.0 for i in range(n)])
    patterns = [elbows, -elbows, alternate, -alternate, np.ones(n), -np.ones(n)]
    radians = np.array([kind == "R" for kind in chain.joint_types])
    rows = [centre]
    for offset in START_OFFSETS:
        step = np.where(radians, np.minimum(offset, room), room * offset / (math.pi / 2))
        rows += [centre + s * step for s in patterns]
    rows = np.array(rows)
    spread = np.linalg.norm((rows - centre) / np.where(room > 0, room, 1.0), axis=1)
    return rows[np.argsort(spread, kind="stable")]


def start_posture(chain: rk.Chain) -> np.ndarray:
    """The posture a scene starts in, read off the arm alone: of :func:`start_candidates` (all
    within the limits, :data:`START_MARGIN` of each range away from them), the one of the best
    manipulability, where candidates within :data:`START_TIE` of the best count as equal and the
    one nearest mid-range wins; then each joint whose move back to mid-range keeps the
    manipulability within :data:`START_TIE` of the best goes back (the base's turn and the tool's
    roll, which do not change it, stay mid-range)."""
    q = start_candidates(chain)
    w = np.asarray(chain.manipulability(q), dtype=float)
    w = np.where(np.isfinite(w), w, 0.0)
    good = START_TIE * np.max(w)
    best = q[int(np.flatnonzero(w >= good)[0])].copy()
    centre = q[0]  # the first candidate: mid-range
    for i in range(chain.dof):
        trial = best.copy()
        trial[i] = centre[i]
        if float(chain.manipulability(trial)) >= good:
            best = trial
    return best


def is_planar(chain: rk.Chain, seed: int = 0) -> bool:
    """Whether the tool moves in the base xy plane only (rows v_z, w_x, w_y of the Jacobian zero
    at a few random postures) with the base at z = 0 (a planar arm, drawn from above)."""
    q = sample(chain, 4, seed)
    jac = chain.jacobian(q)
    origins = chain.frames(q[0])[:, 2, 3]
    return bool(np.max(np.abs(jac[:, 2:5, :])) < 1e-12 and np.max(np.abs(origins)) < 1e-12)


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


#: Postures sampled (within the limits, seeded) for the lowest point the arm reaches.
FLOOR_SAMPLES = 2048
#: Clearance (relative to the arm's size) between the lowest point sampled and the floor: as long
#: as the joint axes drawn about a joint (render_serial.AXIS).
FLOOR_CLEARANCE = 0.08


def floor_height(chain: rk.Chain, q_start, size: float) -> float:
    """The height (base z, m) of the floor the arm stands on: the base's own height when no frame
    origin of the arm goes below it, else below the lowest origin of a seeded sample of postures
    (and of ``q_start``) by :data:`FLOOR_CLEARANCE` of ``size``: the arm then stands on a pedestal.
    A prismatic joint without limits stays at its start value in the sample (its travel has no
    lowest point); the scene lowers the floor further if the arm ever goes below it."""
    q_start = np.asarray(q_start, dtype=float)
    q = sample(chain, FLOOR_SAMPLES, seed=2)
    lower, upper = chain.limits
    free = np.array([t == "P" for t in chain.joint_types]) & ~(np.isfinite(lower) & np.isfinite(upper))
    q[:, free] = q_start[free]
    base = float(chain.frames(q_start)[0, 2, 3])
    lowest = min(float(np.min(chain.frames(row)[:, 2, 3])) for row in np.vstack([q_start, q]))
    if lowest >= base - 1e-9 * max(size, 1.0):
        return base
    return lowest - FLOOR_CLEARANCE * size


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
    if name == "planar_3r":
        def planar(T):
            return rk.closed.planar_3r((T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])), limits=chain)

        return planar
    if name == "rp":
        return lambda T: rk.closed.planar_rp(T[:2, 3], limits=chain)
    solver = rk.closed.ClosedSolver.find(chain) if chain.dof == 6 else None
    if solver is not None:
        return solver.solve  # a UR table, a UR URDF, a spherical wrist
    if chain.dof == 3 and chain.joint_types == "RRR":
        return lambda T: rk.closed.general_3r(T[:3, 3], chain)
    return None
