"""Velocity-level inverse kinematics: resolved-rate control and a servo loop along a Cartesian
trajectory. Both run in the C++ core with the damped least-squares step and the null-space term of
the Reach loop (cpp/src/linalg.hpp)."""

from __future__ import annotations

from typing import Union

import numpy as np

from . import _core
from ._checks import frame_like
from ._core import RateOptions, ServoOptions, ServoResult
from ._options import with_options

__all__ = ["RateOptions", "ServoOptions", "ServoResult", "resolved_rate", "servo"]

Nullspace = Union[None, str, np.ndarray]


@with_options(RateOptions)
def resolved_rate(chain: _core.Chain, q, twist, *, nullspace: Nullspace = None, **options) -> np.ndarray:
    """Joint velocities that move the tool with ``twist`` (resolved-rate control).

    ``qd = J^p twist + (1 - J^p J) h`` with the damped least-squares pseudoinverse
    ``J^p = J^T (J J^T + damping^2 I)^-1`` (the minimum-norm pseudoinverse when ``damping = 0``) and
    the null-space term of the RPR study, ``h = -grad z`` (see ``nullspace``).

    Args:
        chain: The serial chain.
        q: Joints, shape (dof,).
        twist: Task velocity, the task's rows of ``(v_x, v_y, v_z, w_x, w_y, w_z)`` in the base frame
            (6 for ``"pose"``, 3 for ``"position"``, 2 for ``"xy"``, 3 for ``"xyphi"``).
        nullspace: None; ``"joint_limits"`` (the seed's joint-limit avoidance,
            ``h = W^T W (qbar - q)``, ``W = diag(1 / (q_max - q_min))``, as :func:`robokin.reach`);
            or (dof,) gains ``g``: ``h = g * (qbar - q)``.

    Returns:
        (dof,) joint velocities.
    """
    return _core.resolved_rate(chain, q, twist, nullspace=nullspace, **options)


@with_options(ServoOptions)
def servo(chain: _core.Chain, poses, q0, dt: float, *, nullspace: Nullspace = None, **options) -> ServoResult:
    """Follows a sampled Cartesian trajectory with resolved-rate control, one step per target.

    At step k the tool's error ``e_k`` toward ``poses[k]`` is measured (and reported), then
    ``q_{k+1} = q_k + dt qd_k`` with ``qd_k = J^p (v_k + gain e_k / dt) + (1 - J^p J) h``: ``v_k``
    is the feed-forward velocity from ``poses[k]`` to ``poses[k + 1]`` (the pose error between them
    over ``dt``; zero after the last), ``gain`` the share of the error corrected per step.

    Args:
        chain: The serial chain.
        poses: Targets at times ``0, dt, 2 dt, ...``: (K, 4, 4) frames for ``task="pose"`` (or a
            :class:`robokin.traj.CartesianTrajectory` sampled every ``dt``, or an object with a
            ``.A`` list of frames), (K, rows) task values otherwise (poses shaped for another task
            name it, as for :func:`robokin.reach`).
        q0: Joints at the start, shape (dof,).
        dt: Control period (s), the spacing of the poses in time.
        nullspace: As for :func:`resolved_rate`.

    Returns:
        ServoResult with read-only arrays ``t`` (K,), ``q`` (K, dof), ``qd`` (K, dof),
        ``error_p`` (K,), ``error_r`` (K,).
    """
    targets = getattr(poses, "poses", poses)
    return _core.servo(chain, frame_like(targets), q0, dt, nullspace=nullspace, **options)
