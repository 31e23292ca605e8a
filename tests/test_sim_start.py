"""Where a serial arm starts and what it stands on: the start posture read off the arm (every
catalogue arm and URDF chains: within its limits, clear of singularities by the panel's own rule)
and the floor (never above a joint: the floor at the lowest point the arm reaches, a pedestal up
to the base when that is below the base)."""

import math

import numpy as np
import pygame
import pytest
import robokin as rk
from sim_helpers import urdf_from_dh
from test_urdf import SMALL

from robokin_sim import theme
from robokin_sim.render_common import Hud
from robokin_sim.render_serial import SerialRenderer
from robokin_sim.scene_serial import SerialScene
from robokin_sim.serial_model import NEAR_RATIO, reference_manipulability, sample, start_posture

PI = math.pi
#: DH rows (a, alpha, d, theta) of the IRB 120 (standard) and the Panda (modified, flange 0.107 m),
#: as their makers publish them; the URDFs written from them are checked against the catalogue.
IRB120_DH = [(0, -PI / 2, 0.29, 0), (0.27, 0, 0, -PI / 2), (0.07, -PI / 2, 0, 0), (0, PI / 2, 0.302, 0),
             (0, -PI / 2, 0, 0), (0, 0, 0.072, PI)]
PANDA_DH = [(0, 0, 0.333, 0), (0, -PI / 2, 0, 0), (0, PI / 2, 0.316, 0), (0.0825, PI / 2, 0, 0),
            (-0.0825, -PI / 2, 0.384, 0), (0, PI / 2, 0, 0), (0.088, PI / 2, 0, 0)]


def urdf_chains():
    """(label, chain, the catalogue arm it equals or None) of a few URDF files."""
    irb, panda = rk.robots.irb120(), rk.robots.panda()
    return [
        ("irb120.urdf", rk.Chain.from_urdf(urdf_from_dh("irb120", IRB120_DH, *irb.limits), "l0", "tool"), irb),
        ("panda.urdf", rk.Chain.from_urdf(urdf_from_dh("panda", PANDA_DH, *panda.limits, modified=True,
                                                       flange=0.107), "l0", "tool"), panda),
        ("small.urdf", rk.Chain.from_urdf(SMALL, "base_link", "tool"), None),
    ]


def every_arm():
    return [(name, rk.robots.get(name)) for name in rk.robots.names()] + [(label, c) for label, c, _ in urdf_chains()]


def test_the_urdf_files_are_the_catalogue_arms():
    rng = np.random.default_rng(5)
    for label, chain, arm in urdf_chains():
        if arm is not None:
            q = rng.uniform(*arm.limits, (20, arm.dof))
            assert np.allclose(chain.fk(q), arm.fk(q), rtol=0, atol=1e-12), label


@pytest.mark.parametrize("label, chain", every_arm(), ids=[label for label, _ in every_arm()])
def test_the_start_posture_is_within_the_limits_and_clear_of_singularities(label, chain):
    q = start_posture(chain)
    assert np.array_equal(q, start_posture(chain))  # deterministic
    lower, upper = chain.limits
    limited = np.isfinite(lower) & np.isfinite(upper)
    span = upper - lower
    # At least 5 % of each range from either limit: clear of the panel's red ends of the bars.
    assert np.all(q[limited] - lower[limited] >= 0.05 * span[limited]), (label, np.degrees(q))
    assert np.all(upper[limited] - q[limited] >= 0.05 * span[limited]), (label, np.degrees(q))
    assert np.all((q >= lower) & (q <= upper))
    # Neither "near" nor "singular" by the panel's own rule: the manipulability against the best
    # of the seeded sample, computed here from the core's values.
    ratio = float(chain.manipulability(q)) / reference_manipulability(chain)
    assert ratio >= NEAR_RATIO, (label, ratio)
    scene = SerialScene(chain, name=label)
    assert np.array_equal(scene.q, q) and scene.sing == "none"


def test_the_start_posture_is_the_best_of_its_candidates_and_keeps_turns_mid_range():
    from robokin_sim.serial_model import START_TIE, start_candidates

    for name in ("ur5", "puma560", "panda", "iiwa14"):
        chain = rk.robots.get(name)
        q, candidates = start_posture(chain), start_candidates(chain)
        w = chain.manipulability(candidates)
        assert chain.manipulability(q) >= START_TIE * np.max(w)
        # The base's turn changes no manipulability: it stays mid-range (0 for these arms).
        lower, upper = chain.limits
        assert q[0] == pytest.approx(0.5 * (lower[0] + upper[0]), abs=1e-12)


def _random_postures(chain, scene, rng, n):
    """n postures within the limits (unlimited revolute joints over a turn); an unlimited prismatic
    joint (a travel without a lowest point) stays where the scene started it."""
    q = sample(chain, n, seed=int(rng.integers(1 << 30)))
    lower, upper = chain.limits
    free = np.array([t == "P" for t in chain.joint_types]) & ~(np.isfinite(lower) & np.isfinite(upper))
    q[:, free] = scene.q_start[free]
    return q


@pytest.mark.parametrize("name", [n for n in rk.robots.names()])
def test_no_joint_is_ever_drawn_below_the_floor(name, rng):
    pygame.display.init()
    chain = rk.robots.get(name)
    scene = SerialScene(chain, name=name)
    floor = scene.floor
    size = (640, 640)
    surface, renderer = pygame.Surface(size), SerialRenderer(size)
    for k, q in enumerate(np.vstack([scene.q_start, _random_postures(chain, scene, rng, 60)])):
        z = chain.frames(q)[:, 2, 3]
        assert np.all(z >= floor), (name, k, z.min(), floor)
        if k < 6:  # and as drawn: in the front view no joint is below the floor's line
            scene._set(q)
            scene.press("f1")
            renderer.draw(surface, scene.state(), Hud())
            floor_row = scene.camera.project([0.0, 0.0, floor])[0][1]
            assert max(y for _, y in renderer.joint_pixels) <= floor_row + 0.5
    assert scene.floor == floor  # never had to go down


def test_the_puma_stands_on_a_pedestal_from_the_floor_to_its_shoulder():
    """The PUMA 560's base frame is at its shoulder: its wrist reaches lower than the upper arm's
    length (0.4318 m) below it, so the floor is that far down and a pedestal holds the base."""
    pygame.display.init()
    scene = SerialScene(rk.robots.puma560(), name="puma560")
    assert scene.floor < -0.4318
    planar = SerialScene(rk.robots.planar_3r(), name="planar_3r")
    assert planar.floor == 0.0  # a planar arm never leaves its plane: the floor is at its base
    size = (640, 640)
    surface, renderer = pygame.Surface(size), SerialRenderer(size)
    scene.press("f1")
    renderer.draw(surface, scene.state(), Hud())
    rgb = pygame.surfarray.array3d(surface)  # (w, h, 3)
    # The pedestal's column: pedestal-coloured pixels on the segment from the floor to the base.
    hits = 0
    for f in np.linspace(0.1, 0.9, 9):
        x, y = np.rint(scene.camera.project([0.0, 0.0, f * scene.floor])[0]).astype(int)
        hits += tuple(rgb[x, y]) == theme.PEDESTAL
    assert hits >= 8
    # Seen edge-on from the front, the floor grid is one line at the floor's height, not at the base's.
    grid = {theme.FLOOR, theme.AXES}
    for y_world in (-0.5, -0.3, 0.15, 0.3):
        x, y_floor = np.rint(scene.camera.project([0.0, y_world, scene.floor])[0]).astype(int)
        _, y_base = np.rint(scene.camera.project([0.0, y_world, 0.0])[0]).astype(int)
        assert tuple(rgb[x, y_floor]) in grid and tuple(rgb[x, y_base]) not in grid


def test_the_floor_goes_down_with_a_prismatic_joint_without_limits():
    chain = rk.robots.prr()  # d1 slides along base z, unlimited
    scene = SerialScene(chain, name="prr")
    floor = scene.floor
    scene.press("1")
    for _ in range(3000):
        scene.step(frozenset({"minus"}))
    assert scene.q[0] < scene.q_start[0] - 5.0
    assert scene.floor < floor and np.all(scene.frames[:, 2, 3] >= scene.floor)
    scene.press("r")
    assert scene.floor == floor
