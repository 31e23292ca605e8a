"""Benchmarks of the closed forms held and built per call, and against EAIK (the same process,
interleaved).

- ``rk.closed.ur(T, chain)`` (the layout read by the chain at its first call, the limits and
  arguments at each) against a held ``rk.closed.ClosedSolver(chain).solve(T)`` on the same UR5
  poses: the price of not holding a solver.
- ``rk.closed.ur(T, table)`` with a dict table (its chain built at each call) against the same.
Run with an older robokin (before ClosedSolver) it times its private ``_URSolver`` as the held one,
for the before / after figures of benchmarks/README.md.
- ``ClosedSolver.solve(T)`` (all solutions) against EAIK's ``IK(T)`` (pip's ``eaik``, the ``bench``
  extra; not needed otherwise) on the UR5 (robokin reading ur_description's URDF, EAIK the DH
  table: the same kinematics), the KUKA KR 16 (robokin reading ROS-Industrial's URDF, EAIK given
  its joint axes), the ABB IRB 120 and the PUMA 560 (their DH tables without theta offsets, as
  EAIK's DhRobot takes them), after checking that both return the same solutions on every pose; goal <= 0.5 x EAIK per call. The
  batch of 1e6 poses on every core (``solve_batch``) against EAIK's ``IK_batched`` with as many
  threads.
- The KUKA iiwa 14 with one joint held (``ClosedSolver(chain, locked={j: v})``, 7-vectors) against
  EAIK's ``DhRobot(..., fixed_axes=[(j, v)])``: for each joint, whether each finds a decomposition,
  and for those both solve, the same solutions on 200 poses and the time per call.
- The Panda with its elbow ``q[3]`` held (a spherical shoulder, axes 5, 6 meeting before axis 7:
  EAIK's SPHERICAL_SECOND_TWO_INTERSECTING) against EAIK given its joint axes (as the KR 16; the
  Panda's table is modified DH, which DhRobot does not take), the same way.
"""

from __future__ import annotations

import itertools
import math
import os
import sys

import numpy as np

import robokin as rk

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _timing import fmt, goal, once_interleaved, per_call_interleaved  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from kr16_urdf import KR16_URDF  # noqa: E402
from ur_urdf import UR5_URDF  # noqa: E402

P = np.pi
# (a, alpha, d) of the DH tables EAIK is given (robokin.robots' tables without their theta offsets).
IRB120 = ((0.0, 0.27, 0.07, 0.0, 0.0, 0.0), (-P / 2, 0.0, -P / 2, P / 2, -P / 2, 0.0), (0.29, 0.0, 0.0, 0.302, 0.0, 0.072))
PUMA560 = (rk.robots.PUMA560_A, rk.robots.PUMA560_ALPHA, rk.robots.PUMA560_D)
UR5 = ((0.0, -0.425, -0.39225, 0.0, 0.0, 0.0), (P / 2, 0.0, 0.0, P / 2, -P / 2, 0.0),
       (0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823))

UR5_TABLE = {"d1": 0.089159, "a2": -0.425, "a3": -0.39225, "d4": 0.10915, "d5": 0.09465, "d6": 0.0823}


def held_solver(chain):
    """The held solver of this robokin: ClosedSolver, or the private _URSolver before it."""
    if hasattr(rk.closed, "ClosedSolver"):
        return rk.closed.ClosedSolver(chain)
    return rk._core._URSolver(chain)


def per_call_figures(goals):
    ur5 = rk.robots.ur5()
    poses = list(ur5.fk(np.random.default_rng(0).uniform(-np.pi, np.pi, (200, 6))))
    solver = held_solver(ur5)
    ns = {"rk": rk, "ur5": ur5, "table": UR5_TABLE, "solver": solver, "frames": itertools.cycle(poses),
          "nxt": next}
    (held, _), (chain, _), (table, _) = per_call_interleaved(
        ["solver.solve(nxt(frames))", "rk.closed.ur(nxt(frames), ur5)", "rk.closed.ur(nxt(frames), table)"], ns)
    print(f"UR5, all solutions per call: held solver {fmt(held)}, closed.ur(T, chain) {fmt(chain)} "
          f"({chain / held:.2f} x), closed.ur(T, table) {fmt(table)} ({table / held:.2f} x)")
    goal(goals, "closed.ur(T, chain) per call / held ClosedSolver.solve", chain / held, "x", 1.5, "held solver")
    return goals


def same_solutions(ours, theirs):
    """Every exact EAIK solution is one of robokin's and the other way round (angles to 1e-6)."""
    q = np.asarray(theirs.Q)[~np.asarray(theirs.is_LS, bool)] if theirs.num_solutions() else np.zeros((0, ours.dof))
    gap = lambda a, b: np.abs(np.remainder(a[:, None, :] - b[None, :, :] + P, 2 * P) - P).max(axis=2)  # noqa: E731
    if len(q) != len(ours) or (len(q) and (gap(q, ours.q).min(axis=1).max() > 1e-6)):
        raise AssertionError(f"EAIK and robokin disagree: {len(q)} against {len(ours)} solutions")


def against_eaik(solver, bot, poses):
    """Checks that the two give the same solutions on every pose, then times one call of each on
    the poses in turn (interleaved): (robokin, EAIK) seconds per call."""
    for T in poses:
        same_solutions(solver.solve(T), bot.IK(T))
    ns = {"solver": solver, "bot": bot, "frames": itertools.cycle(poses), "nxt": next}
    ours, theirs = per_call_interleaved(["solver.solve(nxt(frames))", "bot.IK(nxt(frames))"], ns)
    return ours[0], theirs[0]


def eaik_of_geometry(chain, locked=None):
    """EAIK's robot of the chain's joint axes at q = 0 (a frame per joint, its z along the axis, and
    the tool frame): the same kinematics whatever describes the chain. (EAIK's own URDF reader,
    given the KR 16's file, returns solutions that miss the poses of its tool frame.) locked={j: v}
    holds joint j at v (EAIK's fixed_axes)."""
    from eaik.IK_Homogeneous import HomogeneousRobot

    frames = []
    for point, z in rk.plots.joint_axes(chain, np.zeros(chain.dof)):
        x = np.cross(z, (1.0, 0.0, 0.0) if abs(z[0]) < 0.9 else (0.0, 1.0, 0.0))
        F = np.eye(4)
        F[:3, 0], F[:3, 2], F[:3, 3] = x / np.linalg.norm(x), z, point
        F[:3, 1] = np.cross(F[:3, 2], F[:3, 0])
        frames.append(F)
    fixed = [(j, float(v)) for j, v in (locked or {}).items()]
    return HomogeneousRobot(np.array(frames + [chain.fk(np.zeros(chain.dof))]), fixed_axes=fixed)


def eaik_figures(goals):
    try:
        from eaik.IK_DH import DhRobot
    except ImportError:
        print("EAIK not installed (pip install eaik, or the bench extra): not measured")
        goal(goals, "closed.ClosedSolver.solve per call vs EAIK", math.nan, "x", 0.5, "EAIK: not installed")
        return goals
    kr16 = rk.Chain.from_urdf(KR16_URDF)
    arms = {"UR5 (URDF)": (rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), UR5),
            "KUKA KR 16 (URDF)": (kr16, eaik_of_geometry(kr16)),
            "IRB 120": (None, IRB120), "PUMA 560": (None, PUMA560)}
    rng = np.random.default_rng(1)
    for name, (chain, arm) in arms.items():
        if isinstance(arm, tuple):
            a, alpha, d = arm
            chain = chain or rk.Chain.from_dh([(a[i], alpha[i], d[i], 0.0, "R") for i in range(6)])
            bot = DhRobot(np.array(alpha, float), np.array(a, float), np.array(d, float))
        else:
            bot = arm
        solver = rk.closed.ClosedSolver(chain, None)
        ours, theirs = against_eaik(solver, bot, list(chain.fk(rng.uniform(-P, P, (200, 6)))))
        print(f"{name} ({bot.getKinematicFamily()}, {solver.family}): robokin {fmt(ours)}, EAIK "
              f"{fmt(theirs)}: {ours / theirs:.3f} x (the same solutions on 200 poses)")
        goal(goals, f"closed.ClosedSolver.solve per call vs EAIK, {name}", ours / theirs, "x", 0.5, "EAIK, same run")
    batch = chain.fk(rng.uniform(-P, P, (1_000_000, 6)))
    threads = os.cpu_count() or 1
    (ours, _), (theirs, _) = once_interleaved([lambda: solver.solve_batch(batch),
                                               lambda: bot.IK_batched(batch, num_worker_threads=threads)], repeat=3)
    print(f"1e6 poses ({name}), {threads} threads: robokin {ours:.2f} s, EAIK {theirs:.2f} s: {ours / theirs:.3f} x")
    goal(goals, "closed.ClosedSolver.solve_batch of 1e6 poses vs EAIK IK_batched", ours / theirs, "x", 1.0, "EAIK, same run")
    return goals


# The iiwa 14's standard DH table (robokin.robots.iiwa14: a = 0, no theta offsets).
IIWA14 = ((0.0,) * 7, (-P / 2, P / 2, P / 2, -P / 2, -P / 2, P / 2, 0.0), (0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.126))


def held_figures(goals):
    """The iiwa 14 with each joint held: robokin's family against EAIK's, then the time per call."""
    try:
        from eaik.IK_DH import DhRobot
    except ImportError:
        print("EAIK not installed: the held-joint comparison not measured")
        return goals
    a, alpha, d = (np.array(v, float) for v in IIWA14)
    iiwa = rk.robots.iiwa14()
    rng = np.random.default_rng(2)
    for j in range(7):
        Q = rng.uniform(-2.0, 2.0, (200, 7))
        Q[:, j] = 0.3
        bot = DhRobot(alpha, a, d, fixed_axes=[(j, 0.3)])
        fam = rk.closed.family(iiwa, locked={j: 0.3})
        line = f"iiwa 14, q[{j}] held at 0.3: robokin {fam.name!r}, EAIK {bot.getKinematicFamily()!r}"
        if not (fam.solvable and bot.hasKnownDecomposition()):
            print(line)
            continue
        solver = rk.closed.ClosedSolver(iiwa, None, locked={j: 0.3})
        ours, theirs = against_eaik(solver, bot, list(iiwa.fk(Q)))
        print(f"{line}: robokin {fmt(ours)}, EAIK {fmt(theirs)}: {ours / theirs:.3f} x "
              "(the same solutions on 200 poses)")
        goal(goals, f"ClosedSolver(locked=).solve per call vs EAIK fixed_axes, iiwa 14 q[{j}]", ours / theirs, "x", 0.5,
             "EAIK, same run")
    return goals


def panda_held_figures(goals):
    """The Panda with q[3] held: robokin's family against EAIK's, the same solutions, the time per call."""
    panda = rk.robots.panda()
    try:
        bot = eaik_of_geometry(panda, {3: -1.2})
    except ImportError:
        print("EAIK not installed: the Panda with q[3] held not measured")
        return goals
    Q = np.random.default_rng(3).uniform(*panda.limits, (200, 7))
    Q[:, 3] = -1.2
    solver = rk.closed.ClosedSolver(panda, None, locked={3: -1.2})
    ours, theirs = against_eaik(solver, bot, list(panda.fk(Q)))
    print(f"Panda, q[3] held at -1.2: robokin {solver.family!r}, EAIK {bot.getKinematicFamily()!r}: robokin "
          f"{fmt(ours)}, EAIK {fmt(theirs)}: {ours / theirs:.3f} x (the same solutions on 200 poses)")
    goal(goals, "ClosedSolver(locked=).solve per call vs EAIK fixed_axes, Panda q[3]", ours / theirs, "x", 0.5,
         "EAIK, same run")
    return goals


def main():
    goals = per_call_figures([])
    goals = eaik_figures(goals)
    goals = held_figures(goals)
    return panda_held_figures(goals)


if __name__ == "__main__":
    main()
