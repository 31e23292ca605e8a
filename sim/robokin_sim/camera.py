"""The serial scene's camera: an orthographic 3-D projection, orbited, zoomed and resized.

The camera looks at ``target`` from the direction ``d = (cos el cos az, cos el sin az, sin el)``
(azimuth ``az`` about the base z axis from +x, elevation ``el`` above the floor). The screen's
right is ``r = (-sin az, cos az, 0)``, its up ``u = d x r``; a world point ``p`` is drawn at
``centre + scale (r . (p - target), -u . (p - target))`` pixels (``centre`` right of the middle of
the drawing area, :data:`CENTRE`, clear of the panel at the top left), and ``d . (p - target)`` is
its depth (larger is nearer the viewer). The drawing area is the window, or the part of it the
help panel leaves (:meth:`Camera.resize`). Preset views: front (from +x), side (from -y), top (from
+z, x right and y up, as the planar scenes) and iso.
"""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np

#: Preset views: name -> (azimuth, elevation) in degrees.
VIEWS = {"front": (0.0, 0.0), "side": (-90.0, 0.0), "top": (-90.0, 90.0), "iso": (-50.0, 25.0)}
#: The order ``v`` cycles through them (and f1 .. f4).
VIEW_ORDER = ("front", "side", "top", "iso")
#: Where ``target`` is drawn, as shares of the drawing area's width and height.
CENTRE = (0.64, 0.52)
#: Half-width and half-height (shares of the drawing area) that :meth:`Camera.fitting` fills: right
#: of the panel at the top left, above the footer.
FIT = (0.32, 0.42)
#: Radians of orbit per pixel dragged.
ORBIT_PER_PIXEL = 0.01
#: Zoom factor per wheel click, and the zoom's bounds.
ZOOM_STEP, ZOOM_RANGE = 1.15, (0.1, 20.0)


class Camera:
    """Orthographic camera.

    Args:
        target: World point (3,) at the centre of the window, metres.
        extent: Radius (m) of the sphere about ``target`` that fits the drawing area at zoom 1.
        view: Starting preset (a key of :data:`VIEWS`).
        size: Window (width, height) in pixels.
    """

    def __init__(self, target, extent: float, view: str = "iso", size=(800, 800)) -> None:
        self.target = np.asarray(target, dtype=float).reshape(3)
        self.extent = float(extent)
        self.zoom = 1.0
        self.view = view
        self.set_view(view)
        self.resize(size)
        self.home = (view, self.target.copy(), self.extent)

    @classmethod
    def fitting(cls, points, view: str = "iso", size=(800, 800)) -> "Camera":
        """A camera whose every preset view shows ``points`` (K, 3) within :data:`FIT` of the
        drawing area at zoom 1: ``target`` the middle of their bounding box, ``extent`` as small
        as that allows."""
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        camera = cls(0.5 * (p.min(axis=0) + p.max(axis=0)), 1.0, view, size)
        need = 1e-3
        for name in VIEW_ORDER:
            camera.set_view(name)
            r, u, _ = camera.basis()
            offset = p - camera.target
            # scale = min(area) / (2 extent) must draw |r . offset| within FIT[0] of the area (and u alike).
            need = max(need, float(np.max(np.abs(offset @ r))) / (2 * FIT[0]),
                       float(np.max(np.abs(offset @ u))) / (2 * FIT[1]))
        camera.extent = need
        camera.set_view(view)
        camera.home = (view, camera.target.copy(), camera.extent)
        return camera

    def reset(self) -> None:
        """Back to the view the camera was made with: its preset, target and extent, zoom 1."""
        view, target, extent = self.home
        self.set_view(view)
        self.target, self.extent, self.zoom = target.copy(), extent, 1.0

    # --- controls -----------------------------------------------------------------------------
    def set_view(self, name: str) -> None:
        """Jumps to a preset view (front, side, top, iso) at zoom 1."""
        az, el = VIEWS[name]
        self.zoom = 1.0
        self.azimuth, self.elevation = math.radians(az), math.radians(el)
        self.view = name

    def next_view(self) -> str:
        """The preset after the current one (the first when the camera was orbited off them)."""
        i = VIEW_ORDER.index(self.view) + 1 if self.view in VIEW_ORDER else 0
        self.set_view(VIEW_ORDER[i % len(VIEW_ORDER)])
        return self.view

    def orbit(self, dx: float, dy: float) -> None:
        """A mouse drag of (dx, dy) pixels: right turns the scene to the right (the camera to the
        left), down tilts it toward the viewer; the elevation stays within +-90 degrees."""
        if not (math.isfinite(dx) and math.isfinite(dy)) or (dx == 0 and dy == 0):
            return
        self.azimuth = math.remainder(self.azimuth - dx * ORBIT_PER_PIXEL, 2 * math.pi)
        self.elevation = min(max(self.elevation + dy * ORBIT_PER_PIXEL, -math.pi / 2), math.pi / 2)
        self.view = "orbit"

    def zoom_by(self, clicks: float) -> None:
        """Wheel clicks: up zooms in by :data:`ZOOM_STEP` each."""
        if math.isfinite(clicks):
            self.zoom = min(max(self.zoom * ZOOM_STEP ** clicks, ZOOM_RANGE[0]), ZOOM_RANGE[1])

    def resize(self, size, area=None) -> None:
        """Fits the view to a window of ``size`` pixels, drawn in ``area`` (x, y, width, height) of
        it (None: the whole window)."""
        w, h = max(int(size[0]), 1), max(int(size[1]), 1)
        x0, y0, aw, ah = area if area is not None else (0, 0, w, h)
        self.size, self.area = (w, h), (int(x0), int(y0), max(int(aw), 1), max(int(ah), 1))
        self.centre = np.array([x0 + CENTRE[0] * self.area[2], y0 + CENTRE[1] * self.area[3]])

    # --- the projection -----------------------------------------------------------------------
    @property
    def scale(self) -> float:
        """Pixels per metre."""
        return self.zoom * min(self.area[2:]) / (2.0 * self.extent)

    def basis(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(right, up, towards the viewer), unit vectors in the world frame."""
        key = (self.azimuth, self.elevation)
        if getattr(self, "_basis", (None,))[0] == key:
            return self._basis[1]
        ca, sa = math.cos(self.azimuth), math.sin(self.azimuth)
        ce, se = math.cos(self.elevation), math.sin(self.elevation)
        d = np.array([ce * ca, ce * sa, se])
        r = np.array([-sa, ca, 0.0])
        self._basis = (key, (r, np.array([-se * ca, -se * sa, ce]), d))  # u = d x r, written out
        return self._basis[1]

    def project(self, points) -> Tuple[np.ndarray, np.ndarray]:
        """World points (..., 3) to pixels (..., 2) (floats) and depths (...,) (nearer is larger)."""
        p = np.asarray(points, dtype=float) - self.target
        r, u, d = self.basis()
        px = np.stack((self.centre[0] + self.scale * (p @ r), self.centre[1] - self.scale * (p @ u)), axis=-1)
        return px, p @ d

    def pixels(self, points) -> list:
        """World points (K, 3) to integer pixels for pygame, dropping non-finite rows."""
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        px, _ = self.project(p)
        px = px[np.all(np.isfinite(px), axis=1)]
        return np.rint(px).astype(int).tolist()

    def key(self) -> tuple:
        """What the projection depends on (for caching drawings of fixed things such as the floor)."""
        return (self.azimuth, self.elevation, self.zoom, self.size, self.area, tuple(self.target), self.extent)
