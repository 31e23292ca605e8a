"""A recording holds the frames the simulation drew, in order: GIF frame j, decoded as a viewer
shows it, is the scene drawn after simulation step j * every + 1, rendered here directly (the
scene stepped with the same keys, drawn by the recording's renderer, quantised to the GIF's
palette)."""

import numpy as np
import pygame
from PIL import Image, ImageSequence
from sim_helpers import run_sim

from robokin_sim import recording
from robokin_sim.render_common import Hud
from robokin_sim.render_rrr3 import Rrr3Renderer
from robokin_sim.scene_rrr3 import Rrr3Scene

SIZE = (240, 240)
PALETTE = Image.new("P", (1, 1))
PALETTE.putpalette([c for rgb in recording.GIF_PALETTE for c in rgb])


def drawn_frames(steps, held):
    """The scene drawn after each of `steps` steps holding `held`, as the GIF would store it."""
    scene = Rrr3Scene("free")
    renderer = Rrr3Renderer(SIZE)
    surface = pygame.Surface(SIZE)
    out = []
    for _ in range(steps):
        scene.step(frozenset(held))
        renderer.draw(surface, scene.state(), Hud(fps=None))
        rgb = pygame.surfarray.array3d(surface).swapaxes(0, 1)
        paletted = Image.fromarray(np.ascontiguousarray(rgb)).quantize(palette=PALETTE, dither=Image.Dither.NONE)
        out.append(np.asarray(paletted.convert("RGB")))
    return out


def test_gif_frames_are_the_frames_drawn_at_their_steps(tmp_path):
    pygame.display.init()
    every, steps = 3, 24
    out = tmp_path / "run.gif"
    run_sim("--frames", str(steps), "--keys", f"right*{steps}", "--record", str(out), "--record-every", str(every),
            "--size", f"{SIZE[0]}x{SIZE[1]}", "--record-width", str(SIZE[0]))
    with Image.open(out) as im:
        recorded = [np.asarray(frame.convert("RGB")) for frame in ImageSequence.Iterator(im)]
    direct = drawn_frames(steps, {"right"})
    assert len(recorded) == steps // every
    # Consecutive steps draw different pictures (the robot moves 1 mm a step): a frame from the
    # wrong step would not match.
    assert all(not np.array_equal(direct[k], direct[k + 1]) for k in range(steps - 1))
    for j, frame in enumerate(recorded):
        assert frame.shape == direct[0].shape
        np.testing.assert_array_equal(frame, direct[j * every], err_msg=f"GIF frame {j}")
