"""Draws docs/circle_sides.png with the simulator's own renderer: why the circle is traced about
phi = +0.46 rad from home (docs/simulator.md).

    .venv/bin/python docs/circle_sides.py
"""

import dataclasses
import os
import sys

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import numpy as np  # noqa: E402
import pygame  # noqa: E402
from PIL import Image  # noqa: E402

from robokin_sim import theme  # noqa: E402
from robokin_sim.panel import Text  # noqa: E402
from robokin_sim.render_common import Hud  # noqa: E402
from robokin_sim.render_rrr3 import Rrr3Renderer  # noqa: E402
from robokin_sim.scene_rrr3 import Rrr3Scene  # noqa: E402

SIZE = (480, 480)


def frame(scene, state, caption):
    surface = pygame.Surface(SIZE)
    Rrr3Renderer(SIZE).draw(surface, state, Hud(fps=None))
    text = Text(20)
    label = text.render(caption, theme.TEXT)
    pygame.draw.rect(surface, theme.PANEL, (0, SIZE[1] - 30, SIZE[0], 30))
    surface.blit(label, (8, SIZE[1] - 24))
    return pygame.surfarray.array3d(surface).swapaxes(0, 1)


def main(out="docs/circle_sides.png"):
    pygame.display.init()
    pygame.font.init()
    home = Rrr3Scene("free")
    circle = home.paths["circle"]
    # (a) Home at phi = 0 with the circle at phi = 0: the pink curve (det A = 0) runs between them.
    a = dataclasses.replace(home.state(), path=circle, mode="free", message="")
    # (b) The circle as the simulator traces it from home: about phi = +0.45, on home's side.
    scene = Rrr3Scene("circle")
    while scene.mode == "approach":
        scene.step(frozenset())
    b = dataclasses.replace(scene.state(), message="")
    left = frame(home, a, "(a) phi = 0: circle across det A = 0 from home")
    right = frame(scene, b, f"(b) phi = {scene.pose[2]:+.2f}: circle on home's side")
    gap = np.full((SIZE[1], 8, 3), 255, dtype=np.uint8)
    Image.fromarray(np.concatenate((left, gap, right), axis=1)).save(out, optimize=True)
    print(out)


if __name__ == "__main__":
    main(*sys.argv[1:])
