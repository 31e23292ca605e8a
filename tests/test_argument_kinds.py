"""One rule for bad arguments across the modules: a value of the wrong kind is a TypeError, one of the
right kind out of range a ValueError, each message naming the argument (the same words for both
where the check is one sentence)."""

import numpy as np
import pytest

import robokin as rk
from robokin import rrr3_design
from robokin.plots_arm import animate

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
    (lambda: rk.closed.ur(POSES[0], dict.fromkeys(UR_TABLE, "x")), TypeError, "robot: the lengths must be real numbers"),
    (lambda: rrr3_design.area_vs_platform_radius(["a"], n=10), TypeError,
     "platform_radii: expected real numbers"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", fps="fast"), TypeError,
     "fps: expected a number in [0.1, 100], got 'fast'"),
    (lambda: animate(UR5, np.zeros((2, 6)), "a.gif", fps=1000), ValueError,
     "fps: expected a number in [0.1, 100], got 1000"),
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

    with pytest.raises(TypeError, match=r"^chunks: expected 'auto' or a positive int \(rows per chunk\), got 1.5$"):
        rkd.fk(UR5, np.zeros((4, 6)), chunks=1.5)
    with pytest.raises(ValueError, match=r"^chunks: expected 'auto' or a positive int \(rows per chunk\), got 0$"):
        rkd.fk(UR5, np.zeros((4, 6)), chunks=0)
