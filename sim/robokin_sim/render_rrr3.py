"""Draws an :class:`~robokin_sim.scene_rrr3.Rrr3State`: workspace, path, trail, legs, platform, panel."""

from __future__ import annotations

import math

import numpy as np
import pygame

from . import theme
from .panel import Text, draw_overlays, draw_panel, number
from .render_common import Hud, draw_grid, draw_rec, fps_rows, polyline, scene_area
from .view import Viewport

#: Cell code of the core's workspace map -> colour (0 unreachable is left transparent).
CELL_COLOURS = {1: theme.WORKSPACE_FILL, 2: theme.SINGULAR_CELL, 3: theme.WORKSPACE}
#: Length of the platform frame's axes (m).
FRAME_AXIS = 0.035


class Rrr3Renderer:
    """Renderer of the 3-RRR scene; the viewport spans +-0.27 m around the base centre."""

    def __init__(self, size) -> None:
        self.view = Viewport(center=(0.0, -0.005), extent=(0.27, 0.27), size=size)
        self.text = Text(18)
        self.small = Text(16)
        #: Where the help panel covers the window (after a draw; empty when hidden).
        self.help_rect = pygame.Rect(0, 0, 0, 0)
        self._backdrops: dict = {}
        self._grids: dict = {}

    # --- pieces -------------------------------------------------------------------------------
    def _backdrop(self, ws) -> pygame.Surface:
        """Background, grid and the core's workspace map at the current orientation, drawn once
        per orientation and window size (a few are kept: the orientation comes back often)."""
        key = (id(ws), self.view.size)
        cached = self._backdrops.get(key)
        if cached is not None:
            return cached[0]
        grid = self._grids.get(self.view.size)
        if grid is None:
            grid = pygame.Surface(self.view.size)
            grid.fill(theme.BACKGROUND)
            draw_grid(grid, self.view, 0.05)
            self._grids = {self.view.size: grid}
        surface = grid.copy()
        if ws is not None:
            # An 8-bit image of the cell codes with a palette: cheap to build and to scale, so a
            # rotation that changes the map every frame stays fast.
            codes = np.asarray(ws.cells, dtype=np.uint8).copy()
            reach = codes > 0
            # Outline: reachable cells next to an unreachable one (the workspace boundary).
            edge = reach & ~(
                np.roll(reach, 1, 0) & np.roll(reach, -1, 0) & np.roll(reach, 1, 1) & np.roll(reach, -1, 1)
            )
            codes[edge] = 3
            # Rows run along y upwards; pygame wants (x, y-down).
            img = pygame.surfarray.make_surface(np.ascontiguousarray(codes[::-1].T))
            img.set_palette([theme.BACKGROUND, *(CELL_COLOURS[k] for k in (1, 2, 3))] + [theme.BACKGROUND] * 252)
            img.set_colorkey(0)
            x0, x1, y0, y1 = ws.extent
            top_left = self.view.point((x0, y1))
            bottom_right = self.view.point((x1, y0))
            size = (max(1, bottom_right[0] - top_left[0]), max(1, bottom_right[1] - top_left[1]))
            surface.blit(pygame.transform.scale(img, size), top_left)
        if len(self._backdrops) >= 8:
            self._backdrops.pop(next(iter(self._backdrops)))
        # Holding ws keeps its id from being reused while it is a key.
        self._backdrops[key] = (surface, ws)
        return surface

    def _robot(self, surface: pygame.Surface, state) -> None:
        v = self.view
        pts = state.points
        o, a, b = (v.to_px(pts[k]) for k in ("O", "A", "B"))
        if not (np.all(np.isfinite(o)) and np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            return
        o, a, b = (np.rint(p).astype(int).tolist() for p in (o, a, b))
        pygame.draw.polygon(surface, theme.AXES, o, 1)  # the base triangle
        state_colour = theme.STATE_COLOURS.get(state.state, theme.SINGULAR)
        pygame.draw.polygon(surface, theme.PLATFORM_FILL, b)
        pygame.draw.polygon(surface, state_colour, b, 3)
        width = max(3, v.length(0.008))
        for i in range(3):
            pygame.draw.line(surface, theme.LINK_1, o[i], a[i], width)
            pygame.draw.line(surface, theme.LINK_2, a[i], b[i], width)
        for i in range(3):
            # Motors at O (filled squares), passive joints at A and B (rings).
            pygame.draw.rect(surface, theme.BASE, (o[i][0] - 7, o[i][1] - 7, 15, 15))
            for c in (a[i], b[i]):
                pygame.draw.circle(surface, theme.JOINT_FILL, c, 6)
                pygame.draw.circle(surface, theme.JOINT_EDGE, c, 6, 2)
        x, y, phi = (float(c) for c in state.pose)
        e = v.point((x, y))
        ux = (x + FRAME_AXIS * math.cos(phi), y + FRAME_AXIS * math.sin(phi))
        uy = (x - FRAME_AXIS * math.sin(phi), y + FRAME_AXIS * math.cos(phi))
        pygame.draw.line(surface, theme.FRAME_X, e, v.point(ux), 3)
        pygame.draw.line(surface, theme.FRAME_Y, e, v.point(uy), 3)
        pygame.draw.circle(surface, theme.TARGET, e, 4)

    # --- the frame ----------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, state, hud: Hud) -> None:
        area = scene_area(surface.get_size(), hud)[2:]
        if area != self.view.size:
            self.view.resize(area)
        v = self.view
        surface.blit(self._backdrop(state.workspace), (0, 0))
        if state.path is not None:
            polyline(surface, theme.PATH, True, v.points(state.path), 2)
        polyline(surface, theme.TRAIL, False, v.points(state.trail), 3)
        if state.points is not None:
            self._robot(surface, state)
        x, y, phi = (float(c) for c in state.pose)
        m = state.working_mode
        rows = [
            ("mode", state.mode, None),
            ("x, y (m)", f"{number(x)}, {number(y)}", None),
            ("phi (rad)", number(phi), None),
            ("alpha (rad)", " ".join(number(a, "{:+.2f}") for a in state.alpha), None),
            ("det_a_norm", number(state.det_a_norm, "{:+.3f}"), None),
            ("det_b_norm", number(state.det_b_norm, "{:+.3f}"), None),
            ("working mode", "({:+d}, {:+d}, {:+d})".format(*m), None),
            ("singularity", state.state, theme.STATE_COLOURS.get(state.state, theme.SINGULAR)),
            ("avoidance", "on" if state.avoid else "off", None),
            *fps_rows(hud),
        ]
        if not hud.help:  # the help panel stands in for it, leaving the robot in sight
            draw_panel(surface, self.text, rows)
        help_rect = draw_overlays(surface, self.text, self.small, "rrr3", state.message, hud.paused, hud.help,
                                  hint="h: keys   pink: parallel singularities at this phi")
        self.help_rect = help_rect or pygame.Rect(0, 0, 0, 0)
        draw_rec(surface, self.text, hud)
