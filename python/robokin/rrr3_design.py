"""The seed's design study of the 3-RRR (the 3-RRR project, section 3): workspace area against the
platform size, and the best second link for a given first one. The areas come from the core's
workspace maps (RRR3.workspace); this module only lays out the studies."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _core
from ._checks import number, positive, rows
from ._options import with_options

__all__ = ["AreaCurve", "BestL2", "STUDY_BASE_RADIUS", "STUDY_LINK", "STUDY_PLATFORM_RADIUS", "area_vs_platform_radius",
           "best_l2"]


@dataclass(frozen=True)
class AreaCurve:
    """Workspace area against one design parameter."""

    values: np.ndarray  # the parameter (m)
    area: np.ndarray    # largest singularity-free region at the orientation studied (m^2)
    base_radius: float  # the geometry the curve was computed for (m)
    l1: float
    l2: float

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
    base_radius: float     # the geometry the study was computed for (m)
    platform_radius: float


def _values(values, name: str) -> np.ndarray:
    return positive(rows(values, name), name)


# The geometry of the seed's design study (the 3-RRR project, section 3), not the simulator's
# robot (RRR3_DEFAULTS): a 0.15 m base radius, 0.10 m links, a 0.15 m equilateral platform.
STUDY_BASE_RADIUS, STUDY_LINK, STUDY_PLATFORM_RADIUS = 0.15, 0.10, 0.0866


@with_options(_core.RRR3WorkspaceOptions)
def area_vs_platform_radius(platform_radii=None, base_radius: float = STUDY_BASE_RADIUS, l1: float = STUDY_LINK,
                            l2: float = STUDY_LINK, *, areas=None, **options) -> AreaCurve:
    """Workspace area as a function of the platform radius (by default the seed's study: 0.15 m
    base radius, 0.10 m links).

    The area is RRR3Workspace.area: the largest region of the constant-orientation workspace
    (the options' orientation ``phi`` and working mode ``mode``) that no singularity crosses, on an
    n x n grid.

    Args:
        platform_radii: The radii tried (m); None: 30 from 0.01 m to ``base_radius``.
        base_radius, l1, l2: The rest of the geometry (m).
        areas: The function computing the areas of the robot rows, ``areas(robots, **options)``
            (None: the core's ``rrr3_region_areas``; robokin.dask passes its chunked one).

    Returns:
        AreaCurve of the radii and their areas.
    """
    areas = _core.rrr3_region_areas if areas is None else areas
    base_radius, l1, l2 = number(base_radius, "base_radius", positive=True), number(l1, "l1", positive=True), number(l2, "l2", positive=True)
    if platform_radii is None:
        with np.errstate(over="ignore"):  # a base radius near the largest double: said below
            platform_radii = np.linspace(0.01, base_radius, 30)
        if not np.all(np.isfinite(platform_radii)):
            raise ValueError(f"base_radius: too large for the default platform radii, got {base_radius!r}")
    radii = _values(platform_radii, "platform_radii")
    robots = np.column_stack((np.full_like(radii, base_radius), radii, np.full_like(radii, l1), np.full_like(radii, l2)))
    return AreaCurve(radii, areas(robots, **options), float(base_radius), float(l1), float(l2))


@with_options(_core.RRR3WorkspaceOptions)
def best_l2(l1_values, l2_values, base_radius: float = STUDY_BASE_RADIUS,
            platform_radius: float = STUDY_PLATFORM_RADIUS, *, areas=None, **options) -> BestL2:
    """For each l1, the l2 (among ``l2_values``) that makes the best use of the links.

    The raw area keeps growing with l2 (longer links reach farther), so the criterion is the
    workspace index ``area / (pi (l1 + l2)^2)``: the share of the disk one leg sweeps that the
    robot can use without crossing a singularity.

    Args:
        l1_values, l2_values: The link lengths tried (m).
        base_radius, platform_radius: The rest of the geometry (m); the seed's study's by default.
        areas: As :func:`area_vs_platform_radius`.

    Returns:
        BestL2 with the areas, the indices and the best l2 of each l1.
    """
    areas = _core.rrr3_region_areas if areas is None else areas
    base_radius, platform_radius = number(base_radius, "base_radius", positive=True), number(platform_radius, "platform_radius", positive=True)
    l1s, l2s = _values(l1_values, "l1_values"), _values(l2_values, "l2_values")
    g1, g2 = np.meshgrid(l1s, l2s, indexing="ij")
    robots = np.column_stack((np.full(g1.size, base_radius), np.full(g1.size, platform_radius), g1.ravel(), g2.ravel()))
    area = areas(robots, **options).reshape(g1.shape)
    index = area / (np.pi * (g1 + g2) ** 2)
    k = np.argmax(index, axis=1)
    return BestL2(l1s, l2s, area, index, l2s[k], area[np.arange(len(l1s)), k], float(base_radius),
                  float(platform_radius))
