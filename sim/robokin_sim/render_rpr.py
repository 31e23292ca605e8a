"""Draws an :class:`~robokin_sim.scene_rpr.RprState`: the arm, the line, the trail, joint bars."""

from __future__ import annotations

import math

import numpy as np
import pygame

from . import theme
from .panel import Text, draw_overlays, draw_panel, number
from .render_common import Hud, draw_grid, draw_rec, fps_rows, polyline, scene_area
from .view import Viewport

JOINT_NAMES = ("t1", "t2", "t3")


class RprRenderer:
    """Renderer of the RPR scene; the viewport spans the arm's reach (about 4 m)."""

    def __init__(self, size) -> None:
        self.view = Viewport(center=(1.3, 1.5), extent=(2.9, 2.9), size=size)
        self.text = Text(18)
        self.small = Text(16)
        #: Where the help panel covers the window (after a draw; empty when hidden).
        self.help_rect = pygame.Rect(0, 0, 0, 0)

    def draw(self, surface: pygame.Surface, state, hud: Hud) -> None:
        area = scene_area(surface.get_size(), hud)[2:]
        if area != self.view.size:
            self.view.resize(area)
        v = self.view
        surface.fill(theme.BACKGROUND)
        draw_grid(surface, v, 0.5)
        # t1's range [0, pi/2]: the quarter the first link sweeps.
        for angle in (state.lower[0], state.upper[0]):
            end = 4.0 * np.array([math.cos(angle), math.sin(angle)])
            pygame.draw.line(surface, theme.AXES, v.point((0, 0)), v.point(end), 1)
        # The line and its ends.
        pygame.draw.line(surface, theme.PATH, v.point(state.line[0]), v.point(state.line[-1]), 3)
        for label, p in (("1", state.line[0]), ("2", state.line[-1])):
            c = v.point(p)
            pygame.draw.circle(surface, theme.PATH, c, 6)
            surface.blit(self.text.render(label, theme.TEXT), (c[0] + 8, c[1] - 20))
        polyline(surface, theme.TRAIL, False, v.points(state.trail), 2)
        self._arm(surface, state)
        joint = state.q
        rows = [
            ("robot", "RPR (redundancy study)", None),
            ("mode", state.mode, None),
            ("solution", "null-space limits" if state.avoid else "minimum norm", None),
            ("tip x, y", f"{number(state.frames[-1][0, 3], '{:+.3f}')}, {number(state.frames[-1][1, 3], '{:+.3f}')}", None),
            ("Reach error", number(state.error, "{:.1e}") + " m", None if state.converged else theme.SINGULAR),
            *fps_rows(hud),
        ]
        bars = [(JOINT_NAMES[i], float(joint[i]), float(state.lower[i]), float(state.upper[i]), False, kind)
                for i, kind in enumerate("RPR")]
        if not hud.help:  # the help panel stands in for it, leaving the arm in sight
            draw_panel(surface, self.text, rows, bars=bars)
        help_rect = draw_overlays(surface, self.text, self.small, "rpr", state.message, hud.paused, hud.help)
        self.help_rect = help_rect or pygame.Rect(0, 0, 0, 0)
        draw_rec(surface, self.text, hud)

    def _arm(self, surface: pygame.Surface, state) -> None:
        v = self.view
        f = state.frames
        o, e1, j3, tip = (v.point(f[i][:2, 3]) for i in range(4))
        # Full stroke of the prismatic joint, faint, so the bar's travel is visible.
        u = f[1][:2, 0]
        stroke_end = f[1][:2, 3] + state.upper[1] * u
        pygame.draw.line(surface, theme.BAR_BACK, e1, v.point(stroke_end), v.length(0.09))
        pygame.draw.line(surface, theme.LINK_1, o, e1, v.length(0.09))
        pygame.draw.line(surface, theme.BAR, e1, j3, v.length(0.05))
        pygame.draw.line(surface, theme.LINK_2, j3, tip, v.length(0.05))
        pygame.draw.polygon(surface, theme.BASE, [(o[0] - 12, o[1] + 14), (o[0] + 12, o[1] + 14), o])
        for c in (o, j3):
            pygame.draw.circle(surface, theme.JOINT_FILL, c, 7)
            pygame.draw.circle(surface, theme.JOINT_EDGE, c, 7, 2)
        pygame.draw.circle(surface, theme.TARGET, v.point(state.target), 4, 1)
        pygame.draw.circle(surface, theme.TRAIL, tip, 5)
