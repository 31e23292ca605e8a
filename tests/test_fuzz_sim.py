"""Property tests of the simulator's user-facing entry points: the command line (any argv gives a
Config or argparse's exit with a usage message, never a traceback), the ``--keys`` script parser
(any string gives a KeyScript or a ValueError naming --keys), and the scenes stepped with any
sequence of key presses and holds (the state and the log row stay finite)."""

import contextlib
import io
import math

import numpy as np
import sim_helpers  # noqa: F401  (SDL dummy drivers before pygame is imported)
import robokin as rk
from fuzz import arrays, check_call, finite_arrays
from hypothesis import given, settings
from hypothesis import strategies as st
from robokin import plots, plots_arm

from robokin_sim.config import MODES, Config, parse_args
from robokin_sim.keys import ALIASES, HELD_KEYS, KEYS, MAX_HOLD, KeyScript, parse_script
from robokin_sim.scene_serial import SerialScene
from robokin_sim.scenes import SCENES

COVERS = {"sim.parse_args", "sim.parse_script", "sim.KeyScript.inputs", "sim.Rrr3Scene", "sim.RprScene",
          "sim.Scene.step", "sim.Scene.press", "sim.Scene.row", "sim.SerialScene", "sim.Scene.pointer",
          "plots.joint_axes", "plots_arm.arm", "plots_arm.animate", "plots_arm.teach"}

OPTIONS = ["--robot", "--mode", "--headless", "--demo", "--frames", "--record", "--record-every", "--record-width",
           "--log", "--screenshot", "--keys", "--no-avoid", "--size", "--fps", "-h", "--help", "--rob", "--bogus", "--"]
VALUES = ["rrr3", "rpr", "free", "circle", "clover", "line", "0", "1", "-3", "10", "1e3", "99999999999999999999",
          "a.gif", "a.mp4", "a.GIF", "a.avi", "", "out/x.csv", "800x600", "10x10", "4096x4096", "1x2x3", "x",
          "right*20,down*10", "fly*2", "l*0", "esc", "nan"]
argv_tokens = st.one_of(st.sampled_from(OPTIONS), st.sampled_from(VALUES), st.text(max_size=8))


@given(argv=st.lists(argv_tokens, max_size=8))
def test_parse_args_any_argv(argv):
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            config = parse_args(argv)
    except SystemExit as exc:
        assert exc.code in (0, 2), exc.code
        if exc.code == 2:  # one line naming the problem
            lines = err.getvalue().splitlines()
            assert len(lines) == 1 and lines[0].startswith("robokin-sim: error: "), lines
        else:
            assert "usage" in out.getvalue()
        return
    assert isinstance(config, Config)
    assert config.robot in MODES and config.mode in MODES[config.robot]
    assert config.frames is None or (isinstance(config.frames, int) and 1 <= config.frames <= 10**9)
    assert config.record is None or config.record.lower().endswith((".gif", ".mp4"))
    assert config.record_every >= 1 and config.fps >= 1
    assert config.record_width is None or 100 <= config.record_width <= 4096
    assert config.fps <= 1000 and config.record_every <= 10_000
    for path in (config.log, config.screenshot, config.record):
        assert path is None or path.strip()
    assert all(100 <= v <= 4096 for v in config.size) and len(config.size) == 2
    assert isinstance(config.keys, KeyScript)


key_names = st.sampled_from(list(KEYS) + list(ALIASES) + ["ESC", "Right", "jump", ""])
counts = st.one_of(st.integers(-2, 50), st.sampled_from([MAX_HOLD, MAX_HOLD + 1, 10**30]))
items = st.one_of(
    st.tuples(key_names, counts).map(lambda kc: f"{kc[0]}*{kc[1]}"),
    key_names,
    st.text(max_size=10),
)


@given(text=st.one_of(st.lists(items, max_size=8).map(",".join), st.text(max_size=30)))
def test_parse_script_any_string(text):
    try:
        script = parse_script(text)
    except ValueError as exc:
        assert str(exc).startswith("--keys: ")
        return
    assert all(all(k in KEYS for k in name.split("+")) and 1 <= n <= MAX_HOLD for name, n in script.items)
    assert script.frames == sum(n for _, n in script.items)
    if script.frames < 2000:
        inputs = list(script.inputs())
        assert len(inputs) == script.frames
        assert sum(bool(i.pressed) for i in inputs) == len(script.items)


@given(script=st.lists(st.tuples(st.sampled_from(KEYS), st.integers(1, 100)), max_size=6))
def test_parse_script_round_trip(script):
    text = ", ".join(f"{k.upper()}*{n}" for k, n in script)
    assert parse_script(text).items == tuple(script)


# --- scenes ------------------------------------------------------------------------------------

_SCENES = {}


def scene_for(robot, mode, avoid):
    """One scene per (robot, mode, avoid), reset for each example: its orientation plans, workspace
    maps and paths are caches (planning a 3-RRR path takes ~0.1 s)."""
    key = (robot, mode, avoid)
    if key not in _SCENES:
        _SCENES[key] = SCENES[robot].scene(Config(robot=robot, mode=mode, avoid=avoid))
    scene = _SCENES[key]
    scene.reset()
    scene.steps = 0
    return scene


NUMERIC = {"rrr3": (3, 11), "rpr": (3, 9)}  # the numeric columns of the log row, [start, stop)
frames = st.tuples(
    st.frozensets(st.sampled_from(KEYS), max_size=2),  # pressed this frame
    st.frozensets(st.sampled_from(sorted(HELD_KEYS)), max_size=3),  # held
    st.integers(1, 25),  # for this many steps
    st.tuples(st.integers(-400, 400), st.integers(-400, 400), st.integers(-5, 5)),  # mouse drag and wheel
)
ROBOT_MODES = [(r, m) for r in MODES if r != "urdf" for m in MODES[r]]


@given(robot_mode=st.sampled_from(ROBOT_MODES), avoid=st.booleans(), inputs=st.lists(frames, max_size=12))
def test_scene_any_key_sequence(robot_mode, avoid, inputs):
    robot, mode = robot_mode
    scene = scene_for(robot, mode, avoid)
    steps = 0
    for pressed, held, n, (dx, dy, wheel) in inputs:
        for key in sorted(pressed):
            scene.press(key, held)
        scene.pointer((dx, dy), wheel)
        for _ in range(n):
            scene.step(held | pressed)
            steps += 1
            row = scene.row()
            assert len(row) == len(scene.columns) and row[0] == steps
            lo, hi = NUMERIC.get(robot, (3, len(row) - 1))
            values = np.array(row[lo:hi], dtype=float)
            assert np.all(np.isfinite(values)), (row, scene.message)
            if isinstance(scene, SerialScene) and scene.mode == "cartesian":
                # The tool is on the pose the jog commanded (the task's rows of it).
                T = scene.chain.fk(scene.q)
                assert np.allclose(T[:3, 3], scene._command[:3, 3], atol=1e-9) or scene.task != "pose"
        assert isinstance(scene.message, str)
    state = scene.state()
    assert scene.steps == steps and math.isclose(scene.time, steps / 60.0)
    if robot == "rrr3":
        assert state.mode in ("free", "approach", "circle", "clover")
        assert np.all(np.isfinite(state.pose)) and np.all(np.isfinite(state.alpha))
        assert all(np.all(np.isfinite(v)) for v in state.points.values())
        # the pose the scene shows is one the robot reaches in its working mode
        assert scene._evaluate(state.pose) is not None
    elif robot == "rpr":
        assert state.mode in ("free", "approach", "line")
        assert np.all(np.isfinite(state.q)) and np.all(np.isfinite(state.frames))
        assert np.allclose(state.frames[-1][:2, 3], scene.tip, atol=1e-12)
        assert np.all(state.q >= state.lower - 1e-9) and np.all(state.q <= state.upper + 1e-9)
    else:
        assert state.mode in ("joint", "cartesian", "posture", "approach", "circle", "line")
        assert np.all(np.isfinite(state.q)) and np.all(np.isfinite(state.frames))
        assert np.all(state.q >= state.lower) and np.all(state.q <= state.upper)
        assert np.allclose(state.frames[-1], scene.chain.fk(state.q), atol=1e-12)
        assert np.all(np.isfinite(state.axes)) and -math.pi / 2 <= state.camera.elevation <= math.pi / 2
        assert state.state in ("none", "near", "singular", "limit", "unreachable")


# --- the serial chains' drawings (robokin.plots) -------------------------------------------------

UR5 = rk.robots.ur5()


@given(q=st.one_of(arrays([(6,), (5,), (6, 1), ()]), finite_arrays((6,), -1e6, 1e6)))
def test_joint_axes_any_q(q):
    axes = check_call(lambda: plots.joint_axes(UR5, q), "q")
    if axes is not None:
        assert axes.shape == (6, 2, 3) and np.all(np.isfinite(axes))
        assert np.allclose(np.linalg.norm(axes[:, 1], axis=1), 1.0)


@settings(max_examples=30)
@given(q=st.one_of(arrays([(6,), (7,)]), finite_arrays((6,), -10, 10)),
       flags=st.tuples(*[st.one_of(st.booleans(), st.sampled_from([None, 1, "yes"]))] * 3))
def test_arm_any_q_and_flags(q, flags):
    frames, axes, ellipsoid = flags
    ax = check_call(lambda: plots_arm.arm(UR5, q, frames=frames, axes=axes, ellipsoid=ellipsoid),
                    "q", "frames", "axes", "ellipsoid")
    if ax is not None:
        assert ax.name == "3d" and len([line for line in ax.lines if line.get_gid() == "tool"]) == 3


@settings(max_examples=20)
@given(q=st.one_of(st.none(), arrays([(6,), (7,)]), finite_arrays((6,), -10, 10)))
def test_teach_any_start(q):
    box = check_call(lambda: plots_arm.teach(UR5, q), "q")
    if box is not None:
        lo, hi = UR5.limits
        values = np.array([s.value for s in box.children[:6]])
        assert np.all((lo <= values) & (values <= hi))


@settings(max_examples=30)
@given(qs=st.one_of(arrays([(1, 6), (2, 6), (2, 5), (0, 6)]), finite_arrays((2, 6), -3, 3)),
       fps=st.one_of(st.floats(-1, 200), st.sampled_from([True, "10", None, math.nan])),
       size=st.one_of(st.tuples(st.integers(0, 3000), st.integers(0, 3000)), st.sampled_from([None, "big", (1,)])),
       suffix=st.sampled_from([".gif", ".mp4", ".png", ""]))
def test_animate_any_arguments(tmp_path_factory, qs, fps, size, suffix):
    directory = tmp_path_factory.mktemp("anim")
    size = size if not isinstance(size, tuple) or len(size) != 2 or max(size) < 700 else (64, 64)
    out = check_call(lambda: plots_arm.animate(UR5, qs, directory / f"a{suffix}", fps=fps, size=size),
                     "qs", "fps", "size", "path")
    names = sorted(p.name for p in directory.iterdir())
    assert names == ([f"a{suffix}"] if out is not None else [])
