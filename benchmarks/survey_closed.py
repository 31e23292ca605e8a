"""Closed-form families of real URDFs: every serial chain of 6 or 7 revolute joints in the URDFs
shipped by ``example-robot-data`` and ``pybullet`` (``pybullet_data``), ``rk.closed.family`` beside
EAIK's verdict on the same geometry, and where both find a decomposition, their solutions compared
on random poses. A survey, not a timing: it prints a table and a summary, and exits 0 whatever it
finds (``--strict``: 1 when EAIK finds a decomposition robokin does not, or a comparison fails).

Its dependencies are the benchmarks' only (the ``bench`` extra of pyproject.toml)::

    .venv/bin/python -m pip install example-robot-data pybullet eaik
    .venv/bin/python benchmarks/survey_closed.py [--poses 200] [--seed 0] [--only SUBSTRING] [--strict]

**Which chains.** A URDF is read here with ``xml.etree`` (its joints' types, parents, children,
origins and axes), independently of robokin's reader. A chain starts at a *root-ish* link: the
URDF's root, or a link with two or more child joints (a torso where the arms part, a mobile base);
a branching link 6 or more revolute joints from the root is a hand, not root-ish (its fingers are
not surveyed). It follows child joints down: revolute and continuous joints (a continuous joint is
a revolute one without limits) count, fixed joints are passed through, any other joint
(prismatic, floating, planar) ends the descent; once past a branching link it takes no further
revolute joint (a hand's finger is not a joint of the arm). It ends at a link reached with exactly
6 or 7 revolute joints that is a leaf, a branching link, or named like a tool (``tool0``,
``flange``, ``tcp``, ``ee``, ``end_effector``, ``tool``); the 6-joint start of a 7-joint arm is
therefore not a chain of its own (a gripper's revolute joint after a 6-joint arm makes it a
7-joint chain: hold that joint). One chain per sequence of joints: its base is the deepest
root-ish link it starts from, its tip the first tool-named link (in the order above), else a leaf,
else the branching link.

**EAIK's verdict.** EAIK is given the same chain as the joint axes and points at the zero
configuration (its H / P description, with the tip's orientation), computed here from the URDF's
origins, not from robokin's chain; the FK of this reading and robokin's are compared on random
configurations first (a difference means the two readings of the URDF differ: reported, and the
chain is not compared). A 7-joint chain goes to EAIK with one joint held (``fixed_axes``), each
joint in turn; robokin is asked ``rk.closed.family(chain, locked={j: value})`` when ``family``
takes ``locked`` (otherwise that column says so). The held value is one of no special geometry,
38 % into the joint's range; the verdict at 0 (the middle of the range when 0 is outside it) is
shown beside it when it differs (a decomposition that exists only where two axes line up).

**The comparison**, where both find a decomposition (a 6-joint chain, or a 7-joint one with the
same joint held): ``--poses`` random configurations q within the joint limits (``[-pi, pi]``
where there are none; a held joint at q's value), their poses T by the chain's FK, and for each:
every robokin solution reaches T (position within 1e-9 x the arm's size, rotation entries within
1e-9), q is among them (1e-6, modulo 2 pi), and every exact EAIK solution (not its least-squares
ones) is one of robokin's and every robokin solution one of EAIK's (1e-6, modulo 2 pi); each
failed check is printed with the Jacobian's smallest singular value at q (how near a singularity
it is). A pose where robokin flags ``singular`` is counted apart (a continuum there has one
representative). Where only robokin finds one, its own checks run (reach, q among them); where
only EAIK does, its solutions are checked the same way, to tell a closed form from a verdict its
solver does not bear out.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import inspect
import math
import pathlib
import re
import sys
import time
import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np

import robokin as rk

MOVABLE = ("revolute", "continuous")
TOOL_NAMES = ("tool0", "flange", "tcp", "ee", "end_effector", "tool")
REACH_TOL = 1e-9  # position relative to the arm's size, rotation entries absolute
SAME_TOL = 1e-6  # joint angles, modulo 2 pi


# --- the URDFs and their chains, read with xml.etree --------------------------------------------


@dataclass
class Joint:
    name: str
    type: str
    parent: str
    child: str
    origin: np.ndarray  # 4x4, the child's frame in the parent's at q = 0
    axis: np.ndarray  # unit, in the joint's frame


@dataclass
class Tree:
    joints: dict  # name -> Joint
    children: dict  # link -> [Joint]
    parent_joint: dict  # link -> Joint
    roots: list


def urdf_files():
    """(package, path) of every URDF the two packages ship; a missing package is named and skipped."""
    found = []
    try:
        dist = importlib.metadata.distribution("example-robot-data")
        robots = pathlib.Path(dist.locate_file("cmeel.prefix/share/example-robot-data/robots"))
        found += [("example-robot-data", p) for p in sorted(robots.rglob("*.urdf"))]
    except importlib.metadata.PackageNotFoundError:
        print("example-robot-data not installed: its URDFs are not surveyed")
    try:
        import pybullet_data

        data = pathlib.Path(pybullet_data.getDataPath())
        found += [("pybullet_data", p) for p in sorted(data.rglob("*.urdf"))]
    except ImportError:
        print("pybullet not installed: pybullet_data's URDFs are not surveyed")
    return found


def rpy_matrix(r, p, y):
    """URDF's fixed-axis roll, pitch, yaw: Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def numbers(element, attribute, default):
    """The first len(default) numbers of an attribute (commas read as spaces, as some files write them)."""
    text = element.get(attribute) if element is not None else None
    if not text:
        return np.array(default, float)
    return np.array([float(v) for v in re.split(r"[\s,]+", text.strip())[:len(default)]])


def read_tree(path):
    """The URDF's joints and their tree (URDF's defaults: origin identity, axis (1, 0, 0))."""
    robot = ET.fromstring(path.read_text(encoding="utf-8").lstrip())  # some files start with a blank line
    joints, children, parent_joint = {}, {}, {}
    links = [link.get("name") for link in robot.findall("link")]
    for j in robot.findall("joint"):
        origin = np.eye(4)
        o = j.find("origin")
        origin[:3, :3] = rpy_matrix(*numbers(o, "rpy", (0, 0, 0)))
        origin[:3, 3] = numbers(o, "xyz", (0, 0, 0))
        axis = numbers(j.find("axis"), "xyz", (1, 0, 0))
        joint = Joint(j.get("name"), j.get("type"), j.find("parent").get("link"), j.find("child").get("link"),
                      origin, axis / (np.linalg.norm(axis) or 1.0))
        joints[joint.name] = joint
        children.setdefault(joint.parent, []).append(joint)
        parent_joint[joint.child] = joint
    return Tree(joints, children, parent_joint, [link for link in links if link not in parent_joint])


def tool_rank(link):
    """0, 1, ... for the tool names in TOOL_NAMES' order (a name ending in one too), None otherwise."""
    name = link.lower()
    for rank, tool in enumerate(TOOL_NAMES):
        if name == tool or name.endswith("_" + tool) or name.endswith("/" + tool):
            return rank
    return None


def serial_chains(tree):
    """[(base, tip, joint names)] of the 6- and 7-revolute chains (the module docstring's rules)."""
    branching = {link for link, js in tree.children.items() if len(js) >= 2}
    depth, turns, order = {}, {}, list(tree.roots)  # links and revolute joints from the root
    for link in order:
        depth.setdefault(link, 0)
        turns.setdefault(link, 0)
        for j in tree.children.get(link, []):
            if j.child not in depth:
                depth[j.child] = depth[link] + 1
                turns[j.child] = turns[link] + (j.type in MOVABLE)
                order.append(j.child)
    chains = {}  # joint names -> (base, {tip: kind})
    starts = set(tree.roots) | {link for link in branching if turns.get(link, 0) < 6}
    for start in sorted(starts, key=lambda s: depth.get(s, 0)):
        stack = [(start, (), False)]
        while stack:
            link, moving, past_branch = stack.pop()
            kind = _end_kind(tree, link, branching)
            if len(moving) in (6, 7) and kind is not None:
                base, tips = chains.setdefault(moving, (start, {}))
                if depth.get(start, 0) > depth.get(base, 0):
                    chains[moving] = base, tips = start, {}
                if base == start:
                    tips[link] = kind
            past = past_branch or (bool(moving) and link in branching)
            for j in tree.children.get(link, []):
                if j.type in MOVABLE and not past and len(moving) < 7:
                    stack.append((j.child, moving + (j.name,), past))
                elif j.type == "fixed":
                    stack.append((j.child, moving, past))
    return [(base, min(tips, key=lambda t: (tips[t], t)), names) for names, (base, tips) in chains.items()]


def _end_kind(tree, link, branching):
    """How well ``link`` ends a chain: (0, rank) tool-named, (1,) leaf, (2,) branching; None: not an end."""
    rank = tool_rank(link)
    if rank is not None:
        return (0, rank)
    if not tree.children.get(link):
        return (1,)
    return (2,) if link in branching else None


def zero_geometry(tree, base, tip):
    """Joint axes (n, 3), joint points (n, 3) and the tip's frame (4, 4) at q = 0, in the base's
    frame, from the URDF's origins along the path from base to tip (fixed joints included)."""
    path, link = [], tip
    while link != base:
        j = tree.parent_joint[link]
        path.append(j)
        link = j.parent
    T, axes, points = np.eye(4), [], []
    for j in reversed(path):
        T = T @ j.origin
        if j.type in MOVABLE:
            axes.append(T[:3, :3] @ j.axis)
            points.append(T[:3, 3].copy())
    return np.array(axes), np.array(points), T


# --- EAIK's side ------------------------------------------------------------------------------------


def eaik_robot(geometry, held=None, value=0.0):
    """EAIK's robot of the geometry (H / P: P[0] from the base to joint 1's point, P[i] from joint
    i's point to joint i + 1's, P[n] to the tip; the tip's orientation at q = 0), joint ``held``
    (0-based) held at ``value``; (robot, "") or (None, EAIK's error)."""
    from eaik.pybindings import EAIK

    axes, points, tip = geometry
    P = np.diff(np.vstack([np.zeros(3), points, tip[:3, 3]]), axis=0)
    fixed = [] if held is None else [(held, float(value))]
    try:
        return EAIK.Robot(np.ascontiguousarray(axes.T), np.ascontiguousarray(P.T), tip[:3, :3], fixed, True), ""
    except Exception as e:  # noqa: BLE001 - EAIK refuses some geometries with a C++ exception: its verdict
        return None, f"EAIK error: {e}"


def eaik_family(geometry, held=None, value=0.0):
    """(EAIK has a decomposition, its family string or error)."""
    robot, error = eaik_robot(geometry, held, value)
    if robot is None:
        return False, error
    return bool(robot.has_known_decomposition()), robot.get_kinematic_family()


def eaik_solutions(robot, T):
    """EAIK's solutions of T: (exact (k, n), least-squares (m, n)); empty when it raises."""
    try:
        sol = robot.calculate_IK(T)
    except Exception:  # noqa: BLE001 - counted as no solution
        return np.zeros((0, 0)), np.zeros((0, 0))
    if not sol.num_solutions():
        return np.zeros((0, 0)), np.zeros((0, 0))
    Q, ls = np.atleast_2d(np.asarray(sol.Q, float)), np.asarray(sol.is_LS, bool)
    return Q[~ls], Q[ls]


def poe_fk(geometry, q):
    """The tip's frame at q from the axes and points alone (a rotation about each axis through its
    point, Rodrigues), for checking that robokin and this reading agree."""
    axes, points, tip = geometry
    T = np.eye(4)
    for h, p, angle in zip(axes, points, q):
        K = np.array([[0, -h[2], h[1]], [h[2], 0, -h[0]], [-h[1], h[0], 0]])
        R = np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K
        A = np.eye(4)
        A[:3, :3], A[:3, 3] = R, p - R @ p
        T = T @ A
    return T @ tip


# --- robokin's side -------------------------------------------------------------------------------


def takes_locked():
    """Whether this robokin's closed.family takes ``locked`` (a 7-joint arm with one joint held)."""
    try:
        return "locked" in inspect.signature(rk.closed.family).parameters
    except (TypeError, ValueError):
        return False


def robokin_family(chain, held=None, value=0.0):
    """(robokin has a closed form, its family name or why not)."""
    try:
        f = rk.closed.family(chain) if held is None else rk.closed.family(chain, locked={held: value})
    except (TypeError, ValueError) as e:
        return False, f"error: {e}"
    return f.solvable, f.name if f.solvable else f.reason


def robokin_solutions(chain, T, held=None, value=0.0, solver=None):
    """robokin's solutions of T (every one, no limits) and the singular flags."""
    if held is None:
        s = solver.solve(T)
    else:
        s = rk.closed.solve(T, chain, limits=None, locked={held: value})
    return np.asarray(s.q, float).reshape(-1, chain.dof), np.asarray(s.singular, bool)




# --- the comparison on random poses ---------------------------------------------------------------


@dataclass
class Comparison:
    poses: int = 0
    solutions: int = 0
    eaik_exact: int = 0
    singular: int = 0
    worst_reach: float = 0.0
    failures: dict = field(default_factory=dict)  # kind -> poses where it happened
    examples: list = field(default_factory=list)

    def fail(self, kind, detail):
        self.failures[kind] = self.failures.get(kind, 0) + 1
        if len(self.examples) < 4:
            self.examples.append(f"{kind}: {detail}")


def angle_gap(A, B):
    """(len(A), len(B)): the largest joint difference of each pair, modulo 2 pi."""
    if not len(A) or not len(B):
        return np.full((len(A), len(B)), np.inf)
    A, B = np.reshape(A, (len(A), -1)), np.reshape(B, (len(B), -1))
    d = np.remainder(A[:, None, :] - B[None, :, :] + np.pi, 2 * np.pi) - np.pi
    return np.abs(d).max(axis=2)


def reach_error(chain, Q, T, size):
    """Per row of Q: the larger of the position error / size and the largest rotation-entry error."""
    if not len(Q):
        return np.zeros(0)
    F = chain.fk(Q).reshape(-1, 4, 4)
    return np.maximum(np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1) / size,
                      np.abs(F[:, :3, :3] - T[:3, :3]).max(axis=(1, 2)))


def text(q):
    return "[" + ", ".join(f"{v:.6f}" for v in q) + "]"


def sigma_min(chain, q, held):
    """The smallest singular value of the Jacobian of the joints not held, at q (how near q is to
    a singularity: solutions there are ill-conditioned, and two solvers may differ by more than 1e-6)."""
    J = np.delete(chain.jacobian(q, task="pose"), [] if held is None else [held], axis=1)
    return np.linalg.svd(J, compute_uv=False).min()


def compare_pose(c, chain, T, q, ours, singular, eaik, size, held=None):
    """One pose's checks (the module docstring's), failures counted by kind into c; ``eaik`` None:
    robokin's alone (reach and q)."""
    at = " (singular pose)" if singular.any() else ""
    failed = sum(c.failures.values())
    exact, ls = eaik if eaik is not None else (np.zeros((0, 0)), np.zeros((0, 0)))
    c.poses, c.solutions, c.eaik_exact = c.poses + 1, c.solutions + len(ours), c.eaik_exact + len(exact)
    c.singular += bool(at)
    reach = reach_error(chain, ours, T, size)
    c.worst_reach = max(c.worst_reach, reach.max(initial=0.0))
    if reach.max(initial=0.0) > REACH_TOL:
        c.fail("a robokin solution off the pose" + at, f"{reach.max():.1e} for q = {text(q)}")
    if not angle_gap(ours, [q]).min(initial=np.inf) <= SAME_TOL:
        c.fail("q not among robokin's" + at, f"q = {text(q)}, {len(ours)} solutions")
    if eaik is not None:
        compare_sets(c, chain, T, q, ours, exact, ls, size, at)
    if sum(c.failures.values()) > failed and len(c.examples) < 4:
        c.examples.append(f"   (at that q the Jacobian's smallest singular value is {sigma_min(chain, q, held):.1e})")


def compare_sets(c, chain, T, q, ours, exact, ls, size, at):
    """Every exact EAIK solution among robokin's and every robokin solution among EAIK's (one
    failure per kind and pose, however many solutions)."""
    kinds = {}
    for e in exact[angle_gap(exact, ours).min(axis=1, initial=np.inf) > SAME_TOL]:
        off = reach_error(chain, [e], T, size)[0] > 1e-6
        kinds.setdefault("an EAIK 'exact' solution off the pose" if off else "an EAIK solution robokin lacks", []).append(e)
    for s in ours[angle_gap(ours, exact).min(axis=1, initial=np.inf) > SAME_TOL]:
        least = angle_gap([s], ls).min(initial=np.inf) <= SAME_TOL
        kinds.setdefault("a robokin solution EAIK has as least-squares only" if least else
                         "a robokin solution EAIK lacks", []).append(s)
    for kind, rows in kinds.items():
        c.fail(kind + at, f"{len(rows)} such, e.g. {text(rows[0])} for q = {text(q)}")


def sample_bounds(chain):
    lo, hi = (np.array(a, float) for a in chain.limits)
    lo[~np.isfinite(lo)], hi[~np.isfinite(hi)] = -np.pi, np.pi
    return lo, hi


def arm_size(geometry):
    """The sum of the distances from the base to joint 1, between joints, and to the tip."""
    axes, points, tip = geometry
    return float(np.linalg.norm(np.diff(np.vstack([np.zeros(3), points, tip[:3, 3]]), axis=0), axis=1).sum()) or 1.0


def compare(chain, geometry, held, poses, rng, against_eaik=True):
    """robokin's and EAIK's solutions on random poses of the chain (joint ``held`` held at q's
    value); robokin's alone (reach and q) when not ``against_eaik``."""
    lo, hi = sample_bounds(chain)
    size = arm_size(geometry)
    solver = rk.closed.ClosedSolver(chain, None) if held is None else None
    robot = eaik_robot(geometry)[0] if held is None and against_eaik else None
    c = Comparison()
    for _ in range(poses):
        q = rng.uniform(lo, hi)
        value = float(q[held]) if held is not None else 0.0
        T = chain.fk(q)
        try:
            ours, singular = robokin_solutions(chain, T, held, value, solver)
        except ValueError as e:  # a held value where the decomposition does not hold
            c.fail("robokin refuses the held value", f"{cut(str(e), 120)} at q = {text(q)}")
            continue
        theirs = None
        if against_eaik:
            theirs = eaik_solutions(robot if held is None else eaik_robot(geometry, held, value)[0], T)
        compare_pose(c, chain, T, q, ours, singular, theirs, size, held)
    return c


def eaik_alone(chain, geometry, held, poses, rng):
    """Where robokin has no closed form: whether EAIK's exact solutions reach the pose and hold q
    (is its decomposition a closed form for this chain?): (poses, poses with q, worst reach)."""
    lo, hi = sample_bounds(chain)
    size, found, worst = arm_size(geometry), 0, 0.0
    robot = eaik_robot(geometry)[0] if held is None else None
    for _ in range(poses):
        q = rng.uniform(lo, hi)
        T = chain.fk(q)
        exact, _ = eaik_solutions(robot if held is None else eaik_robot(geometry, held, float(q[held]))[0], T)
        found += bool(angle_gap(exact, [q]).min(initial=np.inf) <= SAME_TOL)
        worst = max(worst, reach_error(chain, exact, T, size).max(initial=0.0))
    return poses, found, worst


# --- the survey -----------------------------------------------------------------------------------


@dataclass
class Row:
    urdf: str
    base: str
    tip: str
    dof: int
    held: str  # "-", or "j4" (1-based) for a 7-joint chain with joint 4 held
    robokin: tuple  # (has a closed form, family or reason)
    eaik: tuple
    comparison: Comparison = None
    eaik_alone: tuple = None  # (poses, poses where EAIK's solutions hold q, worst reach) where robokin has none
    note: str = ""

    @property
    def agreement(self):
        ours, theirs = self.robokin[0], self.eaik[0]
        return "both" if ours and theirs else "neither" if not (ours or theirs) else "robokin only" if ours else "EAIK only"


def load_chain(path, base, tip):
    """robokin's chain (its URDF warnings joined), or (None, why)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            chain = rk.Chain.from_urdf(path, base, tip)
        except (ValueError, TypeError) as e:
            return None, f"robokin cannot read it: {e}"
    return chain, "; ".join(str(w.message) for w in caught)


def reading_gap(chain, geometry, rng):
    """The largest difference of robokin's FK and this reading's on 5 random configurations."""
    lo, hi = sample_bounds(chain)
    return max(np.abs(chain.fk(q) - poe_fk(geometry, q)).max() for q in rng.uniform(lo, hi, (5, chain.dof)))


def check(row, chain, geometry, held, same, args, rng):
    """The random-pose checks the row's verdicts call for (none when the two readings differ)."""
    if same and row.agreement in ("both", "robokin only"):
        row.comparison = compare(chain, geometry, held, args.poses, rng, row.agreement == "both")
    elif same and row.agreement == "EAIK only":
        row.eaik_alone = eaik_alone(chain, geometry, held, args.poses, rng)


def survey_chain(name, tree, base, tip, names, path, args, rng):
    """The rows of one chain: the chain itself, and for a 7-joint chain each held joint where
    robokin or EAIK finds a decomposition."""
    chain, note = load_chain(path, base, tip)
    dof = len(names)
    geometry = zero_geometry(tree, base, tip)
    if chain is None:
        theirs = eaik_family(geometry) if dof == 6 else (False, "-")
        return [Row(name, base, tip, dof, "-", (False, note), theirs, note=note)]
    if tuple(chain.joint_names) != tuple(names):
        note = f"robokin reads the joints {chain.joint_names}; " + note
    gap = reading_gap(chain, geometry, rng)
    same = gap <= 1e-9 * arm_size(geometry)
    if not same:
        note = f"robokin's FK and this reading differ by {gap:.1e}; " + note
    if dof == 6:
        row = Row(name, base, tip, dof, "-", robokin_family(chain), eaik_family(geometry), note=note)
        check(row, chain, geometry, None, same, args, rng)
        return [row]
    rows = [Row(name, base, tip, dof, "-", robokin_family(chain), (False, "7 joints: one held, below"), note=note)]
    for j in range(7):
        values = held_values(chain, j)
        ours = at_values(lambda v: robokin_family(chain, j, v), values) if args.locked else (
            False, "n/a: no closed.family(locked=)")
        row = Row(name, base, tip, dof, f"j{j + 1}", ours, at_values(lambda v: eaik_family(geometry, j, v), values))
        check(row, chain, geometry, j, same, args, rng)
        if ours[0] or row.eaik[0]:
            rows.append(row)
    return rows


def held_values(chain, j):
    """A value of no special geometry for joint j (38 % into its range: the verdict), and 0 (the
    middle of the range when 0 is outside it)."""
    lo, hi = sample_bounds(chain)
    zero = 0.0 if lo[j] <= 0.0 <= hi[j] else 0.5 * (lo[j] + hi[j])
    return lo[j] + 0.382 * (hi[j] - lo[j]), zero


def at_values(verdict, values):
    """The verdict at the first value, and the one at the second beside it when they differ (a
    decomposition that exists only at one value of the held joint, such as two axes lining up)."""
    generic, special = verdict(values[0]), verdict(values[1])
    if special == generic:
        return generic
    return generic[0], f"{generic[1]} (at {values[1]:.3g}: {special[1]})"


def survey(args):
    rows, unread = [], []
    rng = np.random.default_rng(args.seed)
    for package, path in urdf_files():
        name = f"{package}/{path.name}"
        if args.only and args.only not in str(path):
            continue
        try:
            tree = read_tree(path)
        except (ET.ParseError, ValueError, AttributeError) as e:
            unread.append(f"{name}: {e}")
            continue
        for base, tip, names in sorted(serial_chains(tree), key=lambda c: (len(c[2]), c[1])):
            rows += survey_chain(name, tree, base, tip, names, path, args, rng)
    return rows, unread


# --- the report -----------------------------------------------------------------------------------


def cut(s, width):
    return s if len(s) <= width else s[:width - 3] + "..."


def mismatches(row):
    if row.comparison is None:
        return "-" if row.agreement != "both" else "not compared"
    c = row.comparison
    alone = "" if row.agreement == "both" else " (robokin alone)"
    return f"{sum(c.failures.values())} in {c.poses} poses{alone}"


def print_table(rows):
    head = ("URDF", "base", "tip", "dof", "held", "robokin family", "EAIK family", "agreement", "mismatches")
    width = (46, 18, 26, 3, 4, 44, 40, 12, 18)
    print("  ".join(h.ljust(w) for h, w in zip(head, width)))
    for r in rows:
        cells = (r.urdf, r.base, r.tip, str(r.dof), r.held, r.robokin[1], r.eaik[1], r.agreement, mismatches(r))
        print("  ".join(cut(c, w).ljust(w) for c, w in zip(cells, width)).rstrip())


def print_details(rows):
    compared = [r for r in rows if r.comparison is not None]
    print(f"\nCompared on random poses: {len(compared)} chains (held joints counted apart)")
    for r in compared:
        c = r.comparison
        print(f"  {r.urdf} {r.base} -> {r.tip} {r.held}: {c.poses} poses, {c.solutions} robokin solutions, "
              f"{c.eaik_exact} EAIK exact ones, {c.singular} singular poses, worst reach {c.worst_reach:.1e}")
        for kind, n in sorted(c.failures.items()):
            print(f"    {n} poses: {kind}")
        for e in c.examples:
            print(f"      e.g. {e}")
    alone = [r for r in rows if r.eaik_alone is not None]
    if alone:
        print("\nEAIK alone, where robokin has no closed form (its exact solutions on random poses):")
    for r in alone:
        poses, found, worst = r.eaik_alone
        print(f"  {r.urdf} {r.base} -> {r.tip} {r.held}: {r.eaik[1]}: q among them on {found} of {poses} poses, "
              f"worst reach {worst:.1e}")
    notes = [r for r in rows if r.note]
    if notes:
        print("\nNotes on reading:")
        for r in notes:
            print(f"  {r.urdf} {r.base} -> {r.tip}: {r.note}")


def print_summary(rows, unread, args):
    print(f"\nURDFs with a chain surveyed: {len({r.urdf for r in rows})}; unreadable here ({len(unread)}):")
    for u in unread:
        print(f"  {cut(u, 150)}")
    for dof, label in ((6, "6-joint chains"), (7, "7-joint chains, one joint held")):
        part = [r for r in rows if r.dof == dof and (dof == 6 or r.held != "-")]
        count = {k: sum(r.agreement == k for r in part) for k in ("both", "EAIK only", "robokin only", "neither")}
        chains = len([r for r in rows if r.dof == dof and r.held == "-"])
        print(f"{label}: {chains} chains; " + ", ".join(f"{k} {v}" for k, v in count.items()) +
              ("" if dof == 6 else " (held joints where either finds one; 'neither' not listed)"))
    if not args.locked:
        print("This robokin's closed.family takes no `locked`: the held-joint column is EAIK's alone.")
    compared = [r.comparison for r in rows if r.comparison is not None]
    bad = sum(sum(c.failures.values()) for c in compared)
    print(f"Comparisons: {len(compared)} chains x {args.poses} poses, {sum(c.solutions for c in compared)} robokin "
          f"solutions, worst reach {max((c.worst_reach for c in compared), default=0):.1e}, {bad} failed checks")
    gaps = [r for r in rows if r.agreement == "EAIK only" and (r.dof == 6 or args.locked)]
    print(f"EAIK finds a decomposition and robokin does not: {len(gaps)}")
    for r in gaps:
        solved = "" if r.eaik_alone is None else f" (EAIK's solutions hold q on {r.eaik_alone[1]} of {r.eaik_alone[0]} poses)"
        print(f"  {r.urdf} {r.base} -> {r.tip} {r.held}: EAIK {r.eaik[1]}{solved}; robokin: {r.robokin[1]}")
    return len(gaps) + bad


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--poses", type=int, default=200, help="random poses per chain where both have a closed form")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--only", default="", help="only the URDFs whose path contains this")
    parser.add_argument("--strict", action="store_true", help="exit 1 on a gap or a failed check")
    args = parser.parse_args(argv)
    try:
        import eaik  # noqa: F401
    except ImportError:
        print("EAIK is not installed: pip install eaik (the bench extra)")
        return 1
    args.locked = takes_locked()
    start = time.perf_counter()
    rows, unread = survey(args)
    print_table(rows)
    print_details(rows)
    problems = print_summary(rows, unread, args)
    print(f"({time.perf_counter() - start:.0f} s, robokin {rk.__version__}, seed {args.seed})")
    return 1 if (args.strict and problems) else 0


if __name__ == "__main__":
    sys.exit(main())
