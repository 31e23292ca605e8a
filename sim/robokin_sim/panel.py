"""Text drawing shared by the renderers: the information panel, joint bars and the help overlay."""

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
        bars: ``(label, value, lower, upper[, selected])`` drawn as a bar filled up to the value
            (a tick within one turn when a limit is infinite), outlined when selected.

    Returns:
        The box's rectangle.
    """
    pad, value_w = 8, 118
    line = text.height
    height = pad * 2 + line * len(rows) + (line + 4) * len(bars)
    widest = max([value_w] + [text.render(value, colour or theme.TEXT).get_width() + (14 if colour else 0) + 4
                              for _, value, colour in rows])
    width = pad * 2 + max(label_w + widest, bar_w + 70 if bars else 0)
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
    for label, value, lower, upper, *selected in bars:
        surface.blit(text.render(label, theme.TEXT if selected and selected[0] else theme.TEXT_DIM), (x, y))
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
        pygame.draw.rect(surface, theme.SELECTED if selected and selected[0] else theme.PANEL_EDGE, bar,
                         2 if selected and selected[0] else 1)
        surface.blit(text.render(number(value, "{:.3f}"), theme.TEXT), (bar.right + 6, y))
        y += line + 4
    return rect


def draw_help(surface: pygame.Surface, text: Text, robot: str) -> None:
    """The key list, centred over a darkened box (as wide as its longest lines need)."""
    items = HELP.get(robot, [])
    line = text.height + 4
    key_w = max([70] + [text.render(key, theme.NEAR).get_width() + 14 for key, _ in items])
    what_w = max([0] + [text.render(what, theme.OVERLAY_TEXT).get_width() for _, what in items])
    width, height = max(470, key_w + what_w + 32), line * (len(items) + 2) + 16
    w, h = surface.get_size()
    rect = pygame.Rect((w - width) // 2, (h - height) // 2, width, height)
    pygame.draw.rect(surface, theme.OVERLAY, rect)
    x, y = rect.x + 16, rect.y + 10
    surface.blit(text.render("keys (h closes this help)", theme.OVERLAY_TEXT), (x, y))
    y += line + 6
    for key, what in items:
        surface.blit(text.render(key, theme.NEAR), (x, y))
        surface.blit(text.render(what, theme.OVERLAY_TEXT), (x + key_w, y))
        y += line


def draw_footer(surface: pygame.Surface, text: Text, lines: List[str]) -> None:
    """Small lines at the bottom left (messages, "paused", the help hint)."""
    y = surface.get_height() - 8 - text.height * len(lines)
    for s in lines:
        surface.blit(text.render(s, theme.TEXT_DIM), (8, y))
        y += text.height


def draw_overlays(surface: pygame.Surface, text: Text, small: Text, robot: str, message: str, paused: bool,
                  show_help: bool, hint: str = "h: keys") -> None:
    """The footer (message, "paused", the help hint) and, when asked for, the key list."""
    lines = [message] if message else []
    if paused:
        lines.append("paused (space)")
    lines.append(hint)
    draw_footer(surface, small, lines)
    if show_help:
        draw_help(surface, text, robot)
