"""The threads test's table: for each public callable (the names test_fuzz_coverage.public_api()
walks) a list of zero-argument calls on different models (catalogue arms, URDF chains, 3-RRR
geometries, options). Each call builds nothing shared that it then changes: the models are built
once here and only read, so the same call made alone and from eight threads must give the same
answer. A call that writes a file writes its own (a name per call) and answers with the bytes.

EXCLUDED names the public callables that cannot be called concurrently at all, each with why."""

import atexit
import itertools
import os
import pathlib
import shutil
import sys
import tempfile

import numpy as np

import robokin as rk
import robokin.dask
import sim_helpers
from robokin import demo, plots, plots_arm, plots_reachability, plots_rrr3, rrr3_design
from robokin_sim.config import parse_args
from robokin_sim.keys import parse_script
from robokin_sim.scene_rpr import RprScene
from robokin_sim.scene_rrr3 import Rrr3Scene
from robokin_sim.scene_serial import SerialScene

rmod = sys.modules["robokin.reachability"]  # rk.reachability is the function

EXCLUDED = {}  # none: every public callable is safe to share

ROOT = pathlib.Path(__file__).resolve().parent.parent
SMALL_URDF = """<?xml version="1.0"?><robot name="small"><link name="base"/><link name="a"/><link name="b"/>
<link name="c"/><joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
<origin xyz="0 0 0.3" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
<joint name="j2" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.1 0 0.2" rpy="0.3 0 0"/>
<axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
<joint name="j3" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.4 0 0" rpy="0 0 0.2"/>
<axis xyz="1 0 0"/><limit lower="0" upper="0.3" effort="1" velocity="1"/></joint></robot>"""
UR3_DH = [(0.0, np.pi / 2, 0.1519, 0.0), (-0.24365, 0.0, 0.0, 0.0), (-0.21325, 0.0, 0.0, 0.0),
          (0.0, np.pi / 2, 0.11235, 0.0), (0.0, -np.pi / 2, 0.08535, 0.0), (0.0, 0.0, 0.0819, 0.0)]
UR_DICT = {"d1": 0.2, "a2": -0.5, "a3": -0.4, "d4": 0.12, "d5": 0.1, "d6": 0.09}
GEOMETRIES = [(0.13, 0.07, 0.12, 0.12), (0.15, 0.06, 0.13, 0.11), (0.12, 0.08, 0.11, 0.12)]
_OUT = tempfile.mkdtemp(prefix="robokin-threads-")
atexit.register(shutil.rmtree, _OUT, True)
_names = itertools.count()


def _file(suffix):
    """A file name of the call's own (itertools.count's next is atomic under the GIL)."""
    return os.path.join(_OUT, f"{next(_names)}{suffix}")


def _bytes_of(path):
    data = pathlib.Path(path).read_bytes()
    os.remove(path)
    return data


def figure_data(fig):
    """What a matplotlib Figure draws, exactly: per Axes its lines' data, images, patches, texts and
    limits (rendering to pixels would cost more and add nothing the data do not say)."""
    out = []
    for ax in fig.axes:
        lines = [np.asarray(line.get_data_3d() if hasattr(line, "get_data_3d") else line.get_xydata(), float).tobytes()
                 for line in ax.lines]
        images = [np.asarray(im.get_array()).tobytes() for im in ax.images]
        patches = [p.get_path().vertices.tobytes() for p in ax.patches]
        collections = [np.asarray(c.get_offsets()).tobytes() for c in ax.collections]
        texts = [ax.get_title(), ax.get_xlabel(), ax.get_ylabel(), *(t.get_text() for t in ax.texts)]
        out.append((lines, images, patches, collections, texts, ax.get_xlim(), ax.get_ylim()))
    return out, fig._suptitle.get_text() if fig._suptitle else None


def _models():
    """The models the calls read: arms, URDF chains, 3-RRR robots."""
    m = {name: rk.robots.get(name) for name in ("ur3", "ur5", "ur10", "ur3e", "ur5e", "ur10e", "ur16e", "puma560",
                                                 "panda", "iiwa14", "irb120", "gen3")}
    m["rpr"], m["rp"], m["prr"] = rk.robots.rpr(), rk.robots.rp(0.8), rk.robots.prr(0.9, 0.7)
    m["planar_3r"] = rk.robots.planar_3r(1.0, 0.8, 0.5)
    m["arm.urdf"] = rk.Chain.from_urdf(str(ROOT / "examples" / "arm.urdf"))
    m["small.urdf"] = rk.Chain.from_urdf(SMALL_URDF)
    lo, hi = np.full(6, -2.5), np.full(6, 2.5)
    m["ur3.urdf"] = rk.Chain.from_urdf(sim_helpers.urdf_from_dh("ur3u", UR3_DH, lo, hi), "l0", "tool")
    m["r3"] = rk.Chain.from_dh([(1.0, -np.pi / 2, 0.0, 0.0, "R"), (2.0, np.pi / 2, 1.0, 0.0, "R"),
                                (1.5, 0.0, 0.0, 0.0, "R")])
    m["segments"] = rk.Chain.from_segments([("R", (0, 0, 1), np.eye(4)), ("P", (1, 0, 0), np.eye(4))])
    d = UR_DICT
    m["ur_dict"] = rk.Chain.from_dh([(0.0, np.pi / 2, d["d1"], 0.0, "R"), (d["a2"], 0.0, 0.0, 0.0, "R"),
                                     (d["a3"], 0.0, 0.0, 0.0, "R"), (0.0, np.pi / 2, d["d4"], 0.0, "R"),
                                     (0.0, -np.pi / 2, d["d5"], 0.0, "R"), (0.0, 0.0, d["d6"], 0.0, "R")])
    m["robots"] = [rk.RRR3(*g) for g in GEOMETRIES]
    return m


M = _models()
SERIAL = ["ur5", "puma560", "panda", "iiwa14", "irb120", "gen3", "rpr", "arm.urdf", "small.urdf", "ur3.urdf"]


def _q(chain, k, count=None):
    """Joints within the chain's limits (at most 2 rad from 0), from a generator seeded by k."""
    lo, hi = chain.limits
    lo, hi = np.maximum(lo, -2.0), np.minimum(hi, 2.0)
    return np.random.default_rng(k).uniform(lo, hi, (chain.dof,) if count is None else (count, chain.dof))


def _target(chain, q):
    """The chain's natural task's target at q (a frame, a point (x, y [, z]) or (x, y, phi))."""
    T = chain.fk(q)
    task = chain.natural_task
    if task == "pose":
        return T
    if task == "position":
        return T[..., :3, 3]
    if task == "xy":
        return T[..., :2, 3]
    return np.concatenate([T[..., :2, 3], np.arctan2(T[..., 1, 0], T[..., 0, 0])[..., None]], axis=-1)


def _each_chain(call, names=SERIAL):
    return [lambda c=M[n], k=k: call(c, k) for k, n in enumerate(names)]


def _chain_cases():
    """Chain's constructors, properties and methods, and the functions over one chain."""
    c = {}
    c["Chain.from_dh"] = [lambda k=k: rk.Chain.from_dh([(0.3 + 0.1 * k, 0.2 * k, 0.1, 0.0, "R"), (0.5, 0.0, 0.0, 0.1, "P")],
                                                       modified=bool(k % 2)).fk([0.3, 0.2]) for k in range(3)]
    c["Chain.from_segments"] = [lambda k=k: rk.Chain.from_segments(
        [("R", (0, 0, 1), np.eye(4)), ("P", (1, 0, 0), np.eye(4)), ("R", (0, 1, 0), np.eye(4))],
        tool=rk.pose.from_rpy((0.0, 0.1 * k, 0.0), (0.2, 0.0, 0.1 * k))).frames([0.1 * k, 0.2, -0.3]) for k in range(2)]
    c["Chain.from_urdf"] = [lambda: rk.Chain.from_urdf(SMALL_URDF).frames([0.2, 0.3, 0.1]),
                            lambda: rk.Chain.from_urdf(str(ROOT / "examples" / "arm.urdf")).link_names]
    for attr in ("dof", "joint_names", "joint_types", "limits", "link_names", "natural_task"):
        c[f"Chain.{attr}"] = _each_chain(lambda ch, k, a=attr: getattr(ch, a))
    c["Chain.fk"] = _each_chain(lambda ch, k: chain_fk(ch, k))
    c["Chain.frames"] = _each_chain(lambda ch, k: ch.frames(_q(ch, k)))
    c["Chain.jacobian"] = _each_chain(lambda ch, k: (ch.jacobian(_q(ch, k)), ch.jacobian(_q(ch, k, 40), task="position")))
    c["Chain.manipulability"] = _each_chain(
        lambda ch, k: (ch.manipulability(_q(ch, k)), ch.manipulability(_q(ch, k, 40), measure=("condition", "yoshikawa",
                                                                                           "min_singular")[k % 3])))
    c["Chain.ellipsoid"] = _each_chain(lambda ch, k: ch.ellipsoid(_q(ch, k), part=("translation", "rotation")[k % 2]),
                                       [n for n in SERIAL if M[n].natural_task == "pose"])
    c["Chain.point_in_frame"] = _each_chain(lambda ch, k: ch.point_in_frame(_q(ch, k), (0.1, 0.2, 0.3), ch.dof, k % 2))
    c["Chain.q_dict"] = _each_chain(lambda ch, k: ch.q_dict(_q(ch, k)))
    c["Chain.table"] = _each_chain(lambda ch, k: (ch.table(), str(ch)))
    c["Chain.q_from"] = _each_chain(lambda ch, k: ch.q_from({ch.joint_names[0]: 0.1 * k}, default=0.05))
    c["joint_limit_cost"] = _each_chain(lambda ch, k: rk.joint_limit_cost(ch, _q(ch, k, 20)), ["rpr", "panda", "gen3"])
    c["urdf_tree"] = [lambda: rk.urdf_tree(SMALL_URDF), lambda: rk.urdf_tree(str(ROOT / "examples" / "arm.urdf"))]
    return c


def chain_fk(chain, k):
    """FK of one configuration, of a batch, and of a batch into the call's own out= buffer."""
    Q = _q(chain, k, 30)
    out = np.empty((30, 4, 4))
    chain.fk(Q, out=out)
    return chain.fk(Q[0]), chain.fk(Q), out


def _numeric_cases():
    """Numerical IK, the Reach loop, tracking, servoing, resolved rate, posture tracking."""
    c = {}
    long = dict(restarts=12, max_iter=150)  # > 1700 iterations in all: the solve releases the GIL

    def ik(ch, k):
        method = ("lm", "gn", "nr")[k % 3]
        return (rk.ik(ch, _target(ch, _q(ch, k)), _q(ch, k + 50), seed=k, method=method, max_iter=60),
                rk.ik(ch, _target(ch, _q(ch, k + 1)), _q(ch, k + 51), seed=k, method=method, **long))
    c["ik"] = _each_chain(ik)
    c["ik_batch"] = _each_chain(lambda ch, k: rk.ik_batch(ch, _target(ch, _q(ch, k, 6)), _q(ch, k + 50), seed=k,
                                                          path=bool(k % 2), max_iter=60))
    c["IKSolver.__init__"] = _each_chain(lambda ch, k: rk.IKSolver(ch, seed=k, restarts=2, max_iter=40).solve(
        _target(ch, _q(ch, k)), _q(ch, k + 50)))
    c["IKSolver.solve"] = _each_chain(lambda ch, k: [SOLVERS[k].solve(t, _q(ch, k + 50))
                                                     for t in _target(ch, _q(ch, k, 3))])
    for attr in ("method", "options", "task"):
        c[f"IKSolver.{attr}"] = [lambda s=s, a=attr: getattr(s, a) for s in SOLVERS]

    def reach(ch, k):
        return rk.reach(ch, _target(ch, _q(ch, k)), _q(ch, k) + 0.05, damping=0.01 * (k % 3),
                        nullspace="joint_limits" if k % 2 else None)
    c["reach"] = _each_chain(reach)
    c["track"] = _each_chain(lambda ch, k: rk.track(ch, _target(ch, _q(ch, k) + np.linspace(0, 0.05, 8)[:, None]),
                                                    _q(ch, k), nullspace="joint_limits"))
    # Long paths: the loop runs for milliseconds with the GIL released, beside the other threads'
    # calls (a buffer shared between two Reach loops would mix their errors).
    c["track"] += [lambda n=n: rk.track(M[n], _target(M[n], _q(M[n], 8) + np.linspace(0, 0.3, 1500)[:, None]),
                                        _q(M[n], 8), nullspace="joint_limits" if n == "rpr" else None)
                   for n in ("rpr", "ur5", "panda")]
    c["servo"] = _each_chain(lambda ch, k: rk.servo(ch, ch.fk(_q(ch, k) + np.linspace(0, 0.05, 6)[:, None]), _q(ch, k),
                                                    0.01, damping=0.01 * (k % 3)), [n for n in SERIAL if M[n].dof == 6])
    c["resolved_rate"] = _each_chain(lambda ch, k: rk.resolved_rate(ch, _q(ch, k), twist(ch, k), damping=0.01 * (k % 3)))
    c["track_postures"] = [lambda: rk.track_postures(M["puma560"], M["puma560"].fk(_q(M["puma560"], 3, 4)), 0.1),
                           lambda: rk.track_postures(M["ur5"], M["ur5"].fk(_q(M["ur5"], 4, 4)), 0.1),
                           lambda: rk.track_postures(M["panda"], M["panda"].fk(_q(M["panda"], 5, 3)), 0.1,
                                                     method="numerical", starts=2, seed=1)]
    c["count_reconfigurations"] = [lambda k=k: rk.count_reconfigurations(_q(M["ur5"], k, 12), 0.1, 2.0 + k,
                                                                         chain=M["ur5"] if k else None) for k in range(2)]
    c["cuspidal"] = [lambda: rk.cuspidal(M["r3"], resolution=24), lambda: rk.cuspidal(M["planar_3r"], resolution=16)]
    return c


def twist(chain, k):
    """A small rate of the chain's natural task (6 for a pose, else the size of its target)."""
    rows = 6 if chain.natural_task == "pose" else len(_target(chain, np.zeros(chain.dof)))
    return np.random.default_rng(k).normal(size=rows) * 0.1


# Solvers shared by every thread. Call k of a seeded solver draws its restarts from seed + k, so
# shared calls would depend on their order: these make no restarts (nothing drawn), and are long
# enough (> 1700 iterations allowed) for the solve to release the GIL.
SOLVERS = [rk.IKSolver(M[n], seed=k, restarts=0, max_iter=1800, method=("lm", "gn", "nr")[k % 3])
           for k, n in enumerate(SERIAL)]


UR_ARMS = ["ur3", "ur5", "ur10", "ur3e", "ur5e", "ur10e", "ur16e", "ur_dict"]


def _ur_cases():
    """The UR closed form on eight UR arms (different lengths, limits and a URDF one), a dict arm
    and given limits: a solver cached for one arm and handed to another's call answers wrongly."""
    calls = []
    for k, name in enumerate(UR_ARMS):
        ch = M[name]
        limits = ("default", None)[k % 2]
        calls.append(lambda ch=ch, k=k, limits=limits: rk.closed.ur(ch.fk(_q(ch, k + 7)), ch, limits=limits))
    calls.append(lambda: rk.closed.ur(M["ur_dict"].fk(_q(M["ur_dict"], 3)), UR_DICT))
    calls.append(lambda: rk.closed.ur(M["ur5"].fk(_q(M["ur5"], 4)), M["ur5"], limits=(np.full(6, -1.0), np.full(6, 1.0))))
    # A new chain at each call: ids of freed chains are reused, and must not find their solvers.
    calls += [lambda f=f, k=k: rk.closed.ur(M[f.__name__].fk(_q(M[f.__name__], k)), f(), limits=(None, "default")[k])
              for k, f in enumerate((rk.robots.ur10, rk.robots.ur3e))]
    # The other limits than closed.ur's for each arm: more bound solvers than the cache keeps.
    batches = [lambda ch=M[n], k=k: rk.closed.ur_batch(ch.fk(_q(ch, k + 20, 5)), ch, limits=(None, "default")[k % 2])
               for k, n in enumerate(UR_ARMS)]
    return {"closed.ur": calls, "closed.ur_batch": batches}


def _closed_cases():
    c = _ur_cases()
    puma = M["puma560"]
    c["closed.puma560"] = [lambda k=k: rk.closed.puma560(puma.fk(_q(puma, k)), limits=("default", None, puma)[k % 3])
                           for k in range(3)]
    c["closed.puma560_path"] = [lambda k=k: rk.closed.puma560_path(puma.fk(_q(puma, k, 5)), _q(puma, k + 9),
                                                                   limits=("default", None)[k]) for k in range(2)]
    c["closed.general_3r"] = [lambda: rk.closed.general_3r(M["r3"].fk(_q(M["r3"], 1))[:3, 3], M["r3"], limits=None),
                              lambda: rk.closed.general_3r(M["r3"].fk(_q(M["r3"], 2))[:3, 3], M["r3"])]
    c["closed.planar_2r"] = [lambda: rk.closed.planar_2r((1.2, 0.4), 1.0, 0.8), lambda: rk.closed.planar_2r((0.3, -0.5))]
    c["closed.planar_3r"] = [lambda: rk.closed.planar_3r((1.1, 0.6, 0.3), 1.0, 0.8, 0.5, limits=M["planar_3r"]),
                             lambda: rk.closed.planar_3r((0.9, -0.4, 1.0), 1.0, 0.8, 0.5, method="geometric")]
    c["closed.planar_rp"] = [lambda: rk.closed.planar_rp((0.5, 0.7)), lambda: rk.closed.planar_rp((-0.2, 0.4), M["rp"])]
    c["closed.anthropomorphic"] = [lambda: rk.closed.anthropomorphic((0.4, 0.3, 0.5), 0.5, 0.45, 0.3),
                                   lambda: rk.closed.anthropomorphic((0.2, -0.3, 0.1), 0.4, 0.4)]
    g = rk.closed.PUMA560
    c["closed.spherical_wrist_6r"] = [
        lambda: rk.closed.spherical_wrist_6r(puma.fk(_q(puma, 5)), g["a2"], g["a3"], g["d3"], g["d4"], g["d1"], g["d6"]),
        lambda: rk.closed.spherical_wrist_6r(puma.fk(_q(puma, 6)), g["a2"], g["a3"], g["d3"], g["d4"], g["d1"], g["d6"],
                                             limits=puma)]
    sols = [rk.closed.ur(M["ur5"].fk(_q(M["ur5"], 1)), M["ur5"]), rk.closed.puma560(puma.fk(_q(puma, 2))),
            rk.closed.planar_3r((1.1, 0.6, 0.3), 1.0, 0.8, 0.5, limits=M["planar_3r"])]
    for attr in ("dof", "postures", "q", "singular", "within_limits"):
        c[f"IKSolutions.{attr}"] = [lambda s=s, a=attr: getattr(s, a) for s in sols]
    c["IKSolutions.nearest"] = [lambda s=s, k=k: s.nearest(np.full(s.dof, 0.1 * k)) for k, s in enumerate(sols)]
    c["IKSolutions.only_within_limits"] = [lambda s=s: s.only_within_limits() for s in sols]
    return c


FAMILY_ARMS = ["ur5", "puma560", "irb120", "ur3.urdf", "ur10e"]
CLOSED_SOLVERS = [rk.closed.ClosedSolver(M[n], limits=(None, "default")[k % 2]) for k, n in enumerate(FAMILY_ARMS)]
# 7-joint arms with one joint held (the families of the joints left, read from the base or the tool).
HELD = [("iiwa14", {2: 0.4}), ("panda", {6: 0.3}), ("gen3", {0: -0.5}), ("iiwa14", {5: -0.7})]
CLOSED_SOLVERS += [rk.closed.ClosedSolver(M[n], limits=(None, "default")[k % 2], locked=lock)
                   for k, (n, lock) in enumerate(HELD)]


def _held_q(name, lock, k):
    """Joints within limits with the held joint at its value."""
    q = _q(M[name], k)
    (j, v), = lock.items()
    q[j] = v
    return q


def _family_cases():
    """The closed form read from a chain's geometry: family, solve and the held ClosedSolver."""
    c = {"closed.family": [lambda n=n: rk.closed.family(M[n]) for n in FAMILY_ARMS + ["panda", "arm.urdf", "rpr"]]}
    c["closed.family"].append(lambda: rk.closed.family(M["puma560"], tol=1e-3))
    c["closed.solve"] = [lambda n=n, k=k: rk.closed.solve(M[n].fk(_q(M[n], k + 30)), M[n], limits=(None, "default")[k % 2])
                         for k, n in enumerate(FAMILY_ARMS)]
    c["closed.family"] += [lambda n=n, lock=lock: rk.closed.family(M[n], locked=lock) for n, lock in HELD]
    c["closed.family"].append(lambda: rk.closed.family(M["iiwa14"], locked={3: 0.2}))  # none: why
    c["closed.solve"] += [lambda n=n, lock=lock, k=k: rk.closed.solve(M[n].fk(_held_q(n, lock, k + 35)), M[n],
                                                                      locked=lock) for k, (n, lock) in enumerate(HELD)]
    c["ClosedSolver.__init__"] = [lambda n=n, k=k: rk.closed.ClosedSolver(M[n]).solve(M[n].fk(_q(M[n], k + 40)))
                                  for k, n in enumerate(FAMILY_ARMS)]
    c["ClosedSolver.__init__"] += [lambda n=n, lock=lock, k=k: rk.closed.ClosedSolver(M[n], locked=lock).solve(
        M[n].fk(_held_q(n, lock, k + 45))) for k, (n, lock) in enumerate(HELD)]
    c["ClosedSolver.solve"] = [lambda s=s, k=k: s.solve(s.chain.fk(_q(s.chain, k + 50)))
                               for k, s in enumerate(CLOSED_SOLVERS)]
    c["ClosedSolver.solve_batch"] = [lambda s=s, k=k: s.solve_batch(s.chain.fk(_q(s.chain, k + 60, 4)))
                                     for k, s in enumerate(CLOSED_SOLVERS)]
    c["ClosedSolver.find"] = [lambda n=n: rk.closed.ClosedSolver.find(M[n]) for n in FAMILY_ARMS + ["panda", "rpr"]]
    c["ClosedSolver.find"] += [lambda n=n, lock=lock: rk.closed.ClosedSolver.find(M[n], locked=lock) for n, lock in HELD]
    for attr in ("chain", "family", "limits", "locked"):
        c[f"ClosedSolver.{attr}"] = [lambda s=s, a=attr: getattr(s, a) for s in CLOSED_SOLVERS]
    return c


def _symbolic_cases():
    """The DH models as sympy matrices, compared as their printed text (exact)."""
    from robokin import symbolic

    arms = ["prr", "r3", "planar_3r"]
    c = {"symbolic.table": [lambda n=n, k=k: str(symbolic.table(M[n], lengths=("values", "symbols")[k % 2]))
                            for k, n in enumerate(arms)]}
    # One simplified model (simplification is slow: the others unsimplified, the same rule on each thread).
    c["symbolic.fk"] = [lambda: str(symbolic.fk(M["prr"]))]
    c["symbolic.fk"] += [lambda n=n: str(symbolic.fk(M[n], simplify=False)) for n in arms[1:]]
    c["symbolic.fk"].append(lambda: str(symbolic.fk(M["ur_dict"], q=(0.5, 0.2, -0.3, 0.1, 0.4, 0.9), simplify=False)))
    c["symbolic.jacobian"] = [lambda n=n: str(symbolic.jacobian(M[n], simplify=False)) for n in arms]
    c["symbolic.jacobian"].append(lambda: str(symbolic.jacobian(M["prr"], task="position", lengths="symbols",
                                                                simplify=False)))
    return c


def _rrr3_cases():
    """The 3-RRR's constructor, properties and models on three geometries."""
    c = {}
    robots = M["robots"]
    c["RRR3.__init__"] = [lambda g=g: rk.RRR3(*g).ik((0.01, 0.0, 0.1)) for g in GEOMETRIES]
    for attr in ("base_joints", "base_radius", "l1", "l2", "modes", "platform_radius"):
        c[f"RRR3.{attr}"] = [lambda r=r, a=attr: getattr(r, a) for r in robots]

    def each(call):
        return [lambda r=r, k=k: call(r, k, np.array([0.01 * (k % 3), -0.005 * k, 0.05 * (k % 2)]),
                                       ((1, 1, 1), (1, -1, 1), (-1, 1, 1))[k]) for k, r in enumerate(robots)]
    c["RRR3.ik"] = each(lambda r, k, p, m: r.ik(p, mode=m))
    c["RRR3.ik_all"] = each(lambda r, k, p, m: r.ik_all(p))
    c["RRR3.ik_batch"] = each(lambda r, k, p, m: r.ik_batch(p + np.random.default_rng(k).uniform(-0.01, 0.01, (16, 3)), m))
    c["RRR3.ik_newton"] = each(lambda r, k, p, m: r.ik_newton(p, np.r_[r.ik(p), np.full(3, 1.0)]))
    c["RRR3.fk"] = each(lambda r, k, p, m: r.fk(r.ik(p), p + 0.002))
    c["RRR3.fk_all"] = each(lambda r, k, p, m: r.fk_all(r.ik(p)))
    c["RRR3.points"] = each(lambda r, k, p, m: r.points(p, m))
    c["RRR3.jacobians"] = each(lambda r, k, p, m: r.jacobians(p, m))
    c["RRR3.singularity"] = each(lambda r, k, p, m: r.singularity(p, m, tol=1e-3 * (k + 1)))
    c["RRR3.plan"] = each(lambda r, k, p, m: r.plan(rk.paths.circle(40, radius=0.02 + 0.005 * k), avoid=bool(k % 2)))
    c["RRR3.plan_loop"] = each(lambda r, k, p, m: r.plan_loop(rk.paths.circle(30, radius=0.02 + 0.005 * k)))
    c["RRR3.connect"] = each(lambda r, k, p, m: r.connect((0.0, 0.0, 0.0), (0.02, 0.01 * k, 0.0), resolution=0.01))
    c["RRR3.workspace"] = each(lambda r, k, p, m: r.workspace(n=24 + 4 * k, phi=0.05 * k, mode=m))
    return c


def _toolkit_cases():
    """Trajectories, poses, paths and the catalogue."""
    c = {}
    rng = np.random.default_rng(5)
    q0, q1 = rng.uniform(-1, 1, (2, 4))
    T0 = rk.pose.from_rpy((0.1, -0.2, 0.3), (0.1, 0.2, 0.3))
    T1 = rk.pose.from_axis_angle((0.3, -0.4, 1.0), 0.7, (0.4, -0.1, 0.2))
    c["traj.quintic"] = [lambda: rk.traj.quintic(q0, q1, np.linspace(0, 1, 50)),
                         lambda: rk.traj.quintic(q1, q0, np.linspace(0, 2, 30), qd0=np.full(4, 0.1))]
    c["traj.trapezoidal"] = [lambda k=k: rk.traj.trapezoidal(q0, q1, 1.0 + k, 2.0) for k in range(2)]
    c["traj.via_points"] = [lambda k=k: rk.traj.via_points(np.array([q0, (q0 + q1) / 2 + 0.1 * k, q1]), 1.0, 2.0)
                            for k in range(2)]
    c["traj.cartesian"] = [lambda: rk.traj.cartesian(T0, T1, np.linspace(0, 1, 20)),
                           lambda: rk.traj.cartesian(T1, T0, law="trapezoidal", vmax=(0.5, 1.0), amax=(1.0, 2.0))]
    c["pose.from_rpy"] = [lambda: rk.pose.from_rpy((0.1, -0.2, 0.3), (1, 2, 3)), lambda: rk.pose.from_rpy(rng_rpy())]
    c["pose.rpy"] = [lambda T=T: rk.pose.rpy(T) for T in (T0, T1)]
    c["pose.quaternion"] = [lambda T=T: rk.pose.quaternion(T) for T in (T0, T1)]
    c["pose.from_quaternion"] = [lambda: rk.pose.from_quaternion((0.5, 0.5, -0.5, 0.5), (1, 0, 0)),
                                 lambda: rk.pose.from_quaternion(rk.pose.quaternion(T1))]
    c["pose.from_axis_angle"] = [lambda: rk.pose.from_axis_angle((0, 0, 1), 0.3), lambda: rk.pose.from_axis_angle(
        (1, 1, 0), -2.0, (0.1, 0.1, 0.1))]
    c["pose.axis_angle"] = [lambda T=T: rk.pose.axis_angle(T) for T in (T0, T1)]
    c["pose.log"] = [lambda T=T: rk.pose.log(T) for T in (T0, T1)]
    c["pose.exp"] = [lambda: rk.pose.exp((0.1, 0.2, 0.3, 0.4, -0.5, 0.6)), lambda: rk.pose.exp(rk.pose.log(T1))]
    c["pose.error"] = [lambda: rk.pose.error(T0, T1), lambda: rk.pose.error(T1, T0)]
    c["paths.line"] = [lambda: rk.paths.line((0, 0), (0.3, 0.1), 0.01), lambda: rk.paths.line((0, 0, 0), (1, 1, 1), 0.1)]
    c["paths.circle"] = [lambda: rk.paths.circle(50), lambda: rk.paths.circle(20, radius=0.3, center=(0.1, -0.1))]
    c["paths.clover"] = [lambda: rk.paths.clover(60), lambda: rk.paths.clover(30, k=0.05, center=(0.2, 0))]
    for name in ("gen3", "iiwa14", "irb120", "panda", "puma560", "rp", "rpr", "ur10", "ur10e", "ur16e", "ur3", "ur3e",
                 "ur5", "ur5e"):
        c[f"robots.{name}"] = [lambda f=getattr(rk.robots, name): f().fk(_q(f(), 1))]
    c["robots.planar_3r"] = [lambda: rk.robots.planar_3r().fk([0.1, 0.2, 0.3]), lambda: rk.robots.planar_3r(1, 2, 3).dof]
    c["robots.prr"] = [lambda: rk.robots.prr().fk([0.1, 0.2, 0.3]), lambda: rk.robots.prr(0.5, 0.4).limits]
    c["robots.names"] = [rk.robots.names]
    c["robots.get"] = [lambda n=n: rk.robots.get(n).frames(_q(M[n], 2)) for n in ("ur5", "panda", "gen3")]
    c["robots.configurations"] = [lambda n=n: rk.robots.configurations(n) for n in ("ur5", "panda", "puma560")]
    c["robots.rpr_self_motion"] = [lambda: rk.robots.rpr_self_motion((0.5, 0.6), num=41),
                                   lambda: rk.robots.rpr_self_motion((0.3, 0.2), t1=np.linspace(0, 1, 7))]
    return c


def rng_rpy():
    return np.random.default_rng(9).uniform(-1, 1, 3)


BOX = ((-0.6, 0.6), (-0.6, 0.6), (0.0, 0.3))


def _map_cases():
    """Reachability maps, the 3-RRR design studies, and both on Dask (threaded scheduler)."""
    c = {}
    reach = dict(orientations=2, restarts=1, max_iter=20)
    c["reachability"] = [lambda: rk.reachability(M["ur5"], BOX, 0.3, seed=3, **reach),
                         lambda: rk.reachability(M["planar_3r"], ((-2, 2), (-2, 2)), 0.5, seed=1, **reach)]
    c["reachability.reachability"] = [lambda: rmod.reachability(M["irb120"], BOX, 0.3, seed=4, **reach)]
    c["reachability.grid"] = [lambda: rmod.grid(BOX, 0.1), lambda: rmod.grid(((0, 1), (0, 2)), 0.3)]
    c["reachability.plan"] = [lambda: plan_blocks(M["ur10"], 5), lambda: plan_blocks(M["gen3"], 6)]
    c["rrr3_design.area_vs_platform_radius"] = [lambda: rrr3_design.area_vs_platform_radius([0.04, 0.06], n=24)]
    c["rrr3_design.best_l2"] = [lambda: rrr3_design.best_l2([0.08, 0.1], [0.06, 0.1], n=20)]
    c["dask.fk"] = [lambda: robokin.dask.fk(M["panda"], _q(M["panda"], 1, 40), chunks=16).compute()]
    c["dask.ik_batch"] = [lambda: robokin.dask.ik_batch(M["ur5"], M["ur5"].fk(_q(M["ur5"], 2, 6)), _q(M["ur5"], 3),
                                                        chunks=4, restarts=1, max_iter=30).compute()]
    c["dask.reachability"] = [lambda: robokin.dask.reachability(M["ur5"], BOX, 0.3, seed=3, chunks=10, **reach)]
    c["dask.region_areas"] = [lambda: robokin.dask.region_areas(np.array(GEOMETRIES), chunks=2, n=20).compute()]
    c["dask.area_vs_platform_radius"] = [lambda: robokin.dask.area_vs_platform_radius([0.05, 0.07], n=20, chunks=1)]
    c["dask.best_l2"] = [lambda: robokin.dask.best_l2([0.09], [0.06, 0.1], n=20, chunks=1)]
    return c


def plan_blocks(chain, seed):
    p = rmod.plan(chain, BOX, 0.3, orientations=2, seed=seed, restarts=1, max_iter=20)
    index, manip = p.block(0, p.voxels)
    return p.shape, index, manip, p.result(index, manip)


def _new_axes(projection=None):
    from matplotlib.figure import Figure

    return Figure().add_subplot(projection=projection)


RPR_POINTS = rk.paths.line(M["rpr"].fk(rk.robots.RPR_LINE_Q1)[:2, 3], rk.robots.RPR_LINE_P2, 0.2)
RPR_TRACKS = {label: rk.track(M["rpr"], RPR_POINTS, rk.robots.RPR_LINE_Q1, nullspace=ns)
              for label, ns in (("minimum norm", None), ("null space", "joint_limits"))}
RMAP = rk.reachability(M["ur5"], BOX, 0.3, orientations=2, restarts=1, max_iter=20, seed=3)
CURVE = rrr3_design.area_vs_platform_radius([0.04, 0.06], n=20)
BEST = rrr3_design.best_l2([0.08, 0.1], [0.06, 0.1], n=20)


def _plot_cases():
    """The figures (compared by what they draw), the animation and the demo (by the bytes written)."""
    c = {}
    robots = M["robots"]
    c["plots.draw_planar_chain"] = [lambda n=n: draw_planar(M[n]) for n in ("rpr", "planar_3r")]
    c["plots.joint_axes"] = _each_chain(lambda ch, k: plots.joint_axes(ch, _q(ch, k)))
    c["plots_arm.arm"] = [lambda n=n, k=k: figure_data(plots_arm.arm(M[n], _q(M[n], k), ellipsoid=k == 1).figure)
                          for k, n in enumerate(("ur5", "panda", "arm.urdf"))]
    c["plots_arm.arm"].append(lambda: figure_data(plots_arm.arm(M["gen3"], _q(M["gen3"], 1), ax=_new_axes("3d"),
                                                                frames=False).figure))
    c["plots_arm.animate"] = [lambda: _bytes_of(plots_arm.animate(M["ur5"], _q(M["ur5"], 1, 2), _file(".gif"),
                                                                  size=(64, 64)))]
    c["plots_arm.teach"] = [lambda n=n, k=k: teach_values(M[n], k) for k, n in enumerate(("ur5", "arm.urdf", "rpr"))]
    c["plots.rpr_line_figure"] = [lambda: figure_data(plots.rpr_line_figure(RPR_POINTS, RPR_TRACKS, surface_samples=4,
                                                                            snapshots=3, title="t"))]
    c["plots.trajectory_figure"] = [lambda: figure_data(plots.trajectory_figure(
        rk.traj.quintic(np.zeros(3), np.ones(3), np.linspace(0, 1, 20)), names=["a", "b", "c"]))]
    c["plots_reachability.plot_reachability"] = [
        lambda: figure_data(plots_reachability.plot_reachability(RMAP, axis="y")),
        lambda: saved_reachability("x")]
    c["plots_rrr3.plot_robot"] = [lambda r=r, k=k: figure_data(plots_rrr3.plot_robot(
        r, (0.01 * k, 0.0, 0.1), path=rk.paths.circle(10, radius=0.02))[0]) for k, r in enumerate(robots)]
    c["plots_rrr3.plot_robot"].append(lambda: figure_data(plots_rrr3.plot_robot(robots[1], (0, 0, 0),
                                                                                ax=_new_axes())[0]))
    c["plots_rrr3.plot_workspace"] = [lambda r=r, k=k: figure_data(plots_rrr3.plot_workspace(r, n=20 + k, phi=0.1 * k)[0])
                                      for k, r in enumerate(robots)]
    c["plots_rrr3.plot_design"] = [lambda: figure_data(plots_rrr3.plot_design(CURVE, BEST)[0])]
    c["demo.main"] = [lambda: demo_main(0.3)]
    return c


def teach_values(chain, k):
    """teach's widgets after moving the first slider: the sliders' values, the picture, the pose text."""
    box = plots_arm.teach(chain, _q(chain, k))
    sliders = box.children[:chain.dof]
    sliders[0].value = (sliders[0].min + sliders[0].max) / 2
    return [s.value for s in sliders], box.children[-2].value, box.children[-1].value


def saved_reachability(axis):
    """The figure saved to a file of the call's own: what it draws and the PNG's bytes."""
    path = _file(".png")
    fig = plots_reachability.plot_reachability(RMAP, path=path, axis=axis)
    return figure_data(fig), _bytes_of(path)


def draw_planar(chain):
    ax = _new_axes()
    plots.draw_planar_chain(ax, chain, _q(chain, 3), color="C1", alpha=0.5)
    return figure_data(ax.figure)


def demo_main(step):
    """The demo's command line: its exit status and the PNG it wrote."""
    out = _file(".png")
    status = demo.main(["--out", out, "--step", str(step)])
    return status, _bytes_of(out)


def _sim_cases():
    """The simulator's command line, key scripts and scenes (each call steps a scene of its own)."""
    c = {}
    c["sim.parse_args"] = [lambda a=a: parse_args(a) for a in (["--robot", "ur5", "--mode", "circle", "--frames", "9"],
                                                              ["--robot", "rrr3", "--keys", "right*3,l*2", "--no-avoid"],
                                                              ["--headless", "--robot", "rpr", "--fps", "30"])]
    c["sim.parse_script"] = [lambda t=t: parse_script(t) for t in ("right*20,down*10,l*10", "m,o*3,shift+up*2")]
    c["sim.Rrr3Scene"] = [lambda m=m, a=a: scene_now(Rrr3Scene(m, a)) for m, a in (("free", True), ("clover", False))]
    c["sim.RprScene"] = [lambda m=m, a=a: scene_now(RprScene(m, a)) for m, a in (("line", True), ("free", False))]
    c["sim.SerialScene"] = [lambda n=n, m=m: scene_now(SerialScene(M[n], n, mode=m))
                            for n, m in (("ur5", "free"), ("panda", "circle"), ("arm.urdf", "line"))]
    c["sim.Scene.step"] = [lambda: stepped(Rrr3Scene("circle", True), {"l"}, 12),
                           lambda: stepped(Rrr3Scene("free", False), {"right", "up"}, 12),
                           lambda: stepped(RprScene("line", True), set(), 12),
                           lambda: stepped(SerialScene(M["ur10"], "ur10"), {"right"}, 6),
                           lambda: stepped(SerialScene(M["iiwa14"], "iiwa14", mode="circle"), set(), 6)]
    c["sim.Scene.pointer"] = [lambda k=k: pointed(SerialScene(M[n], n), k) for k, n in enumerate(("ur5", "gen3"))]
    return c


def scene_now(scene):
    return scene.row(), scene.state()


def stepped(scene, held, n):
    rows = []
    for _ in range(n):
        scene.step(frozenset(held))
        rows.append(scene.row())
    return rows, scene.state()


def pointed(scene, k):
    scene.pointer((30 * (k + 1), -20), k - 1)
    scene.step(frozenset())
    return scene.row(), scene.state()


def _cases():
    cases = {}
    for group in (_chain_cases, _numeric_cases, _closed_cases, _family_cases, _symbolic_cases, _rrr3_cases, _toolkit_cases, _map_cases, _plot_cases,
                  _sim_cases):
        cases.update(group())
    return cases


CASES = _cases()
