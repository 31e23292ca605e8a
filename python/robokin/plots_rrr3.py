"""Matplotlib figures of the 3-RRR: the robot at a pose, a workspace map with its singular cells in
red, the design-study curves. Everything drawn comes from the core (RRR3.points, RRR3.workspace,
robokin.rrr3_design). Figures are returned, made outside pyplot, not shown."""

from __future__ import annotations

import numpy as np

from . import _core, rrr3_design
from ._checks import instance, rows
from ._figures import new_figure
from ._options import with_options

__all__ = ["CELL_COLOURS", "plot_robot", "plot_workspace", "plot_design"]

# Workspace cell codes -> colours: unreachable, regular, parallel singular, serial singular.
CELL_COLOURS = np.array([[1.0, 1.0, 1.0], [0.68, 0.82, 0.93], [0.85, 0.1, 0.1], [0.95, 0.6, 0.1]])


def _axes(ax):
    """The Figure and Axes to draw on: ``ax``'s, or a new Figure's outside pyplot (its global state
    is not safe to share between threads; save the figure with fig.savefig)."""
    if ax is not None:
        return ax.figure, ax
    fig = new_figure(figsize=(6, 6))
    return fig, fig.add_subplot()


def _path(path):
    """None, or the path as a finite (K, 2) array."""
    return None if path is None else rows(path, "path", (2,))


def plot_robot(robot, pose, mode=None, ax=None, path=None):
    """Draws the robot at ``pose`` in ``mode`` (None: the core's default working mode): base, legs
    O-A-B, platform; optional (K, 2) path.

    Returns:
        (figure, axes).
    """
    if mode is None:
        mode = _core.RRR3WorkspaceOptions().mode  # the core's one default working mode
    pts = robot.points(pose, mode)  # checks pose and mode
    pose = np.asarray(pose, dtype=float)
    path = _path(path)
    fig, ax = _axes(ax)
    o, a, b = pts["O"], pts["A"], pts["B"]
    s = robot.singularity(pose, mode)
    if path is not None:
        ax.plot(path[:, 0], path[:, 1], color="0.6", lw=1, ls="--", label="path")
    ax.fill(*np.vstack((o, o[:1])).T, color="0.92", ec="0.4", lw=1, label="base")
    for i in range(3):
        ax.plot([o[i, 0], a[i, 0]], [o[i, 1], a[i, 1]], color="tab:blue", lw=4, solid_capstyle="round",
                label="link 1" if i == 0 else None)
        ax.plot([a[i, 0], b[i, 0]], [a[i, 1], b[i, 1]], color="tab:green", lw=3, solid_capstyle="round",
                label="link 2" if i == 0 else None)
        ax.annotate(f"O{i}", o[i], textcoords="offset points", xytext=(6, -12), fontsize=9)
    colour = {"none": "tab:purple", "parallel": "tab:red", "serial": "tab:orange"}[s.kind]
    ax.fill(*np.vstack((b, b[:1])).T, color=colour, alpha=0.35, ec=colour, lw=2, label="platform")
    ax.plot(*o.T, "ks", ms=8)
    ax.plot(*a.T, "o", color="tab:blue", ms=6, mfc="white")
    ax.plot(*b.T, "o", color=colour, ms=6, mfc="white")
    ax.plot(pose[0], pose[1], "+", color=colour, ms=12, mew=2)
    ax.set_title(f"pose ({pose[0]:.3f}, {pose[1]:.3f}, {np.degrees(pose[2]):.1f} deg), mode {tuple(mode)}\n"
                 f"{s.kind}: det A / R_e = {s.det_a_norm:.3f}, det B / l1^3 = {s.det_b_norm:.3f}", fontsize=10)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="upper right", fontsize=8)
    reach = robot.base_radius + 0.5 * (robot.l1 + robot.l2)
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    return fig, ax


@with_options(_core.RRR3WorkspaceOptions)
def plot_workspace(robot, *, ax=None, **options):
    """Constant-orientation workspace map (``robot.workspace(**options)``): reachable cells in blue,
    singular ones in red (parallel) and orange (serial), the base joints as squares.

    Returns:
        (figure, axes, RRR3Workspace).
    """
    w = robot.workspace(**options)  # checks the options
    shown = _core.RRR3WorkspaceOptions(**options)
    fig, ax = _axes(ax)
    ax.imshow(CELL_COLOURS[w.cells], origin="lower", extent=w.extent, interpolation="nearest")
    o = robot.base_joints
    ax.plot(*o.T, "ks", ms=7)
    ax.set_title(f"workspace at phi = {np.degrees(shown.phi):.1f} deg, mode {shown.mode}\n"
                 f"reachable {w.reachable_area * 1e4:.0f} cm^2, largest singularity-free region "
                 f"{w.area * 1e4:.0f} cm^2", fontsize=10)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    from matplotlib.patches import Patch

    ax.legend(handles=[Patch(color=CELL_COLOURS[1], label="reachable"), Patch(color=CELL_COLOURS[2], label="parallel"),
                       Patch(color=CELL_COLOURS[3], label="serial")], loc="upper right", fontsize=8)
    return fig, ax, w


def _links(l1: float, l2: float) -> str:
    return f"l1 = l2 = {l1 * 100:g} cm" if l1 == l2 else f"l1 = {l1 * 100:g} cm, l2 = {l2 * 100:g} cm"


def plot_design(curve: "rrr3_design.AreaCurve | None" = None, best: "rrr3_design.BestL2 | None" = None):
    """The design study: area against platform radius, and the best l2 for each l1.

    Computes the seed's studies (0.15 m base radius, 0.10 m links) when not given; the titles give
    the geometry the curve was computed for.

    Returns:
        (figure, (axes_area, axes_l2)).
    """
    instance(curve, "curve", rrr3_design.AreaCurve, "an rrr3_design.AreaCurve", optional=True)
    instance(best, "best", rrr3_design.BestL2, "an rrr3_design.BestL2", optional=True)
    curve = curve or rrr3_design.area_vs_platform_radius()
    # 627 robots: a coarser grid than one map's keeps the figure quick.
    best = best or rrr3_design.best_l2(np.linspace(0.05, 0.15, 11), np.linspace(0.02, 0.30, 57), n=100)
    fig = new_figure(figsize=(11, 4.5))
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot(curve.values * 100, curve.area * 1e4, "o-", ms=3)
    k = int(np.argmax(curve.area))
    ax1.axvline(curve.values[k] * 100, color="0.5", ls=":", label=f"largest: R_e = {curve.values[k] * 100:.1f} cm")
    ax1.axvline(15 / np.sqrt(3), color="tab:red", ls="--", lw=1, label="seed: 15 cm side (R_e = 8.7 cm)")
    ax1.legend(fontsize=8, loc="upper left")
    ax1.set_xlabel("platform radius R_e (cm)")
    ax1.set_ylabel("largest singularity-free area (cm^2)")
    ax1.set_title(f"area vs platform size (R_b = {curve.base_radius * 100:g} cm, "
                  f"{_links(curve.l1, curve.l2)})", fontsize=10)
    ax1.grid(alpha=0.3)
    ax2.plot(best.l1 * 100, best.best_l2 * 100, "o-", ms=4, label="best l2")
    ax2.plot(best.l1 * 100, best.l1 * 100, color="0.6", ls="--", lw=1, label="l2 = l1")
    ax2.set_xlabel("l1 (cm)")
    ax2.set_ylabel("best l2 (cm)")
    ax2.set_title(f"best l2 for a given l1 (max of area / pi (l1 + l2)^2)\n"
                  f"R_b = {best.base_radius * 100:g} cm, R_e = {best.platform_radius * 100:.3g} cm", fontsize=10)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    return fig, (ax1, ax2)
