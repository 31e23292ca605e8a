"""robokin.plots.arm / animate / teach: the drawing's links join the joint origins that the FK of
the chain cut after each joint gives (a DH arm and a URDF arm), the joint axes, frame triads, tool
triad and velocity ellipsoid against FK and the Jacobian, rendered pictures, the animation's
frames (written whole or not at all), and the sliders of teach."""

import sys

import numpy as np
import pytest
from PIL import Image

import robokin as rk
from robokin import plots, plots_arm
from test_printing import ARM


def lines(ax, gid):
    return [np.array(line.get_data_3d()).T for line in ax.lines if line.get_gid() == gid]


def dh_origins(chain, q):
    """The base and the origin after each joint, from the FK of the DH table cut after it."""
    state = chain.__getstate__()
    rows, modified = state[3], state[4]
    return np.array([np.zeros(3)] + [rk.Chain.from_dh(rows[:i], modified=modified).fk(q[:i])[:3, 3]
                                     for i in range(1, chain.dof + 1)])


def urdf_origins(chain, q):
    """The base and each joint's child link, from the FK of the URDF chain ending there (the last
    joint's with the fixed flange: the chain's tip)."""
    cut = [rk.Chain.from_urdf(ARM, tip=link).fk(q[:i + 1])[:3, 3] for i, link in enumerate(chain.link_names[1:-1])]
    return np.array([np.zeros(3), *cut, chain.fk(q)[:3, 3]])


def links_of(origins):
    return [np.stack([a, b]) for a, b in zip(origins[:-1], origins[1:]) if np.linalg.norm(b - a) > 1e-9]


def puma():
    return rk.robots.get("puma560")


Q_PUMA = np.radians([10, 40, -140, 20, 50, 30])
Q_UR5 = np.array([0.3, -1.2, 1.4, -0.7, -1.57, 0.4])


@pytest.mark.parametrize("case", ["puma", "ur5 urdf"])
def test_the_links_join_the_joint_origins_from_fk(case):
    if case == "puma":
        chain, q = puma(), Q_PUMA
        expected = links_of(dh_origins(chain, q))
    else:
        chain, q = rk.Chain.from_urdf(ARM), Q_UR5
        assert chain.link_names[-1] == "tool0" and len(chain.link_names) == chain.dof + 1
        expected = links_of(urdf_origins(chain, q))
    ax = rk.plots.arm(chain, q)
    drawn = lines(ax, "link")
    assert len(drawn) == len(expected) >= 3
    for seg, truth in zip(drawn, expected):
        np.testing.assert_allclose(seg, truth, atol=1e-12)


def test_triads_axes_and_the_tool_against_fk():
    chain, q = puma(), Q_PUMA
    T = chain.fk(q)
    ax = plots_arm.arm(chain, q)
    tool = lines(ax, "tool")
    assert len(tool) == 3
    for k, seg in enumerate(tool):
        np.testing.assert_allclose(seg[0], T[:3, 3], atol=1e-12)
        direction = (seg[1] - seg[0]) / np.linalg.norm(seg[1] - seg[0])
        np.testing.assert_allclose(direction, T[:3, k], atol=1e-12)
    frames = lines(ax, "frame")
    origins = dh_origins(chain, q)
    assert len(frames) == 3 * chain.dof
    for i in range(chain.dof):
        for seg in frames[3 * i:3 * i + 3]:
            np.testing.assert_allclose(seg[0], origins[i], atol=1e-12)
    # Standard DH: joint i turns about the z axis of frame i - 1, the base's z for the first.
    axes = lines(ax, "joint axis")
    assert len(axes) == chain.dof
    np.testing.assert_allclose(np.cross(axes[0][1] - axes[0][0], [0, 0, 1]), 0, atol=1e-12)
    bare = plots_arm.arm(chain, q, frames=False, axes=False)
    assert lines(bare, "frame") == [] and lines(bare, "joint axis") == [] and len(lines(bare, "tool")) == 3
    assert not any(c.get_gid() == "ellipsoid" for c in bare.collections)


def test_the_ellipsoid_is_the_jacobians():
    """Every drawn point x satisfies (x - p)^T (J J^T)^-1 (x - p) = r^2 for one r: the ellipsoid
    of the translational rows of the Jacobian about the tool point p, whatever its drawing scale."""
    chain, q = puma(), Q_PUMA
    ax = plots_arm.arm(chain, q, ellipsoid=True)
    (wire,) = [c for c in ax.collections if c.get_gid() == "ellipsoid"]
    points = np.concatenate([np.asarray(s) for s in wire._segments3d])
    J = chain.jacobian(q)[:3]
    d = points - chain.fk(q)[:3, 3]
    values = np.einsum("ij,jk,ik->i", d, np.linalg.inv(J @ J.T), d)
    assert np.ptp(values) < 1e-9 * values.max()


def test_rendered_pictures(tmp_path):
    for name, chain, q in (("puma560", puma(), Q_PUMA), ("ur5_urdf", rk.Chain.from_urdf(ARM), Q_UR5)):
        ax = rk.plots.arm(chain, q, ellipsoid=True)
        path = tmp_path / f"{name}.png"
        ax.figure.savefig(path, dpi=60)
        with Image.open(path) as im:
            rgb = np.asarray(im.convert("RGB")).astype(int)
        assert rgb.shape == (360, 360, 3)
        # The links' colour (between the near and far blues) covers a part of the picture.
        bluish = (rgb[..., 2] > rgb[..., 0] + 40) & (rgb[..., 2] > 120)
        assert 0.005 < bluish.mean() < 0.5


def test_arguments_are_checked():
    chain = puma()
    with pytest.raises(ValueError, match="q"):
        plots_arm.arm(chain, np.zeros(5))
    with pytest.raises(ValueError, match="q"):
        plots_arm.arm(chain, np.full(6, np.nan))
    with pytest.raises(TypeError, match="chain"):
        plots_arm.arm("puma", np.zeros(6))
    with pytest.raises(TypeError, match="frames"):
        plots_arm.arm(chain, np.zeros(6), frames="yes")
    from matplotlib.figure import Figure

    with pytest.raises(TypeError, match="ax"):
        plots_arm.arm(chain, np.zeros(6), ax=Figure().add_subplot())
    ax = Figure().add_subplot(projection="3d")
    assert plots_arm.arm(chain, np.zeros(6), ax=ax) is ax


def test_animate_writes_every_frame_as_gif_and_mp4_atomically(tmp_path):
    chain = rk.robots.ur5()
    q0 = np.array([0, -1.9, 1.7, -1.4, -1.57, 0])
    qs = rk.traj.quintic(q0, q0 + 0.6, np.linspace(0, 1, 7)).q
    gif = rk.plots.animate(chain, qs, tmp_path / "arm.gif", fps=10, size=(200, 160))
    with Image.open(gif) as im:
        assert im.n_frames == 7 and im.size == (200, 160)
        pictures = []
        for k in range(7):
            im.seek(k)
            assert im.info["duration"] == 100
            pictures.append(np.asarray(im.convert("RGB")).astype(int))
    assert all(np.abs(a - b).sum() > 0 for a, b in zip(pictures[:-1], pictures[1:]))  # the arm moves every frame
    mp4 = plots_arm.animate(chain, qs, str(tmp_path / "arm.mp4"), fps=10, size=(201, 160))
    assert open(mp4, "rb").read()[4:8] == b"ftyp"
    import imageio.v2 as imageio

    with imageio.get_reader(mp4) as reader:
        assert reader.count_frames() == 7
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.gif", "arm.mp4"]
    for bad, match in (((qs, tmp_path / "a.avi"), "path"), ((qs[:, :5], tmp_path / "a.gif"), "qs"),
                       ((qs * np.nan, tmp_path / "a.gif"), "qs")):
        with pytest.raises(ValueError, match=match):
            plots_arm.animate(chain, *bad)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["arm.gif", "arm.mp4"]


def test_an_interrupted_gif_animation_leaves_nothing(tmp_path, monkeypatch):
    from PIL import GifImagePlugin

    encode, calls = GifImagePlugin.getdata, []

    def interrupted(*args, **kwargs):
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return encode(*args, **kwargs)

    monkeypatch.setattr(GifImagePlugin, "getdata", interrupted)
    chain = rk.robots.ur5()
    qs = np.linspace(0, 0.5, 5)[:, None] * np.ones(6)
    with pytest.raises(KeyboardInterrupt):
        plots_arm.animate(chain, qs, tmp_path / "arm.gif", fps=10, size=(100, 80))
    assert len(calls) == 3 and list(tmp_path.iterdir()) == []


def test_teach_builds_a_slider_per_joint_and_redraws():
    import ipywidgets as widgets  # the test extra installs it
    chain = rk.Chain.from_urdf(ARM)
    box = rk.plots.teach(chain)
    assert isinstance(box, widgets.VBox)
    sliders, (image, text) = box.children[:-2], box.children[-2:]
    lo, hi = chain.limits
    assert [s.description for s in sliders] == list(chain.joint_names)
    assert np.allclose([s.min for s in sliders], lo) and np.allclose([s.max for s in sliders], hi)
    first = image.value
    assert first[:8] == b"\x89PNG\r\n\x1a\n"
    sliders[1].value = -1.0
    sliders[2].value = 1.2
    assert image.value != first
    q = np.array([s.value for s in sliders])
    xyz = chain.fk(q)[:3, 3]
    assert "xyz (" + ", ".join(f"{v:.4f}" for v in xyz) + ") m" in text.value


def test_teach_without_ipywidgets_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "ipywidgets", None)  # import ipywidgets raises ImportError
    with pytest.raises(ImportError, match=r"robokin\[teach\]"):
        plots.teach(puma())


def test_rk_plots_is_there_after_import_robokin():
    import subprocess

    code = "import robokin as rk; print(rk.plots.arm.__module__, rk.plots.teach.__name__)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["robokin.plots_arm", "teach"]
