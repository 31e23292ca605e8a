"""robokin.plots.joint_axes for serial chains (what the simulator and plots.arm draw): against the
DH frames and a URDF chain's joints. The drawing itself: tests/test_plots_arm.py."""

import math

import numpy as np
import pytest
import robokin as rk
from robokin import plots
from test_urdf import SMALL


def _on_line(point, origin, direction):
    return np.linalg.norm(np.cross(point - origin, direction)) < 1e-9


@pytest.mark.parametrize("name, after", [("ur5", False), ("puma560", False), ("iiwa14", False), ("panda", True)])
def test_joint_axes_are_the_dh_z_axes(name, after, rng):
    # Standard DH: joint i turns about z of frame i - 1 (frames[i]); modified DH (Craig): about z of
    # frame i (frames[i + 1]).
    chain = rk.robots.get(name)
    lo, hi = chain.limits
    for _ in range(5):
        q = rng.uniform(lo, hi)
        frames = chain.frames(q)
        for i, (point, direction) in enumerate(plots.joint_axes(chain, q)):
            f = frames[i + 1] if after else frames[i]
            assert abs(abs(np.dot(direction, f[:3, 2])) - 1) < 1e-12
            assert _on_line(point, f[:3, 3], f[:3, 2])


def test_joint_axes_of_a_urdf_chain():
    chain = rk.Chain.from_urdf(SMALL, "base_link", "tool")  # z, then x (prismatic), then y
    q = np.array([0.4, 0.1, -0.3])
    frames = chain.frames(q)
    axes = plots.joint_axes(chain, q)
    c, s = math.cos(0.4), math.sin(0.4)
    assert np.allclose(axes[0, 1], [0, 0, 1]) and _on_line(axes[0, 0], [0, 0, 0.1], np.array([0, 0, 1.0]))
    assert np.allclose(axes[1, 1], [c, s, 0]) and np.allclose(axes[1, 0], frames[2][:3, 3])
    # j3 sits at link3's origin, 0.5 + q1 + 0.2 along x1 (frames[3] carries the tool's 0.1 on top).
    j3 = np.array([0.8 * c, 0.8 * s, 0.1])
    assert np.allclose(np.abs(axes[2, 1]), np.abs([-s, c, 0])) and _on_line(axes[2, 0], j3, axes[2, 1])
    assert np.linalg.norm(axes[2, 0] - j3) < 1e-9
