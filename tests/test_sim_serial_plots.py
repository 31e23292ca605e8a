"""robokin.plots for serial chains: joint axes against the DH frames, plot_chain's lines against
chain.frames, animate_chain's files (GIF frames, MP4 header, atomic writes)."""

import io
import math

import numpy as np
import pytest
import robokin as rk
from PIL import Image
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


def test_plot_chain_draws_the_links_between_the_frames_origins():
    chain = rk.robots.puma560()
    q = np.radians([10, 40, -140, 20, 50, 30])
    ax = plots.plot_chain(chain, q)
    origins = chain.frames(q)[:, :3, 3]
    segments = [np.array(line.get_data_3d()).T for line in ax.lines if line.get_linewidth() == 7]
    expected = [(origins[i], origins[i + 1]) for i in range(6) if np.linalg.norm(origins[i + 1] - origins[i]) > 1e-9]
    assert len(segments) == len(expected)
    for seg, (a, b) in zip(segments, expected):
        assert np.allclose(seg, [a, b], atol=1e-12)
    # Shaded by depth along the view: the link nearest the viewer is the darkest.
    view = np.array([math.cos(math.radians(ax.elev)) * math.cos(math.radians(ax.azim)),
                     math.cos(math.radians(ax.elev)) * math.sin(math.radians(ax.azim)), math.sin(math.radians(ax.elev))])
    lines = [line for line in ax.lines if line.get_linewidth() == 7]
    depth = [float(np.dot(0.5 * (a + b), view)) for a, b in expected]
    brightness = [sum(line.get_color()) for line in lines]
    assert int(np.argmax(depth)) == int(np.argmin(brightness))
    ax.figure.savefig(io.BytesIO(), format="png")  # draws without a display
    with pytest.raises(ValueError, match="q"):
        plots.plot_chain(chain, np.zeros(5))
    with pytest.raises(TypeError, match="ax"):
        from matplotlib.figure import Figure

        plots.plot_chain(chain, q, ax=Figure().add_subplot())


def test_animate_chain_writes_gif_and_mp4_atomically(tmp_path):
    chain = rk.robots.ur5()
    q0 = np.array([0, -1.9, 1.7, -1.4, -1.57, 0])
    Q = rk.traj.quintic(q0, q0 + 0.4, np.linspace(0, 1, 6)).q
    gif = plots.animate_chain(chain, Q, tmp_path / "arm.gif", fps=10, size=(200, 160))
    with Image.open(gif) as im:
        assert im.n_frames == 6 and im.size == (200, 160)
        first = np.asarray(im.convert("RGB")).astype(int)
        im.seek(5)
        last = np.asarray(im.convert("RGB")).astype(int)
    assert np.abs(first - last).sum() > 0  # the arm moved
    mp4 = plots.animate_chain(chain, Q, str(tmp_path / "arm.mp4"), fps=10, size=(201, 160))
    assert open(mp4, "rb").read()[4:8] == b"ftyp"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.gif", "arm.mp4"]
    for bad, match in (((Q, tmp_path / "a.avi"), "path"), ((Q[:, :5], tmp_path / "a.gif"), "Q"),
                       ((Q * np.nan, tmp_path / "a.gif"), "Q")):
        with pytest.raises(ValueError, match=match):
            plots.animate_chain(chain, *bad)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.gif", "arm.mp4"]
