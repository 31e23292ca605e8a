"""Trajectories with time laws; planning and evaluation run in the C++ core (cpp/src/traj.cpp).

- :func:`quintic`: joint-space quintic polynomial between two configurations (zero acceleration at
  both ends, given or zero velocities), sampled at given times.
- :func:`trapezoidal`: trapezoidal velocity with per-joint velocity and acceleration limits, the
  slowest joint time-optimal and the others synchronised to arrive with it.
- :func:`via_points`: straight segments through via points joined by parabolic blends.
- :func:`cartesian`: a straight line between two poses, the position linear and the orientation by
  quaternion SLERP, under the quintic or the trapezoidal law.

Each returns its samples as arrays: times ``t`` (K,), and positions, velocities and accelerations.
Only :func:`quintic` takes ``out=`` (arrays to write the samples into): the others choose their
sample count from ``dt`` (:func:`cartesian` from ``dt`` or ``t`` by its law), so the caller cannot
size the arrays before the call.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from ._checks import frame_like, instance, real_array

__all__ = ["Trajectory", "CartesianTrajectory", "quintic", "trapezoidal", "via_points", "cartesian"]


@dataclass(frozen=True)
class Trajectory:
    """A sampled joint trajectory.

    Attributes:
        t: (K,) sample times (s), increasing.
        q: (K, n) positions.
        qd: (K, n) velocities.
        qdd: (K, n) accelerations.
        via_times: for :func:`via_points`, the (M,) times at which the straight segments pass the
            via points (the middle of each blend); None otherwise.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    via_times: Optional[np.ndarray] = None

    @property
    def duration(self) -> float:
        """Time from the first sample to the last (s)."""
        return float(self.t[-1] - self.t[0])

    def __len__(self) -> int:
        return len(self.t)


@dataclass(frozen=True)
class CartesianTrajectory:
    """A sampled Cartesian trajectory.

    Attributes:
        t: (K,) sample times (s), increasing.
        poses: (K, 4, 4) tool frames.
        velocity: (K, 6) twists ``(v_x, v_y, v_z, w_x, w_y, w_z)`` in the base frame (the linear
            velocity of the frame's origin and the angular velocity).
        acceleration: (K, 6) their time derivatives.
    """

    t: np.ndarray
    poses: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray

    @property
    def duration(self) -> float:
        """Time from the first sample to the last (s)."""
        return float(self.t[-1] - self.t[0])

    def __len__(self) -> int:
        return len(self.t)


def _limits(value, n: int, name: str):
    """A scalar limit repeated for every joint; arrays pass unchanged (the core checks them)."""
    if value is None:
        return value
    a = real_array(value, name)
    return np.full(n, float(a)) if a.ndim == 0 else a


def _joints(value, name: str) -> int:
    a = real_array(value, name)
    return a.shape[-1] if a.ndim >= 1 else 0


def quintic(q0, q1, t, qd0=None, qd1=None, *, out=None) -> Trajectory:
    """Joint-space quintic polynomial from ``q0`` at ``t[0]`` to ``q1`` at ``t[-1]``.

    Per joint ``q(s) = sum c_k s^k``, ``s = (t - t[0]) / (t[-1] - t[0])``, with the positions,
    velocities (``qd0``, ``qd1``, zero by default) and zero accelerations imposed at both ends; with
    zero end velocities ``q = q0 + (q1 - q0) (10 s^3 - 15 s^4 + 6 s^5)``. The samples at ``t[0]``
    and ``t[-1]`` are the boundary values exactly.

    Args:
        q0, q1: Start and end configurations, shape (n,).
        t: Sample times, shape (K,), K >= 2, strictly increasing.
        qd0, qd1: Velocities at the start and end, shape (n,); zero when None.
        out: None, or a :class:`Trajectory` whose ``q``, ``qd`` and ``qdd`` arrays receive the
            samples (numpy's idiom: reuse memory across calls; a Trajectory from an earlier call of
            the same shape, or one made of ``np.empty((K, n))`` arrays): each a writable, aligned,
            C-contiguous float64 array of shape (K, n), sharing no memory with ``t`` or with the
            others (a field that is None gets a new array). ``out.t`` is neither read nor written.

    Returns:
        Trajectory with ``t`` (K,), ``q``, ``qd``, ``qdd`` (K, n). With ``out``, a new Trajectory
        holding a copy of ``t`` (as without ``out``) and ``out``'s ``q``, ``qd``, ``qdd`` arrays
        themselves, their values the same as without ``out``.

    Raises:
        TypeError: ``out`` is not a Trajectory, or one of its arrays not a float64 numpy array.
        ValueError: one of ``out``'s arrays has the wrong shape or layout, or shares memory.
    """
    if out is None:
        return Trajectory(*_core.traj_quintic(q0, q1, t, qd0, qd1))
    instance(out, "out", Trajectory, "a robokin.traj.Trajectory", optional=True)
    return Trajectory(*_core.traj_quintic(q0, q1, t, qd0, qd1, q_out=out.q, qd_out=out.qd, qdd_out=out.qdd))


def trapezoidal(q0, q1, vmax, amax, dt: float = 0.01) -> Trajectory:
    """Trapezoidal velocity profile from rest at ``q0`` to rest at ``q1``, joints synchronised.

    The slowest joint runs its time-optimal profile: full acceleration ``amax`` up to ``vmax``,
    cruise, full deceleration (a triangle when the distance is too short to reach ``vmax``). Every
    other joint accelerates at its own limit to the lower cruise speed that makes it arrive at the
    same time, so the motion lasts as long as the slowest joint needs, and no joint exceeds its
    limits: ``|qd_i| <= vmax_i``, ``|qdd_i| <= amax_i``.

    Args:
        q0, q1: Start and end configurations, shape (n,).
        vmax, amax: Velocity and acceleration limits, positive, shape (n,) or one number for all.
        dt: Sample period (s): samples at 0, dt, 2 dt, ... and at the end time.

    Returns:
        Trajectory with ``t`` from 0 to the duration, ``q``, ``qd``, ``qdd``.
    """
    n = _joints(q0, "q0")
    return Trajectory(*_core.traj_trapezoidal(q0, q1, _limits(vmax, n, "vmax"), _limits(amax, n, "amax"), dt))


def via_points(points, vmax, amax, dt: float = 0.01) -> Trajectory:
    """Straight segments through via points joined by parabolic blends (linear segments with
    parabolic blends, Craig's *Introduction to Robotics*, section 7.3).

    Segment j takes as long as its slowest joint needs at its velocity limit; at each via point the
    velocity changes during a blend as long as the joint with the largest change needs at its
    acceleration limit; a segment too short for its two half blends is lengthened. The motion starts
    at rest exactly on the first point and ends at rest exactly on the last one; an inner via point
    is passed within its blend (through it exactly when the velocity does not change there).
    ``|qd_i| <= vmax_i`` and ``|qdd_i| <= amax_i`` throughout.

    Args:
        points: (M, n) via points, M >= 1 (repeated consecutive points are merged).
        vmax, amax: Velocity and acceleration limits, positive, shape (n,) or one number for all.
        dt: Sample period (s).

    Returns:
        Trajectory with ``via_times`` (the times the straight segments pass each via point).
    """
    p = real_array(points, "points")
    n = p.shape[-1] if p.ndim == 2 else 0
    return Trajectory(*_core.traj_via_points(points, _limits(vmax, n, "vmax"), _limits(amax, n, "amax"), dt))


def cartesian(T0, T1, t=None, law: str = "quintic", vmax=None, amax=None, dt: float = 0.01) -> CartesianTrajectory:
    """Straight-line Cartesian trajectory from frame ``T0`` to frame ``T1``.

    The origin moves along the segment from ``p0`` to ``p1``; the orientation turns by SLERP of the
    unit quaternions of ``R0`` and ``R1`` (the shorter arc: about one fixed axis, the angle
    interpolated linearly in the law's parameter). The time law moves the distance along the
    segment and the rotation angle:

    - ``law="quintic"``: both by the quintic of :func:`quintic` over the sample times ``t``;
    - ``law="trapezoidal"``: by a synchronised trapezoid with ``vmax = (linear m/s, angular rad/s)``
      and ``amax = (linear m/s^2, angular rad/s^2)``, sampled every ``dt`` from 0.

    The last sample is ``T1`` exactly.

    Args:
        T0, T1: (4, 4) frames (or objects with ``__array__`` or a ``.A`` matrix, as spatialmath's SE3).
        t: Sample times for the quintic law, (K,), K >= 2, strictly increasing.
        law: ``"quintic"`` or ``"trapezoidal"``.
        vmax, amax: Limits of the trapezoidal law, each (linear, angular).
        dt: Sample period of the trapezoidal law (s).

    Returns:
        CartesianTrajectory with ``t``, ``poses`` (K, 4, 4), ``velocity`` and ``acceleration`` (K, 6).
    """
    return CartesianTrajectory(*_core.traj_cartesian(frame_like(T0), frame_like(T1), law, t, vmax, amax, dt))
