"""Text drawing shared by the renderers: the information panel, joint bars and the help panel."""

from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence, Tuple

import pygame

from . import theme
from .scenes import SCENES

Colour = Tuple[int, int, int]

#: Key list of each robot's help overlay (from the table of scenes).
HELP = {name: list(entry.help) for name, entry in SCENES.items()}


class Text:
    """Renders strings with a cache (the panel redraws the same labels every frame)."""

    def __init__(self, size: int = 18) -> None:
        if not pygame.font.get_init():
            pygame.font.init()
        self.font = pygame.font.Font(None, size)
        self.height = self.font.get_linesize()
        self._cache: Dict[Tuple[str, Colour], pygame.Surface] = {}

    def render(self, text: str, colour: Colour = theme.TEXT) -> pygame.Surface:
        key = (text, colour)
        surf = self._cache.get(key)
        if surf is None:
            if len(self._cache) > 512:  # numbers change every frame: keep the cache bounded
                self._cache.clear()
            surf = self.font.render(text, True, colour)
            self._cache[key] = surf
        return surf


def number(value: float, fmt: str = "{:+.4f}") -> str:
    """A value for display: never 'nan' (shows a dash instead)."""
    return fmt.format(value) if math.isfinite(value) else "-"


def joint_value(value: float, kind: str) -> str:
    """A joint's value as the panel shows it, with its unit: degrees for a revolute joint ("R"),
    metres for a prismatic one ("P")."""
    if kind == "R":
        return number(math.degrees(value), "{:+.1f}") + " deg"
    return number(value, "{:+.3f}") + " m"


def draw_panel(surface: pygame.Surface, text: Text, rows: Sequence[Tuple[str, str, Optional[Colour]]],
               topleft=(8, 8), bars: Sequence[Tuple[str, float, float, float]] = (), label_w: int = 92,
               bar_w: int = 160) -> pygame.Rect:
    """Draws a box of ``label: value`` rows (value in ``colour`` when given) and joint bars.

    Args:
        surface: Where to draw.
        text: The text renderer.
        rows: ``(label, value, colour)``; colour None draws the value in the text colour.
        topleft: Pixel position of the box.
        label_w: Width of the label column (pixels).
        bar_w: Width of the joint bars (pixels).
        bars: ``(label, value, lower, upper[, selected[, kind]])`` drawn as a bar filled up to the
            value (a tick within one turn when a limit is infinite), outlined when selected, the
            value written after it with its unit when ``kind`` ("R" or "P") is given
            (:func:`joint_value`).

    Returns:
        The box's rectangle.
    """
    pad, value_w = 8, 118
    line = text.height
    height = pad * 2 + line * len(rows) + (line + 4) * len(bars)
    widest = max([value_w] + [text.render(value, colour or theme.TEXT).get_width() + (14 if colour else 0) + 4
                              for _, value, colour in rows])
    shown = [joint_value(value, more[1]) if len(more) > 1 and more[1] else number(value, "{:.3f}")
             for _, value, _, _, *more in bars]
    bar_text_w = max([0] + [text.render(v, theme.TEXT).get_width() for v in shown])
    width = pad * 2 + max(label_w + widest, bar_w + 40 + bar_text_w if bars else 0)
    rect = pygame.Rect(topleft[0], topleft[1], width, height)
    pygame.draw.rect(surface, theme.PANEL, rect)
    pygame.draw.rect(surface, theme.PANEL_EDGE, rect, 1)
    x, y = rect.x + pad, rect.y + pad
    for label, value, colour in rows:
        surface.blit(text.render(label, theme.TEXT_DIM), (x, y))
        if colour is not None:
            pygame.draw.rect(surface, colour, (x + label_w, y + 2, 10, line - 6))
            surface.blit(text.render(value, colour), (x + label_w + 14, y))
        else:
            surface.blit(text.render(value, theme.TEXT), (x + label_w, y))
        y += line
    for (label, value, lower, upper, *more), value_text in zip(bars, shown):
        selected = bool(more and more[0])
        surface.blit(text.render(label, theme.TEXT if selected else theme.TEXT_DIM), (x, y))
        bar = pygame.Rect(x + 34, y + 2, bar_w, line - 6)
        pygame.draw.rect(surface, theme.BAR_BACK, bar)
        limited = math.isfinite(lower) and math.isfinite(upper) and upper > lower
        if limited and math.isfinite(value):
            share = min(max((value - lower) / (upper - lower), 0.0), 1.0)
            # Red within 5 % of a limit: that is what joint-limit avoidance keeps away from.
            colour = theme.SINGULAR if share < 0.05 or share > 0.95 else theme.BAR
            pygame.draw.rect(surface, colour, (bar.x, bar.y, max(1, int(bar.w * share)), bar.h))
        elif math.isfinite(value):
            # Unlimited: a tick at the angle within one turn (-pi to pi).
            share = (math.remainder(value, 2 * math.pi) + math.pi) / (2 * math.pi)
            pygame.draw.rect(surface, theme.BAR, (bar.x + int((bar.w - 3) * share), bar.y, 3, bar.h))
        pygame.draw.rect(surface, theme.SELECTED if selected else theme.PANEL_EDGE, bar, 2 if selected else 1)
        surface.blit(text.render(value_text, theme.TEXT), (bar.right + 6, y))
        y += line + 4
    return rect


#: Width of the help panel: this share of the window's, within HELP_WIDTH pixels (and at most half
#: the window).
HELP_SHARE, HELP_WIDTH = 0.36, (200, 340)


def help_width(window_width: int) -> int:
    """Pixels the help panel takes at the right of a window ``window_width`` pixels wide."""
    low, high = HELP_WIDTH
    return int(min(max(HELP_SHARE * window_width, low), high, window_width // 2))


def wrap(text: Text, words: str, width: int, first: int = 0) -> List[str]:
    """``words`` broken into lines of at most ``width`` pixels (the first line ``first`` pixels
    shorter); a word longer than a line gets a line of its own."""
    lines: List[str] = []
    line = ""
    for word in words.split():
        trial = f"{line} {word}" if line else word
        room = width - (first if not lines else 0)
        if line and text.font.size(trial)[0] > room:
            lines.append(line)
            line = word
        else:
            line = trial
    return lines + [line] if line else lines


def draw_help(surface: pygame.Surface, text: Text, robot: str) -> pygame.Rect:
    """The key list in a dark panel down the right side of the window (the scene is drawn beside
    it, :func:`robokin_sim.render_common.scene_area`, without the information panel): each key in
    the accent colour followed by what it does, wrapped to the panel's width. Returns the panel's
    rectangle."""
    w, h = surface.get_size()
    rect = pygame.Rect(w - help_width(w), 0, help_width(w), h)
    pygame.draw.rect(surface, theme.OVERLAY, rect)
    pad, line = 12, text.height + 2
    x, y, inner = rect.x + pad, rect.y + 10, rect.w - 2 * pad
    surface.blit(text.render("keys (h closes this help)", theme.OVERLAY_TEXT), (x, y))
    y += line + 8
    for key, what in HELP.get(robot, []):
        key_w = text.render(key, theme.NEAR).get_width() + 8
        surface.blit(text.render(key, theme.NEAR), (x, y))
        indent = key_w if key_w <= inner // 2 else 0
        if not indent:  # a long key name: its text starts on the next line
            y += line
        for k, piece in enumerate(wrap(text, what, inner - 10, first=indent - 10 if indent else 0)):
            surface.blit(text.render(piece, theme.OVERLAY_TEXT), (x + (indent if k == 0 and indent else 10), y))
            y += line
        y += 3
    return rect


def draw_footer(surface: pygame.Surface, text: Text, lines: List[str]) -> None:
    """Small lines at the bottom left (messages, "paused", the help hint)."""
    y = surface.get_height() - 8 - text.height * len(lines)
    for s in lines:
        surface.blit(text.render(s, theme.TEXT_DIM), (8, y))
        y += text.height


def draw_overlays(surface: pygame.Surface, text: Text, small: Text, robot: str, message: str, paused: bool,
                  show_help: bool, hint: str = "h: keys") -> Optional[pygame.Rect]:
    """The footer (message, "paused", the help hint) and, when asked for, the key list; returns the
    help panel's rectangle (None when hidden)."""
    lines = [message] if message else []
    if paused:
        lines.append("paused (space)")
    lines.append(hint)
    draw_footer(surface, small, lines)
    return draw_help(surface, text, robot) if show_help else None
