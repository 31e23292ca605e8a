"""Velocity-level inverse kinematics: resolved-rate control and a servo loop along a Cartesian
trajectory. Both run in the C++ core with the damped least-squares step and the null-space term of
the Reach loop (cpp/src/dls.hpp)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Union

import numpy as np

from . import _core
from ._checks import frame_like

__all__ = ["resolved_rate", "ServoResult", "servo"]

Nullspace = Union[None, str, np.ndarray]


def resolved_rate(chain: _core.Chain, q, twist, damping: float = 0.0, nullspace: Nullspace = None,
                  task: Optional[str] = None) -> np.ndarray:
    """Joint velocities that move the tool with ``twist`` (resolved-rate control).

    ``qd = J^p twist + (1 - J^p J) h`` with the damped least-squares pseudoinverse
    ``J^p = J^T (J J^T + damping^2 I)^-1`` (the minimum-norm pseudoinverse when ``damping = 0``) and
    the null-space term of the RPR study, ``h = -grad z`` (see ``nullspace``).

    Args:
        chain: The serial chain.
        q: Joints, shape (dof,).
        twist: Task velocity, the task's rows of ``(v_x, v_y, v_z, w_x, w_y, w_z)`` in the base frame
            (6 for ``"pose"``, 3 for ``"position"``, 2 for ``"xy"``, 3 for ``"xyphi"``).
        damping: lambda of the damped least squares (>= 0), for use near singularities.
        nullspace: None; ``"joint_limits"`` (the seed's joint-limit avoidance,
            ``h = W^T W (qbar - q)``, ``W = diag(1 / (q_max - q_min))``, as :func:`robokin.reach`);
            or (dof,) gains ``g``: ``h = g * (qbar - q)``.
        task: Which rows of the Jacobian are controlled; None: ``chain.natural_task``.

    Returns:
        (dof,) joint velocities.
    """
    return _core.resolved_rate(chain, q, twist, damping, nullspace, task)


@dataclass(frozen=True)
class ServoResult:
    """What the servo loop did, one row per control step.

    Attributes:
        t: (K,) step times ``k dt``.
        q: (K, dof) joints at each step (before its velocity is applied).
        qd: (K, dof) joint velocities commanded at each step.
        error_p: (K,) position error (m) at each step: the norm of the task's translational rows.
        error_r: (K,) orientation error (rad): the rotation angle to the target (``"pose"``),
            ``|phi error|`` (``"xyphi"``), 0 for tasks without orientation.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    error_p: np.ndarray
    error_r: np.ndarray


def servo(chain: _core.Chain, poses, q0, dt: float, gain: float = 0.75, damping: float = 0.0,
          nullspace: Nullspace = None, task: Optional[str] = None, saturate: bool = True) -> ServoResult:
    """Follows a sampled Cartesian trajectory with resolved-rate control, one step per target.

    At step k the tool's error ``e_k`` toward ``poses[k]`` is measured (and reported), then
    ``q_{k+1} = q_k + dt qd_k`` with ``qd_k = J^p (v_k + gain e_k / dt) + (1 - J^p J) h``: ``v_k``
    is the feed-forward velocity from ``poses[k]`` to ``poses[k + 1]`` (the pose error between them
    over ``dt``; zero after the last), ``gain`` the share of the error corrected per step.

    Args:
        chain: The serial chain.
        poses: Targets at times ``0, dt, 2 dt, ...``: (K, 4, 4) frames for ``task="pose"`` (or a
            :class:`robokin.traj.CartesianTrajectory` sampled every ``dt``, or an object with a
            ``.A`` list of frames), (K, rows) task values otherwise.
        q0: Joints at the start, shape (dof,).
        dt: Control period (s).
        gain: Feedback gain, >= 0 (0: feed-forward only).
        damping, nullspace, task: As for :func:`resolved_rate` (task None: ``chain.natural_task``;
            poses shaped for another task name it, as for :func:`robokin.reach`).
        saturate: Clamp the joints to their limits after every step.

    Returns:
        ServoResult with ``t``, ``q``, ``qd``, ``error_p``, ``error_r``.
    """
    targets = getattr(poses, "poses", poses)
    q, qd, error_p, error_r = _core.servo(chain, frame_like(targets), q0, dt, gain, damping, nullspace, task, saturate)
    return ServoResult(np.arange(len(q)) * float(dt), q, qd, error_p, error_r)
