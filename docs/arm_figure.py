"""Draws docs/arm_ur5.png: the UR5 of examples/arm.urdf drawn by robokin.plots.arm, with its joint
frames, joint axes and the tool's velocity ellipsoid (docs/plots.md).

    .venv/bin/python docs/arm_figure.py
"""

import os

import numpy as np

import robokin as rk

HERE = os.path.dirname(os.path.abspath(__file__))

chain = rk.Chain.from_urdf(os.path.join(HERE, "..", "examples", "arm.urdf"))
ax = rk.plots.arm(chain, np.array([0.3, -1.2, 1.4, -0.7, -1.57, 0.4]), ellipsoid=True)
ax.set_title("UR5 (examples/arm.urdf): rk.plots.arm(chain, q, ellipsoid=True)")
ax.figure.savefig(os.path.join(HERE, "arm_ur5.png"), dpi=80)
