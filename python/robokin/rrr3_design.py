"""The seed's design study of the 3-RRR (the 3-RRR project, section 3): workspace area against the
platform size, and the best second link for a given first one. The areas come from the core's
workspace maps (RRR3.workspace); this module only lays out the studies."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _core
from ._checks import number

__all__ = ["AreaCurve", "BestL2", "area_vs_platform_radius", "best_l2"]


@dataclass(frozen=True)
class AreaCurve:
    """Workspace area against one design parameter."""

    values: np.ndarray  # the parameter (m)
    area: np.ndarray    # largest singularity-free region at the orientation studied (m^2)
    base_radius: float = 0.15  # the geometry the curve was computed for (m)
    l1: float = 0.10
    l2: float = 0.10

    @property
    def best(self) -> float:
        """The parameter value of the largest area."""
        return float(self.values[int(np.argmax(self.area))])


@dataclass(frozen=True)
class BestL2:
    """For each l1, the l2 of the best workspace index."""

    l1: np.ndarray
    l2: np.ndarray        # the l2 values tried
    area: np.ndarray      # (len(l1), len(l2)) largest singularity-free region (m^2)
    index: np.ndarray     # area / (pi (l1 + l2)^2): the share of one leg's reach disk that is usable
    best_l2: np.ndarray   # (len(l1),) the l2 of the largest index
    best_area: np.ndarray  # the area there
    base_radius: float = 0.15  # the geometry the study was computed for (m)
    platform_radius: float = 0.0866


def _values(values, name: str) -> np.ndarray:
    try:
        v = np.asarray(values)
        if v.dtype.kind not in "biuf":  # complex would lose its imaginary part in a float cast
            raise TypeError
        v = v.astype(float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected an array of real numbers") from None
    if v.ndim != 1 or v.size == 0:
        raise ValueError(f"{name}: expected a non-empty 1-D array, got shape {v.shape}")
    if not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise ValueError(f"{name}: lengths must be positive and finite")
    return v


def area_vs_platform_radius(platform_radii=None, base_radius: float = 0.15, l1: float = 0.10, l2: float = 0.10,
                            phi: float = 0.0, mode=(1, 1, 1), n: int = 150, tol: float = _core.RRR3_DEFAULTS["singular_tol"],
                            *, areas=None) -> AreaCurve:
    """Workspace area as a function of the platform radius (the seed: 0.15 m base radius, 0.10 m links).

    The area is RRR3Workspace.area: the largest region of the constant-orientation workspace
    (orientation ``phi``, working mode ``mode``) that no singularity crosses, on an n x n grid.
    ``areas``: the function computing the areas of the robot rows (None: the core's
    ``rrr3_region_areas``; robokin.dask passes its chunked one).
    """
    areas = _core.rrr3_region_areas if areas is None else areas
    base_radius, l1, l2 = number(base_radius, "base_radius", positive=True), number(l1, "l1", positive=True), number(l2, "l2", positive=True)
    radii = _values(np.linspace(0.01, base_radius, 30) if platform_radii is None else platform_radii, "platform_radii")
    robots = np.column_stack((np.full_like(radii, base_radius), radii, np.full_like(radii, l1), np.full_like(radii, l2)))
    return AreaCurve(radii, areas(robots, phi, mode, n, tol), float(base_radius), float(l1),
                     float(l2))


def best_l2(l1_values, l2_values, base_radius: float = 0.15, platform_radius: float = 0.0866, phi: float = 0.0,
            mode=(1, 1, 1), n: int = 100, tol: float = _core.RRR3_DEFAULTS["singular_tol"], *,
            areas=None) -> BestL2:
    """For each l1, the l2 (among ``l2_values``) that makes the best use of the links.

    The raw area keeps growing with l2 (longer links reach farther), so the criterion is the
    workspace index ``area / (pi (l1 + l2)^2)``: the share of the disk one leg sweeps that the
    robot can use without crossing a singularity. The default platform radius is the seed's
    0.15 m equilateral platform (side / sqrt(3)). ``areas``: as :func:`area_vs_platform_radius`.
    """
    areas = _core.rrr3_region_areas if areas is None else areas
    base_radius, platform_radius = number(base_radius, "base_radius", positive=True), number(platform_radius, "platform_radius", positive=True)
    l1s, l2s = _values(l1_values, "l1_values"), _values(l2_values, "l2_values")
    g1, g2 = np.meshgrid(l1s, l2s, indexing="ij")
    robots = np.column_stack((np.full(g1.size, base_radius), np.full(g1.size, platform_radius), g1.ravel(), g2.ravel()))
    area = areas(robots, phi, mode, n, tol).reshape(g1.shape)
    index = area / (np.pi * (g1 + g2) ** 2)
    k = np.argmax(index, axis=1)
    return BestL2(l1s, l2s, area, index, l2s[k], area[np.arange(len(l1s)), k], float(base_radius),
                  float(platform_radius))
