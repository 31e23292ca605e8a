"""Draws docs/reachability_ur5.png: the UR5's reachability map (README, "Reachability maps").

    .venv/bin/python docs/reachability_ur5.py
"""

import os

import robokin as rk
from robokin.plots_reachability import plot_reachability

HERE = os.path.dirname(os.path.abspath(__file__))

rmap = rk.reachability(rk.robots.ur5(), ((-1.0, 1.0), (-1.0, 1.0), (-0.7, 1.1)), 0.1, orientations=20, seed=0)
plot_reachability(rmap, os.path.join(HERE, "reachability_ur5.png"), axis="y", slices=[0.0, 0.3],
                  title="UR5: share of 20 random tool orientations solved per 10 cm voxel")
