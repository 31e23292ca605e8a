"""Figures of reachability maps (matplotlib, the ``[plot]`` extra): slices of the index through
the grid and a projection (the largest index along an axis). Files are written atomically."""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

from ._checks import choice, instance, real_array, rows
from ._figures import new_figure
from .files import AtomicPath
from .reachability import ReachabilityMap

__all__ = ["plot_reachability"]

_AXES = "xyz"


def plot_reachability(rmap: ReachabilityMap, path=None, axis: str = "z", slices: Optional[Sequence[float]] = None,
                      title: Optional[str] = None):
    """A figure of ``rmap``: slices of the reachability index perpendicular to ``axis`` (at the
    coordinates ``slices``, m; None: three evenly spread through the grid), then the projection
    along ``axis`` (the largest index over it). A planar map is one panel. ``title`` heads the
    figure (None: the orientations per voxel and the voxel size). With ``path`` the figure is also saved there (atomically: the
    whole file or none).

    Returns:
        The matplotlib Figure.
    """
    instance(rmap, "rmap", ReachabilityMap, "a ReachabilityMap")
    choice(axis, "axis", ("z",) if rmap.index.ndim == 2 else tuple(_AXES))
    if rmap.index.ndim == 2:
        panels = [("", rmap.index, (0, 1))]
    else:
        k = _AXES.index(axis)
        coords = rmap.axes[k]
        picks = _slices(coords, slices)
        panels = [(f"{axis} = {coords[i]:.3g} m", np.take(rmap.index, i, axis=k), [j for j in range(3) if j != k])
                  for i in picks]
        panels.append((f"projection along {axis} (max)", rmap.index.max(axis=k), [j for j in range(3) if j != k]))
    fig = new_figure(figsize=(3.2 * len(panels) + 0.8, 3.4), layout="constrained")
    axs = fig.subplots(1, len(panels), squeeze=False)[0]
    extent = rmap.extent
    image = None
    for ax, (label, plane, (a, b)) in zip(axs, panels):
        image = ax.imshow(plane.T, origin="lower", extent=(*extent[a], *extent[b]), vmin=0.0, vmax=1.0,
                          cmap="viridis", interpolation="nearest")
        ax.set_xlabel(f"{_AXES[a]} (m)")
        ax.set_ylabel(f"{_AXES[b]} (m)")
        ax.set_title(label, fontsize=9)
        ax.set_aspect("equal")
    fig.colorbar(image, ax=list(axs), shrink=0.85, label="reachability index")
    fig.suptitle(title or f"reachability ({rmap.orientations} orientations per voxel, {rmap.resolution:g} m voxels)",
                 fontsize=10)
    if path is not None:
        with AtomicPath(path) as tmp:
            fig.savefig(tmp, dpi=90)
    return fig


def _slices(coords: np.ndarray, slices) -> list:
    if slices is None:
        n = len(coords)
        return sorted({int(round(f * (n - 1))) for f in (0.25, 0.5, 0.75)})
    values = rows(np.atleast_1d(real_array(slices, "slices")), "slices", most=12)
    return [int(np.argmin(np.abs(coords - v))) for v in values]
