"""RRR3.plan_loop: the simulator's loops (circle, clover) planned on one side of the parallel
singularities, about the first nominal orientation that allows it. Checked pose by pose through
RRR3.singularity, and against the simulator's former Python implementation (rrr3_loop_reference)."""

import pickle

import numpy as np
import pytest

import robokin as rk

from rrr3_loop_reference import NOMINALS, path_orientations
from test_rrr3_plan import check_closed_plan, simulator_paths

MODE = (1, 1, 1)


@pytest.fixture(scope="module")
def robot():
    return rk.RRR3()


@pytest.fixture(scope="module")
def paths():
    return simulator_paths()


def test_default_nominals_are_the_simulators():
    assert rk.RRR3LoopOptions().nominals == NOMINALS
    assert rk.RRR3LoopOptions().sign == 1
    assert rk.RRR3LoopOptions.fields == ("sign", "nominals")


@pytest.mark.parametrize("name", ["circle", "clover"])
@pytest.mark.parametrize("sign", [1, -1])
def test_the_loop_with_avoidance_keeps_its_side_and_is_the_old_python(robot, paths, name, sign):
    path = paths[name]
    loop = robot.plan_loop(path, sign=sign, mode=MODE)
    assert loop.found and loop.reason is None and loop.nominal in NOMINALS
    assert loop.plan.feasible and loop.plan.sign == sign
    check_closed_plan(robot, path, loop.plan)
    # The nominal orientation just before the one used (of the same side at the start) gives none.
    earlier = [phi for phi in NOMINALS[:NOMINALS.index(loop.nominal)]
               if np.sign(robot.singularity((*path[0], phi), MODE).det_a_norm) == sign]
    if earlier:
        tried = robot.plan(path, phi=earlier[-1], mode=MODE, closed=True)
        assert not (tried.feasible and tried.sign == sign)
    orientation, nominal = path_orientations(robot, path, MODE, sign, True)
    assert loop.nominal == nominal
    np.testing.assert_allclose(loop.plan.poses[:, 2], orientation, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["circle", "clover"])
@pytest.mark.parametrize("sign", [1, -1])
def test_the_loop_without_avoidance_is_constant_and_the_old_python(robot, paths, name, sign):
    path = paths[name]
    loop = robot.plan_loop(path, sign=sign, mode=MODE, avoid=False)
    assert loop.found
    np.testing.assert_array_equal(loop.plan.poses[:, 2], loop.nominal)
    assert np.sign(robot.singularity((*path[0], loop.nominal), MODE).det_a_norm) == sign
    orientation, nominal = path_orientations(robot, path, MODE, sign, False)
    assert loop.nominal == nominal
    np.testing.assert_array_equal(loop.plan.poses[:, 2], orientation)


def test_without_avoidance_the_clover_crosses_at_zero(robot, paths):
    """At phi = 0 the clover starts with det A < 0 and crosses singularities: what turning the
    avoidance off shows (found, not feasible)."""
    loop = robot.plan_loop(paths["clover"], sign=-1, avoid=False)
    assert loop.found and loop.nominal == 0.0 and not loop.plan.feasible
    det = np.array([robot.singularity(p).det_a_norm for p in loop.plan.poses])
    assert np.any(np.sign(det) != -1)


def test_nominals_are_tried_in_order(robot, paths):
    path = paths["circle"]
    loop = robot.plan_loop(path, sign=-1, nominals=(0.0, 0.6, 0.45))  # 0 has det A > 0 at the start
    assert loop.found and loop.nominal == 0.6
    np.testing.assert_array_equal(loop.plan.poses, robot.plan(path, phi=0.6, closed=True).poses)
    # Plan options pass through: a margin no pose reaches leaves no plan.
    none = robot.plan_loop(path, sign=1, nominals=(0.0,), margin=0.9)
    assert not none.found and none.reason == "plan" and none.nominal is None
    assert none.plan.poses.shape == (0, 3)
    # A loop no leg reaches: no start on either side.
    far = robot.plan_loop(np.array([[1.0, 1.0], [1.0, 1.01]]), nominals=(0.0, 0.5))
    assert not far.found and far.reason == "start"
    assert not robot.plan_loop(np.zeros((0, 2))).found


def test_loop_result_pickles_and_reprs(robot, paths):
    loop = robot.plan_loop(paths["circle"][::20], sign=1, nominals=(0.0,))
    copy = pickle.loads(pickle.dumps(loop))
    assert (copy.found, copy.nominal, copy.reason) == (loop.found, loop.nominal, loop.reason)
    np.testing.assert_array_equal(copy.plan.poses, loop.plan.poses)
    assert repr(loop) == repr(copy) == f"RRR3Loop(plan={loop.plan!r}, nominal=0.0, found=True, reason=None)"
    assert repr(loop.plan).startswith(f"RRR3Plan(poses=<array ({len(loop.plan.poses)}, 3) float64>")
    o = rk.RRR3LoopOptions(sign=-1, nominals=[0.1, -0.2])
    assert pickle.loads(pickle.dumps(o)) == o and o.nominals == (0.1, -0.2)


def test_loop_bad_input_names_the_argument(robot):
    path = rk.paths.circle(20)
    for kwargs, kind, name in [
            (dict(sign=0), ValueError, "sign"), (dict(sign=2), ValueError, "sign"), (dict(sign=True), TypeError, "sign"),
            (dict(sign=1.0), TypeError, "sign"), (dict(nominals=[]), ValueError, "nominals"),
            (dict(nominals=[np.nan]), ValueError, "nominals"), (dict(nominals=[[0.0, 1.0]]), ValueError, "nominals"),
            (dict(nominals="a"), TypeError, "nominals"), (dict(nominals=np.zeros(10001)), ValueError, "nominals"),
            (dict(phi=0.1), TypeError, "phi"), (dict(closed=False), TypeError, "closed"),
            (dict(span=4.0), ValueError, "span"), (dict(mode=(1, 0, 1)), ValueError, "mode"),
            (dict(bogus=1), TypeError, "bogus")]:
        with pytest.raises(kind, match=name):
            robot.plan_loop(path, **kwargs)
    with pytest.raises(ValueError, match="points"):
        robot.plan_loop(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="points"):
        robot.plan_loop(np.full((4, 2), np.inf))
    with pytest.raises(TypeError):
        robot.plan_loop(path, 1)  # options are keyword-only
    with pytest.raises(ValueError, match="sign"):
        rk.RRR3LoopOptions(sign=3).validate()
