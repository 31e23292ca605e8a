"""The Reach loop of seed 000 (Algorithm 1) and path tracking; the loops run in the C++ core."""

from __future__ import annotations

import warnings
from typing import Optional, Union

import numpy as np

from . import _core
from .errors import PrecisionWarning

Nullspace = Union[None, str, np.ndarray]


def reach(
    chain: _core.Chain,
    target,
    q,
    task: str = "xy",
    max_iter: int = 25,
    tol: float = 1e-5,
    gain: float = 0.75,
    dt: float = 0.025,
    saturate: bool = True,
    nullspace: Nullspace = None,
    damping: float = 0.0,
) -> _core.ReachResult:
    """Moves the joints ``q`` so that the tool reaches a nearby ``target``.

    Each iteration takes the seed's damped step ``dq = J^p d (target - p) / dt`` with the
    minimum-norm pseudoinverse ``J^p = J^T (J J^T + damping^2 I)^-1``, advances ``q += dt dq`` and
    clamps it to the joint limits (when ``saturate``), until the task error is below ``tol`` or
    ``max_iter`` iterations have run.

    Args:
        chain: The serial chain.
        target: For ``task="xy"`` (x, y); ``"position"`` (x, y, z); ``"xyphi"`` (x, y, phi);
            ``"pose"`` a (4, 4) frame.
        q: Start joints, shape (dof,); the target should be close to the tool at q.
        task: Which rows of the geometric Jacobian are controlled.
        max_iter: Iterations at most (the seed's n = 25), in [1, 100000].
        tol: Tolerance on the norm of the task error (metres for positions; 1e-5 in the seed).
        gain: The seed's damping factor d.
        dt: The seed's time step.
        saturate: Clamp to the joint limits after every step.
        nullspace: ``"joint_limits"`` adds the homogeneous term ``(1 - J^p J) h`` with
            ``h = W (qbar - q)``, ``W = diag(1 / (q_max - q_min))`` (seed eqs. 5-7), on the first
            iteration of each call; the remaining iterations are minimum-norm corrections, so the
            tolerance is still met. An array of ``dof`` gains replaces ``W``'s diagonal.
        damping: lambda of the damped least-squares pseudoinverse, for use near singularities.

    Returns:
        ReachResult with ``q``, ``converged``, ``iterations`` and ``error``.

    Warns:
        PrecisionWarning: When the tolerance was not reached ("precision not reached").
    """
    result = _core.reach(chain, target, q, task, max_iter, tol, gain, dt, saturate, nullspace, damping)
    if not result.converged:
        warnings.warn(
            f"precision not reached: task error {result.error:.3g} >= tol {tol:g} "
            f"after {result.iterations} iterations",
            PrecisionWarning,
            stacklevel=2,
        )
    return result


def track(
    chain: _core.Chain,
    points,
    q0,
    task: str = "xy",
    max_iter: int = 25,
    tol: float = 1e-5,
    gain: float = 0.75,
    dt: float = 0.025,
    saturate: bool = True,
    nullspace: Nullspace = None,
    damping: float = 0.0,
) -> _core.TrackResult:
    """Follows a path: one Reach per point, each starting from the joints the previous one left.

    Args:
        chain: The serial chain.
        points: (K, rows) targets for the task ((K, 4, 4) frames for ``"pose"``), close together.
        q0: Joints at the start of the path, shape (dof,).
        task, max_iter, tol, gain, dt, saturate, nullspace, damping: As for :func:`reach`.

    Returns:
        TrackResult with ``q`` (K, dof), ``error`` (K,), ``converged`` (K,), ``iterations`` (K,).

    Warns:
        PrecisionWarning: When any point was not reached within ``tol``.
    """
    result = _core.track(chain, points, q0, task, max_iter, tol, gain, dt, saturate, nullspace, damping)
    missed = int(np.count_nonzero(~result.converged))
    if missed:
        warnings.warn(
            f"precision not reached on {missed} of {len(result.error)} path points "
            f"(worst task error {float(np.max(result.error)):.3g}, tol {tol:g})",
            PrecisionWarning,
            stacklevel=2,
        )
    return result
