"""Draws a :class:`~robokin_sim.scene_serial.SerialState`: floor grid (at the state's floor height,
with a pedestal up to the base when the arm reaches below its base), path and trail, the arm from
its frames (links as thick segments shaded by depth, joints, joint axes), the tool's triad, the
velocity ellipsoid, and the panel (tool pose, manipulability, joint-limit bars).

Everything is drawn through the state's :class:`~robokin_sim.camera.Camera`; the 3-D items are
painted far to near, and each joint's centre (the origin of ``chain.frames(q)``) is dotted on top,
so that it is always visible where the projection puts it (``joint_pixels`` after a draw).
"""

from __future__ import annotations

import math

import numpy as np
import pygame

from . import theme
from .panel import Text, draw_overlays, draw_panel, number
from .render_common import Hud, draw_rec, fps_rows, polyline, scene_area

#: Velocity ellipsoid drawn as the tool's displacement in this many seconds at unit joint speed.
ELLIPSOID_SECONDS = 0.15
#: Triad and joint-axis lengths relative to the arm's size.
TRIAD, AXIS = 0.12, 0.07
#: Joint-state colours.
STATE_COLOURS = {"none": theme.CLEAR, "limit": theme.NEAR, "near": theme.NEAR, "singular": theme.SINGULAR,
                 "unreachable": theme.SINGULAR}


def _nice(x: float) -> float:
    """1, 2 or 5 times a power of ten, at most x."""
    e = 10 ** math.floor(math.log10(x))
    return max(m * e for m in (1, 2, 5) if m * e <= x)


def _mix(a, b, t: float):
    t = min(max(t, 0.0), 1.0)
    return tuple(int(round(a[k] + (b[k] - a[k]) * t)) for k in range(3))


class SerialRenderer:
    """Renderer of the serial scene."""

    def __init__(self, size) -> None:
        self.size = tuple(size)
        # Smaller text in small windows and recordings (a GIF is 480 px wide): the panel of a
        # 7-joint arm would cover the arm.
        self.text = Text(18 if min(size) >= 600 else 15)
        self.small = Text(16 if min(size) >= 600 else 14)
        self._floor = (None, None)
        #: Integer pixels of the frames' origins drawn last (base first).
        self.joint_pixels: list = []
        self.panel_rect = pygame.Rect(0, 0, 0, 0)
        self.help_rect = pygame.Rect(0, 0, 0, 0)

    # --- fixed things -----------------------------------------------------------------------------
    def _floor_surface(self, camera, size: float, floor: float, surface_size) -> pygame.Surface:
        """Background and the floor grid (z = ``floor``), drawn once per camera position."""
        key = (camera.key(), size, floor, surface_size)
        if self._floor[0] == key:
            return self._floor[1]
        surface = pygame.Surface(surface_size)
        surface.fill(theme.BACKGROUND)
        spacing = _nice(size / 4.0)
        k = int(math.ceil(1.25 * size / spacing))
        ends = k * spacing
        for i in range(-k, k + 1):
            c = i * spacing
            colour = theme.AXES if i == 0 else theme.FLOOR
            for a, b in (((c, -ends, floor), (c, ends, floor)), ((-ends, c, floor), (ends, c, floor))):
                pa, pb = camera.pixels([a, b])
                pygame.draw.line(surface, colour, pa, pb, 1)
        self._floor = (key, surface)
        return surface

    # --- the frame --------------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, state, hud: Hud) -> None:
        cam = state.camera
        area = scene_area(surface.get_size(), hud)
        if cam.size != surface.get_size() or cam.area != area:
            cam.resize(surface.get_size(), area)
        surface.blit(self._floor_surface(cam, state.size, state.floor, surface.get_size()), (0, 0))
        if state.path is not None:
            polyline(surface, theme.PATH, True, cam.pixels(state.path), 2)
            if state.missed is not None and np.any(state.missed):
                for p in cam.pixels(state.path[state.missed]):
                    pygame.draw.circle(surface, theme.SINGULAR, p, 3)
        if len(state.trail) >= 2:
            polyline(surface, theme.TRAIL, False, cam.pixels(state.trail), 3)
        self._arm(surface, state)
        if state.ellipsoid is not None:
            self._ellipsoid(surface, state)
        self._triad(surface, state)
        for c in self.joint_pixels[:-1]:  # the joints' centres on top; the tool's marker is the triad's
            pygame.draw.circle(surface, theme.JOINT_EDGE, c, 2)
        if hud.help:  # the help panel stands in for the information panel, leaving the arm in sight
            self.panel_rect = pygame.Rect(0, 0, 0, 0)
        else:
            self._panel(surface, state, hud)
        hint = "h: keys   drag: orbit   wheel: zoom"
        # Every serial arm has the same keys (the table's "urdf" entry has them too).
        help_rect = draw_overlays(surface, self.text, self.small, "urdf", state.message, hud.paused, hud.help,
                                  hint=hint)
        #: Where the help panel covers the window (after a draw; empty when hidden).
        self.help_rect = help_rect or pygame.Rect(0, 0, 0, 0)
        draw_rec(surface, self.text, hud)

    def _arm(self, surface: pygame.Surface, state) -> None:
        cam = state.camera
        origins = state.frames[:, :3, 3]
        px, depth = cam.project(origins)
        if not np.all(np.isfinite(px)):
            self.joint_pixels = []
            return
        width = int(min(max(0.035 * state.size * cam.scale, 4), 22))
        far = 0.8 * state.size

        def shade(d):  # near links dark and strong, far ones pale
            return _mix(theme.LINK_NEAR, theme.LINK_FAR, 0.5 - d / (2 * far))

        items = []  # (depth, kind, data)
        for i in range(len(origins) - 1):
            if np.linalg.norm(origins[i + 1] - origins[i]) > 1e-9:
                items.append((0.5 * (depth[i] + depth[i + 1]), "link", (px[i], px[i + 1], shade(0.5 * (depth[i] + depth[i + 1])))))
        half = AXIS * state.size * state.axes[:, 1]
        ends, ends_depth = cam.project(np.stack([state.axes[:, 0] - half, state.axes[:, 0] + half], axis=1))
        for i in range(len(state.axes)):
            items.append((float(np.max(ends_depth[i])) + 1e-6, "axis", (ends[i], state.joint_types[i], i == state.selected)))
        for i in range(1, len(origins) - 1):
            items.append((depth[i] + 2e-6, "joint", (px[i], False)))
        if 0 <= state.selected < len(state.axes):  # the selected joint: a ring on its axis, over its neighbours
            point, d = cam.project(state.axes[state.selected, 0])
            items.append((float(d) + 3e-6, "joint", (point, True)))
        items += self._base_items(state, width)
        items.sort(key=lambda item: item[0])
        foot = np.rint(cam.project([*origins[0, :2], min(state.floor, origins[0, 2])])[0]).astype(int)
        pygame.draw.polygon(surface, theme.BASE, [(foot[0] - 14, foot[1] + 12), (foot[0] + 14, foot[1] + 12),
                                                  (foot[0], foot[1] - 6)])
        for _, kind, data in items:
            if kind in ("pedestal", "base axis"):
                a, b = np.rint(data[0]).astype(int)
                pygame.draw.line(surface, data[1], a, b, data[2])
            elif kind == "link":
                a, b, colour = (np.rint(data[0]).astype(int), np.rint(data[1]).astype(int), data[2])
                pygame.draw.line(surface, colour, a, b, width)
                for c in (a, b):
                    pygame.draw.circle(surface, colour, c, width // 2)
            elif kind == "axis":
                ends, kind_, selected = data
                a, b = np.rint(ends).astype(int)
                colour = theme.SELECTED if selected else theme.JOINT_AXIS
                pygame.draw.line(surface, colour, a, b, 3 if kind_ == "R" else 5)
            else:
                c, selected = np.rint(data[0]).astype(int), data[1]
                r = max(width // 2 + 3, 6)
                pygame.draw.circle(surface, theme.JOINT_FILL, c, r)
                pygame.draw.circle(surface, theme.SELECTED if selected else theme.JOINT_EDGE, c, r, 2)
        self.joint_pixels = np.rint(px).astype(int).tolist()

    def _base_items(self, state, width: int) -> list:
        """The depth-sorted items of the base: its frame's x, y, z axes and, when the floor is below
        the base (the arm reaches below its base), the pedestal from the floor up to it."""
        cam = state.camera
        base = state.frames[0][:3, 3]
        items = []
        if state.floor < base[2] - 1e-9:
            ends, depth = cam.project(np.array([[base[0], base[1], state.floor], base]))
            items.append((float(np.mean(depth)), "pedestal", (ends, theme.PEDESTAL, max(2 * width, 10))))
        for axis, colour in zip(np.eye(3), (theme.FRAME_X, theme.FRAME_Y, theme.FRAME_Z)):
            ends, depth = cam.project(np.array([base, base + axis * 0.1 * state.size]))
            items.append((float(np.max(depth)) + 1e-6, "base axis", (ends, colour, 2)))
        return items

    def _triad(self, surface: pygame.Surface, state) -> None:
        cam, tool = state.camera, state.frames[-1]
        o = tool[:3, 3]
        px = cam.pixels(np.vstack([o, o + TRIAD * state.size * tool[:3, :3].T]))
        if len(px) == 4:
            for k, colour in enumerate((theme.FRAME_X, theme.FRAME_Y, theme.FRAME_Z)):
                pygame.draw.line(surface, colour, px[0], px[k + 1], 3)
            pygame.draw.circle(surface, theme.TARGET, px[0], 4)

    def _ellipsoid(self, surface: pygame.Surface, state) -> None:
        cam = state.camera
        axes, lengths = state.ellipsoid
        centre = state.frames[-1][:3, 3]
        semi = axes * (ELLIPSOID_SECONDS * lengths)  # columns: the principal semi-axes
        t = np.linspace(0.0, 2 * math.pi, 73)
        for i, j in ((0, 1), (1, 2), (0, 2)):
            ring = centre + np.outer(np.cos(t), semi[:, i]) + np.outer(np.sin(t), semi[:, j])
            polyline(surface, theme.ELLIPSOID, True, cam.pixels(ring), 2)
        for k in range(3):
            a, b = cam.pixels([centre - semi[:, k], centre + semi[:, k]])
            pygame.draw.line(surface, theme.ELLIPSOID, a, b, 1)

    def _panel(self, surface: pygame.Surface, state, hud: Hud) -> None:
        x, y, z = (float(v) for v in state.position)
        roll, pitch, yaw = (math.degrees(float(v)) for v in state.rpy)
        colour = STATE_COLOURS.get(state.state, theme.SINGULAR)
        rows = [
            ("robot", state.title, None),
            ("mode", state.mode, None),
            ("tool x y z (m)", f"{number(x, '{:+.3f}')} {number(y, '{:+.3f}')} {number(z, '{:+.3f}')}", None),
            ("roll pitch yaw", f"{number(roll, '{:+.1f}')} {number(pitch, '{:+.1f}')} {number(yaw, '{:+.1f}')} deg", None),
            ("manipulability", f"{number(state.manipulability, '{:.4f}')} ({100 * state.ratio:.0f} % of best) "
             f"{state.state if state.state != 'none' else ''}".rstrip(), colour),
        ]
        if state.posture:
            rows.append(("posture", state.posture, None))
        if state.redundant:
            rows.append(("null space", "joint limits" if state.avoid else "minimum norm", None))
        rows.append(("view", state.camera.view, None))
        rows += fps_rows(hud)
        bars = []
        for i, kind in enumerate(state.joint_types):
            bars.append((f"q{i + 1}", float(state.q[i]), float(state.lower[i]), float(state.upper[i]),
                         i == state.selected, kind))
        #: Where the panel covers the scene (after a draw).
        small = self.text.height < 16
        self.panel_rect = draw_panel(surface, self.text, rows, bars=bars, label_w=92 if small else 112,
                                     bar_w=110 if small else 160)
