"""Pieces every renderer uses: what the loop tells it besides the state, and the background grid."""

from __future__ import annotations

import dataclasses
import math
from typing import Optional

import pygame

from . import theme
from .panel import help_width
from .view import Viewport


@dataclasses.dataclass
class Hud:
    """Loop state shown on screen: measured frames per second (None: no fps row, as in a
    recording), pause and help flags, and whether the run is recording (the window's REC mark)."""

    fps: Optional[float] = 0.0
    paused: bool = False
    help: bool = False
    recording: bool = False


def fps_rows(hud: Hud) -> list:
    """The panel's fps row, or none (recorded frames)."""
    return [] if hud.fps is None else [("fps", f"{hud.fps:.0f}", None)]


def scene_area(size, hud: Hud) -> tuple:
    """(x, y, width, height) of the part of a surface of ``size`` pixels the scene is drawn in: all
    of it, or with the help shown the part left of the help panel (so the robot stays in sight)."""
    w, h = int(size[0]), int(size[1])
    return (0, 0, w - help_width(w), h) if hud.help else (0, 0, w, h)


def draw_rec(surface: pygame.Surface, text, hud: Hud) -> None:
    """A red dot and "REC" at the top right of the scene's area while the run is recording (the
    window only)."""
    if not hud.recording:
        return
    label = text.render("REC", theme.SINGULAR)
    w = scene_area(surface.get_size(), hud)[2]
    x, y = w - label.get_width() - 12, 10
    pygame.draw.circle(surface, theme.SINGULAR, (x - 11, y + label.get_height() // 2 - 1), 7)
    surface.blit(label, (x, y))


def draw_grid(surface: pygame.Surface, view: Viewport, spacing: float) -> None:
    """Grid lines every ``spacing`` metres and the world axes through the origin."""
    w, h = view.size
    lo = view.to_world((0, h))
    hi = view.to_world((w, 0))
    if not all(math.isfinite(c) for c in (*lo, *hi)):
        return
    for axis in (0, 1):
        k0, k1 = math.ceil(lo[axis] / spacing), math.floor(hi[axis] / spacing)
        for k in range(k0, k1 + 1):
            p = [0.0, 0.0]
            p[axis] = k * spacing
            px = view.point(p)
            colour = theme.AXES if k == 0 else theme.GRID
            if axis == 0:
                pygame.draw.line(surface, colour, (px[0], 0), (px[0], h), 1)
            else:
                pygame.draw.line(surface, colour, (0, px[1]), (w, px[1]), 1)


def polyline(surface: pygame.Surface, colour, closed: bool, points: list, width: int) -> None:
    """pygame.draw.lines, skipped when fewer than two (finite) points are left to draw."""
    if len(points) >= 2:
        pygame.draw.lines(surface, colour, closed, points, width)
