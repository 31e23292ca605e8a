"""Draws docs/traj.png, the README's trajectory figure: three UR5 joints through via points with
parabolic blends (robokin.traj.via_points), positions, velocities and accelerations.

Run: .venv/bin/python scripts/traj_figure.py
"""

from pathlib import Path

import numpy as np

from robokin import plots, traj
from robokin.files import AtomicPath

OUT = Path(__file__).resolve().parents[1] / "docs" / "traj.png"


def main() -> None:
    points = np.array([[0.0, -1.2, 1.0], [0.8, -0.6, 1.4], [1.2, -1.0, 0.4], [0.4, -1.4, 0.9]])
    tr = traj.via_points(points, vmax=[1.0, 0.8, 1.2], amax=[2.0, 2.0, 3.0], dt=0.005)
    fig = plots.trajectory_figure(tr, names=["shoulder pan", "shoulder lift", "elbow"],
                                  title="traj.via_points: straight segments, parabolic blends")
    for ax in fig.axes:
        for tv in tr.via_times:
            ax.axvline(tv, color="0.6", lw=0.8, ls=":")
    with AtomicPath(OUT) as tmp:
        fig.savefig(tmp, dpi=80)
    print(f"{OUT} ({OUT.stat().st_size // 1024} KB)")


if __name__ == "__main__":
    main()
