"""Postures along a straight line (``python -m robokin.demo_postures``; ``make demo-postures``).

The PUMA 560 follows a straight line of tool frames twice: greedily (at each frame the closed-form
solution nearest the previous joints, :func:`robokin.closed.puma560_path`) and with the plan of
:func:`robokin.track_postures` (fewest reconfigurations, then least motion). A step that moves some
joint faster than ``qdot_max`` is a reconfiguration. Prints both counts and writes a figure of the
joint angles along the line with the reconfigurations marked.
"""

from __future__ import annotations

import argparse
import os

import numpy as np

from . import closed, robots
from .files import AtomicPath
from .postures import count_reconfigurations, track_postures

#: The demo's line: start joints, direction and length of the tool's straight move, waypoints,
#: time step and joint speed limit.
LINE_Q0 = (-0.79, 1.367, -3.266, 1.629, 0.45, -2.227)
LINE_DIRECTION = (-0.962, -0.141, 0.234)
LINE_LENGTH = 0.528
LINE_POINTS = 200
LINE_DT = 0.02
LINE_QDOT_MAX = 2.0


def demo_line():
    """``(chain, poses, q0, dt, qdot_max)`` of the demo: a straight line of the PUMA 560's tool,
    orientation kept, from the frame at ``LINE_Q0``."""
    chain = robots.puma560()
    q0 = np.array(LINE_Q0, dtype=float)
    T0 = chain.fk(q0)
    s = np.linspace(0.0, LINE_LENGTH, LINE_POINTS)
    direction = np.asarray(LINE_DIRECTION) / np.linalg.norm(LINE_DIRECTION)
    poses = np.repeat(T0[None], LINE_POINTS, axis=0)
    poses[:, :3, 3] += s[:, None] * direction[None, :]
    return chain, poses, q0, LINE_DT, LINE_QDOT_MAX


def postures_figure(q_greedy, r_greedy, q_plan, r_plan, title: str = ""):
    """Joint angles along the path (one panel per joint), greedy dashed and planned solid, with
    vertical marks where each reconfigures. Returns the matplotlib Figure."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    n = q_plan.shape[1]
    fig = Figure(figsize=(8, 1.2 * n + 0.8))
    axes = fig.subplots(n, 1, sharex=True)
    k = np.arange(len(q_plan))
    for i, ax in enumerate(np.atleast_1d(axes)):
        ax.plot(k, np.degrees(q_greedy[:, i]), "--", color="tab:red", lw=1.2, label="greedy")
        ax.plot(k, np.degrees(q_plan[:, i]), "-", color="tab:blue", lw=1.4, label="plan")
        for r in r_greedy:
            ax.axvline(r, color="tab:red", alpha=0.5, lw=0.8)
        for r in r_plan:
            ax.axvline(r, color="tab:blue", alpha=0.9, lw=1.2, ls="-.")
        ax.set_ylabel(f"q{i + 1} (deg)", fontsize=8)
        ax.tick_params(labelsize=7)
    axes[0].legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("waypoint (vertical lines: reconfigurations)", fontsize=8)
    if title:
        fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


#: A cuspidal orthogonal 3R arm (Baili, Wenger and Chablat's parametrisation, modified DH): d2, d3, d4, r2, r3.
CUSPIDAL_3R = (1.0, 2.0, 1.5, 1.0, 0.0)


def orthogonal_3r(d2, d3, d4, r2, r3):
    """The orthogonal 3R arm (Craig's modified DH, alpha = 0, -90, 90 deg; tool d4 along x3)."""
    from ._core import Chain

    tool = np.eye(4)
    tool[0, 3] = d4
    p = np.pi
    rows = [(0.0, 0.0, 0.0, 0.0, "R"), (d2, -p / 2, r2, 0.0, "R"), (d3, p / 2, r3, 0.0, "R")]
    return Chain.from_dh(rows, modified=True, tool=tool)


def aspects_figure(c, title: str = ""):
    """The aspects of a 3R arm on the (q2, q3) torus (sign of det J), its cusp points and, when
    there is one, the non-singular posture change of :func:`robokin.cuspidal`."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(5, 4.4))
    ax = fig.subplots()
    g = np.degrees(c.grid)
    ax.pcolormesh(g, g, c.sign.T, cmap="coolwarm", shading="nearest", vmin=-1.5, vmax=1.5)
    if len(c.cusps):
        ax.plot(np.degrees(c.cusps[:, 0]), np.degrees(c.cusps[:, 1]), "k*", ms=10, label="cusp points")
    if c.path is not None:
        w = np.degrees(np.remainder(c.path[:, 1:] + np.pi, 2 * np.pi) - np.pi)
        jumps = np.nonzero(np.any(np.abs(np.diff(w, axis=0)) > 180, axis=1))[0] + 1
        for seg in np.split(w, jumps):
            ax.plot(seg[:, 0], seg[:, 1], "g-", lw=2)
        ax.plot(w[[0, -1], 0], w[[0, -1], 1], "go", ms=6, label="posture change, no singularity")
    ax.set_xlabel("q2 (deg)")
    ax.set_ylabel("q3 (deg)")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(title or f"{c.aspects} aspects (red: det J > 0, blue: det J < 0)", fontsize=9)
    fig.tight_layout()
    return fig


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/postures_line.png", help="where to write the figure")
    parser.add_argument("--aspects-out", default="out/cuspidal_aspects.png",
                        help="where to write the figure of a cuspidal 3R arm's aspects")
    args = parser.parse_args(argv)
    from matplotlib.backend_bases import FigureCanvasBase

    for flag, path in (("--out", args.out), ("--aspects-out", args.aspects_out)):
        ext = os.path.splitext(path)[1][1:].lower()
        if ext and ext not in FigureCanvasBase.get_supported_filetypes():
            parser.error(f"{flag}: cannot write a figure as .{ext} (use .png, .pdf, .svg, ...)")
        if not os.path.basename(path):
            parser.error(f"{flag}: expected a file name, got {path!r}")
    ext = os.path.splitext(args.out)[1][1:].lower()
    chain, poses, q0, dt, vmax = demo_line()
    qg, ok, _ = closed.puma560_path(poses, q0)
    rg = count_reconfigurations(qg, dt, vmax, q0=q0, chain=chain)
    plan = track_postures(chain, poses, dt, qdot_max=vmax, q0=q0)
    print(f"PUMA 560: straight line of {len(poses)} tool frames, dt = {dt} s, qdot_max = {vmax} rad/s")
    print(f"  greedy (nearest solution): {len(rg)} reconfiguration(s) at waypoints {[int(k) for k in rg]}, "
          f"{int(ok.sum())}/{len(ok)} reached")
    print(f"  plan (track_postures):     {len(plan.reconfigurations)} reconfiguration(s) at waypoints "
          f"{[int(k) for k in plan.reconfigurations]}, {int(plan.success.sum())}/{len(ok)} reached, "
          f"motion {plan.motion:.3f} rad")
    fig = postures_figure(qg, rg, plan.q, plan.reconfigurations,
                          title=f"PUMA 560, straight line: greedy {len(rg)} vs planned "
                                f"{len(plan.reconfigurations)} reconfigurations")
    with AtomicPath(args.out) as tmp:
        fig.savefig(tmp, dpi=70, format=ext or "png")
    print(f"Figure written to {os.path.abspath(args.out)}")
    from .cuspidality import cuspidal

    arm = orthogonal_3r(*CUSPIDAL_3R)
    c = cuspidal(arm)
    print(f"Orthogonal 3R arm d2, d3, d4, r2, r3 = {CUSPIDAL_3R}: cuspidal = {c.cuspidal}; {c.evidence}")
    fig = aspects_figure(c, title=f"Orthogonal 3R {CUSPIDAL_3R}: {c.aspects} aspects, {len(c.cusps)} cusps")
    a_ext = os.path.splitext(args.aspects_out)[1][1:].lower()
    with AtomicPath(args.aspects_out) as tmp:
        fig.savefig(tmp, dpi=70, format=a_ext or "png")
    print(f"Figure written to {os.path.abspath(args.aspects_out)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
