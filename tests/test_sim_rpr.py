"""The RPR scene: the Reach loop along the RPR study's line, both solutions, free mode, joint limits."""

import math
import warnings

import numpy as np
import pytest
import robokin as rk
from sim_helpers import read_log, run_sim

from robokin_sim.scene_rpr import P2, Q1, RprScene


def _floats(rows, *names):
    return np.array([[float(r[n]) for n in names] for r in rows])


@pytest.mark.parametrize("avoid", [True, False])
def test_line_run_logs_reach_results(tmp_path, avoid):
    log, gif = tmp_path / "rpr.csv", tmp_path / "rpr.gif"
    args = ["--robot", "rpr", "--frames", "750", "--log", str(log), "--record", str(gif), "--record-every", "10"]
    res = run_sim(*args, *([] if avoid else ["--no-avoid"]))
    assert res.frames == 750 and gif.stat().st_size > 0
    rows = read_log(log)
    assert len(rows) == 750 and list(rows[0]) == list(RprScene.columns)
    assert {r["mode"] for r in rows} == {"line"}
    q = _floats(rows, "q_0", "q_1", "q_2")
    xy = _floats(rows, "x", "y")
    err = _floats(rows, "error")[:, 0]
    lower, upper = rk.robots.RPR_LIMITS
    assert np.all(np.isfinite(q)) and np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12)
    # Every logged tip is the core's forward model of the logged joints, within Reach's tolerance of the line.
    chain = rk.robots.rpr()
    np.testing.assert_allclose(chain.fk(q)[:, :2, 3], xy, atol=1e-12)
    p1, p2 = chain.fk(Q1)[:2, 3], P2
    out = len(rk.paths.line(p1, p2, 0.01)) - 1  # steps from point 1 to point 2
    # Outbound every point converges; coming back, point 1 sits on the boundary (t1 at its limit)
    # and Reach may stop short there: the log shows that error, it does not hide it.
    assert err[:out].max() < 1e-5 and np.all(np.isfinite(err)) and err.max() < 0.05
    d = p2 - p1
    off_line = np.abs(d[0] * (xy[:, 1] - p1[1]) - d[1] * (xy[:, 0] - p1[0])) / np.linalg.norm(d)
    assert off_line[:out].max() < 1e-5
    # It went to point 2 and came back (ping-pong).
    assert np.linalg.norm(xy - p2, axis=1).min() < 1e-5
    assert np.linalg.norm(xy[-1] - p1) < np.linalg.norm(xy[340] - p1)


def test_nullspace_keeps_joints_further_from_limits():
    lower, upper = (np.asarray(v) for v in rk.robots.RPR_LIMITS)
    mid, w = (lower + upper) / 2, 1 / (upper - lower)

    def cost(avoid):
        scene = RprScene("line", avoid=avoid)
        z = []
        for _ in range(300):
            scene.step(frozenset())
            z.append(0.5 * np.sum((w * (mid - scene.q)) ** 2))
        return np.mean(z)

    assert cost(True) < cost(False)


def test_s_switches_solution_and_free_mode_moves_one_cm():
    scene = RprScene("line", avoid=True)
    scene.press("s")
    assert scene.avoid is False
    scene.press("m")
    start = scene.tip.copy()
    for _ in range(5):
        scene.step(frozenset({"right"}))
    np.testing.assert_allclose(scene.tip, start + [0.05, 0.0], atol=1e-5)


def test_free_mode_refuses_moves_out_of_reach():
    scene = RprScene("free")
    for _ in range(600):  # 6 m: far beyond the 4 m reach
        scene.step(frozenset({"up", "right"}))
    assert np.all(np.isfinite(scene.q)) and np.linalg.norm(scene.tip) <= 4.0 + 1e-9
    assert "refused" in scene.message
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene.step(frozenset({"left"}))  # and it can come back


def test_switching_to_line_approaches_first():
    scene = RprScene("free")
    for _ in range(30):
        scene.step(frozenset({"right"}))
    assert scene.tip[0] > -0.75
    scene.press("o")
    assert scene.mode == "approach"
    modes = []
    for _ in range(80):
        scene.step(frozenset())
        modes.append(scene.mode)
    assert "line" in modes
    assert math.dist(scene.trail[0], scene.trail[1]) <= 0.0100001
