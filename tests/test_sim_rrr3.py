"""The 3-RRR scene: headless runs of each mode, the log against the core, paths, free mode."""

import math

import numpy as np
import pytest
import robokin as rk
from sim_helpers import read_log, run_sim

from robokin_sim.scene_rrr3 import Rrr3Scene

COLUMNS = ["step", "time", "mode", "x", "y", "phi", "alpha_0", "alpha_1", "alpha_2", "det_a", "det_b", "det_a_norm",
           "det_b_norm", "distance", "avoid", "state"]
NUMERIC = [c for c in COLUMNS if c not in ("mode", "state")]


def _array(rows, *names):
    return np.array([[float(r[n]) for n in names] for r in rows]).reshape(len(rows), len(names))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """One headless run per mode and avoidance setting, with a recording and a log."""
    out = tmp_path_factory.mktemp("sim")
    result = {}
    for mode in ("free", "circle", "clover"):
        for avoid in (True, False):
            name = f"{mode}-{'avoid' if avoid else 'noavoid'}"
            log, rec = out / f"{name}.csv", out / f"{name}.gif"
            args = ["--mode", mode, "--frames", "720", "--log", str(log)]
            if avoid:  # record one run per mode (GIF) to keep the suite quick
                args += ["--record", str(rec), "--record-every", "24", "--record-width", "200"]
            else:
                args += ["--no-avoid"]
            keys = ["--keys", "right*30,up*30,l*20,left*60,k*40"] if mode == "free" else []
            res = run_sim(*args, *keys, render=avoid)
            result[name] = (res, read_log(log), rec if avoid else None)
    return result


def test_every_mode_writes_a_recording_and_a_log(runs):
    for name, (res, rows, rec) in runs.items():
        assert res.frames == 720 and len(rows) == 720, name
        assert list(rows[0]) == COLUMNS
        assert np.all(np.isfinite(_array(rows, *NUMERIC))), name
        assert {r["state"] for r in rows} <= {"none", "near", "parallel", "serial"}
        if rec is not None:
            assert rec.stat().st_size > 0 and res.record == str(rec)


def test_logged_alphas_are_the_cores_inverse_model(runs):
    robot = rk.RRR3()
    for name, (_, rows, _) in runs.items():
        pose = _array(rows, "x", "y", "phi")
        alpha = _array(rows, "alpha_0", "alpha_1", "alpha_2")
        np.testing.assert_array_equal(alpha, robot.ik_batch(pose, (1, 1, 1)), err_msg=name)
        for k in range(0, len(rows), 97):
            sing = robot.singularity(pose[k], (1, 1, 1))
            assert float(rows[k]["det_a"]) == sing.det_a and float(rows[k]["det_b"]) == sing.det_b
            assert float(rows[k]["det_a_norm"]) == sing.det_a_norm and float(rows[k]["det_b_norm"]) == sing.det_b_norm
            assert float(rows[k]["distance"]) == sing.distance
            # The normalised determinants are the raw ones over R_e and l1^3.
            assert float(rows[k]["det_a_norm"]) == pytest.approx(float(rows[k]["det_a"]) / robot.platform_radius)
            assert float(rows[k]["det_b_norm"]) == pytest.approx(float(rows[k]["det_b"]) / robot.l1**3)


def test_circle_stays_on_the_circle(runs):
    for name in ("circle-avoid", "circle-noavoid"):
        rows = runs[name][1]
        modes = [r["mode"] for r in rows]
        assert modes[0] == "approach" and "circle" in modes
        first = modes.index("circle")
        assert set(modes[first:]) == {"circle"}  # once on it, it stays on it
        xy = _array(rows[first:], "x", "y")
        assert np.abs(np.hypot(xy[:, 0], xy[:, 1]) - 0.1).max() < 1e-6
        # t advances about 0.01 rad per step.
        t = np.unwrap(np.arctan2(xy[:, 1], xy[:, 0]))
        np.testing.assert_allclose(np.diff(t), 2 * np.pi / 628, rtol=1e-9)
        # The approach moves at most 1 mm per step: no jump to the path.
        steps = np.diff(_array(rows[: first + 1], "x", "y"), axis=0)
        assert np.hypot(steps[:, 0], steps[:, 1]).max() <= 0.001 + 1e-12


def _clover_error(xy):
    t = np.arctan2(xy[:, 1], xy[:, 0])
    r = 0.02 * (1 + np.cos(4 * t) + 2 * np.sin(4 * t) ** 2)
    return np.abs(np.hypot(xy[:, 0], xy[:, 1]) - r)


def test_clover_with_avoidance_tilts_and_never_meets_a_singularity(runs):
    rows = runs["clover-avoid"][1]
    on = [r for r in rows if r["mode"] == "clover"]
    assert len(on) > 600
    assert _clover_error(_array(on, "x", "y")).max() < 1e-6
    assert {r["state"] for r in on} == {"none"}
    det_a = _array(on, "det_a")[:, 0]
    assert np.all(det_a < 0) or np.all(det_a > 0)
    phi = _array(on, "phi")[:, 0]
    assert np.abs(phi).max() > 0.05  # it does tilt ...
    assert np.abs(np.diff(phi)).max() <= 0.01 + 1e-12  # ... in bounded steps
    # ... and comes back: out and back once per leaf at most, no chattering.
    turns = np.count_nonzero(np.diff(np.sign(np.round(np.diff(phi), 12))[np.round(np.diff(phi), 12) != 0]) != 0)
    assert turns <= 16


def test_clover_without_avoidance_reports_the_singularity(runs):
    rows = runs["clover-noavoid"][1]
    on = [r for r in rows if r["mode"] == "clover"]
    assert _clover_error(_array(on, "x", "y")).max() < 1e-6
    assert np.all(_array(on, "phi") == 0.0)
    det_a = _array(on, "det_a")[:, 0]
    assert np.any(det_a < 0) and np.any(det_a > 0)
    states = [r["state"] for r in on]
    assert "parallel" in states and "near" in states
    # Every sign change of det A is logged as a parallel singularity on that step.
    for k in np.nonzero(np.sign(det_a[1:]) != np.sign(det_a[:-1]))[0]:
        assert states[k + 1] == "parallel"


def test_free_mode_script_ends_exactly_there(tmp_path):
    log = tmp_path / "free.csv"
    run_sim("--keys", "right*20,down*10,l*10", "--log", str(log))
    last = read_log(log)[-1]
    assert (float(last["x"]), float(last["y"]), float(last["phi"])) == (0.02, -0.01, 0.1)
    assert last["step"] == "40" and last["mode"] == "free"


def test_free_mode_stops_at_the_boundary(tmp_path):
    log = tmp_path / "down.csv"
    res = run_sim("--keys", "down*400", "--log", str(log), render=False)
    rows = read_log(log)
    assert len(rows) == 400 and np.all(np.isfinite(_array(rows, *NUMERIC)))
    y = _array(rows, "y")[:, 0]
    assert -0.4 < y[-1] < -0.03 and np.all(np.diff(y) <= 0)
    assert np.all(y[-50:] == y[-1])  # it stopped and stays put
    assert "refused" in res.scene.message
    # One more step down would be a serial singularity or out of reach.
    robot = rk.RRR3()
    nxt = [0.0, y[-1] - 0.001, 0.0]
    try:
        assert robot.singularity(nxt).kind == "serial"
    except rk.UnreachableError:
        pass


def test_switching_paths_approaches_from_where_it_is():
    scene = Rrr3Scene("free")
    for _ in range(15):
        scene.step(frozenset({"up", "l"}))
    scene.press("p")
    assert scene.mode == "approach"
    poses = []
    while scene.mode == "approach":
        scene.step(frozenset())
        poses.append(scene.pose.copy())
    poses = np.array(poses)
    assert np.hypot(*np.diff(poses[:, :2], axis=0).T).max() <= 0.001 + 1e-12
    assert np.abs(np.diff(poses[:, 2])).max() <= 0.01 + 1e-12
    np.testing.assert_allclose(poses[-1, :2], [0.04, 0.0], atol=1e-12)


def test_avoidance_toggle_mid_path_approaches_instead_of_jumping():
    scene = Rrr3Scene("clover", avoid=True)
    phis = []
    for k in range(900):
        if k == 500:
            scene.press("s")
        scene.step(frozenset())
        phis.append(scene.pose[2])
    assert np.abs(np.diff(phis)).max() <= 0.01 + 1e-12
    assert scene.avoid is False


def test_reset_and_pause_keys(tmp_path):
    log = tmp_path / "r.csv"
    run_sim("--mode", "circle", "--keys", "right*50,space*1,up*10,space*1,r*1,m*1", "--frames", "80",
            "--log", str(log), render=False)
    rows = read_log(log)
    # Paused from the first space to the second (11 frames): no step, no row.
    assert len(rows) == 80 - 11 and [int(r["step"]) for r in rows] == list(range(1, 70))
    # r went back towards the circle's start from where the robot was (one step of at most 1 mm),
    # m then froze free mode where it was.
    after = rows[51:]  # from the frame r was pressed on
    step = np.hypot(float(after[0]["x"]) - float(rows[50]["x"]), float(after[0]["y"]) - float(rows[50]["y"]))
    assert after[0]["mode"] == "approach" and step <= 0.001 + 1e-12
    assert {r["mode"] for r in after[1:]} == {"free"}


#: Every start the simulator offers before a path: home, free-mode moves, k / l rotations.
STARTS = ["", "l*5,", "k*30,", "l*40,", "k*60,", "right*40,up*20,", "left*50,down*30,l*10,", "up*60,k*20,",
          "down*45,right*30,"]


@pytest.mark.parametrize("path", ["o", "p"])
@pytest.mark.parametrize("start", STARTS)
def test_no_approach_crosses_a_parallel_singularity(tmp_path, start, path):
    """From every start to the circle and the clover, with avoidance on: no logged step is
    parallel and det A never changes sign (approach included)."""
    log = tmp_path / "a.csv"
    frames = sum(int(k.split("*")[1]) for k in start.split(",") if k) + 450
    run_sim("--keys", start + path, "--frames", str(frames), "--log", str(log), render=False)
    rows = read_log(log)
    det = _array(rows, "det_a")[:, 0]
    assert "parallel" not in {r["state"] for r in rows}
    assert np.all(det < 0) or np.all(det > 0)
    name = {"o": "circle", "p": "clover"}[path]
    assert rows[-1]["mode"] in ("approach", name) and name in {r["mode"] for r in rows}
    first = [r["mode"] for r in rows].index(name)
    pose = _array(rows[: first + 1], "x", "y", "phi")  # the moves up to the path: 1 mm, 0.01 rad at most
    assert np.hypot(*np.diff(pose[:, :2], axis=0).T).max() <= 0.001 + 1e-12
    assert np.abs(np.diff(pose[:, 2])).max() <= 0.01 + 1e-12


@pytest.mark.parametrize("mode", ["circle", "clover"])
def test_headless_paths_have_no_parallel_row(tmp_path, mode):
    """The issue's check: robokin-sim --headless --mode circle --log c.csv (the default 700 frames)."""
    log = tmp_path / "c.csv"
    run_sim("--mode", mode, "--log", str(log), render=False)
    rows = read_log(log)
    det = _array(rows, "det_a_norm")[:, 0]
    assert len(rows) == 700 and "parallel" not in {r["state"] for r in rows}
    assert np.all(det < 0) or np.all(det > 0)


def test_reset_keeps_avoidance_and_goes_home_without_crossing():
    scene = Rrr3Scene("free", avoid=True)
    scene.press("s")
    assert scene.avoid is False
    for _ in range(30):
        scene.step(frozenset({"right", "l"}))
    scene.press("r")
    assert scene.avoid is False and "reset" in scene.message  # said, and not silently turned back on
    dets = []
    while scene.mode == "approach":
        scene.step(frozenset())
        dets.append(scene.det_a)
    assert scene.mode == "free" and np.array_equal(scene.pose, [0.0, 0.0, 0.0]) and np.all(np.array(dets) < 0)


def test_reset_after_crossing_in_free_mode_restarts_at_home():
    """Free mode may cross a parallel singularity (the user drives); r then has no way back."""
    scene = Rrr3Scene("free")
    for _ in range(80):
        scene.step(frozenset({"right"}))
    assert scene.det_a > 0  # across the singularity between x = 0.054 and 0.055
    scene.press("r")
    assert "restarted at home" in scene.message and scene.mode == "free"
    assert np.array_equal(scene.pose, [0.0, 0.0, 0.0])


def test_mode_change_clears_the_trail_and_m_in_free_mode_says_so():
    scene = Rrr3Scene("free")
    scene.press("m")
    assert scene.message.startswith("already in free mode")
    for _ in range(10):
        scene.step(frozenset({"up"}))
    assert len(scene.state().trail) == 10
    scene.press("o")
    assert len(scene.state().trail) == 0
    for _ in range(20):
        scene.step(frozenset())
    assert len(scene.state().trail) == 20
    scene.press("m")
    assert len(scene.state().trail) == 0 and scene.mode == "free"


def test_a_path_across_the_singularity_is_refused_with_a_message():
    """On the far side of the parallel singularity (driven there in free mode) the clover at its
    planned orientations is out of reach without crossing back: refused, the robot stays."""
    scene = Rrr3Scene("free")
    for _ in range(80):
        scene.step(frozenset({"right"}))
    pose = scene.pose.copy()
    scene.press("p")
    if scene.mode == "approach":  # a route on this side exists: it must then keep det A > 0
        while scene.mode == "approach":
            scene.step(frozenset())
            assert scene.det_a > 0 and scene.sing != "parallel"
    else:
        assert "refused" in scene.message and np.array_equal(scene.pose, pose) and scene.mode == "free"
