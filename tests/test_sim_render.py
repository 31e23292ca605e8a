"""Rendering: a headless frame shows the robot where the model says it is."""

import os

import numpy as np
import pygame
import robokin as rk
from sim_helpers import run_sim

from robokin_sim import theme
from robokin_sim.render_common import Hud
from robokin_sim.render_rpr import RprRenderer
from robokin_sim.render_rrr3 import Rrr3Renderer
from robokin_sim.scene_rpr import RprScene
from robokin_sim.scene_rrr3 import Rrr3Scene


def _pixels(surface):
    return pygame.surfarray.array3d(surface).swapaxes(0, 1)  # (h, w, 3)


def _share_on_segment(rgb, view, p, q, colour, fractions=np.linspace(0.3, 0.7, 9)):
    """Share of the points of segment p-q (world) whose pixel has ``colour``."""
    hits = 0
    for f in fractions:
        x, y = view.point(np.asarray(p) + f * (np.asarray(q) - np.asarray(p)))
        hits += tuple(rgb[y, x]) == colour
    return hits / len(fractions)


def test_rrr3_legs_are_drawn_where_the_model_puts_them(tmp_path):
    pygame.display.init()
    scene = Rrr3Scene("clover")
    for _ in range(150):
        scene.step(frozenset())
    surface = pygame.Surface((800, 800))
    renderer = Rrr3Renderer(surface.get_size())
    renderer.draw(surface, scene.state(), Hud())
    path = tmp_path / "rrr3.png"
    pygame.image.save(surface, str(path))
    assert path.stat().st_size > 0
    rgb = _pixels(surface)
    pts = rk.RRR3().points(scene.pose, (1, 1, 1))  # the model, asked independently of the scene
    for i in range(3):
        assert _share_on_segment(rgb, renderer.view, pts["O"][i], pts["A"][i], theme.LINK_1) >= 0.6, f"leg {i} link 1"
        assert _share_on_segment(rgb, renderer.view, pts["A"][i], pts["B"][i], theme.LINK_2) >= 0.6, f"leg {i} link 2"
    # And not where it is not: the same legs turned by 90 degrees about the origin fall on no link.
    turn = np.array([[0.0, -1.0], [1.0, 0.0]])
    misses = [_share_on_segment(rgb, renderer.view, pts["O"][i] @ turn.T, pts["A"][i] @ turn.T, theme.LINK_1)
              for i in range(3)]
    assert min(misses) < 0.5
    # The platform centre carries the frame's origin marker.
    x, y = renderer.view.point(scene.pose[:2])
    assert tuple(rgb[y, x]) == theme.TARGET


def test_rpr_links_are_drawn_where_the_chain_puts_them():
    pygame.display.init()
    scene = RprScene("line")
    for _ in range(100):
        scene.step(frozenset())
    surface = pygame.Surface((800, 800))
    renderer = RprRenderer(surface.get_size())
    renderer.draw(surface, scene.state(), Hud())
    rgb = _pixels(surface)
    frames = rk.robots.rpr().frames(scene.q)[:, :2, 3]
    assert _share_on_segment(rgb, renderer.view, frames[0], frames[1], theme.LINK_1) >= 0.8
    assert _share_on_segment(rgb, renderer.view, frames[2], frames[3], theme.LINK_2) >= 0.8


def test_screenshot_option_and_resized_window(tmp_path):
    shot = tmp_path / "small.png"
    res = run_sim("--size", "500x360", "--frames", "5", "--screenshot", str(shot))
    assert res.screenshot == str(shot)
    image = pygame.image.load(str(shot))
    assert image.get_size() == (500, 360)
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".part.png")]  # no temporary left over


def test_the_footer_names_the_colour_the_singular_cells_are_drawn_in(monkeypatch):
    """The hint says "pink", and pink (theme.SINGULAR_CELL, light red) is what the parallel
    singular cells of the workspace map are drawn in."""
    from robokin_sim import panel

    pygame.display.init()
    scene = Rrr3Scene("free")
    surface = pygame.Surface((800, 800))
    drawn = []
    original = panel.draw_footer
    monkeypatch.setattr(panel, "draw_footer", lambda s, t, lines: (drawn.extend(lines), original(s, t, lines)))
    Rrr3Renderer(surface.get_size()).draw(surface, scene.state(), Hud())
    assert any("pink: parallel singularities" in line for line in drawn)
    r, g, b = theme.SINGULAR_CELL
    assert r > 230 and g < r - 30 and b < r - 30 and min(g, b) > 150  # light red: pink
    rgb = _pixels(surface)
    assert np.count_nonzero(np.all(rgb == theme.SINGULAR_CELL, axis=2)) > 100
    # No red cells: nothing else on the map is drawn in the singular (red) colour.
    assert np.count_nonzero(np.all(rgb == theme.SINGULAR, axis=2)) == 0


def test_the_readme_lists_every_key_of_both_scenes():
    from robokin_sim.panel import HELP

    readme = open(os.path.join(os.path.dirname(__file__), "..", "README.md"), encoding="utf-8").read()
    section = readme[readme.index("## The simulator"):readme.index("## Conventions")]
    for robot in ("rrr3", "rpr"):
        for keys, _ in HELP[robot]:
            for key in keys.split(" / "):
                assert f"`{key}`" in section, (robot, key)
    assert "--robot rpr" in section and "null-space joint-limit avoidance" in section
