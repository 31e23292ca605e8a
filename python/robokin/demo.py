"""The RPR straight-line demo of seed 000 (``python -m robokin.demo``; ``make run``).

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
from ._core import joint_limit_cost
from .reach import track

Q1, P2 = robots.RPR_LINE_Q1, robots.RPR_LINE_P2


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/rpr_line.png", help="where to write the figure")
    parser.add_argument("--step", type=float, default=1e-3, help="path point spacing (m)")
    args = parser.parse_args(argv)

    from .plots import rpr_line_figure

    chain = robots.rpr()
    p1 = chain.fk(Q1)[:2, 3]
    points = paths.line(p1, P2, args.step)
    tracks = {}
    print(f"RPR (seed 000): line from point 1 {np.round(p1, 3)} to point 2 {P2}, {len(points)} points")
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
    fig = rpr_line_figure(points, tracks, title="RPR arm, straight line from 1 to 2 (seed 000, Figure 2)")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=90)
    print(f"Figure written to {os.path.abspath(args.out)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
