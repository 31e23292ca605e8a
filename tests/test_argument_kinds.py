"""One rule for bad arguments across the modules: a value of the wrong kind is a TypeError, one of the
right kind out of range a ValueError, each message naming the argument (the same words for both
where the check is one sentence)."""

import numpy as np
import pytest

import robokin as rk
from robokin import rrr3_design
from robokin.plots_arm import animate
from robokin.plots_reachability import plot_reachability
from robokin.plots_rrr3 import plot_design

UR5 = rk.robots.ur5()
POSES = UR5.fk(np.array([[0.1, -1.0, 1.0, -0.5, 0.4, 0.2]] * 2))
UR_TABLE = ("d1", "a2", "a3", "d4", "d5", "d6")
ROBOT = "robot: expected a Chain or a dict with the keys " + ", ".join(UR_TABLE)

CASES = [
    (lambda: rk.track_postures(UR5, POSES, dt="x"), TypeError, "dt: expected a number, got str"),
    (lambda: rk.track_postures(UR5, POSES, dt=0.0), ValueError, "dt: must be a positive finite number, got 0.0"),
    (lambda: rk.track_postures(UR5, POSES, dt=0.1, method=3), TypeError,
     "method: expected 'closed', 'numerical' or an IK method, got 3"),
    (lambda: rk.count_reconfigurations(np.zeros((3, 6)), dt=[0.1], qdot_max=1.0), TypeError,
     "dt: expected a number, got list"),
    (lambda: rk.reachability(UR5, ((0, 1),) * 3, 0.5, task=3), TypeError,
     "task: expected one of ('pose', 'position', 'xy', 'xyphi'), got int"),
    (lambda: rk.reachability(UR5, ((0, 1),) * 3, 0.5, task="nope"), ValueError,
     "task: expected one of ('pose', 'position', 'xy', 'xyphi'), got 'nope'"),
    (lambda: rk.closed.ur(POSES[0], 3), TypeError, ROBOT + ", got 3"),
    (lambda: rk.closed.ur(POSES[0], {"d1": 0.1}), ValueError, ROBOT + ", got {'d1': 0.1}"),
    (lambda: rk.closed.ur(POSES[0], dict.fromkeys(UR_TABLE, "x")), TypeError, "robot['d1']: expected a number, got str"),
    (lambda: rk.closed.ur(POSES[0], {**dict.fromkeys(UR_TABLE, 0.1), "a3": np.inf}), ValueError,
     "robot['a3']: must be finite, got inf"),
    (lambda: rrr3_design.area_vs_platform_radius(["a"], n=10), TypeError,
     "platform_radii: expected real numbers"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", fps="fast"), TypeError, "fps: expected a number, got str"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", fps=1000), ValueError,
     "fps: must be a finite number in [0.1, 100], got 1000"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", size=(640.5, 480)), TypeError,
     "size: expected an int (pixels), got 640.5"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", size=(640, 4800)), ValueError,
     "size: expected an int in [64, 2048] (pixels), got 4800"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", size=640), ValueError, "size: expected (width, height), got 640"),
    (lambda: animate(UR5, np.zeros((2, 6)), 3), TypeError, "path: expected a file name (str or os.PathLike), got int"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.png"), ValueError, "path: must end in .gif or .mp4, got 'a.png'"),
    # an instance of a class (_checks.instance)
    (lambda: plot_reachability("map"), TypeError, "rmap: expected a ReachabilityMap, got str"),
    (lambda: plot_design(curve=3), TypeError, "curve: expected an rrr3_design.AreaCurve or None, got int"),
    (lambda: rk.traj.quintic(np.zeros(2), np.ones(2), np.linspace(0, 1, 3), out=()), TypeError,
     "out: expected a robokin.traj.Trajectory or None, got tuple"),
    (lambda: rk.Chain.from_urdf("<robot name='r'/>", base=3), TypeError, "base: expected a link name (str) or None, got int"),
    (lambda: rk.count_reconfigurations(np.zeros((2, 6)), dt=0.1, qdot_max=1.0, chain="ur5"), TypeError,
     "chain: expected a robokin.Chain, got str"),
    (lambda: rk.Chain.from_dh([3]), TypeError, "rows[0]: expected (a, alpha, d, theta"),
    (lambda: rk.Chain.from_dh([(0, 0, 0, "R")]), ValueError, "rows[0]: expected (a, alpha, d, theta"),
    (lambda: rk.ik(UR5, POSES[0], np.zeros(6), seed="x"), TypeError, "seed: expected None or an int"),
    (lambda: rk.closed.ur(POSES[0], UR5, limits="nope"), ValueError, "limits: expected 'default', None or a pair"),
    (lambda: rk.closed.ur(POSES[0], UR5, limits=5), TypeError, "limits: expected None or a pair (lower, upper)"),
    (lambda: rk.closed.ur(POSES[0], UR5, limits=(1, 2, 3)), ValueError, "limits: expected None or a pair (lower, upper)"),
    (lambda: rk.closed.planar_2r((1.0, 0.5), limits=5), TypeError, "limits: expected None or a pair (lower, upper)"),
    # batches of rows (_checks.rows): one sentence for the shape, one for NaN or inf
    (lambda: rk.track_postures(UR5, POSES[0], dt=0.1), ValueError,
     "poses: expected a (K, 4, 4) array, K >= 1, got shape (4, 4)"),
    (lambda: rk.count_reconfigurations(np.zeros(6), dt=0.1, qdot_max=1.0), ValueError,
     "q: expected a (K, n) array, K >= 1, got shape (6,)"),
    (lambda: rk.count_reconfigurations(np.full((2, 6), np.nan), dt=0.1, qdot_max=1.0), ValueError,
     "q: contains NaN or inf"),
    (lambda: rk.count_reconfigurations(np.zeros((2, 6)), dt=0.1, qdot_max=1.0, q0=np.zeros(5)), ValueError,
     "q0: expected shape (6,), got (5,)"),
    (lambda: animate(UR5, np.zeros((2, 5)), "a.gif"), ValueError, "qs: expected a (K, 6) array, 1 <= K <= "),
    (lambda: rk.count_reconfigurations(np.zeros((2, 5)), dt=0.1, qdot_max=1.0, chain=UR5), ValueError,
     "q: expected a (K, 6) array, K >= 1, got shape (2, 5)"),
    # a value per joint (_checks.per_joint), positive (_checks.positive)
    (lambda: rk.count_reconfigurations(np.zeros((2, 6)), dt=0.1, qdot_max=np.ones(5)), ValueError,
     "qdot_max: expected shape (6,), got (5,)"),
    (lambda: rk.count_reconfigurations(np.zeros((2, 6)), dt=0.1, qdot_max=[1, 1, 1, 1, 1, -2]), ValueError,
     "qdot_max: must be positive, got -2.0"),
    (lambda: rk.count_reconfigurations(np.zeros((2, 6)), dt=0.1, qdot_max="fast"), TypeError,
     "qdot_max: expected real numbers"),
    (lambda: rrr3_design.area_vs_platform_radius([0.1, 0.0], n=10), ValueError, "platform_radii: must be positive, got 0.0"),
    (lambda: rrr3_design.area_vs_platform_radius([], n=10), ValueError,
     "platform_radii: expected a (K,) array, K >= 1, got shape (0,)"),
    (lambda: rk.plots.rpr_line_figure(np.zeros((0, 2)), {}), ValueError, "points: expected a (K, 2) array, K >= 1, got shape (0, 2)"),
]


@pytest.mark.parametrize("call, error, message", CASES)
def test_wrong_kind_is_a_type_error_out_of_range_a_value_error(call, error, message):
    with pytest.raises(Exception) as raised:
        call()
    assert type(raised.value) is error, f"{type(raised.value).__name__}: {raised.value}"
    assert str(raised.value).startswith(message)


def test_dask_chunks_kind_and_range():
    pytest.importorskip("dask")
    import robokin.dask as rkd

    with pytest.raises(TypeError, match=r"^chunks: expected an int \(rows per chunk, or 'auto'\), got 1.5$"):
        rkd.fk(UR5, np.zeros((4, 6)), chunks=1.5)
    with pytest.raises(TypeError, match=r"^chunks: expected an int \(rows per chunk, or 'auto'\), got 'many'$"):
        rkd.fk(UR5, np.zeros((4, 6)), chunks="many")
    with pytest.raises(ValueError, match=r"^chunks: expected an int in \[1, 9223372036854775807\] \(rows per chunk, or 'auto'\), got 0$"):
        rkd.fk(UR5, np.zeros((4, 6)), chunks=0)
