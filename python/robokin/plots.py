"""Figures for serial chains (matplotlib, the ``[plot]`` extra). Figures are returned, not shown.

The 3-D arm (``arm``, ``animate``, ``teach``) lives in :mod:`robokin.plots_arm` and is reached here
too: ``robokin.plots.arm(chain, q)``.
"""

from __future__ import annotations

from typing import Dict, Optional

import numpy as np

from . import robots
from ._checks import chain as check_chain
from ._checks import instance, real_array, rows, whole
from ._core import Chain, TrackResult, joint_limit_cost
from ._figures import new_figure

__all__ = ["MAX_DRAWN", "draw_planar_chain", "joint_axes", "rpr_line_figure", "trajectory_figure"]


def draw_planar_chain(ax, chain: Chain, q, color="C0", alpha=1.0, lw=2.0) -> None:
    """Draws a planar chain's links at ``q`` in the xy plane on the matplotlib Axes ``ax``: a
    polyline through its frames' origins, in ``color`` with opacity ``alpha`` and width ``lw``."""
    origins = chain.frames(q)[:, :2, 3]
    ax.plot(origins[:, 0], origins[:, 1], "-", color=color, alpha=alpha, lw=lw, solid_capstyle="round")
    ax.plot(origins[:-1, 0], origins[:-1, 1], "o", color=color, alpha=alpha, ms=3)


#: Most samples or snapshots a figure draws (each is a few matplotlib lines).
MAX_DRAWN = 1000


def _count(n, name: str) -> int:
    return whole(n, name, 1, MAX_DRAWN)


def _line_figure_arguments(points, tracks):
    """The path as a finite (K, 2) array and the tracks as a non-empty dict of K-row TrackResults."""
    p = rows(points, "points", (2,))
    if not isinstance(tracks, dict) or not tracks:
        raise TypeError("tracks: expected a non-empty dict label -> TrackResult")
    for label, tr in tracks.items():
        instance(tr, f"tracks[{label!r}]", TrackResult, "a TrackResult")
        if tr.q.shape != (len(p), 3):
            raise ValueError(f"tracks: {label!r} has joints of shape {tr.q.shape}, expected ({len(p)}, 3) for the points")
    return p, tracks


def rpr_line_figure(points: np.ndarray, tracks: Dict[str, TrackResult], surface_samples: int = 60,
                    snapshots: int = 8, title: Optional[str] = None):
    """The RPR study's Figure 2: the RPR arm following a straight line.

    (a) the self-motion surface of the path's points inside the joint-limit box with every joint
    path drawn on it; (b) the joint-limit cost z along the path; then the robot's motion for each
    track.

    Args:
        points: (K, 2) path points.
        tracks: label -> TrackResult of the same path (e.g. minimum norm, null space).
        surface_samples: Path points whose self-motion curves draw the surface.
        snapshots: Robot poses drawn per track.
        title: Figure title.

    Returns:
        The matplotlib Figure.
    """
    points, tracks = _line_figure_arguments(points, tracks)
    surface_samples, snapshots = _count(surface_samples, "surface_samples"), _count(snapshots, "snapshots")
    instance(title, "title", str, "a string", optional=True)
    chain = robots.rpr()
    lower, upper = chain.limits
    colors = ["tab:green", "tab:blue", "tab:red", "tab:purple"]
    fig = new_figure(figsize=(13, 10), layout="constrained")
    grid = fig.add_gridspec(2, 2)

    ax = fig.add_subplot(grid[0, 0], projection="3d")
    for k in np.linspace(0, len(points) - 1, surface_samples).astype(int):
        for branch in robots.rpr_self_motion(points[k], num=181):
            ax.plot(*branch.T, color="0.6", lw=0.6, alpha=0.7)
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)])
    box = lower + corners * (upper - lower)
    for i in range(8):
        for j in range(i + 1, 8):
            if np.sum(corners[i] != corners[j]) == 1:
                ax.plot(*np.stack([box[i], box[j]]).T, color="k", lw=0.5, alpha=0.4)
    for (label, tr), color in zip(tracks.items(), colors):
        ax.plot(*tr.q.T, color=color, lw=2.5, label=label)
    ax.scatter(*tracks[next(iter(tracks))].q[0], color="k", s=30)
    ax.set_xlabel("t1 (rad)")
    ax.set_ylabel("t2 (m)")
    ax.set_zlabel("t3 (rad)")
    ax.set_title("(a) self-motion surface in the joint-limit box")
    ax.legend(loc="upper left")

    ax = fig.add_subplot(grid[0, 1])
    s = np.r_[0, np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))]
    for (label, tr), color in zip(tracks.items(), colors):
        z = joint_limit_cost(chain, tr.q)
        ax.plot(s, z, color=color, label=f"{label}: mean z = {z.mean():.4f}")
    ax.set_xlabel("distance along the line (m)")
    ax.set_ylabel("joint-limit cost z")
    ax.set_title("(b) joint-limit cost along the path")
    ax.grid(alpha=0.3)
    ax.legend()

    for index, ((label, tr), color) in enumerate(zip(tracks.items(), colors)):
        ax = fig.add_subplot(grid[1, index % 2])
        ax.plot(points[:, 0], points[:, 1], "k--", lw=1)
        for j, k in enumerate(np.linspace(0, len(points) - 1, snapshots).astype(int)):
            draw_planar_chain(ax, chain, tr.q[k], color=color, alpha=0.25 + 0.75 * j / max(1, snapshots - 1))
        ax.annotate("1", points[0], xytext=(6, 6), textcoords="offset points", fontsize=13, weight="bold")
        ax.annotate("2", points[-1], xytext=(6, 6), textcoords="offset points", fontsize=13, weight="bold")
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(f"({'cd'[index % 2]}) robot motion, {label}")
        if index == 1:
            break
    if title:
        fig.suptitle(title)
    return fig


def trajectory_figure(trajectory, names=None, title: Optional[str] = None):
    """Positions, velocities and accelerations of a joint trajectory against time, one panel each.

    Args:
        trajectory: A :class:`robokin.traj.Trajectory` (anything with ``t`` (K,) and ``q``,
            ``qd``, ``qdd`` (K, n)).
        names: n labels for the joints; ``q_0 ... q_{n-1}`` when None.
        title: Figure title.

    Returns:
        A matplotlib Figure (three stacked axes sharing the time axis).
    """
    try:
        t = real_array(trajectory.t, "trajectory.t")
        parts = [real_array(getattr(trajectory, name), f"trajectory.{name}") for name in ("q", "qd", "qdd")]
    except AttributeError as exc:
        raise TypeError(f"trajectory: expected t, q, qd and qdd arrays ({exc})") from None
    if t.ndim != 1 or any(p.ndim != 2 or p.shape[0] != len(t) for p in parts):
        raise ValueError("trajectory: expected t (K,) and q, qd, qdd (K, n)")
    n = parts[0].shape[1]
    labels = [f"q_{i}" for i in range(n)] if names is None else [str(s) for s in names]
    if len(labels) != n:
        raise ValueError(f"names: expected {n} labels, got {len(labels)}")
    fig = new_figure(figsize=(6.4, 5.6), layout="constrained")
    axes = fig.subplots(3, 1, sharex=True)
    for ax, values, unit in zip(axes, parts, ("position (rad, m)", "velocity (rad/s, m/s)", "acceleration (rad/s², m/s²)")):
        for i in range(n):
            ax.plot(t, values[:, i], lw=1.4, label=labels[i])
        ax.set_ylabel(unit)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="best", fontsize="small", ncol=min(n, 3))
    axes[-1].set_xlabel("time (s)")
    if title:
        fig.suptitle(title)
    return fig


# --- serial chains in 3-D (the simulator's drawing rules) --------------------------------------

def joint_axes(chain: Chain, q) -> np.ndarray:
    """Each joint's axis at q, for drawing: ``(dof, 2, 3)``, a point on the axis next to the joint
    and the axis's unit direction, in the base frame.

    Read off the geometric Jacobian's columns: a revolute joint turns about ``w_i`` through the foot
    ``p + w_i x v_i`` of the tool point ``p``'s perpendicular (since ``v_i = w_i x (p - c)``); the
    point drawn is the one of the frame origins before and after the joint (``chain.frames``)
    nearest the axis, put on it. A prismatic joint slides along ``v_i``, drawn through the frame
    after it.
    """
    frames = chain.frames(q)
    jac = chain.jacobian(q)
    origins, tool = frames[:, :3, 3], frames[-1][:3, 3]
    v, w = jac[:3].T, jac[3:].T  # (dof, 3) each
    revolute = np.array([kind == "R" for kind in chain.joint_types])
    direction = np.where(revolute[:, None], w, v)
    direction = direction / np.maximum(np.linalg.norm(direction, axis=1), 1e-300)[:, None]
    foot = tool + np.cross(direction, v)
    # The frame origins before and after each joint; the one nearest the axis, put on it.
    candidates = np.stack([origins[:-1], origins[1:]], axis=1)  # (dof, 2, 3)
    offsets = candidates - foot[:, None]
    along = np.einsum("ikj,ij->ik", offsets, direction)
    distance = np.linalg.norm(offsets - along[..., None] * direction[:, None], axis=2)
    pick = np.argmin(distance, axis=1)
    rows = np.arange(chain.dof)
    points = np.where(revolute[:, None], foot + along[rows, pick][:, None] * direction, origins[1:])
    return np.stack([points, direction], axis=1)


def __getattr__(name):
    # The 3-D arm (robokin.plots_arm) under robokin.plots too, imported on first use (plots_arm
    # imports joint_axes from here).
    if name in ("arm", "animate", "teach"):
        from . import plots_arm

        return getattr(plots_arm, name)
    raise AttributeError(f"module 'robokin.plots' has no attribute {name!r}")
