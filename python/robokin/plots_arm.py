"""A serial arm drawn in 3-D as the simulator draws it (matplotlib, the ``[plot]`` extra): at one
configuration (:func:`arm`), along a joint path into a GIF or MP4 (:func:`animate`), and under
sliders per joint in a notebook (:func:`teach`, ipywidgets: the ``[teach]`` extra).

Also reached as ``robokin.plots.arm``, ``robokin.plots.animate`` and ``robokin.plots.teach``.
Figures are made without pyplot (no display, safe in threads) and returned, not shown.
"""

from __future__ import annotations

import io
import math
import os

import numpy as np

from ._checks import chain as check_chain
from ._checks import file_name, flag, joints, number, pixels, rows
from ._core import Chain
from ._figures import new_figure
from .plots import joint_axes

__all__ = ["ISO_VIEW", "MAX_FRAMES", "animate", "arm", "teach"]

#: Preset view of :func:`arm` (elevation, azimuth in degrees): the simulator's iso view.
ISO_VIEW = (25.0, -50.0)
#: Most frames :func:`animate` writes.
MAX_FRAMES = 10_000

# Colours (as the simulator's serial scene): links from near to far, joints, joint axes, x y z triads.
_LINK_NEAR, _LINK_FAR = "#2e62b2", "#96b0d6"
_JOINT_EDGE, _JOINT_AXIS = "#1e1e1e", "#78788c"
_TRIAD = ("#d23232", "#32a03c", "#3250dc")
# Lengths drawn, as fractions of the arm's size: joint axes (half), frame triads, the tool triad,
# the velocity ellipsoid's longest semi-axis.
_AXIS, _FRAME, _TOOL, _ELLIPSOID = 0.07, 0.06, 0.12, 0.25
# Each kind of line carries its name as its gid (Artist.get_gid): "link", "joint axis", "frame",
# "tool", "ellipsoid", "floor".


def _chain_q(chain, q, name: str = "q") -> np.ndarray:
    return joints(check_chain(chain), q, name)


def _arm_size(frames: np.ndarray) -> float:
    """The length of the polyline through the frames' origins (at least 0.1 m): the drawing's scale."""
    origins = frames[:, :3, 3]
    return max(float(np.sum(np.linalg.norm(np.diff(origins, axis=0), axis=1))), 0.1)


def _floor(ax, size: float) -> None:
    spacing = 10 ** np.floor(np.log10(size / 4.0))
    k = int(np.ceil(1.25 * size / spacing))
    for c in np.arange(-k, k + 1) * spacing:
        ax.plot([c, c], [-k * spacing, k * spacing], [0, 0], color="0.88", lw=0.6, gid="floor")
        ax.plot([-k * spacing, k * spacing], [c, c], [0, 0], color="0.88", lw=0.6, gid="floor")


def _links(ax, origins: np.ndarray, size: float) -> None:
    """Segments between consecutive origins, shaded by depth along the view (near dark, far pale)."""
    from matplotlib.colors import to_rgb

    elev, azim = np.radians(ax.elev), np.radians(ax.azim)
    view = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    near, far = np.array(to_rgb(_LINK_NEAR)), np.array(to_rgb(_LINK_FAR))
    for a, b in zip(origins[:-1], origins[1:]):
        if np.linalg.norm(b - a) <= 1e-9:
            continue
        depth = float(np.dot(0.5 * (a + b), view))
        t = float(np.clip(0.5 - depth / (1.6 * size), 0.0, 1.0))
        ax.plot(*np.stack([a, b]).T, color=near + (far - near) * t, lw=7, solid_capstyle="round", gid="link")


def _triad(ax, T: np.ndarray, length: float, lw: float, gid: str) -> None:
    for k, colour in enumerate(_TRIAD):
        ax.plot(*np.stack([T[:3, 3], T[:3, 3] + length * T[:3, k]]).T, color=colour, lw=lw, gid=gid)


def _ellipsoid(ax, chain: Chain, q: np.ndarray, center: np.ndarray, size: float) -> None:
    """The translational velocity ellipsoid at the tool, scaled so its longest semi-axis is
    _ELLIPSOID * size (its shape and directions are the Jacobian's; its scale is the drawing's)."""
    axes, lengths = chain.ellipsoid(q, part="translation")
    if lengths[0] <= 0:
        return  # the tool cannot move: nothing to draw
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 25), np.linspace(0, np.pi, 13))
    sphere = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])  # (3, 13, 25)
    radii = _ELLIPSOID * size * np.asarray(lengths) / lengths[0]
    points = np.einsum("ij,jkl->ikl", axes * radii, sphere) + center[:, None, None]
    ax.plot_wireframe(*points, color="#b05fc0", lw=0.5, alpha=0.6, gid="ellipsoid")


def _draw(ax, chain: Chain, q: np.ndarray, size: float, frames: bool, axes: bool, ellipsoid: bool) -> None:
    """The arm on a 3-D Axes: floor, links, joint axes, joints, frame triads, tool triad, ellipsoid."""
    all_frames = chain.frames(q)
    origins = all_frames[:, :3, 3]
    _floor(ax, size)
    _links(ax, origins, size)
    if axes:
        for point, direction in joint_axes(chain, q):
            ends = np.stack([point - _AXIS * size * direction, point + _AXIS * size * direction])
            ax.plot(*ends.T, color=_JOINT_AXIS, lw=2, gid="joint axis")
    ax.scatter(*origins[:-1].T, s=40, facecolor="white", edgecolor=_JOINT_EDGE, depthshade=False)
    if frames:
        for T in all_frames[:-1]:
            _triad(ax, T, _FRAME * size, 1.0, "frame")
    _triad(ax, all_frames[-1], _TOOL * size, 2.5, "tool")
    if ellipsoid:
        _ellipsoid(ax, chain, q, origins[-1], size)


def _limits(ax, size: float) -> None:
    half = 0.6 * size
    ax.set_xlim(-half, half)
    ax.set_ylim(-half, half)
    ax.set_zlim(-0.2 * size, 1.3 * half)
    ax.set_box_aspect((1, 1, (1.3 * half + 0.2 * size) / (2 * half)))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


def arm(chain: Chain, q, ax=None, *, frames=True, axes=True, ellipsoid=False):
    """Draws a serial arm at q in 3-D as the simulator does: links as thick segments between the
    origins of ``chain.frames(q)`` (the base, then the frame after each joint) shaded by depth along
    the view, joints as rings, the tool's x, y, z triad (always) and a floor grid at z = 0; the
    axes' limits are set from the arm's length.

    Args:
        chain: The arm.
        q: Joints, shape (dof,) (radians, metres).
        ax: A matplotlib 3-D Axes to draw on; None makes a new Figure (no pyplot, no display) in the
            simulator's iso view (:data:`ISO_VIEW`).
        frames: Draw each joint's frame as a small x, y, z triad (red, green, blue).
        axes: Draw each joint's axis as a short grey segment through it
            (:func:`robokin.plots.joint_axes`).
        ellipsoid: Draw the tool's translational velocity ellipsoid (``chain.ellipsoid``) as a
            wireframe, its longest semi-axis a quarter of the arm's length.

    Returns:
        The Axes (its ``.figure`` is the Figure to save).

    Raises:
        TypeError: chain is not a Chain; ax is not a 3-D Axes; a flag is not a bool.
        ValueError: q has not dof finite entries.
    """
    q = _chain_q(chain, q)
    flags = [flag(v, n) for v, n in ((frames, "frames"), (axes, "axes"), (ellipsoid, "ellipsoid"))]
    if ax is None:
        fig = new_figure(figsize=(6, 6), layout="constrained")
        ax = fig.add_subplot(projection="3d")
        ax.view_init(*ISO_VIEW)
    elif getattr(ax, "name", "") != "3d":
        raise TypeError("ax: expected a 3-D Axes (projection='3d')")
    size = _arm_size(chain.frames(q))
    _draw(ax, chain, q, size, *flags)
    _limits(ax, size)
    return ax


def _animate_arguments(chain, qs, path, fps, size):
    """The checked arguments of :func:`animate`: qs, the file's kind, fps, (width, height)."""
    check_chain(chain)
    qs = rows(qs, "qs", (chain.dof,), most=MAX_FRAMES)
    kind = file_name(path, "path", (".gif", ".mp4"))
    fps = number(fps, "fps", minimum=0.1, maximum=100)
    width, height = pixels(size, "size", 64, 2048)
    if kind == ".mp4":
        width, height = width - width % 2, height - height % 2
    return qs, kind, fps, (width, height)


def animate(chain: Chain, qs, path, fps: float = 30.0, size=(480, 480)) -> str:
    """Writes an animation of the arm through the joint configurations ``qs``, one frame each (drawn
    as :func:`arm` draws, in the iso view, the axes' limits fixed over the whole motion), as a GIF
    (Pillow) or an MP4 (imageio with imageio-ffmpeg, the ``[sim]`` extra). Frames stream to the
    file as they are drawn (memory does not grow with their number), under a temporary name
    renamed into place when complete: an interrupted write leaves nothing.

    Args:
        chain: The arm.
        qs: (K, dof) configurations, 1 <= K <= :data:`MAX_FRAMES`.
        path: ``.gif`` or ``.mp4`` file.
        fps: Frames per second (0.1 to 100; a GIF shows frames on 10 ms ticks, at least 20 ms each:
            :class:`robokin.gif.GifWriter`).
        size: (width, height) in pixels, each 64 to 2048 (made even for MP4).

    Returns:
        The path written.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from .files import AtomicPath
    from .gif import GifWriter

    qs, kind, fps, (width, height) = _animate_arguments(chain, qs, path, fps, size)
    scale = max(_arm_size(chain.frames(q)) for q in qs[:: max(1, len(qs) // 50)])
    fig = new_figure(figsize=(width / 100, height / 100), dpi=100)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")

    def frames():
        for q in qs:
            ax.cla()
            ax.view_init(*ISO_VIEW)
            _draw(ax, chain, q, scale, True, True, False)
            _limits(ax, scale)
            canvas.draw()
            yield np.asarray(canvas.buffer_rgba())[..., :3]

    with AtomicPath(path) as tmp:
        if kind == ".gif":
            with GifWriter(tmp, (width, height), 1.0 / fps) as writer:
                for image in frames():
                    writer.add(image)
        else:
            import imageio.v2 as imageio

            with imageio.get_writer(tmp, format="FFMPEG", mode="I", fps=fps, codec="libx264", macro_block_size=1,
                                    pixelformat="yuv420p", output_params=["-loglevel", "error"]) as writer:
                for image in frames():
                    writer.append_data(np.ascontiguousarray(image))
    return os.fspath(path)


def _slider_range(lower: float, upper: float, prismatic: bool):
    """A joint's slider range: its limits, or +-pi rad (revolute) / +-1 m (prismatic) where unlimited."""
    default = 1.0 if prismatic else math.pi
    return (lower if math.isfinite(lower) else -default), (upper if math.isfinite(upper) else default)


def _pose_html(T: np.ndarray) -> str:
    from . import pose

    xyz = ", ".join(f"{v:.4f}" for v in T[:3, 3])
    rpy = ", ".join(f"{math.degrees(v):.2f}" for v in pose.rpy(T))
    rows = "\n".join("  ".join(f"{v:8.4f}" for v in row) for row in T)
    return f"<pre>tool: xyz ({xyz}) m, rpy ({rpy}) deg\n{rows}</pre>"


def teach(chain: Chain, q=None):
    """Sliders per joint (ranges: the joint limits) redrawing the arm (:func:`arm`) and showing the
    tool pose, for a Jupyter notebook: display the returned widget (the cell's value).

    Args:
        chain: The arm.
        q: Starting joints, shape (dof,); None: zeros, clipped into the limits. An unlimited joint's
            slider spans -pi to pi rad (revolute) or -1 to 1 m (prismatic).

    Returns:
        An ``ipywidgets.VBox``: the sliders (radians, metres; described by the joint names), the
        picture (an ``ipywidgets.Image``, PNG) and the tool pose (an ``ipywidgets.HTML``: xyz in
        metres, roll, pitch, yaw in degrees, the 4 x 4 matrix), redrawn whenever a slider moves.

    Raises:
        ImportError: ipywidgets is not installed (``pip install 'robokin[teach]'``).
    """
    check_chain(chain)
    try:
        import ipywidgets as widgets
    except ImportError:
        raise ImportError("robokin.plots.teach needs ipywidgets: pip install 'robokin[teach]'") from None
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    lower, upper = chain.limits
    ranges = [_slider_range(lo, hi, kind == "P") for lo, hi, kind in zip(lower, upper, chain.joint_types)]
    start = np.clip(np.zeros(chain.dof), lower, upper) if q is None else _chain_q(chain, q)
    start = np.clip(start, [r[0] for r in ranges], [r[1] for r in ranges])
    sliders = [widgets.FloatSlider(value=v, min=lo, max=hi, step=(hi - lo) / 500, description=name,
                                   continuous_update=False, readout_format=".3f")
               for v, (lo, hi), name in zip(start, ranges, chain.joint_names)]
    # The scale is fixed over the sliders' ranges: the picture does not zoom as the arm moves.
    corners = [start] + [np.array([r[k] for r in ranges]) for k in (0, 1)]
    scale = max(_arm_size(chain.frames(c)) for c in corners)
    fig = new_figure(figsize=(5, 5), dpi=80, layout="constrained")
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    image = widgets.Image(format="png")
    text = widgets.HTML()

    def redraw(change=None):
        values = np.array([s.value for s in sliders])
        ax.cla()
        ax.view_init(*ISO_VIEW)
        _draw(ax, chain, values, scale, True, True, False)
        _limits(ax, scale)
        canvas.draw()
        png = io.BytesIO()
        canvas.print_png(png)
        image.value = png.getvalue()
        text.value = _pose_html(chain.fk(values))

    for s in sliders:
        s.observe(redraw, names="value")
    redraw()
    return widgets.VBox([*sliders, image, text])
