"""Path tracking with the fewest reconfigurations (IKLink's objective: Y. Wang,
C. Sifferman, M. Gleicher, "IKLink: End-Effector Trajectory Tracking with Minimal
Reconfigurations", ICRA 2024).

At every waypoint, the set of inverse solutions (the closed forms of :mod:`robokin.closed` when the
arm has one, otherwise numerical IK from many starts with duplicates merged); between consecutive
waypoints, a step is *continuous* when no joint moves more than ``qdot_max * dt`` and a
*reconfiguration* otherwise (the arm must leave the path to change posture). A dynamic programme
over the layered graph of solutions (in the core, ``_core.track_postures``, which also writes the
joint path) picks one solution per waypoint minimising first the number of reconfigurations, then
the joint motion (the sum over steps of the Euclidean norm of the joint change); among equal plans,
the lowest-numbered solutions. Greedy tracking (the solution nearest the previous one,
:func:`robokin.closed.puma560_path`) is one path of that graph: the plan never has more
reconfigurations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import List, Optional

import numpy as np

from . import _core, closed
from ._checks import chain as check_chain
from ._checks import joints, number, per_joint, positive, rows, vector, whole
from ._checks import seed as check_seed
from ._core import Chain
from ._options import with_options
from ._printing import summary

__all__ = ["TrackPosturesResult", "track_postures", "count_reconfigurations"]


@dataclass
class TrackPosturesResult:
    """Result of :func:`track_postures`.

    Attributes:
        q: (K, n) joints; a waypoint without solution repeats the previous joints (leading ones
            ``q0``, or else the first solution's; no solution at all: ``q0`` or zeros).
        success: (K,) booleans: the waypoint has an inverse solution (within the limits).
        reconfigurations: Indices ``k`` of the waypoints entered by a reconfiguration: the step from
            the previous waypoint with a solution (``q0`` before the first) to ``k`` exceeds
            ``qdot_max * dt`` times their intervals on some joint.
        motion: Sum over the steps of the norm of the joint change (rad).
        solutions: The solution set of each waypoint, (m_k, n) arrays.
        postures: The posture label of each chosen solution (closed forms), else None.
    """

    q: np.ndarray
    success: np.ndarray
    reconfigurations: np.ndarray
    motion: float
    solutions: List[np.ndarray]
    postures: Optional[List[Optional[str]]]

    def __str__(self) -> str:
        return summary(self, [f.name for f in fields(self)])


def _continuous(chain: Chain) -> np.ndarray:
    """Joints whose range spans a whole turn: their steps are taken the short way round."""
    lo, hi = chain.limits
    kinds = chain.joint_types
    return np.array([k == "R" and (hi[i] - lo[i]) >= 2 * math.pi for i, k in enumerate(kinds)])


def count_reconfigurations(q, dt: float, qdot_max, q0=None, chain: Optional[Chain] = None) -> np.ndarray:
    """Indices ``k`` where the joint path ``q`` (K, n) steps more than ``qdot_max * dt`` on some joint
    from ``k - 1`` (from ``q0`` for ``k = 0`` when given). With ``chain``, joints whose limits span a
    whole turn are compared the short way round.

    Args:
        q: (K, n) joint path.
        dt: Time between waypoints (s), positive.
        qdot_max: Joint speed limit, a positive scalar or (n,).
        q0: Optional (n,) joints before the path.
        chain: Optional chain (for its continuous joints).
    """
    if chain is not None:
        check_chain(chain)
    q = rows(q, "q", (None if chain is None else chain.dof,))
    n = q.shape[1]
    speed, step = _speed(qdot_max, n), number(dt, "dt", positive=True)
    cont = _continuous(chain) if chain is not None else np.zeros(n, bool)
    start = None if q0 is None else vector(q0, "q0", n)
    return _core.count_reconfigurations(q, speed, step, cont, start)


def _speed(qdot_max, n) -> np.ndarray:
    return positive(per_joint(qdot_max, "qdot_max", n), "qdot_max")


def _closed_sets(chain: Chain, poses):
    """Solutions and labels per pose from a closed form; None when the chain has none."""
    solver = closed.ClosedSolver.find(chain)
    if solver is None:
        return None
    # A UR table (closed.ur's form) or any arm closed.family recognises (closed.solve's), by slot.
    q, _, within = solver.solve_batch(poses)  # within: a solution, within the limits
    names = list(closed.UR_POSTURES)
    sets, labels = [], []
    for row, keep in zip(q, within):
        sets.append(row[keep])
        labels.append([names[k] for k in np.nonzero(keep)[0]])
    return sets, labels


def _numerical_sets(chain: Chain, poses, starts: int, seed: int, cont, ik_options: dict):
    from .ik import ik_batch

    n = chain.dof
    lo, hi = chain.limits
    lo_s = np.where(np.isfinite(lo), np.maximum(lo, -math.pi), -math.pi)
    hi_s = np.where(np.isfinite(hi), np.minimum(hi, math.pi), math.pi)
    hi_s = np.maximum(hi_s, lo_s)
    rng = np.random.default_rng(seed)
    K = len(poses)
    q0 = rng.uniform(lo_s, hi_s, (K * starts, n))
    res = ik_batch(chain, np.repeat(poses, starts, axis=0), q0, seed=seed, **ik_options)
    # One row per posture each waypoint's starts reached (copies within 1e-6 dropped).
    return _core.distinct_solutions(res.q.reshape(K, starts, n), res.success.reshape(K, starts), cont)


def _ik_options(method: str, ik_options: dict) -> dict:
    """The numerical IK's options of ``track_postures(method=...)``: ``method`` an IK method or
    "numerical" (the IK's default), ``ik_options`` checked by the core's IKOptions; the task is the
    tool frames' ("pose")."""
    task = ik_options.get("task")
    if task is not None and task != "pose":
        raise ValueError(f"task: track_postures follows tool frames: expected None or 'pose', got {task!r}")
    options = {**ik_options, "task": "pose"}
    if method != "numerical":
        options["method"] = method
    try:
        _core.IKOptions(**options).validate()
    except ValueError as exc:
        if str(exc).startswith("method:"):
            raise ValueError(f"method: expected 'closed', 'numerical' or an IK method ('lm', 'gn', 'nr', 'halley'), "
                             f"got {method!r}") from None
        raise
    return options


@with_options(_core.IKOptions, exclude=("method", "task"))
def track_postures(chain: Chain, poses, dt: float, qdot_max=math.pi, method: str = "closed", q0=None,
                   starts: int = 32, seed: int = 0, **ik_options) -> TrackPosturesResult:
    """Follows the tool frames ``poses`` with the fewest reconfigurations, then the least joint motion.

    Args:
        chain: The arm. ``method="closed"`` needs a closed form: any arm :func:`robokin.closed.family`
            recognises (a UR arm from its DH table or URDF, a spherical wrist such as the PUMA 560:
            :func:`robokin.closed.solve`).
        poses: (K, 4, 4) tool frames, one per waypoint.
        dt: Time between waypoints (s).
        qdot_max: Joint speed limit (rad/s, m/s), a scalar or (n,): a step moving some joint more
            than ``qdot_max * dt`` is a reconfiguration.
        method: ``"closed"``, or numerical IK (:func:`robokin.ik_batch` from ``starts`` random
            starts per waypoint, seeded by ``seed``, duplicates within 1e-6 rad merged) with the IK's
            default method (``"numerical"``) or the one named (``"lm"``, ``"gn"``, ``"nr"``,
            ``"halley"``: IKOptions' ``method``).
        q0: Optional (n,) joints before the path: the step to the first waypoint counts too.
            Without it the plan starts in whichever posture is best.
        starts, seed: For the numerical IK, whose options follow (its method is ``method``, its task
            ``"pose"``: the waypoints are tool frames); none apply to ``method="closed"``.

    Returns:
        TrackPosturesResult (``q``, ``success``, ``reconfigurations``, ``motion``, ``solutions``,
        ``postures``). Joints whose limits span a whole turn step the short way round (and the path
        keeps them continuous, shifted by whole turns within the limits).
    """
    check_chain(chain)
    P, step_dt, vmax, options, start = _track_arguments(chain, poses, dt, qdot_max, method, q0, starts, seed,
                                                         ik_options)
    cont = _continuous(chain)
    labels = None
    if method == "closed":
        got = _closed_sets(chain, P)
        if got is None:
            raise ValueError("method: 'closed' needs an arm with a closed form (robokin.closed.family); "
                             "use method='numerical'")
        sets, labels = got
    else:
        sets = _numerical_sets(chain, P, int(starts), int(seed), cont, options)
    plan = _core.track_postures(sets, vmax, step_dt, cont, start, chain.limits)
    success = np.array([len(s) > 0 for s in sets])
    chosen = None if labels is None else [labels[k][p] if p >= 0 else None for k, p in enumerate(plan.pick)]
    # Copies: the plan's arrays are read-only, the dataclass's fields the caller's to change.
    return TrackPosturesResult(np.array(plan.q), success, np.array(plan.reconfigured), plan.motion, sets, chosen)


def _track_arguments(chain: Chain, poses, dt, qdot_max, method, q0, starts, seed, ik_options):
    """track_postures' arguments checked: the (K, 4, 4) poses, dt, the (n,) speed limits, the
    numerical IK's options (None for the closed form) and q0 (or None)."""
    n = chain.dof
    P = rows(poses, "poses", (4, 4))
    step_dt = number(dt, "dt", positive=True)
    vmax = _speed(qdot_max, n)
    if not isinstance(method, str):
        raise TypeError(f"method: expected 'closed', 'numerical' or an IK method, got {method!r}")
    if method == "closed" and ik_options:
        raise ValueError(f"ik_options: {sorted(ik_options)} apply to the numerical IK only (method='closed')")
    options = None if method == "closed" else _ik_options(method, ik_options)
    whole(starts, "starts", 1, 10_000, "IK starts per waypoint")
    check_seed(seed)
    start = None if q0 is None else joints(chain, q0, "q0")
    return P, step_dt, vmax, options, start
