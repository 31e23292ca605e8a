"""Every column of the simulator's CSV logs against the model, recomputed here from independent truth:
KDL's recursive forward kinematics and Jacobian for serial arms (with the roll-pitch-yaw rotation
written out), the 3-RRR's loop closure and the seed's Jacobians in numpy (tests/rrr3_truth.py), and
the clearance every 3-RRR approach promises."""

import math

import numpy as np
import pytest
import robokin as rk
from rrr3_truth import base, elbows, platform, seed_jacobians
from sim_helpers import read_log, run_sim

from robokin_sim import rrr3_model, serial_model
from robokin_sim.scene import DT


def column(rows, name):
    return np.array([float(r[name]) for r in rows])


def rpy_matrix(roll, pitch, yaw):
    """Rz(yaw) Ry(pitch) Rx(roll), written out."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return rz @ ry @ rx


def check_steps_and_time(rows):
    steps = column(rows, "step")
    assert np.all(np.diff(steps) == 1)
    np.testing.assert_allclose(column(rows, "time"), steps * DT, rtol=1e-12, atol=0)


# --- serial arms ----------------------------------------------------------------------------------

SERIAL_RUNS = [
    ("ur5", "free", "shift+right*40,shift+up*25,right*30,shift+pageup*20,up*15"),
    ("ur5", "circle", ""),
    ("puma560", "line", ""),
    ("panda", "free", "shift+left*30,down*20,shift+pagedown*30"),
]


@pytest.mark.parametrize("name, mode, keys", SERIAL_RUNS)
def test_serial_log_columns_are_the_model_at_the_logged_joints(tmp_path, name, mode, keys):
    log = tmp_path / "serial.csv"
    args = ["--robot", name, "--mode", mode, "--frames", "150", "--log", str(log)]
    run_sim(*args, *(["--keys", keys] if keys else []), render=False)
    rows = read_log(log)
    chain = rk.robots.get(name)
    lower, upper = chain.limits
    w_ref = serial_model.reference_manipulability(chain)
    assert len(rows) == 150
    check_steps_and_time(rows)
    rpy = []
    for r in rows:
        q = np.array([float(r[f"q_{i}"]) for i in range(chain.dof)])
        assert np.all(q >= lower) and np.all(q <= upper)
        F = chain._fk_kdl(q)  # KDL's recursive FK: independent of the fast path the scene calls
        np.testing.assert_allclose([float(r[c]) for c in "xyz"], F[:3, 3], rtol=0, atol=1e-12)
        angles = [float(r[c]) for c in ("roll", "pitch", "yaw")]
        rpy.append(angles)
        assert abs(angles[1]) <= math.pi / 2 + 1e-12 and max(abs(angles[0]), abs(angles[2])) <= math.pi + 1e-12
        np.testing.assert_allclose(rpy_matrix(*angles), F[:3, :3], rtol=0, atol=1e-9)
        w = np.prod(np.linalg.svd(chain._jacobian_kdl(q), compute_uv=False))  # Yoshikawa: product of singular values
        assert float(r["manipulability"]) == pytest.approx(w, rel=1e-8, abs=1e-12)
        ratio = w / w_ref
        at_limit = np.any((q - lower <= 1e-9) | (upper - q <= 1e-9))
        if abs(ratio / serial_model.SINGULAR_RATIO - 1) > 1e-6 and abs(ratio / serial_model.NEAR_RATIO - 1) > 1e-6:
            expected = ("singular" if ratio < serial_model.SINGULAR_RATIO else "near" if ratio < serial_model.NEAR_RATIO
                        else "limit" if at_limit else "none")
            assert r["state"] in (expected, "unreachable"), (r["state"], expected)
    # Roll differs from yaw: an exchange of the two columns would show.
    rpy = np.array(rpy)
    assert np.abs(rpy[:, 0] - rpy[:, 2]).max() > 0.1


# --- RPR ------------------------------------------------------------------------------------------

@pytest.mark.parametrize("mode, keys", [("line", ""), ("free", "right*30,up*40,left*80,down*20")])
def test_rpr_log_columns_are_the_model_at_the_logged_joints(tmp_path, mode, keys):
    log = tmp_path / "rpr.csv"
    res = run_sim("--robot", "rpr", "--mode", mode, "--frames", "200", "--log", str(log),
                  *(["--keys", keys] if keys else []), render=False)
    rows = read_log(log)
    chain = rk.robots.rpr()
    lower, upper = chain.limits
    assert len(rows) == 200
    check_steps_and_time(rows)
    tips = []
    for r in rows:
        q = np.array([float(r[f"q_{i}"]) for i in range(3)])
        assert np.all(q >= lower) and np.all(q <= upper)
        tip = chain._fk_kdl(q)[:2, 3]
        np.testing.assert_allclose([float(r["x"]), float(r["y"])], tip, rtol=0, atol=1e-12)
        assert 0 <= float(r["error"]) < 1e-3
        tips.append(tip)
    if mode == "line":
        # Every point on the line's points reached within the logged error: the traced segment.
        line = res.scene.line
        on = [k for k, r in enumerate(rows) if r["mode"] == "line"]
        assert len(on) > 100
        for k in on:
            d = np.min(np.linalg.norm(line - tips[k], axis=1))
            assert d <= float(rows[k]["error"]) + 1e-12, (k, d)


# --- 3-RRR ----------------------------------------------------------------------------------------

def check_rrr3_row(robot, r, avoid, previous_det_a):
    pose = np.array([float(r[c]) for c in ("x", "y", "phi")])
    alpha = np.array([float(r[f"alpha_{i}"]) for i in range(3)])
    a, b, o = elbows(robot, alpha), platform(robot, pose), base(robot)
    # Each leg closes (|A_i B_i| = l2) with its elbow on the side of working mode (1, 1, 1): the
    # elbow angle from link 1 to link 2 positive.
    np.testing.assert_allclose(np.linalg.norm(b - a, axis=1), robot.l2, rtol=0, atol=1e-12)
    bend = (a - o)[:, 0] * (b - a)[:, 1] - (a - o)[:, 1] * (b - a)[:, 0]
    assert np.all(bend >= -1e-15), bend
    A, B = seed_jacobians(robot, pose, alpha)
    det_a, det_b = np.linalg.det(A), np.linalg.det(B)
    assert float(r["det_a"]) == pytest.approx(det_a, rel=1e-9, abs=1e-15)
    assert float(r["det_b"]) == pytest.approx(det_b, rel=1e-9, abs=1e-15)
    assert float(r["det_a_norm"]) == pytest.approx(det_a / robot.platform_radius, rel=1e-9, abs=1e-14)
    assert float(r["det_b_norm"]) == pytest.approx(det_b / robot.l1**3, rel=1e-9, abs=1e-12)
    # The distance to a parallel singularity: the inverse condition number of A with its moment
    # column in units of R_e.
    s = np.linalg.svd(A / [1.0, 1.0, robot.platform_radius], compute_uv=False)
    distance = s[-1] / s[0]
    assert float(r["distance"]) == pytest.approx(distance, rel=1e-7, abs=1e-12)
    assert r["avoid"] == str(int(avoid))
    tol = rk.RRR3_DEFAULTS["singular_tol"]  # the core's default, which the simulator uses
    kind = "serial" if abs(det_b / robot.l1**3) < tol else "parallel" if abs(det_a / robot.platform_radius) < tol else (
        "near" if distance < rrr3_model.NEAR_DISTANCE else "none")
    if kind in ("none", "near") and previous_det_a * det_a < 0:
        kind = "parallel"  # det A changed sign since the row before: a parallel singularity between them
    assert r["state"] == kind
    return distance


#: (keys before the path, path key): starts from which the approach to the path passes by a parallel
#: singularity, and free-mode moves across one.
RRR3_RUNS = [("k*60,", "p"), ("l*40,", "o"), ("down*45,right*30,", "p"), ("right*40,up*20,", "o"),
             ("up*60,k*20,", "p"), ("right*80,left*40,", "")]


@pytest.mark.parametrize("avoid", [True, False])
@pytest.mark.parametrize("start, path", RRR3_RUNS)
def test_rrr3_log_columns_are_the_model_and_approaches_keep_their_clearance(tmp_path, start, path, avoid):
    log = tmp_path / "rrr3.csv"
    frames = sum(int(k.split("*")[1]) for k in start.split(",") if k) + 250
    run_sim("--keys", (start + path).strip(","), "--frames", str(frames), "--log", str(log),
            *([] if avoid else ["--no-avoid"]), render=False)
    rows = read_log(log)
    robot = rk.RRR3()
    assert len(rows) == frames
    check_steps_and_time(rows)
    det_a = column(rows, "det_a")
    distance = np.array([check_rrr3_row(robot, r, avoid, det_a[k - 1] if k else det_a[k]) for k, r in enumerate(rows)])
    modes = [r["mode"] for r in rows]
    # An approach keeps the clearance RRR3.connect was asked for (NEAR_DISTANCE), or the distance
    # of its own ends when an end is nearer than that.
    k = 0
    while k < len(rows):
        if modes[k] != "approach":
            k += 1
            continue
        end = k
        while end + 1 < len(rows) and modes[end + 1] == "approach":
            end += 1
        ends = [distance[k - 1] if k > 0 else distance[k], distance[end]]
        need = min(rrr3_model.NEAR_DISTANCE, *ends)
        assert distance[k:end + 1].min() >= need - 1e-12, (k, end, distance[k:end + 1].min(), need)
        det = column(rows[max(k - 1, 0):end + 1], "det_a")
        assert np.all(det < 0) or np.all(det > 0)
        k = end + 1
    if path:
        assert "approach" in modes
