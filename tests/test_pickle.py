"""Pickling and deep copies: models and results survive pickle and copy.deepcopy, and a
copy computes the same bits as the original (compared with ==, not a tolerance), also when it is
unpickled in a fresh interpreter. Chain == compares the kinematics."""

import copy
import dataclasses
import math
import pickle
import subprocess
import sys

import numpy as np
import pytest

import robokin as rk
from robokin import rrr3_design

# A URDF whose axes are not unit vectors and not along z: KDL normalises an axis when it builds a
# joint, and a normalised axis normalised again changes in the last bit about one time in four, so
# a chain rebuilt from KDL's own accessors would not give the same bits.
ODD_URDF = """<?xml version="1.0"?>
<robot name="odd">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0.1 0.02 0.3" rpy="0.1 0.2 0.3"/><axis xyz="0.3 0.7 1.1"/>
    <limit lower="-2" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.4 0 0.05" rpy="-0.4 0.05 0"/><axis xyz="1 1 0.3"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.3 0.1 0" rpy="0 0.7 0"/><axis xyz="-0.2 0.9 0.4"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="l3"/><child link="tool"/>
    <origin xyz="0.05 0.01 0.12" rpy="0.3 -0.2 1.1"/></joint>
</robot>"""


def odd_urdf():
    return rk.Chain.from_urdf(ODD_URDF, "base", "tool")


def odd_segments():
    tip = rk.pose.from_rpy((0.3, -0.7, 0.2), (0.1, 0.2, -0.05))
    return rk.Chain.from_segments([("R", (0.3, 0.7, 1.1), tip), ("P", (1, 1, 0.3), tip), ("F", (0, 0, 1), tip),
                                   ("R", (-0.2, 0.9, 0.4), tip)], tool=tip, limits=((-3, 0, -1), (3, 0.4, 2)))


CHAINS = {
    "ur5": rk.robots.ur5,
    "panda (modified DH, tool, limits)": rk.robots.panda,
    "rpr (segments)": rk.robots.rpr,
    "gen3 (segments)": rk.robots.gen3,
    "odd segments": odd_segments,
    "odd urdf": odd_urdf,
    "planar 3R": rk.robots.planar_3r,
}


def configurations(chain, count=64, seed=1):
    lo, hi = chain.limits
    lo, hi = np.maximum(lo, -3.0), np.minimum(hi, 3.0)
    return np.random.default_rng(seed).uniform(lo, hi, (count, chain.dof))


def same_outputs(a, b):
    """Everything a chain computes, compared bit for bit."""
    q = configurations(a)
    assert a == b and hash(a) == hash(b) and repr(a) == repr(b)
    assert a.dof == b.dof and a.joint_types == b.joint_types
    assert all(np.array_equal(x, y) for x, y in zip(a.limits, b.limits))
    assert np.array_equal(a.fk(q), b.fk(q))
    assert np.array_equal(a.fk(q[0]), b.fk(q[0]))
    assert np.array_equal(a.jacobian(q), b.jacobian(q))
    assert np.array_equal(a.frames(q[0]), b.frames(q[0]))
    assert np.array_equal(a._fk_kdl(q[0]), b._fk_kdl(q[0]))
    assert np.array_equal(a._jacobian_kdl(q[0]), b._jacobian_kdl(q[0]))
    assert np.array_equal(a.manipulability(q), b.manipulability(q))
    task = "pose" if a.dof >= 6 else "xy" if a.fk(q[0])[2, 3] == 0 and a.dof < 6 else "position"
    targets = a.fk(q[:8]) if task == "pose" else a.fk(q[:8])[:, : (2 if task == "xy" else 3), 3]
    ra = rk.ik_batch(a, targets, q[9], task=task, restarts=3, seed=7)
    rb = rk.ik_batch(b, targets, q[9], task=task, restarts=3, seed=7)
    assert np.array_equal(ra.q, rb.q) and np.array_equal(ra.iterations, rb.iterations)


@pytest.mark.parametrize("make", CHAINS.values(), ids=CHAINS.keys())
def test_chain_pickles_and_copies_to_the_same_bits(make):
    chain = make()
    for copied in (pickle.loads(pickle.dumps(chain)), copy.deepcopy(chain), copy.copy(chain),
                   pickle.loads(pickle.dumps(chain, protocol=2))):
        assert copied is not chain
        same_outputs(chain, copied)


def test_chain_copies_in_a_fresh_interpreter_give_the_same_bits(tmp_path):
    chains = {name: make() for name, make in CHAINS.items()}
    qs = {name: configurations(c, 32, seed=3) for name, c in chains.items()}
    (tmp_path / "in.pkl").write_bytes(pickle.dumps((chains, qs)))
    child = (
        "import pickle, sys, numpy as np\n"
        "chains, qs = pickle.loads(open(sys.argv[1], 'rb').read())\n"
        "out = {n: (c.fk(qs[n]), c.jacobian(qs[n]), c.frames(qs[n][0]), repr(c)) for n, c in chains.items()}\n"
        "open(sys.argv[2], 'wb').write(pickle.dumps(out))\n"
    )
    subprocess.run([sys.executable, "-c", child, str(tmp_path / "in.pkl"), str(tmp_path / "out.pkl")], check=True,
                   timeout=120)
    out = pickle.loads((tmp_path / "out.pkl").read_bytes())
    for name, chain in chains.items():
        fk, jac, frames, text = out[name]
        assert np.array_equal(fk, chain.fk(qs[name])), name
        assert np.array_equal(jac, chain.jacobian(qs[name])), name
        assert np.array_equal(frames, chain.frames(qs[name][0])), name
        assert text == repr(chain)


def test_equality_compares_the_kinematics():
    rows = [(0.0, math.pi / 2, 0.3, 0.0, "R"), (0.4, 0.0, 0.0, 0.1, "R"), (0.3, 0.0, 0.0, 0.0, "P")]
    a = rk.Chain.from_dh(rows)
    assert a == rk.Chain.from_dh(rows) and hash(a) == hash(rk.Chain.from_dh(rows))
    assert a != rk.Chain.from_dh(rows, limits=((-1, -1, 0), (1, 1, 1)))
    assert a != rk.Chain.from_dh(rows[:2] + [(0.3, 0.0, 0.0, 0.0, "R")])
    assert a != rk.Chain.from_dh(rows[:2] + [(0.3 + 1e-15, 0.0, 0.0, 0.0, "P")])
    assert a != rk.Chain.from_dh(rows, modified=True)
    assert a != rk.Chain.from_dh(rows, tool=rk.pose.from_rpy((0, 0, 0), (0, 0, 0.1)))
    assert (a == "chain") is False and a != 3
    # The same kinematics built two ways: a DH row and its segment (the tool as a fixed frame).
    tip = np.array(rk.Chain.from_dh([(0.5, 0.0, 0.0, 0.0, "R")]).frames(np.zeros(1))[1])
    assert rk.Chain.from_dh([(0.5, 0.0, 0.0, 0.0, "R")]) == rk.Chain.from_segments([("R", (0, 0, 1), tip)])


def test_repr_shows_the_joints_and_the_dh_rows():
    text = repr(rk.robots.ur5())
    assert text.startswith("Chain(dof=6, joints='RRRRRR', dh=[")
    assert "(-0.425, 0.0, 0.0, 0.0, 'R')" in text and "0.089159" in text
    assert "modified dh=" in repr(rk.robots.panda()) and ", tool" in repr(rk.robots.panda())
    assert repr(rk.robots.rpr()) == "Chain(dof=3, joints='RPR')"
    # The rows shown are the rows given: eval'd back they build the same chain.
    rows = eval(text[text.index("[") : text.rindex("]") + 1])
    assert rk.Chain.from_dh(rows, limits=rk.robots.ur5().limits) == rk.robots.ur5()


def test_bad_chain_states_are_value_errors():
    state = rk.robots.ur5().__getstate__()
    for bad in [state[:2] + (99,) + state[3:], (state[0], 3) + state[2:], (state[0], 0) + state[2:], ("x",),
                state[:5], state[:2] + ("nothing",) + state[3:]]:
        chain = rk.Chain.__new__(rk.Chain)
        with pytest.raises(ValueError, match="Chain state"):
            chain.__setstate__(bad)
    seg = rk.robots.rpr().__getstate__()
    record = list(seg[3][0])
    record[2] = 42  # not a KDL joint type
    with pytest.raises(ValueError, match="joint type"):
        rk.Chain.__new__(rk.Chain).__setstate__(seg[:3] + ((tuple(record),) + seg[3][1:],) + seg[4:])


def test_rrr3_pickles_and_copies():
    robot = rk.RRR3(0.15, 0.08, 0.11, 0.1)
    poses = np.array([[0.01, 0.02, 0.1], [-0.02, 0.0, -0.2], [0.0, 0.03, 0.0]])
    for copied in (pickle.loads(pickle.dumps(robot)), copy.deepcopy(robot)):
        assert copied == robot and hash(copied) == hash(robot) and repr(copied) == repr(robot)
        assert np.array_equal(copied.ik_batch(poses), robot.ik_batch(poses), equal_nan=True)
        assert np.array_equal(copied.fk_all(robot.ik(poses[0])), robot.fk_all(robot.ik(poses[0])))
    assert robot != rk.RRR3()
    with pytest.raises(ValueError, match="RRR3 state"):
        rk.RRR3.__new__(rk.RRR3).__setstate__((2, 0.1, 0.1, 0.1, 0.1))


def test_ik_solver_pickles_with_its_chain_options_and_seed_sequence():
    chain = rk.robots.ur5()
    solver = rk.IKSolver(chain, method="halley", tol_p=1e-8, max_iter=60, restarts=4, seed=11, damping=1e-8)
    q = configurations(chain, 6)
    solver.solve(chain.fk(q[0]), q[1])  # one call made: the copy continues from call 1
    copies = [pickle.loads(pickle.dumps(solver)), copy.deepcopy(solver)]
    for c in copies:
        assert repr(c) == repr(solver) and c.method == "halley"
    for k in range(2, 6):
        expected = solver.solve(chain.fk(q[k]), q[1])
        for c in copies:
            got = c.solve(chain.fk(q[k]), q[1])
            assert np.array_equal(got.q, expected.q) and got.iterations == expected.iterations
    with pytest.raises(ValueError, match="IKSolver state"):
        rk.IKSolver.__new__(rk.IKSolver).__setstate__((1, chain))


def attributes(obj):
    if dataclasses.is_dataclass(obj):
        return {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
    names = [n for n, v in vars(type(obj)).items() if not n.startswith("_") and type(v).__name__ == "property"]
    return {n: getattr(obj, n) for n in names}


def same_value(a, b):
    if isinstance(a, (tuple, list)) and not isinstance(a, str):
        return len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b, equal_nan=np.asarray(a).dtype.kind == "f") and np.asarray(a).dtype == np.asarray(b).dtype
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return type(a) is type(b) and a == b


def on_ur5(call):
    """call(chain, q) on the UR5 and four configurations of it."""
    chain = rk.robots.ur5()
    return call(chain, configurations(chain, 4))


#: One builder per result type, called inside the test: a builder that raises fails its own test
#: (a list computed while the module is collected would stop the collection, and with it the run).
RESULTS = {
    "IKResult": lambda: on_ur5(lambda c, q: rk.ik(c, c.fk(q[0]), q[1], restarts=2, seed=1)),
    "IKBatchResult": lambda: on_ur5(lambda c, q: rk.ik_batch(c, c.fk(q), q[1], restarts=2, seed=1)),
    "IKSolutions": lambda: on_ur5(lambda c, q: rk.closed.ur(c.fk(q[0]), c)),
    "IKSolutions (some outside the limits)": lambda: rk.closed.puma560(
        rk.robots.puma560().fk([0.3, 0.4, -0.5, 0.4, 0.5, 0.6])),
    "ReachResult": lambda: rk.reach(rk.robots.planar_3r(), (1.2, 0.7), np.zeros(3), task="xy"),
    "TrackResult": lambda: rk.track(rk.robots.planar_3r(), rk.paths.line((1.2, 0.7), (1.4, 0.7), 0.05), np.zeros(3),
                                    task="xy"),
    "RRR3Newton": lambda: rk.RRR3().ik_newton((0.01, 0.0, 0.0), (np.zeros(3), np.ones(3))),
    "RRR3Fk": lambda: rk.RRR3().fk(rk.RRR3().ik((0.01, 0.0, 0.0)), (0.0, 0.0, 0.0)),
    "RRR3Singularity": lambda: rk.RRR3().singularity((0.0, 0.0, 0.0)),
    "RRR3Plan": lambda: rk.RRR3().plan(rk.paths.circle(12)),
    "RRR3Workspace": lambda: rk.RRR3().workspace(n=20),
    "ServoResult": lambda: on_ur5(lambda c, q: rk.servo(c, c.fk(q[:2]), q[0], 0.01)),
    "Trajectory": lambda: rk.traj.quintic(np.zeros(2), np.ones(2), np.linspace(0, 1, 5)),
    "Cuspidality": lambda: rk.cuspidal(rk.robots.planar_3r()),
    "DesignStudy": lambda: rrr3_design.best_l2([0.1], [0.1, 0.12], n=20),
    "ReachabilityMap": lambda: rk.reachability(rk.robots.planar_3r(), ((0.5, 1.5), (0.0, 1.0)), 0.5, orientations=3,
                                               task="xyphi"),
}


@pytest.mark.parametrize("name", RESULTS)
def test_every_result_type_pickles_and_copies(name):
    result = RESULTS[name]()
    before = attributes(result)
    assert before, name
    for copied in (pickle.loads(pickle.dumps(result)), copy.deepcopy(result)):
        assert type(copied) is type(result)
        after = attributes(copied)
        assert after.keys() == before.keys()
        for field in before:
            assert same_value(before[field], after[field]), (name, field)
        assert repr(copied) == repr(result)


def test_ik_solutions_state_beyond_the_inline_capacity_is_refused():
    """An IKSolutions holds at most 8 solutions of at most 7 joints (inline, no allocation; 7: a
    7-joint arm with one joint held): a state asking for more is refused with ValueError, not
    written past the end."""
    good = rk.closed.ur(rk.robots.ur5().fk(np.full(6, 0.4)), rk.robots.ur5())
    version, dof, q, postures, singular, within = good.__getstate__()
    copied = type(good).__new__(type(good))
    copied.__setstate__((version, dof, q, postures, singular, within))
    assert np.array_equal(copied.q, good.q) and copied.postures == good.postures
    assert np.array_equal(copied.within_limits, good.within_limits)
    nine = (version, 6, np.zeros((9, 6)), ("a",) * 9, False, (True,) * 9)
    eight_joints = (version, 8, np.zeros((1, 8)), ("a",), False, (True,))
    ragged = (version, 6, np.zeros((2, 5)), ("a", "b"), False, (True, True))
    unflagged = (version, 6, np.zeros((2, 6)), ("a", "b"), False, (True,))
    for state in (nine, eight_joints, ragged, unflagged):
        with pytest.raises(ValueError, match=r"IKSolutions state: q must have one row of dof \(1 to 7\) values "
                                             r"per posture and per within_limits flag, at most 8 rows"):
            type(good).__new__(type(good)).__setstate__(state)


CORE_RESULTS = ["IKResult", "IKBatchResult", "IKSolutions", "ReachResult", "TrackResult", "RRR3Newton", "RRR3Fk",
                "RRR3Plan", "RRR3Workspace", "ServoResult"]


@pytest.mark.parametrize("name", CORE_RESULTS)
def test_a_core_results_arrays_are_read_only_and_made_once(name):
    result = RESULTS[name]()
    arrays = {f: getattr(result, f) for f in dir(result) if isinstance(getattr(result, f, None), np.ndarray)}
    assert arrays, name
    for field, a in arrays.items():
        assert not a.flags.writeable, (name, field)
        assert getattr(result, field) is getattr(result, field) or a.base is not None, (name, field)
        with pytest.raises(ValueError, match="read-only"):
            a[...] = 0


def test_ik_solutions_of_a_held_joint_round_trip():
    iiwa = rk.robots.iiwa14()
    s = rk.closed.solve(iiwa.fk(np.full(7, 0.3)), iiwa, locked={2: 0.3})
    back = pickle.loads(pickle.dumps(s))
    assert back.q.shape == (8, 7) and np.array_equal(back.q, s.q) and back.postures == s.postures
