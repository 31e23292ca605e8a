"""Figures for serial chains (matplotlib, the ``[plot]`` extra). Figures are returned, not shown."""

from __future__ import annotations

from typing import Dict, Optional

import numpy as np

from . import robots
from ._checks import chain as check_chain
from ._checks import planar_points, real_array, whole
from ._core import Chain, TrackResult, joint_limit_cost
from ._figures import new_figure

__all__ = ["ISO_VIEW", "MAX_DRAWN", "MAX_FRAMES", "animate_chain", "draw_planar_chain", "joint_axes", "plot_chain",
           "rpr_line_figure", "trajectory_figure"]


def draw_planar_chain(ax, chain: Chain, q, color="C0", alpha=1.0, lw=2.0) -> None:
    """Draws a planar chain's links in the xy plane: a polyline through its frames' origins."""
    origins = chain.frames(q)[:, :2, 3]
    ax.plot(origins[:, 0], origins[:, 1], "-", color=color, alpha=alpha, lw=lw, solid_capstyle="round")
    ax.plot(origins[:-1, 0], origins[:-1, 1], "o", color=color, alpha=alpha, ms=3)


#: Most samples or snapshots a figure draws (each is a few matplotlib lines).
MAX_DRAWN = 1000


def _count(n, name: str) -> int:
    return whole(n, name, 1, MAX_DRAWN)


def _line_figure_arguments(points, tracks):
    """The path as a finite (K, 2) array and the tracks as a non-empty dict of K-row TrackResults."""
    p = planar_points(points, "points")
    if not isinstance(tracks, dict) or not tracks:
        raise TypeError("tracks: expected a non-empty dict label -> TrackResult")
    for label, tr in tracks.items():
        if not isinstance(tr, TrackResult):
            raise TypeError(f"tracks: {label!r} is a {type(tr).__name__}, not a TrackResult")
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
    if title is not None and not isinstance(title, str):
        raise TypeError(f"title: expected a string or None, got {type(title).__name__}")
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

#: Colours of :func:`plot_chain` (as the simulator's serial scene): links from near to far, joints,
#: joint axes, the tool triad's x, y, z.
_LINK_NEAR, _LINK_FAR = "#2e62b2", "#96b0d6"
_JOINT_EDGE, _JOINT_AXIS = "#1e1e1e", "#78788c"
_TRIAD = ("#d23232", "#32a03c", "#3250dc")
#: Preset view of :func:`plot_chain` (elevation, azimuth in degrees): the simulator's iso view.
ISO_VIEW = (25.0, -50.0)


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


def _chain_q(chain, q, name: str = "q") -> np.ndarray:
    check_chain(chain)
    a = real_array(q, name)
    if a.shape != (chain.dof,):
        raise ValueError(f"{name}: expected shape ({chain.dof},), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: contains NaN or inf")
    return a


def _arm_size(frames: np.ndarray) -> float:
    origins = frames[:, :3, 3]
    return max(float(np.sum(np.linalg.norm(np.diff(origins, axis=0), axis=1))), 0.1)


def _draw_chain(ax, chain: Chain, q: np.ndarray, size: float) -> None:
    """The arm on a 3-D Axes: floor grid, links shaded by depth along the view, joints, axes, triad."""
    from matplotlib.colors import to_rgb

    frames = chain.frames(q)
    origins = frames[:, :3, 3]
    elev, azim = np.radians(ax.elev), np.radians(ax.azim)
    view = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    near, far = np.array(to_rgb(_LINK_NEAR)), np.array(to_rgb(_LINK_FAR))
    spacing = 10 ** np.floor(np.log10(size / 4.0))
    k = int(np.ceil(1.25 * size / spacing))
    for c in np.arange(-k, k + 1) * spacing:
        ax.plot([c, c], [-k * spacing, k * spacing], [0, 0], color="0.88", lw=0.6)
        ax.plot([-k * spacing, k * spacing], [c, c], [0, 0], color="0.88", lw=0.6)
    for i in range(len(origins) - 1):
        a, b = origins[i], origins[i + 1]
        if np.linalg.norm(b - a) <= 1e-9:
            continue
        depth = float(np.dot(0.5 * (a + b), view))
        t = float(np.clip(0.5 - depth / (1.6 * size), 0.0, 1.0))
        ax.plot(*np.stack([a, b]).T, color=near + (far - near) * t, lw=7, solid_capstyle="round")
    for point, direction in joint_axes(chain, q):
        ends = np.stack([point - 0.07 * size * direction, point + 0.07 * size * direction])
        ax.plot(*ends.T, color=_JOINT_AXIS, lw=2)
    ax.scatter(*origins[:-1].T, s=40, facecolor="white", edgecolor=_JOINT_EDGE, depthshade=False)
    tool = frames[-1]
    for k, colour in enumerate(_TRIAD):
        ax.plot(*np.stack([tool[:3, 3], tool[:3, 3] + 0.12 * size * tool[:3, k]]).T, color=colour, lw=2.5)


def _frame_axes(ax, size: float) -> None:
    half = 0.6 * size
    ax.set_xlim(-half, half)
    ax.set_ylim(-half, half)
    ax.set_zlim(-0.2 * size, 1.3 * half)
    ax.set_box_aspect((1, 1, (1.3 * half + 0.2 * size) / (2 * half)))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


def plot_chain(chain: Chain, q, ax=None):
    """Draws a serial chain at q in 3-D as the simulator does: links as thick segments between the
    origins of ``chain.frames(q)`` shaded by depth along the view (near dark, far pale), joints as
    rings, joint axes (:func:`joint_axes`), the tool's x, y, z triad and a floor grid at z = 0.

    Args:
        chain: The arm.
        q: Joints, shape (dof,).
        ax: A matplotlib 3-D Axes to draw on; None makes a new Figure (no pyplot, no display) in the
            simulator's iso view.

    Returns:
        The Axes (its ``.figure`` is the Figure to save).
    """
    q = _chain_q(chain, q)
    if ax is None:
        fig = new_figure(figsize=(6, 6), layout="constrained")
        ax = fig.add_subplot(projection="3d")
        ax.view_init(*ISO_VIEW)
    elif getattr(ax, "name", "") != "3d":
        raise TypeError("ax: expected a 3-D Axes (projection='3d')")
    size = _arm_size(chain.frames(q))
    _draw_chain(ax, chain, q, size)
    _frame_axes(ax, size)
    return ax


#: Most frames :func:`animate_chain` writes.
MAX_FRAMES = 10_000


def animate_chain(chain: Chain, Q, path, fps: float = 30.0, size=(480, 480)) -> str:
    """Writes an animation of the chain through the joint configurations ``Q`` (one frame each,
    drawn by :func:`plot_chain` in the iso view, the axes' limits fixed over the whole motion) as a
    GIF (Pillow) or an MP4 (imageio with imageio-ffmpeg, the ``[sim]`` extra), atomically: under a
    temporary name renamed into place when complete (an interrupted write leaves nothing).

    Args:
        chain: The arm.
        Q: (K, dof) configurations, 1 <= K <= 10,000.
        path: ``.gif`` or ``.mp4`` file.
        fps: Frames per second (0.1 to 100; a GIF keeps 10 ms ticks).
        size: (width, height) in pixels, each 64 to 2048 (even for MP4).

    Returns:
        The path written.
    """
    import os

    from .files import AtomicPath

    check_chain(chain)
    Q = real_array(Q, "Q")
    if Q.ndim != 2 or Q.shape[1] != chain.dof or not 1 <= len(Q) <= MAX_FRAMES:
        raise ValueError(f"Q: expected shape (K, {chain.dof}) with 1 <= K <= {MAX_FRAMES}, got {Q.shape}")
    if not np.all(np.isfinite(Q)):
        raise ValueError("Q: contains NaN or inf")
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path: expected a file name, got {type(path).__name__}")
    kind = os.path.splitext(os.fspath(path))[1].lower()
    if kind not in (".gif", ".mp4"):
        raise ValueError(f"path: must end in .gif or .mp4, got {os.fspath(path)!r}")
    if isinstance(fps, bool) or not isinstance(fps, (int, float)) or not 0.1 <= fps <= 100:
        raise ValueError(f"fps: expected a number in [0.1, 100], got {fps!r}")
    try:
        width, height = (int(v) for v in size)
    except (TypeError, ValueError):
        raise ValueError(f"size: expected (width, height) in pixels, got {size!r}") from None
    if not (64 <= width <= 2048 and 64 <= height <= 2048):
        raise ValueError(f"size: each side must be 64 to 2048 pixels, got {size!r}")
    if kind == ".mp4":
        width, height = width - width % 2, height - height % 2
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    scale = max(_arm_size(chain.frames(q)) for q in Q[:: max(1, len(Q) // 50)])
    fig = new_figure(figsize=(width / 100, height / 100), dpi=100)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    images = []
    for q in Q:
        ax.cla()
        ax.view_init(*ISO_VIEW)
        _draw_chain(ax, chain, q, scale)
        _frame_axes(ax, scale)
        canvas.draw()
        images.append(np.asarray(canvas.buffer_rgba())[..., :3].copy())
    with AtomicPath(path) as tmp:
        if kind == ".gif":
            from PIL import Image

            pictures = [Image.fromarray(im).quantize(colors=255, method=Image.Quantize.MEDIANCUT) for im in images]
            pictures[0].save(tmp, format="GIF", save_all=True, append_images=pictures[1:], loop=0,
                             duration=max(10, int(round(1000.0 / fps / 10)) * 10))
        else:
            import imageio.v2 as imageio

            with imageio.get_writer(tmp, format="FFMPEG", mode="I", fps=fps, codec="libx264", macro_block_size=1,
                                    pixelformat="yuv420p", output_params=["-loglevel", "error"]) as writer:
                for im in images:
                    writer.append_data(im)
    return os.fspath(path)
