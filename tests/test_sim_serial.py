"""The serial-arm scene: drawing, joint and Cartesian jog, limits, singularities, postures, paths
and URDF files, checked against independent truth (the projection formula written out here, the
closed forms, forward kinematics, the rotation matrices about the base axes, the planar 3R's
reach)."""

import math
import os
import subprocess
import sys

import numpy as np
import pygame
import pytest
import robokin as rk
from sim_helpers import read_log, run_sim
from test_urdf import PUMA_DH, SMALL, UR5_DH, urdf_from_dh
from test_urdf_names import Y_TREE

from robokin_sim import theme
from robokin_sim.camera import CENTRE
from robokin_sim.render_common import Hud
from robokin_sim.render_serial import ELLIPSOID_SECONDS, SerialRenderer
from robokin_sim.scene_serial import JOINT_STEP, MAX_JOINT_STEP, MOVE_STEP, PATH_SIZE, TURN_STEP, SerialScene
from robokin_sim.serial_model import start_posture


def rot(axis, angle):
    """Rotation matrix about base axis 0, 1 or 2 (written out, not from robokin)."""
    c, s = math.cos(angle), math.sin(angle)
    return [np.array([[1, 0, 0], [0, c, -s], [0, s, c]]), np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])][axis]


def joints(row, dof):
    return np.array([float(row[f"q_{i}"]) for i in range(dof)])


def steps(scene, held, n):
    for _ in range(n):
        scene.step(frozenset(held))


# --- drawing -----------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["ur5", "puma560", "panda", "prr"])
def test_drawn_joints_are_the_projection_of_the_frames(name, rng):
    pygame.display.init()
    chain = rk.robots.get(name)
    scene = SerialScene(chain, name=name)
    lower, upper = chain.limits
    lo, hi = np.where(np.isfinite(lower), lower, -3), np.where(np.isfinite(upper), upper, 3)
    size = (640, 520)
    surface = pygame.Surface(size)
    renderer = SerialRenderer(size)
    for _ in range(5):
        q = rng.uniform(lo, hi)
        az, el, zoom = rng.uniform(-math.pi, math.pi), rng.uniform(-1.4, 1.4), rng.uniform(0.6, 1.6)
        scene._set(q)
        cam = scene.camera
        cam.azimuth, cam.elevation, cam.zoom = az, el, zoom
        renderer.draw(surface, scene.state(), Hud())
        # The projection, written out: camera direction d, screen right r, up u = d x r.
        d = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
        r = np.array([-math.sin(az), math.cos(az), 0.0])
        u = np.cross(d, r)
        scale = zoom * min(size) / (2 * cam.extent)
        p = chain.frames(q)[:, :3, 3] - cam.target
        cx, cy = CENTRE[0] * size[0], CENTRE[1] * size[1]
        expected = np.column_stack([cx + scale * p @ r, cy - scale * p @ u])
        assert np.array_equal(np.array(renderer.joint_pixels), np.rint(expected).astype(int))
        rgb = pygame.surfarray.array3d(surface)  # (w, h, 3)
        pixels = [tuple(p) for p in np.rint(expected).astype(int)]
        for k, (x, y) in enumerate(pixels):
            if 0 <= x < size[0] and 0 <= y < size[1] and not renderer.panel_rect.collidepoint(x, y):
                # Joint centres are dotted on top; the tool point carries the tool's marker.
                colour = theme.JOINT_EDGE if (x, y) in pixels[:-1] else theme.TARGET
                assert tuple(rgb[x, y]) == colour, (name, k, x, y)


def test_preset_views_put_the_axes_where_they_belong():
    scene = SerialScene(rk.robots.ur5(), name="ur5")
    cam = scene.camera
    for key, right, up in (("f1", 1, 2), ("f2", 0, 2), ("f3", 0, 1)):  # front: y right; side: x right; top: x, y
        scene.press(key)
        origin = cam.project([0.0, 0.0, 0.0])[0]
        e = np.eye(3)
        assert cam.project(e[right])[0][0] > origin[0] and abs(cam.project(e[right])[0][1] - origin[1]) < 1e-9
        assert cam.project(e[up])[0][1] < origin[1] and abs(cam.project(e[up])[0][0] - origin[0]) < 1e-9
    planar = SerialScene(rk.robots.planar_3r(), name="planar_3r")
    assert planar.camera.view == "top" and scene.camera.view == "top"
    assert SerialScene(rk.robots.ur5(), name="ur5").camera.view == "iso"
    # A drag orbits, the wheel zooms, v cycles the presets.
    az, zoom = cam.azimuth, cam.zoom
    scene.pointer((50, 0), 2)
    assert cam.azimuth == pytest.approx(az - 0.5) and cam.zoom == pytest.approx(zoom * 1.15 ** 2)
    scene.press("v")
    assert cam.view == "front"


def test_ellipsoid_is_drawn_along_its_principal_axes():
    pygame.display.init()
    scene = SerialScene(rk.robots.ur5(), name="ur5")
    surface = pygame.Surface((800, 800))
    renderer = SerialRenderer((800, 800))
    renderer.draw(surface, scene.state(), Hud())
    rgb = pygame.surfarray.array3d(surface)
    assert np.count_nonzero(np.all(rgb == theme.ELLIPSOID, axis=2)) == 0
    scene.press("e")
    renderer.draw(surface, scene.state(), Hud())
    rgb = pygame.surfarray.array3d(surface)
    # The singular vectors of the Jacobian's translation rows (numpy, independently of the core).
    u, s, _ = np.linalg.svd(scene.chain.jacobian(scene.q)[:3])
    tip = scene.chain.fk(scene.q)[:3, 3]
    hits = 0
    for k in range(3):
        for sign in (-1, 1):
            x, y = np.rint(scene.camera.project(tip + sign * ELLIPSOID_SECONDS * s[k] * u[:, k])[0]).astype(int)
            window = rgb[max(x - 1, 0):x + 2, max(y - 1, 0):y + 2].reshape(-1, 3)
            hits += any(tuple(c) == theme.ELLIPSOID for c in window)
    assert hits >= 5


# --- joint jog ---------------------------------------------------------------------------------

def test_joint_keys_land_on_exact_joint_values(tmp_path):
    log = tmp_path / "j.csv"
    run_sim("--robot", "ur5", "--keys", "2,plus*20,3,minus*7,tab,plus*5,6,+*3", "--log", str(log), render=False)
    rows = read_log(log)
    q0 = start_posture(rk.robots.ur5())
    q = joints(rows[-1], 6)
    expected = q0.copy()
    expected[1] = q0[1] + 20 * JOINT_STEP["R"]
    expected[2] = q0[2] - 7 * JOINT_STEP["R"]
    expected[3] = q0[3] + 5 * JOINT_STEP["R"]
    expected[5] = q0[5] + 3 * JOINT_STEP["R"]
    assert np.array_equal(q, expected)
    assert {r["mode"] for r in rows} == {"joint"}
    # The logged tool pose is the forward model's at the logged joints.
    T = rk.robots.ur5().fk(q)
    assert np.allclose([float(rows[-1][c]) for c in "xyz"], T[:3, 3], atol=1e-12)


def test_jogging_a_joint_into_its_limit_stops_on_it():
    chain = rk.robots.puma560()
    scene = SerialScene(chain, name="puma560")
    scene.press("5")
    steps(scene, {"plus"}, 400)  # q5 from its start (at most 90 % of the way up) to its 100 deg limit
    assert scene.q[4] == chain.limits[1][4]
    assert scene.sing == "limit" and "limit" in scene.message
    steps(scene, {"minus"}, 3)
    assert scene.q[4] == pytest.approx(chain.limits[1][4] - 3 * JOINT_STEP["R"], abs=1e-15)
    # A prismatic joint (the DH exercise's PRR) jogs in metres.
    prr = SerialScene(rk.robots.prr(), name="prr")
    d1 = prr.q[0]
    steps(prr, {"plus"}, 10)
    assert prr.q[0] == d1 + 10 * JOINT_STEP["P"]


# --- Cartesian jog -----------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["ur5", "puma560", "panda"])
def test_cartesian_keys_move_the_tool_by_the_commanded_amount(name, tmp_path):
    log = tmp_path / "c.csv"
    chain = rk.robots.get(name)
    run_sim("--robot", name, "--keys", "right*20,space,space,up*10,pagedown*15", "--log", str(log), render=False)
    rows = read_log(log)
    q0, q = start_posture(chain), joints(rows[-1], chain.dof)
    T0, T = chain.fk(q0), chain.fk(q)
    assert np.allclose(T[:3, 3] - T0[:3, 3], np.array([20, 10, -15]) * MOVE_STEP, rtol=0, atol=1e-9)
    assert np.allclose(T[:3, :3], T0[:3, :3], rtol=0, atol=1e-9)
    assert rows[-1]["mode"] == "cartesian"
    # Shift turns about the base axes through the tool point.
    log2 = tmp_path / "r.csv"
    run_sim("--robot", name, "--keys", "shift+right*10,shift+pageup*5", "--log", str(log2), render=False)
    q = joints(read_log(log2)[-1], chain.dof)
    T = chain.fk(q)
    assert np.allclose(T[:3, 3], T0[:3, 3], rtol=0, atol=1e-9)
    assert np.allclose(T[:3, :3], rot(2, 5 * TURN_STEP) @ rot(0, 10 * TURN_STEP) @ T0[:3, :3], rtol=0, atol=1e-9)


def test_the_null_space_term_moves_a_redundant_arm_differently_for_the_same_tool_path():
    chain = rk.robots.panda()
    q0 = np.radians([0, -45, 0, -135, 0, 90, 45])  # off mid-range, where the term's gradient is not zero
    with_term, without = (SerialScene(chain, name="panda", q0=q0, avoid=avoid) for avoid in (True, False))
    for scene in (with_term, without):
        steps(scene, {"left"}, 60)
    assert np.allclose(chain.fk(with_term.q), chain.fk(without.q), rtol=0, atol=1e-9)
    assert np.max(np.abs(with_term.q - without.q)) > 1e-3
    # The term pulls toward the middle of the ranges (the RPR study's cost z), so z is lower with it.
    assert rk.joint_limit_cost(chain, with_term.q) < rk.joint_limit_cost(chain, without.q)


def test_jogging_into_a_singularity_stays_finite_and_warns(tmp_path):
    # The PUMA's tool pushed outward: the elbow straightens toward the workspace boundary.
    log = tmp_path / "s.csv"
    run_sim("--robot", "puma560", "--keys", "right*400", "--log", str(log), render=False)
    rows = read_log(log)
    q = np.array([joints(r, 6) for r in rows])
    w = np.array([float(r["manipulability"]) for r in rows])
    assert np.all(np.isfinite(q)) and np.all(np.isfinite(w))
    assert np.max(np.abs(np.diff(q, axis=0))) <= MAX_JOINT_STEP
    assert "near" in {r["state"] for r in rows}
    assert w[-1] <= np.min(w) and w[-1] < 0.5 * w[0]  # it got close, and stopped: the last rows no longer move
    assert np.array_equal(q[-1], q[-20])
    scene = SerialScene(rk.robots.puma560(), name="puma560")
    steps(scene, {"right"}, 400)
    assert scene.message.startswith("step refused: near a singularity")
    # UR5 at its wrist singularity (q5 = 0: axes 4 and 6 parallel): a turn about that axis is refused
    # or taken without a joint jump, never a NaN.
    ur = SerialScene(rk.robots.ur5(), name="ur5", q0=[0, -1.9, 1.7, -1.4, 1e-4, 0])
    assert ur.sing == "singular"
    for held in ({"shift", "up"}, {"shift", "right"}, {"left"}, {"pageup"}):
        before = ur.q.copy()
        steps(ur, held, 20)
        assert np.all(np.isfinite(ur.q)) and np.max(np.abs(ur.q - before)) <= 20 * MAX_JOINT_STEP


def test_a_planar_arm_refuses_what_it_cannot_do():
    scene = SerialScene(rk.robots.planar_3r(), name="planar_3r")
    q0, T0 = scene.q.copy(), scene.chain.fk(scene.q)
    steps(scene, {"pageup"}, 5)
    assert np.array_equal(scene.q, q0) and "cannot" in scene.message
    steps(scene, {"shift", "pageup"}, 10)  # about z: the planar orientation phi
    T = scene.chain.fk(scene.q)
    assert np.allclose(T[:3, :3], rot(2, 10 * TURN_STEP) @ T0[:3, :3], atol=1e-9)
    assert np.allclose(T[:3, 3], T0[:3, 3], atol=1e-9)


# --- postures ----------------------------------------------------------------------------------

# The PUMA from a posture whose 8 closed-form postures are all within its limits (at its start
# posture only some are).
@pytest.mark.parametrize("name, solve, q0", [("puma560", lambda T, c: rk.closed.puma560(T), [0, 50, -150, -20, 60, 0]),
                                             ("ur5", lambda T, c: rk.closed.ur(T, c), None)])
def test_cycling_postures_visits_every_closed_form_solution(name, solve, q0):
    chain = rk.robots.get(name)
    scene = SerialScene(chain, name=name, q0=None if q0 is None else np.radians(q0))
    T0 = chain.fk(scene.q)
    solutions = solve(T0, chain)
    assert len(solutions) == 8
    visited, labels = [], set()
    for _ in range(8):
        scene.press("n")
        assert scene.mode == "posture"
        path = [scene.q.copy()]
        while scene.mode == "posture":
            scene.step(frozenset())
            path.append(scene.q.copy())
        assert len(path) > 20  # animated, not a jump
        assert np.max(np.abs(np.diff(path, axis=0))) < 0.1
        visited.append(scene.q.copy())
        labels.add(scene.posture.split(": ", 1)[1])
        assert np.allclose(chain.fk(scene.q), T0, rtol=0, atol=1e-9)  # verified by FK
    match = [int(np.argmin(np.max(np.abs(solutions.q - v), axis=1))) for v in visited]
    assert sorted(match) == list(range(8))
    assert all(np.max(np.abs(solutions.q[k] - v)) < 1e-12 for k, v in zip(match, visited))
    assert labels == set(solutions.postures)


def test_an_arm_without_a_closed_form_says_so():
    scene = SerialScene(rk.robots.panda(), name="panda")
    q = scene.q.copy()
    scene.press("n")
    assert "no closed form" in scene.message and scene.mode == "joint"
    scene.step(frozenset())
    assert np.array_equal(scene.q, q)


# --- paths -------------------------------------------------------------------------------------

def test_the_circle_is_traced_with_the_orientation_kept(tmp_path):
    log = tmp_path / "circle.csv"
    res = run_sim("--robot", "ur5", "--mode", "circle", "--frames", "400", "--log", str(log), render=False)
    rows = read_log(log)
    chain = rk.robots.ur5()
    T0 = chain.fk(start_posture(chain))
    p = np.array([[float(r[c]) for c in "xyz"] for r in rows])
    scene = res.scene
    radius = 0.12 * scene.size
    centre = p[:360].mean(axis=0)
    assert np.allclose(np.linalg.norm(p - centre, axis=1), radius, rtol=0, atol=1e-6)
    # Through the start's tool point, in the vertical plane facing the robot (normal: the horizontal
    # direction from the base to the tool).
    out = T0[:3, 3] * [1, 1, 0] / np.linalg.norm(T0[:2, 3])
    assert np.allclose(centre, T0[:3, 3] - radius * np.cross([0, 0, 1], out), atol=1e-6)
    assert np.allclose((p - centre) @ out, 0, atol=1e-9)
    for r in rows[::37]:
        assert np.allclose(chain.fk(joints(r, 6))[:3, :3], T0[:3, :3], atol=1e-8)
    assert {r["mode"] for r in rows} == {"circle"} and "unreachable" not in {r["state"] for r in rows}
    assert "all reached" in scene.message


def test_unreachable_path_points_are_reported():
    # Planar 3R (a = 1, 1, 1) at a fixed phi: the tip reaches p when the wrist p - (cos phi, sin phi)
    # is within a1 + a2 = 2 of the base (the IK course, example 2). Started nearly stretched, every
    # size of circle through the start leaves that disc.
    chain = rk.robots.planar_3r()
    scene = SerialScene(chain, name="planar_3r", mode="circle", q0=np.radians([30, 2, 2]))
    points, missed = scene.path, scene.missed
    phi = sum(np.radians([30, 2, 2]))
    wrist = np.linalg.norm(points[:, :2] - [math.cos(phi), math.sin(phi)], axis=1)
    assert np.any(missed) and np.any(~missed)
    clear = np.abs(wrist - 2.0) > 1e-3
    assert np.array_equal(missed[clear], wrist[clear] > 2.0)
    assert "unreachable" in scene.message
    states = []
    for _ in range(len(points)):
        scene.step(frozenset())
        states.append(scene.sing)
    assert states.count("unreachable") == np.count_nonzero(missed)


def test_a_circle_out_of_reach_is_made_smaller_until_every_point_is_reached():
    # The Panda and the iiwa14 from their ready poses, the orientation kept: a circle of PATH_SIZE
    # leaves their reach (74 and 91 of 360 points), one of half that size does not.
    for name in ("panda", "iiwa14"):
        scene = SerialScene(rk.robots.get(name), name=name, mode="circle")
        p = scene.path
        radius = np.linalg.norm(p - p.mean(axis=0), axis=1)
        assert not scene.missed.any() and "all reached" in scene.message, name
        assert np.allclose(radius, 0.5 * PATH_SIZE * scene.size, rtol=0, atol=1e-9), name
        # Reached indeed: the path's joints put the tool on every point (KDL's FK, the start's orientation).
        T0 = scene.chain._fk_kdl(scene.q_start)
        for point, q in zip(p, scene._path_q):
            T = scene.chain._fk_kdl(q)
            assert np.allclose(T[:3, 3], point, atol=1e-8) and np.allclose(T[:3, :3], T0[:3, :3], atol=1e-8), name
    ur5 = SerialScene(rk.robots.ur5(), name="ur5", mode="circle")  # reached at full size
    assert np.allclose(np.linalg.norm(ur5.path - ur5.path.mean(axis=0), axis=1), PATH_SIZE * ur5.size)


def test_switching_to_the_line_approaches_it_first():
    scene = SerialScene(rk.robots.puma560(), name="puma560")
    steps(scene, {"up"}, 10)
    scene.press("p")
    assert scene.mode == "approach"
    while scene.mode == "approach":
        scene.step(frozenset())
    assert scene.mode == "line"
    scene.press("m")
    assert scene.mode == "joint" and scene.path is None


# --- URDF --------------------------------------------------------------------------------------

def test_urdf_scenes_load_the_suites_files(tmp_path):
    small = tmp_path / "small.urdf"
    small.write_text(SMALL)
    log = tmp_path / "u.csv"
    res = run_sim("--urdf", str(small), "--keys", "plus*5,right*3", "--log", str(log), "--screenshot",
                  str(tmp_path / "u.png"))
    assert res.scene.dof == 3 and res.scene.title == "small.urdf (base_link -> tool)"
    assert read_log(log)[0].keys() >= {"q_0", "q_1", "q_2", "manipulability"}
    ur5 = tmp_path / "ur5.urdf"
    lo, hi = rk.robots.ur5().limits
    ur5.write_text(urdf_from_dh("ur5", UR5_DH, lo, hi))
    res = run_sim("--urdf", str(ur5), "--frames", "2")
    scene = res.scene
    assert np.allclose(scene.chain.fk(scene.q), rk.robots.ur5().fk(scene.q), atol=1e-12)
    puma = tmp_path / "puma.urdf"
    lo, hi = rk.robots.puma560().limits
    puma.write_text(urdf_from_dh("puma", PUMA_DH, lo, hi))
    scene = run_sim("--urdf", str(puma), "--base", "l1", "--tip", "l4", "--frames", "1").scene
    assert scene.dof == 3


@pytest.mark.parametrize("content, extra, says", [
    (None, [], "no such file"),
    ("<robot name='x'><link name='a'/>", [], "--urdf"),
    ("not xml at all", [], "--urdf"),
    (SMALL, ["--tip", "nowhere"], "nowhere"),
    (SMALL, ["--base", "link3", "--tip", "tool"], "no moving joint"),
    (Y_TREE, [], "end at 'left_tip' and 'right_tip' (3 movable joints each): pass --tip LINK"),
])
def test_a_bad_urdf_is_one_line_and_exit_2(tmp_path, content, extra, says):
    path = tmp_path / "bad.urdf"
    if content is not None:
        path.write_text(content)
    env = dict(os.environ, SDL_VIDEODRIVER="dummy")
    out = subprocess.run([sys.executable, "-m", "robokin_sim", "--headless", "--urdf", str(path), *extra],
                         capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("robokin-sim: error: --urdf") and says in lines[0], lines


def test_robot_names_and_options():
    from robokin_sim.config import parse_args

    for name in rk.robots.names():
        assert parse_args(["--robot", name]).robot == name
    assert parse_args(["--robot", "planar3r"]).robot == "planar_3r"
    assert parse_args(["--robot", "ur5"]).mode == "free"
    for argv in (["--robot", "ur5", "--mode", "clover"], ["--tip", "x"], ["--robot", "ur5", "--urdf", "x.urdf"]):
        with pytest.raises(SystemExit):
            parse_args(argv)


def test_every_catalogue_arm_runs_every_mode_headless(tmp_path):
    for name in rk.robots.names():
        if name == "rpr":
            continue
        for mode in ("free", "circle", "line"):
            log = tmp_path / f"{name}-{mode}.csv"
            res = run_sim("--robot", name, "--mode", mode, "--frames", "30", "--keys", "n,e,right*5,f2", "--log",
                          str(log), render=mode == "free")
            rows = read_log(log)
            assert len(rows) == 30 and list(rows[0])[:3] == ["step", "time", "mode"]
            assert list(rows[0])[-8:] == ["x", "y", "z", "roll", "pitch", "yaw", "manipulability", "state"]
            dof = res.scene.dof
            assert list(rows[0])[3:3 + dof] == [f"q_{i}" for i in range(dof)]
            values = np.array([[float(r[c]) for c in list(r)[3:-1]] for r in rows])
            assert np.all(np.isfinite(values)), (name, mode)


def test_the_readme_lists_every_key_of_the_serial_scene():
    from robokin_sim.scenes import SERIAL_HELP

    readme = open(os.path.join(os.path.dirname(__file__), "..", "README.md"), encoding="utf-8").read()
    section = readme[readme.index("### Serial arms in the simulator"):readme.index("## Conventions")]
    for keys, _ in SERIAL_HELP:
        for key in keys.replace(" - ", " / ").split(" / "):
            assert f"`{key}`" in section, key
    assert "step,time,mode,q_0..q_{n-1},x,y,z,roll,pitch,yaw,manipulability,state" in section
    assert "docs/sim_puma560.png" in section and os.path.getsize(os.path.join(os.path.dirname(__file__), "..", "docs",
                                                                              "sim_puma560.png")) < 200_000


def test_recording_and_random_keys_while_drawing(tmp_path):
    from PIL import Image

    gif = tmp_path / "ur5.gif"
    run_sim("--robot", "ur5", "--mode", "line", "--frames", "40", "--record", str(gif), "--record-width", "200",
            "--size", "640x400")
    with Image.open(gif) as im:
        assert im.n_frames == 20 and im.size == (200, 125)
    rng = np.random.default_rng(3)
    from robokin_sim.keys import KEYS

    keys = [k for k in KEYS if k != "esc"]
    for name in ("panda", "planar_3r"):
        items = [f"{k}*{int(rng.integers(1, 15))}" for k in rng.choice(keys, size=50)]
        items += [f"shift+{k}*{int(rng.integers(1, 30))}" for k in rng.choice(["up", "left", "pageup"], size=10)]
        rng.shuffle(items)
        res = run_sim("--robot", name, "--keys", ",".join(items), "--screenshot", str(tmp_path / f"{name}.png"))
        assert res.frames > 50 and (tmp_path / f"{name}.png").stat().st_size > 0
        q = res.scene.q
        assert np.all(np.isfinite(q)) and np.all(q >= res.scene.lower) and np.all(q <= res.scene.upper)
