"""World-to-pixel scaling, in one place: metres with y up to pixels with y down."""

from __future__ import annotations

import numpy as np


class Viewport:
    """Fits a world rectangle into a surface with one scale for both axes, centred.

    Args:
        center: World point (x, y) shown at the middle of the surface, metres.
        extent: Half-widths (x, y) of the world rectangle that must stay visible, metres.
        size: Surface size (width, height) in pixels.
    """

    def __init__(self, center, extent, size) -> None:
        self.center = np.asarray(center, dtype=float)
        self.extent = np.asarray(extent, dtype=float)
        self.resize(size)

    def resize(self, size) -> None:
        """Refits the world rectangle to a new surface size (the window was resized)."""
        w, h = max(int(size[0]), 1), max(int(size[1]), 1)
        self.size = (w, h)
        #: Pixels per metre.
        self.scale = min(w / (2.0 * self.extent[0]), h / (2.0 * self.extent[1]))
        self._offset = np.array([w / 2.0, h / 2.0])

    def to_px(self, points) -> np.ndarray:
        """World points (..., 2) to pixel coordinates (..., 2), floats (NaN stays NaN)."""
        p = np.asarray(points, dtype=float)[..., :2] - self.center
        return self._offset + self.scale * np.stack((p[..., 0], -p[..., 1]), axis=-1)

    def point(self, xy) -> tuple:
        """One world point to an integer pixel (x, y) for pygame's drawing calls."""
        px = self.to_px(xy)
        return int(round(px[0])), int(round(px[1]))

    def points(self, xy) -> list:
        """World points (K, 2) to a list of integer pixels, dropping non-finite rows."""
        xy = np.asarray(xy, dtype=float)
        if xy.size == 0:  # an empty trail is (0,), not (0, 2)
            return []
        px = self.to_px(xy.reshape(-1, xy.shape[-1]))
        px = px[np.all(np.isfinite(px), axis=1)]
        return np.rint(px).astype(int).tolist()

    def length(self, metres: float) -> int:
        """A world length in whole pixels (at least 1)."""
        return max(1, int(round(metres * self.scale)))

    def to_world(self, px) -> np.ndarray:
        """Pixel coordinates (..., 2) back to world points (inverse of :meth:`to_px`)."""
        q = (np.asarray(px, dtype=float) - self._offset) / self.scale
        return self.center + np.stack((q[..., 0], -q[..., 1]), axis=-1)
