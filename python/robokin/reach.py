"""The Reach loop of the RPR study (Algorithm 1) and path tracking; the loops run in the C++ core."""

from __future__ import annotations

import warnings
from typing import Optional, Union

import numpy as np

from . import _core
from ._options import with_options
from .errors import PrecisionWarning

__all__ = ["reach", "track"]

Nullspace = Union[None, str, np.ndarray]


@with_options(_core.ReachOptions)
def reach(chain: _core.Chain, target, q, task: Optional[str] = None, *, nullspace: Nullspace = None,
          **options) -> _core.ReachResult:
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
        task: Which rows of the geometric Jacobian are controlled; None: ``chain.natural_task``
            (``"xy"`` for the seed's RPR, ``"xyphi"`` for a planar 3R, ``"pose"`` for a 6-joint
            arm, ``"position"`` for a spatial arm of fewer joints).
        nullspace: ``"joint_limits"`` adds the homogeneous term ``(1 - J^p J) h`` (seed eqs. 5-7)
            with ``h = -grad z = W^T W (qbar - q)``, the descent direction of the seed's
            joint-limit cost ``z = 1/2 |W (qbar - q)|^2``, ``W = diag(1 / (q_max - q_min))``
            (:func:`robokin.joint_limit_cost`), on the first iteration of each call; the remaining
            iterations are minimum-norm corrections, so the tolerance is still met. An array of
            ``dof`` gains ``g`` gives ``h = g * (qbar - q)``, the descent direction of
            ``1/2 sum g_i (qbar_i - q_i)^2`` (``"joint_limits"`` is ``g = 1 / (q_max - q_min)^2``;
            ``k`` times those gains pulls ``k`` times harder toward the least cost, 0 for a joint
            that should not be pulled).

    Returns:
        ReachResult with ``q``, ``converged``, ``iterations`` and ``error``.

    Raises:
        ValueError: An option out of range, a target or joints of the wrong shape, NaN or inf (a
            target shaped for another task names it: ``target (3,) is a position (x, y, z): pass
            task="position" (task 'pose' takes a (4, 4) frame)``).
        TypeError: An unknown option, or one of the wrong kind.

    Warns:
        PrecisionWarning: When the tolerance was not reached ("precision not reached").
    """
    result = _core.reach(chain, target, q, task, nullspace=nullspace, **options)
    if not result.converged:
        tol = _core.ReachOptions(**options).tol
        warnings.warn(
            f"precision not reached: task error {result.error:.3g} >= tol {tol:g} "
            f"after {result.iterations} iterations",
            PrecisionWarning,
            stacklevel=2,
        )
    return result


@with_options(_core.ReachOptions)
def track(chain: _core.Chain, points, q0, task: Optional[str] = None, *, nullspace: Nullspace = None,
          **options) -> _core.TrackResult:
    """Follows a path: one Reach per point, each starting from the joints the previous one left.

    Args:
        chain: The serial chain.
        points: (K, rows) targets for the task ((K, 4, 4) frames for ``"pose"``), close together.
        q0: Joints at the start of the path, shape (dof,).
        task, nullspace: As for :func:`reach` (task None: ``chain.natural_task``).

    Returns:
        TrackResult with read-only arrays ``q`` (K, dof), ``error`` (K,), ``converged`` (K,),
        ``iterations`` (K,).

    Warns:
        PrecisionWarning: When any point was not reached within ``tol``.
    """
    result = _core.track(chain, points, q0, task, nullspace=nullspace, **options)
    missed = int(np.count_nonzero(~result.converged))
    if missed:
        tol = _core.ReachOptions(**options).tol
        warnings.warn(
            f"precision not reached on {missed} of {len(result.error)} path points "
            f"(worst task error {float(np.max(result.error)):.3g}, tol {tol:g})",
            PrecisionWarning,
            stacklevel=2,
        )
    return result
