"""The RPR straight-line demo of the RPR study (``python -m robokin.demo``; ``make run``).

Tracks the line from point 1, on the workspace boundary (t1 = pi/2), to point 2 with the Reach
loop, once with the minimum-norm step and once with null-space joint-limit avoidance, prints a
summary and writes Figure 2 of the seed to a PNG.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from . import paths, robots
from .files import AtomicPath
from ._core import joint_limit_cost
from .reach import track

Q1, P2 = robots.RPR_LINE_Q1, robots.RPR_LINE_P2
#: Most path points the demo tracks and draws (--step 1e-9 would take hours).
MAX_POINTS = 1_000_000


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/rpr_line.png", help="where to write the figure")
    parser.add_argument("--step", type=float, default=1e-3, help="path point spacing (m)")
    args = parser.parse_args(argv)

    from matplotlib.backend_bases import FigureCanvasBase

    from .plots import rpr_line_figure

    # Checked before the work: the format comes from the extension (none: PNG).
    ext = os.path.splitext(args.out)[1][1:].lower()
    if ext and ext not in FigureCanvasBase.get_supported_filetypes():
        parser.error(f"--out: cannot write a figure as .{ext} (use .png, .pdf, .svg, ...)")
    if not os.path.basename(args.out):
        parser.error(f"--out: expected a file name, got {args.out!r}")
    chain = robots.rpr()
    p1 = chain.fk(Q1)[:2, 3]
    try:
        points = paths.line(p1, P2, args.step)
    except ValueError as exc:
        parser.error(f"--{exc}")
    if len(points) > MAX_POINTS:
        parser.error(f"--step: {args.step!r} gives {len(points)} path points, the demo draws at most {MAX_POINTS}")
    tracks = {}
    print(f"RPR (redundancy study): line from point 1 {np.round(p1, 3)} to point 2 {P2}, {len(points)} points")
    for label, nullspace in (("minimum norm", None), ("null-space joint-limit avoidance", "joint_limits")):
        start = time.perf_counter()
        tr = track(chain, points, Q1, nullspace=nullspace)
        elapsed = time.perf_counter() - start
        tracks[label] = tr
        z = joint_limit_cost(chain, tr.q)
        print(
            f"  {label:34s} converged {int(tr.converged.sum())}/{len(points)}, max error {tr.error.max():.2e} m, "
            f"mean z {z.mean():.4f}, {tr.iterations.mean():.2f} iterations/point, {1e6 * elapsed / len(points):.2f} us/point"
        )
    fig = rpr_line_figure(points, tracks, title="RPR arm, straight line from 1 to 2 (the RPR study, Figure 2)")
    # Written under a temporary name and renamed: an interrupted save leaves no truncated PNG.
    with AtomicPath(args.out) as tmp:
        fig.savefig(tmp, dpi=90, format=ext or "png")
    print(f"Figure written to {os.path.abspath(args.out)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
