"""Pose helpers: roll-pitch-yaw, unit quaternions, axis-angle, the SE(3) exponential and logarithm,
and the pose error of the IK. The formulas run in the C++ core (cpp/src/pose.cpp), where the
Cartesian trajectories and the IK use the same ones.

Conventions:

- Frames are (4, 4) homogeneous matrices; calls that read a rotation also take a (3, 3) matrix.
  A batch is (N, 4, 4) (or (N, 3, 3)) and gives a batch. Every call that takes a frame also takes an
  object with ``__array__`` or with a ``.A`` matrix (spatialmath's ``SE3``), without needing
  spatialmath.
- RPY: ``R = Rz(yaw) Ry(pitch) Rx(roll)`` (rotations about the fixed x, then y, then z axes; the
  URDF and ROS convention), angles in radians, ``(roll, pitch, yaw)``.
- Quaternions are ``(w, x, y, z)``, scalar first, unit norm, ``w >= 0`` when returned.
- Twists are ``(v, w)``: linear part first, as the rows of the Jacobian.
"""

from __future__ import annotations

import numpy as np

from . import _core
from ._checks import finite, frame_like, real_array

__all__ = [
    "from_rpy",
    "rpy",
    "from_quaternion",
    "quaternion",
    "from_axis_angle",
    "axis_angle",
    "exp",
    "log",
    "error",
]


def _with_position(frames: np.ndarray, position) -> np.ndarray:
    """Frames with their translation set to ``position`` ((3,) or (N, 3), broadcast)."""
    if position is None:
        return frames
    p = real_array(position, "position")
    if p.ndim not in (1, 2) or p.shape[-1] != 3:
        raise ValueError(f"position: expected shape (3,) or (N, 3), got {p.shape}")
    finite(p, "position")
    if p.ndim == 2:
        if frames.ndim == 2:
            frames = np.repeat(frames[None], len(p), axis=0)
        elif len(frames) != len(p):
            raise ValueError(f"position: {len(p)} positions for {len(frames)} rotations")
    frames[..., :3, 3] = p
    return frames


def from_rpy(rpy, position=None) -> np.ndarray:
    """Frame of roll, pitch, yaw: ``R = Rz(yaw) Ry(pitch) Rx(roll)``.

    Args:
        rpy: ``(roll, pitch, yaw)`` in radians, shape (3,) or (N, 3).
        position: Translation (3,) or (N, 3); zero when None.

    Returns:
        (4, 4) frame, or (N, 4, 4).
    """
    return _with_position(_core.pose_from_rpy(rpy), position)


def rpy(T) -> np.ndarray:
    """``(roll, pitch, yaw)`` of a rotation, with ``R = Rz(yaw) Ry(pitch) Rx(roll)``.

    Pitch is in [-pi/2, pi/2], roll and yaw in [-pi, pi]. At pitch = +-pi/2 (gimbal lock) only
    ``yaw -+ roll`` is defined: roll is returned as 0.

    Args:
        T: (4, 4) frame or (3, 3) rotation, or a batch (N, 4, 4) / (N, 3, 3).

    Returns:
        (3,) or (N, 3).
    """
    return _core.pose_rpy(frame_like(T))


def from_quaternion(quaternion, position=None) -> np.ndarray:
    """Frame of a quaternion ``(w, x, y, z)`` (normalised first; it must not be zero).

    Args:
        quaternion: (4,) or (N, 4), scalar first.
        position: Translation (3,) or (N, 3); zero when None.

    Returns:
        (4, 4) frame, or (N, 4, 4).
    """
    return _with_position(_core.pose_from_quaternion(quaternion), position)


def quaternion(T) -> np.ndarray:
    """Unit quaternion ``(w, x, y, z)`` of a rotation, with ``w >= 0`` (Shepperd's method).

    Args:
        T: (4, 4) frame or (3, 3) rotation, or a batch.

    Returns:
        (4,) or (N, 4).
    """
    return _core.pose_quaternion(frame_like(T))


def from_axis_angle(axis, angle, position=None) -> np.ndarray:
    """Frame of the rotation by ``angle`` (radians, right hand) about ``axis`` (Rodrigues' formula).

    Args:
        axis: (3,) or (N, 3), not zero (normalised first).
        angle: A number, or (N,) with a batch of axes.
        position: Translation (3,) or (N, 3); zero when None.

    Returns:
        (4, 4) frame, or (N, 4, 4).
    """
    a = real_array(axis, "axis")
    if a.ndim not in (1, 2) or a.shape[-1] != 3:
        raise ValueError(f"axis: expected shape (3,) or (N, 3), got {a.shape}")
    finite(a, "axis")
    big = np.max(np.abs(a), axis=-1, keepdims=True)
    if np.any(big == 0):
        raise ValueError("axis: must not be zero")
    a = a / big  # the norm of huge or tiny axes neither overflows nor underflows
    norm = np.linalg.norm(a, axis=-1, keepdims=True)
    theta = real_array(angle, "angle")
    if theta.ndim > 1 or (theta.ndim == 1 and (a.ndim != 2 or len(theta) != len(a))):
        raise ValueError(f"angle: expected a number, or shape (N,) with axis (N, 3), got {theta.shape}")
    finite(theta, "angle")
    return _with_position(_core.pose_from_rotation_vector((a / norm) * theta[..., None]), position)


def axis_angle(T):
    """Axis and angle of a rotation: ``angle`` in [0, pi], ``axis`` a unit vector (``(0, 0, 1)``
    when the angle is 0).

    Args:
        T: (4, 4) frame or (3, 3) rotation, or a batch.

    Returns:
        ``(axis, angle)``: (3,) and a float, or (N, 3) and (N,).
    """
    w = _core.pose_rotation_vector(frame_like(T))
    angle = np.linalg.norm(w, axis=-1)
    safe = np.where(angle > 0, angle, 1.0)[..., None]
    axis = np.where(angle[..., None] > 0, w / safe, np.array([0.0, 0.0, 1.0]))
    return axis, (float(angle) if w.ndim == 1 else angle)


def exp(xi) -> np.ndarray:
    """SE(3) exponential: the frame ``T = exp([xi])`` of the twist ``xi = (v, w)``,
    ``[xi] = [[w]x, v; 0, 0]``: rotation by ``|w|`` about ``w``, translation ``V(w) v``.

    Args:
        xi: (6,) or (N, 6).

    Returns:
        (4, 4) frame, or (N, 4, 4).
    """
    return _core.pose_exp(xi)


def log(T) -> np.ndarray:
    """SE(3) logarithm, the inverse of :func:`exp`: ``xi = (v, w)`` with ``|w|`` in [0, pi].

    Args:
        T: (4, 4) frame or a batch (N, 4, 4).

    Returns:
        (6,) or (N, 6).
    """
    return _core.pose_log(frame_like(T))


def error(target, current) -> np.ndarray:
    """The pose error the IK drives to zero: ``(p_t - p, rotation vector of R_t R^T)`` in the base
    frame (the orientation part's norm is the rotation angle between the two, in [0, pi]).

    Args:
        target, current: (4, 4) frames, or batches (N, 4, 4); a single frame is paired with every
            frame of a batch.

    Returns:
        (6,) or (N, 6).
    """
    return _core.pose_error(frame_like(target), frame_like(current))
