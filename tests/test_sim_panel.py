"""What the window shows and how keys reach the arm: the help panel beside the robot (never over
it), one unit per quantity in the panel (degrees for angles, metres for slides), the camera reset
by r and by the preset views, and keys pressed during an animated move applied after it."""

import itertools
import math

import numpy as np
import pygame
import pytest
import robokin as rk
from sim_helpers import read_log, run_sim

from robokin_sim import panel, theme
from robokin_sim.render_common import Hud
from robokin_sim.render_rpr import RprRenderer
from robokin_sim.render_rrr3 import Rrr3Renderer
from robokin_sim.render_serial import SerialRenderer
from robokin_sim.scene_rpr import RprScene
from robokin_sim.scene_rrr3 import Rrr3Scene
from robokin_sim.scene_serial import SerialScene
from robokin_sim.serial_model import start_posture

SIZES = [(800, 800), (480, 480), (900, 500)]


def _inside(rect, points):
    return [p for p in points if rect.collidepoint(int(p[0]), int(p[1]))]


def _on_surface(size, points):
    return all(0 <= p[0] < size[0] and 0 <= p[1] < size[1] for p in points)


# --- the help panel ----------------------------------------------------------------------------

@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("name", ["puma560", "ur5", "panda", "planar_3r", "prr"])
def test_the_help_leaves_a_serial_arm_in_sight(name, size):
    pygame.display.init()
    scene = SerialScene(rk.robots.get(name), name=name)
    surface, renderer = pygame.Surface(size), SerialRenderer(size)
    renderer.draw(surface, scene.state(), Hud(help=False))
    assert renderer.help_rect.w == 0
    renderer.draw(surface, scene.state(), Hud(help=True))
    rect = renderer.help_rect
    assert rect.w > 0 and rect.h == size[1] and rect.right == size[0]  # a panel down the right side
    rgb = pygame.surfarray.array3d(surface)
    assert tuple(rgb[rect.x + 3, size[1] // 2]) == theme.OVERLAY
    # Every joint is drawn beside the panel, in the window, and its centre dot is visible.
    joints = renderer.joint_pixels
    assert not _inside(rect, joints) and _on_surface(size, joints), (name, size, rect, joints)
    for x, y in joints[:-1]:
        assert tuple(rgb[x, y]) == theme.JOINT_EDGE
    # The joints are where the projection (of the drawing area left of the panel) puts them.
    expected = np.rint(scene.camera.project(scene.frames[:, :3, 3])[0]).astype(int)
    assert np.array_equal(np.array(joints), expected)
    renderer.draw(surface, scene.state(), Hud(help=False))  # h again: the whole window is the scene's
    assert renderer.help_rect.w == 0 and scene.camera.area == (0, 0, *size)


@pytest.mark.parametrize("size", SIZES)
def test_the_help_leaves_the_3rrr_and_the_rpr_in_sight(size):
    pygame.display.init()
    surface = pygame.Surface(size)
    rrr3, renderer = Rrr3Scene("free"), Rrr3Renderer(size)
    renderer.draw(surface, rrr3.state(), Hud(help=True))
    points = np.vstack([renderer.view.to_px(rrr3.state().points[k]) for k in ("O", "A", "B")])
    assert renderer.help_rect.w > 0 and not _inside(renderer.help_rect, points) and _on_surface(size, points)
    rgb = pygame.surfarray.array3d(surface)
    assert tuple(rgb[renderer.view.point(rrr3.pose[:2])]) == theme.TARGET  # the platform's centre shows
    rpr, renderer = RprScene("line"), RprRenderer(size)
    renderer.draw(surface, rpr.state(), Hud(help=True))
    points = renderer.view.to_px(rpr.state().frames[:, :2, 3])
    assert renderer.help_rect.w > 0 and not _inside(renderer.help_rect, points) and _on_surface(size, points)


def test_the_help_lists_every_key_in_its_panel(monkeypatch):
    pygame.display.init()
    drawn = []
    original = panel.Text.render
    monkeypatch.setattr(panel.Text, "render", lambda self, s, colour=theme.TEXT: (drawn.append((s, colour)),
                                                                                  original(self, s, colour))[1])
    scene = SerialScene(rk.robots.ur5(), name="ur5")
    SerialRenderer((480, 480)).draw(pygame.Surface((480, 480)), scene.state(), Hud(help=True))
    keys = [k for k, _ in itertools.groupby(s for s, colour in drawn if colour == theme.NEAR)]  # measured, drawn
    assert keys == [k for k, _ in panel.HELP["urdf"]]
    words = " ".join(s for s, colour in drawn if colour == theme.OVERLAY_TEXT).split()
    assert words == "keys (h closes this help)".split() + " ".join(w for _, w in panel.HELP["urdf"]).split()


# --- units -------------------------------------------------------------------------------------

def _panel_strings(monkeypatch, renderer, surface, state):
    drawn = []
    original = panel.Text.render
    monkeypatch.setattr(panel.Text, "render", lambda self, s, colour=theme.TEXT: (drawn.append(s),
                                                                                  original(self, s, colour))[1])
    renderer.draw(surface, state, Hud())
    monkeypatch.setattr(panel.Text, "render", original)
    return drawn


@pytest.mark.parametrize("name", ["ur5", "prr", "rp"])
def test_the_panel_shows_angles_in_degrees_and_slides_in_metres(name, monkeypatch):
    pygame.display.init()
    chain = rk.robots.get(name)
    scene = SerialScene(chain, name=name)
    scene._set(scene.q + 0.123)
    drawn = _panel_strings(monkeypatch, SerialRenderer((800, 800)), pygame.Surface((800, 800)), scene.state())
    for q, kind in zip(scene.q, chain.joint_types):
        shown = f"{math.degrees(q):+.1f} deg" if kind == "R" else f"{q:+.3f} m"
        assert shown in drawn, (name, shown, drawn)
        assert f"{q:.3f}" not in drawn  # no bare number (radians) beside it
    roll, pitch, yaw = np.degrees(rk.pose.rpy(chain.fk(scene.q)))
    assert f"{roll:+.1f} {pitch:+.1f} {yaw:+.1f} deg" in drawn


def test_the_rpr_panel_gives_its_joints_units(monkeypatch):
    pygame.display.init()
    scene = RprScene("line")
    drawn = _panel_strings(monkeypatch, RprRenderer((800, 800)), pygame.Surface((800, 800)), scene.state())
    t1, d2, t3 = scene.q
    assert {f"{math.degrees(t1):+.1f} deg", f"{d2:+.3f} m", f"{math.degrees(t3):+.1f} deg"} <= set(drawn)


# --- the camera --------------------------------------------------------------------------------

def test_r_resets_the_view_and_the_preset_views_reset_the_zoom():
    scene = SerialScene(rk.robots.puma560(), name="puma560")
    cam = scene.camera
    start = (cam.azimuth, cam.elevation, cam.zoom, cam.view, tuple(cam.target), cam.extent)
    scene.pointer((80, -40), 3)  # a drag orbits, the wheel zooms in
    assert (cam.azimuth, cam.elevation, cam.zoom) != start[:3] and cam.view == "orbit"
    scene.press("2")
    scene.step(frozenset({"plus"}))
    scene.press("r")
    assert (cam.azimuth, cam.elevation, cam.zoom, cam.view, tuple(cam.target), cam.extent) == start
    assert np.array_equal(scene.q, scene.q_start)
    for key in ("f1", "f2", "f3", "f4", "v"):
        scene.pointer((0, 0), -4)
        assert cam.zoom == pytest.approx(1.15 ** -4)
        scene.press(key)
        assert cam.zoom == 1.0


# --- keys during an animated move --------------------------------------------------------------

def _posture_runs(rows):
    """(first, last) row index of each run of "posture" rows."""
    runs, i = [], 0
    for mode, group in itertools.groupby(r["mode"] for r in rows):
        n = len(list(group))
        if mode == "posture":
            runs.append((i, i + n - 1))
        i += n
    return runs


def test_n_pressed_during_a_posture_move_is_applied_after_it(tmp_path):
    """Nine presses of n on nine frames in a row (all but the first during the first move) show
    nine postures one after the other: the UR5's eight, then the first again."""
    log = tmp_path / "n.csv"
    run_sim("--robot", "ur5", "--keys", ",".join(["n"] * 9), "--frames", "3000", "--log", str(log), render=False)
    rows = read_log(log)
    runs = _posture_runs(rows)
    assert len(runs) == 9
    chain = rk.robots.ur5()
    # The row after each run: the move's last sample, logged with the arm at rest ("joint").
    assert all(rows[last + 1]["mode"] == "joint" for _, last in runs)
    q = np.array([[float(rows[last + 1][f"q_{i}"]) for i in range(6)] for _, last in runs])
    T0 = chain.fk(start_posture(chain))
    solutions = rk.closed.ur(T0, chain)
    for k in range(9):  # each move ends on a closed-form solution of the start's tool pose
        assert np.allclose(chain.fk(q[k]), T0, rtol=0, atol=1e-9)
        assert np.min(np.max(np.abs(solutions.q - q[k]), axis=1)) < 1e-9
    assert len({tuple(np.round(v, 9)) for v in q[:8]}) == 8 and np.allclose(q[8], q[0], atol=1e-9)
    # Back to back: one row of the arm at rest between two moves.
    assert all(b[0] == a[1] + 2 for a, b in zip(runs, runs[1:]))


def test_keys_wait_for_the_move_and_r_does_not():
    scene = SerialScene(rk.robots.ur5(), name="ur5")
    scene.press("n")
    scene.step(frozenset())
    scene.press("3")  # select joint 3: after the move
    scene.press("e")  # the ellipsoid: at once (it does not move the arm)
    assert scene.selected == 0 and scene.show_ellipsoid and scene.mode == "posture"
    while scene.mode == "posture":
        scene.step(frozenset())
    scene.step(frozenset())
    assert scene.selected == 2
    scene.press("n")
    scene.step(frozenset())
    scene.press("n")
    scene.press("r")  # a reset stops the move and drops what waited
    assert scene.mode == "joint" and np.array_equal(scene.q, scene.q_start)
    for _ in range(5):
        scene.step(frozenset())
    assert scene.mode == "joint" and np.array_equal(scene.q, scene.q_start)
