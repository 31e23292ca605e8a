"""One set of defaults, read from the chain: task=None is the chain's natural task in every call
that takes a task; a target shaped for another task says which; every IKOptions field is accepted
by every caller of the batch IK."""

import math
import warnings

import numpy as np
import pytest

import robokin as rk

#: The catalogue's arms and the task each controls by default: the seeds' planar arms their tip
#: (rp, and the redundant RPR of the RPR study) or tip and angle (the IK course's 3R), the spatial arms their
#: tool pose with six joints or more, their tool point with fewer (the DH exercise's PRR moves in its base
#: xz plane: not planar in the base xy plane).
NATURAL = {
    "gen3": "pose", "iiwa14": "pose", "irb120": "pose", "panda": "pose", "puma560": "pose",
    "ur3": "pose", "ur3e": "pose", "ur5": "pose", "ur5e": "pose", "ur10": "pose", "ur10e": "pose", "ur16e": "pose",
    "planar_3r": "xyphi", "rp": "xy", "rpr": "xy", "prr": "position",
}
TASK_ROWS = {"pose": [0, 1, 2, 3, 4, 5], "position": [0, 1, 2], "xy": [0, 1], "xyphi": [0, 1, 5]}


def test_natural_task_of_every_catalogue_arm():
    assert set(NATURAL) == set(rk.robots.names())
    for name, task in NATURAL.items():
        assert rk.robots.get(name).natural_task == task, name


def frame(x=0.0, z=0.0):
    T = np.eye(4)
    T[0, 3], T[2, 3] = x, z
    return T


@pytest.mark.parametrize("segments, task", [
    # A planar 4R: redundant for (x, y, phi).
    ([("R", (0, 0, 1), frame(0.3))] * 4, "xyphi"),
    # A 3R on a rail in the plane (PRRR): three revolute joints set tip and angle.
    ([("P", (1, 0, 0), np.eye(4))] + [("R", (0, 0, 1), frame(0.3))] * 3, "xyphi"),
    # Revolute axes along -z are parallel to z: still planar.
    ([("R", (0, 0, -1), frame(0.3))] * 3, "xyphi"),
    # Planar RRP: two revolute joints, a stroke: the tip only.
    ([("R", (0, 0, 1), frame(0.3)), ("R", (0, 0, 1), np.eye(4)), ("P", (1, 0, 0), frame(0.1))], "xy"),
    # A SCARA (RRPR, the stroke along z): not planar, four joints: the tool point.
    ([("R", (0, 0, 1), frame(0.3)), ("R", (0, 0, 1), frame(0.3)), ("P", (0, 0, 1), np.eye(4)),
      ("R", (0, 0, 1), np.eye(4))], "position"),
    # A planar 3R whose plane is the base xz plane (axes along y): spatial for the base.
    ([("R", (0, 1, 0), frame(0.3))] * 3, "position"),
    # A 6R whose axes are all parallel to z but one: spatial with six joints.
    ([("R", (0, 0, 1), frame(0.3))] * 5 + [("R", (1e-3, 0, 1), frame(0.1))], "pose"),
])
def test_natural_task_from_the_geometry(segments, task):
    chain = rk.Chain.from_segments(segments)
    assert chain.natural_task == task
    # The rule's input, independently: rows v_z, w_x, w_y of KDL's Jacobian at random joints.
    q = np.random.default_rng(0).uniform(-math.pi, math.pi, chain.dof)
    planar = np.max(np.abs(chain._jacobian_kdl(q)[2:5])) < 1e-12
    assert planar == (task in ("xy", "xyphi"))


# --- task=None everywhere --------------------------------------------------------------------

ARMS = ["rpr", "planar_3r", "rp", "prr", "ur5", "panda"]


def start(chain, seed=0):
    lo, hi = chain.limits
    lo, hi = np.where(np.isfinite(lo), lo, -1.0), np.where(np.isfinite(hi), hi, 1.0)
    return np.random.default_rng(seed).uniform(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo))


def task_value(chain, q, task):
    """The task's target at q: (4, 4) for "pose", the task's coordinates otherwise."""
    T = chain.fk(q)
    xyphi = np.array([T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])])
    return {"pose": T, "position": T[:3, 3], "xy": T[:2, 3], "xyphi": xyphi}[task]


def same(a, b):
    """Two results field by field (numpy arrays bit for bit)."""
    for name in [n for n in dir(a) if not n.startswith("_")]:
        va, vb = getattr(a, name), getattr(b, name)
        if callable(va):
            continue
        if isinstance(va, np.ndarray):
            np.testing.assert_array_equal(va, vb, err_msg=name)
        else:
            assert va == vb, name


@pytest.mark.parametrize("name", ARMS)
def test_task_none_is_the_natural_task_in_every_call(name):
    chain = rk.robots.get(name)
    task = chain.natural_task
    q0 = start(chain)
    q1 = start(chain, 1)
    near = q0 + 0.01
    target = task_value(chain, near, task)
    path = np.array([task_value(chain, q0 + 0.002 * k, task) for k in range(1, 6)])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rk.PrecisionWarning)
        same(rk.reach(chain, target, q0), rk.reach(chain, target, q0, task=task))
        same(rk.track(chain, path, q0), rk.track(chain, path, q0, task=task))
    same(rk.ik(chain, task_value(chain, q1, task), q0, seed=3, restarts=3),
         rk.ik(chain, task_value(chain, q1, task), q0, seed=3, restarts=3, task=task))
    same(rk.ik_batch(chain, path, q0, seed=3, restarts=3), rk.ik_batch(chain, path, q0, seed=3, restarts=3, task=task))
    solver = rk.IKSolver(chain, seed=3, restarts=3)
    assert solver.task == task
    same(solver.solve(target, q0), rk.IKSolver(chain, seed=3, restarts=3, task=task).solve(target, q0))
    twist = np.linspace(0.1, 0.3, len(TASK_ROWS[task]))
    np.testing.assert_array_equal(rk.resolved_rate(chain, q0, twist), rk.resolved_rate(chain, q0, twist, task=task))
    servo = rk.servo(chain, path, q0, 0.01)
    np.testing.assert_array_equal(servo.q, rk.servo(chain, path, q0, 0.01, task=task).q)
    assert chain.manipulability(q0) == chain.manipulability(q0, task=task)
    # > 0 (a planar arm's "pose" rows gave 0), but for the PRR, whose plane is its base's xz: its
    # position rows have rank 2.
    assert (chain.manipulability(q0) > 1e-9) == (name != "prr")
    np.testing.assert_array_equal(chain.jacobian(q0, task=None), chain.jacobian(q0)[TASK_ROWS[task]])
    assert chain.jacobian(q0).shape == (6, chain.dof)  # the geometric Jacobian stays the default


def test_reachability_of_a_planar_arm_needs_no_task():
    """The RPR's map without task (natural "xy": a 2-D grid, one target per voxel) is the map with
    task="xy" spelled out; the planar 3R's ("xyphi") samples the default 50 angles."""
    rpr = rk.robots.rpr()
    bounds = ((0.0, 2.0), (0.0, 2.0))
    m = rk.reachability(rpr, bounds, 0.5)
    assert m.task == "xy" and m.orientations == 1 and m.index.shape == (4, 4)
    np.testing.assert_array_equal(m.index, rk.reachability(rpr, bounds, 0.5, task="xy").index)
    assert 0 < m.index.sum() < 16
    p3 = rk.reachability(rk.robots.planar_3r(), ((0.5, 1.5), (0.0, 1.0)), 0.5, restarts=2)
    assert p3.task == "xyphi" and p3.orientations == 50


def test_a_six_joint_arm_reaches_and_tracks_frames_by_default():
    """rk.reach / rk.track took task="xy" on every arm: a frame on the UR5 was refused ("expected
    shape (2,), got (4, 4)")."""
    ur5 = rk.robots.ur5()
    q = np.array([0.3, -1.0, 1.2, 0.4, 0.5, 0.6])
    T = ur5.fk(q + 0.01)
    r = rk.reach(ur5, T, q)
    assert r.converged and np.abs(ur5.fk(r.q) - T).max() < 1e-5
    poses = ur5.fk(q + np.linspace(0, 0.01, 5)[:, None])
    assert rk.track(ur5, poses, q).converged.all()


def test_dask_calls_take_the_natural_task():
    rdask = pytest.importorskip("robokin.dask")
    rpr = rk.robots.rpr()
    q0 = np.array([0.5, 0.5, 0.5])
    targets = rpr.fk(q0 + np.linspace(0, 0.1, 6)[:, None])[:, :2, 3]
    got = rdask.ik_batch(rpr, targets, q0, seed=1, restarts=2, chunks=4).compute()
    ref = rk.ik_batch(rpr, targets, q0, seed=1, restarts=2, task="xy")
    np.testing.assert_array_equal(got.q, ref.q)
    m = rdask.reachability(rpr, ((0.0, 2.0), (0.0, 2.0)), 0.5, chunks=5)
    assert m.task == "xy"
    np.testing.assert_array_equal(m.index, rk.reachability(rpr, ((0.0, 2.0), (0.0, 2.0)), 0.5).index)


# --- a target shaped for another task says which -------------------------------------------

UR5, P3, RPR = rk.robots.ur5(), rk.robots.planar_3r(), rk.robots.rpr()
Q6, Q3 = np.array([0.3, -1.0, 1.2, 0.4, 0.5, 0.6]), np.array([0.3, 0.4, 0.5])


@pytest.mark.parametrize("call, message", [
    (lambda: rk.ik(UR5, [0.3, 0.1, 0.4], Q6),
     'target (3,) is a position (x, y, z): pass task="position" (task \'pose\' takes a (4, 4) frame)'),
    (lambda: rk.reach(UR5, [0.3, 0.1], Q6),
     'target (2,) is a point (x, y): pass task="xy" (task \'pose\' takes a (4, 4) frame)'),
    (lambda: rk.IKSolver(UR5).solve([0.3, 0.1, 0.4], Q6),
     'target (3,) is a position (x, y, z): pass task="position" (task \'pose\' takes a (4, 4) frame)'),
    (lambda: rk.reach(RPR, [1.0, 1.0, 0.2], Q3),
     'target (3,) is a planar pose (x, y, phi) or a position (x, y, z): pass task="xyphi" or task="position" '
     '(task \'xy\' takes a (2,) point (x, y))'),
    (lambda: rk.reach(RPR, np.eye(4), Q3),
     'target (4, 4) is a frame: pass task="pose" (task \'xy\' takes a (2,) point (x, y))'),
    (lambda: rk.ik(P3, [1.0, 1.0], Q3),
     'target (2,) is a point (x, y): pass task="xy" (task \'xyphi\' takes a (3,) planar pose (x, y, phi))'),
    (lambda: rk.ik(UR5, [0.3, 0.1, 0.4], Q6, task="xy"),
     'target (3,) is a position (x, y, z): pass task="position" (task \'xy\' takes a (2,) point (x, y))'),
    (lambda: rk.track(RPR, np.zeros((5, 4, 4)), Q3),
     'points (5, 4, 4) are frames: pass task="pose" (task \'xy\' takes (K, 2) points (x, y))'),
    (lambda: rk.track(UR5, np.zeros((5, 3)), Q6),
     'points (5, 3) are positions (x, y, z): pass task="position" (task \'pose\' takes (K, 4, 4) frames)'),
    (lambda: rk.ik_batch(UR5, np.zeros((5, 2)), Q6),
     'targets (5, 2) are points (x, y): pass task="xy" (task \'pose\' takes (N, 4, 4) frames)'),
    (lambda: rk.ik_batch(P3, np.zeros((5, 2)), Q3),
     'targets (5, 2) are points (x, y): pass task="xy" (task \'xyphi\' takes (N, 3) planar poses (x, y, phi))'),
    (lambda: rk.servo(UR5, np.zeros((5, 3)), Q6, 0.01),
     'poses (5, 3) are positions (x, y, z): pass task="position" (task \'pose\' takes (K, 4, 4) frames)'),
    (lambda: rk.servo(P3, np.zeros((5, 4, 4)), Q3, 0.01),
     'poses (5, 4, 4) are frames: pass task="pose" (task \'xyphi\' takes (K, 3) planar poses (x, y, phi))'),
])
def test_a_target_of_another_task_names_it(call, message):
    with pytest.raises(ValueError) as err:
        call()
    assert str(err.value) == message


def test_a_target_of_no_task_keeps_the_shape_message():
    with pytest.raises(ValueError, match=r"^target: expected a \(4, 4\) homogeneous matrix, got shape \(5,\)$"):
        rk.ik(UR5, np.zeros(5), Q6)
    with pytest.raises(ValueError, match=r"^targets: expected shape \(N, 4, 4\) for task 'pose', got \(5, 5\)$"):
        rk.ik_batch(UR5, np.zeros((5, 5)), Q6)
    with pytest.raises(ValueError, match="target: contains NaN or inf"):  # the right shape, bad values
        rk.reach(RPR, [np.nan, 1.0], Q3)


def test_a_frame_that_is_not_rigid_is_named_alone_or_by_its_index_in_a_batch():
    """One check of every frame argument (rigid_at): a single frame by its argument's name, a
    batch's by its index as well, whichever call reads the batch."""
    bad = np.eye(4)
    bad[0, 1] = 0.5  # not orthonormal
    frames = np.repeat(UR5.fk(Q6)[None], 3, axis=0)
    frames[2] = bad
    rigid = "not a rigid transform (rotation must be orthonormal, last row 0 0 0 1)"
    with pytest.raises(ValueError) as err:
        rk.ik(UR5, bad, Q6)
    assert str(err.value) == "target: " + rigid
    for call in (lambda: rk.ik_batch(UR5, frames, Q6), lambda: rk.closed.ClosedSolver(UR5).solve_batch(frames),
                 lambda: rk.closed.ur_batch(frames, UR5)):
        with pytest.raises(ValueError) as err:
            call()
        assert str(err.value) == "targets: frame 2 is " + rigid


# --- every IKOptions field is accepted by every caller of the batch IK --------------------------

def bad_value(kind):
    """A value of the right kind that no option of that kind accepts (negative numbers, unknown
    names): the core's validation must name the option."""
    return {"int": -1, "float": -1.0, "str": "nonsense"}[kind.replace("None or ", "")]


def callers():
    """Each caller of the batch IK as ``call(**ik_options)`` on a small problem."""
    rpr, ur5 = rk.robots.rpr(), rk.robots.ur5()
    q0 = np.array([0.5, 0.5, 0.5])
    points = rpr.fk(q0 + np.linspace(0, 0.05, 2)[:, None])[:, :2, 3]
    poses = ur5.fk(Q6 + np.linspace(0, 0.05, 2)[:, None])
    box = ((1.5, 2.0), (1.0, 1.5))
    yield "ik", lambda **o: rk.ik(rpr, points[0], q0, seed=0, **o)
    yield "ik_batch", lambda **o: rk.ik_batch(rpr, points, q0, seed=0, **o)
    yield "IKSolver", lambda **o: rk.IKSolver(rpr, seed=0, **o).solve(points[0], q0)
    yield "reachability", lambda **o: rk.reachability(rpr, box, 0.5, **o)
    yield "track_postures", lambda **o: rk.track_postures(ur5, poses, 0.01, starts=2, **{"method": "numerical", **o})
    try:
        import robokin.dask as rdask
    except ImportError:
        return
    yield "dask.ik_batch", lambda **o: rdask.ik_batch(rpr, points, q0, chunks=1, **o).compute()
    yield "dask.reachability", lambda **o: rdask.reachability(rpr, box, 0.5, chunks=2, **o)


@pytest.mark.parametrize("name, call", list(callers()), ids=lambda v: v if isinstance(v, str) else "")
def test_every_ikoptions_field_is_accepted_by_every_caller(name, call):
    defaults = rk.IKOptions()
    assert rk.IKOptions.fields  # walked, not listed here
    for field, kind in zip(rk.IKOptions.fields, rk.IKOptions.kinds):
        value = getattr(defaults, field)
        if name == "track_postures" and field == "method":
            value = "lm"  # its own method argument names an IK method (or "closed" / "numerical")
        call(**{field: value})  # accepted
        with pytest.raises(ValueError, match=field):  # and forwarded: the core checks it
            call(**{field: bad_value(kind)})
