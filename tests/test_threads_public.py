"""Every public call is safe to share between threads: eight threads call a broad set of robokin's
public callables at once (the calls test_fuzz_*.py's COVERS sets name: chains' FK, Jacobians and
manipulability single and batch, numerical IK and IKSolver, reach, track, servo, resolved rate, the
closed forms, the 3-RRR's models, planner and workspace, trajectories, poses, posture tracking,
reachability) on different models (catalogue arms, a URDF chain, several 3-RRR geometries,
different options), and each answer must equal, bit for bit, the same call made alone before.
Any state kept between calls (solver caches, bound evaluators, scratch buffers) must be per call or
per thread: a thread handed another's would give a different answer here."""

import dataclasses
import pathlib
import sys
import threading

import numpy as np
import pytest

import robokin as rk

URDF = pathlib.Path(__file__).resolve().parent.parent / "examples" / "arm.urdf"
THREADS = 8
REPEAT = 30  # passes each thread makes over the calls, each in an order of its own


def digest(value, depth=0):
    """A comparable, exact form of a result: arrays by their bytes, objects by their public data."""
    if isinstance(value, np.ndarray):
        return ("array", value.shape, value.dtype.str, value.tobytes())
    if isinstance(value, (bool, int, str, bytes, type(None))):
        return value
    if isinstance(value, (float, np.floating, np.integer, np.bool_)):
        return ("scalar", np.asarray(value).tobytes(), type(value).__name__)
    if isinstance(value, (list, tuple)):
        return tuple(digest(v, depth + 1) for v in value)
    if isinstance(value, dict):
        return tuple((k, digest(v, depth + 1)) for k, v in sorted(value.items()))
    if depth > 3:
        return repr(value)
    if dataclasses.is_dataclass(value):
        return tuple((f.name, digest(getattr(value, f.name), depth + 1)) for f in dataclasses.fields(value))
    out = []
    for name in dir(value):
        if name.startswith("_"):
            continue
        item = getattr(value, name)
        if not callable(item):
            out.append((name, digest(item, depth + 1)))
    return (type(value).__name__, tuple(out))


def _chain_calls(chain, rng, tag):
    """Calls on one serial chain: FK, Jacobian, manipulability (single and batch), numerical IK
    (function, batch, a solver of the call's own), reach, track, servo and resolved rate."""
    lo, hi = chain.limits
    lo, hi = np.maximum(lo, -2.0), np.minimum(hi, 2.0)
    Q = rng.uniform(lo, hi, (12, chain.dof))
    q, q0 = Q[0], Q[1]
    T = chain.fk(Q[2])
    poses = chain.fk(Q[3:6])
    point, points = T[:3, 3], poses[:, :3, 3]
    task = chain.natural_task
    if task == "xy":  # a planar arm's targets are points (x, y)
        T, poses = T[:2, 3], poses[:, :2, 3]
    twist = rng.normal(size=6 if task == "pose" else 2) * 0.1
    damping = 0.01 * (tag % 3)
    return [
        (f"{tag} fk", lambda: chain.fk(q)),
        (f"{tag} fk batch", lambda: chain.fk(Q)),
        (f"{tag} frames", lambda: chain.frames(q)),
        (f"{tag} jacobian", lambda: chain.jacobian(q)),
        (f"{tag} jacobian batch", lambda: chain.jacobian(Q)),
        (f"{tag} manipulability", lambda: chain.manipulability(q)),
        (f"{tag} manipulability batch", lambda: chain.manipulability(Q, measure="condition" if tag % 2 else "yoshikawa")),
        (f"{tag} ellipsoid", lambda: chain.ellipsoid(q)),
        (f"{tag} ik", lambda: rk.ik(chain, T, q0, seed=tag, method=("lm", "gn", "nr")[tag % 3], max_iter=60)),
        (f"{tag} ik_batch", lambda: rk.ik_batch(chain, poses, q0, seed=tag, path=bool(tag % 2), max_iter=60)),
        (f"{tag} IKSolver", lambda: [rk.IKSolver(chain, seed=tag, restarts=2, max_iter=50).solve(p, q0) for p in poses]),
        (f"{tag} reach", lambda: rk.reach(chain, point, q0, task="position", damping=damping)),
        (f"{tag} track", lambda: rk.track(chain, points, q0, task="position", nullspace="joint_limits")),
        (f"{tag} servo", lambda: rk.servo(chain, poses, q0, 0.01, damping=damping)),
        (f"{tag} resolved_rate", lambda: rk.resolved_rate(chain, q, twist, damping=damping)),
    ]


def _closed_calls(rng):
    """The closed forms on different arms and limits."""
    ur5, ur10, puma = rk.robots.ur5(), rk.robots.ur10(), rk.robots.puma560()
    Tu = ur5.fk(rng.uniform(-3, 3, (4, 6)))
    Tt = ur10.fk(rng.uniform(-3, 3, 6))
    Tp = puma.fk(rng.uniform(-2, 2, (6, 6)))
    r3 = rk.Chain.from_dh([(1.0, -np.pi / 2, 0.0, 0.0, "R"), (2.0, np.pi / 2, 1.0, 0.0, "R"),
                           (1.5, 0.0, 0.0, 0.0, "R")])
    p3 = r3.fk(rng.uniform(-2, 2, 3))[:3, 3]
    planar = rk.robots.planar_3r(1.0, 0.8, 0.5)
    Tpl = planar.fk(rng.uniform(-2, 2, 3))
    return [
        ("closed.ur", lambda: rk.closed.ur(Tu[0], ur5)),
        ("closed.ur no limits", lambda: rk.closed.ur(Tt, ur10, limits=None)),
        ("closed.ur_batch", lambda: rk.closed.ur_batch(Tu, ur5)),
        ("closed.puma560", lambda: rk.closed.puma560(Tp[0])),
        ("closed.puma560_path", lambda: rk.closed.puma560_path(Tp, np.zeros(6))),
        ("closed.general_3r", lambda: rk.closed.general_3r(p3, r3, limits=None)),
        ("closed.planar_2r", lambda: rk.closed.planar_2r((1.2, 0.4), 1.0, 0.8)),
        ("closed.planar_3r", lambda: rk.closed.planar_3r((Tpl[0, 3], Tpl[1, 3], 0.3), 1.0, 0.8, 0.5)),
        ("closed.planar_rp", lambda: rk.closed.planar_rp((0.5, 0.7))),
        ("cuspidal", lambda: rk.cuspidal(r3, resolution=24)),
        ("track_postures", lambda: rk.track_postures(puma, Tp[:3], 0.1, starts=2)),
        ("reachability", lambda: rk.reachability(ur5, ((-0.6, 0.6), (-0.6, 0.6), (0.0, 0.3)), 0.3, orientations=2,
                                                 restarts=1, max_iter=20, seed=3)),
    ]


def _rrr3_calls(rng, geometry, tag):
    """The 3-RRR's models, planner and workspace for one geometry."""
    robot = rk.RRR3(*geometry)
    pose = np.array([0.01 * (tag % 3), -0.005 * tag, 0.05 * (tag % 2)])
    poses = pose + rng.uniform(-0.01, 0.01, (16, 3))
    alpha = robot.ik(pose)
    mode = ((1, 1, 1), (1, -1, 1), (-1, 1, 1))[tag % 3]
    circle = rk.paths.circle(40, radius=0.02 + 0.005 * tag)
    return [
        (f"rrr3 {tag} ik", lambda: robot.ik(pose, mode=mode)),
        (f"rrr3 {tag} ik_all", lambda: robot.ik_all(pose)),
        (f"rrr3 {tag} ik_batch", lambda: robot.ik_batch(poses, mode)),
        (f"rrr3 {tag} fk_all", lambda: robot.fk_all(alpha)),
        (f"rrr3 {tag} fk", lambda: robot.fk(alpha, pose + 0.002)),
        (f"rrr3 {tag} singularity", lambda: robot.singularity(pose, mode)),
        (f"rrr3 {tag} jacobians", lambda: robot.jacobians(pose, mode)),
        (f"rrr3 {tag} plan", lambda: robot.plan(circle, avoid=bool(tag % 2))),
        (f"rrr3 {tag} connect", lambda: robot.connect((0.0, 0.0, 0.0), (0.02, 0.01, 0.0), resolution=0.01)),
        (f"rrr3 {tag} workspace", lambda: robot.workspace(n=24 + 4 * tag, phi=0.05 * tag)),
    ]


def _toolkit_calls(rng, tag):
    """Trajectories and pose conversions."""
    q0, q1 = rng.uniform(-1, 1, (2, 4))
    T0 = rk.pose.from_rpy(rng.uniform(-1, 1, 3), rng.uniform(-1, 1, 3))
    T1 = rk.pose.from_axis_angle(rng.normal(size=3), 0.5 + 0.1 * tag, rng.uniform(-1, 1, 3))
    return [
        (f"traj {tag} quintic", lambda: rk.traj.quintic(q0, q1, np.linspace(0, 1, 50))),
        (f"traj {tag} trapezoidal", lambda: rk.traj.trapezoidal(q0, q1, 1.0 + tag, 2.0)),
        (f"traj {tag} via_points", lambda: rk.traj.via_points(np.array([q0, (q0 + q1) / 2, q1]), 1.0, 2.0)),
        (f"traj {tag} cartesian", lambda: rk.traj.cartesian(T0, T1, np.linspace(0, 1, 20))),
        (f"pose {tag} rpy", lambda: rk.pose.rpy(T1)),
        (f"pose {tag} quaternion", lambda: rk.pose.quaternion(T1)),
        (f"pose {tag} from_quaternion", lambda: rk.pose.from_quaternion(rk.pose.quaternion(T0), T0[:3, 3])),
        (f"pose {tag} axis_angle", lambda: rk.pose.axis_angle(T0)),
        (f"pose {tag} log exp", lambda: rk.pose.exp(rk.pose.log(T1))),
        (f"pose {tag} error", lambda: rk.pose.error(T0, T1)),
    ]


def _all_calls():
    rng = np.random.default_rng(11)
    chains = [rk.robots.get(name) for name in ("ur5", "puma560", "panda", "iiwa14", "irb120", "gen3", "rpr")]
    chains.append(rk.Chain.from_urdf(str(URDF)))
    geometries = [(0.13, 0.07, 0.12, 0.12), (0.15, 0.06, 0.13, 0.11), (0.12, 0.08, 0.11, 0.12)]
    calls = []
    for tag, chain in enumerate(chains):
        calls += _chain_calls(chain, rng, tag)
    for tag, geometry in enumerate(geometries):
        calls += _rrr3_calls(rng, geometry, tag)
    calls += _closed_calls(rng)
    for tag in range(2):
        calls += _toolkit_calls(rng, tag)
    return calls


@pytest.fixture
def fast_switching():
    before = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)  # threads interleave often, inside Python and around released GILs
    yield
    sys.setswitchinterval(before)


def test_public_calls_from_eight_threads_match_the_calls_made_alone(fast_switching):
    calls = _all_calls()
    alone = {name: digest(call()) for name, call in calls}
    # Each thread walks every call in its own order (so different models and calls overlap).
    orders = [np.concatenate([rng.permutation(len(calls)) for _ in range(REPEAT)])
              for rng in (np.random.default_rng(100 + i) for i in range(THREADS))]
    got = [dict() for _ in range(THREADS)]
    errors = []
    start = threading.Barrier(THREADS)

    def work(i):
        try:
            start.wait()
            for k in orders[i]:
                name, call = calls[k]
                answer = digest(call())
                if got[i].setdefault(name, answer) != answer:
                    got[i][name] = None  # differed between passes: reported below
        except Exception as exc:  # noqa: BLE001 - reported below, with the thread
            errors.append((i, repr(exc)))

    threads = [threading.Thread(target=work, args=(i,)) for i in range(THREADS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    for i in range(THREADS):
        differ = sorted(name for name in alone if got[i].get(name) != alone[name])
        assert not differ, f"thread {i}: answers that differ from the call made alone: {differ}"


def test_the_calls_cover_the_models_and_families_asked_for():
    names = " ".join(name for name, _ in _all_calls())
    for part in ("fk batch", "jacobian batch", "manipulability batch", "ik_batch", "IKSolver", "reach", "track",
                 "servo", "resolved_rate", "closed.ur_batch", "closed.puma560", "closed.general_3r", "planar",
                 "rrr3 2 workspace", "plan", "connect", "fk_all", "traj", "pose", "track_postures", "reachability",
                 "7 fk"):  # tag 7: the URDF chain
        assert part in names, part
