"""Benchmarks of the closed forms held and built per call (the same process, interleaved).

- ``rk.closed.ur(T, chain)`` (the arm read off the chain at each call) against a held
  ``rk.closed.ClosedSolver(chain).solve(T)`` on the same UR5 poses: the price of not holding a solver.
- ``rk.closed.ur(T, table)`` with a dict table (its chain looked up by value) against the same.
Run with an older robokin (before ClosedSolver) it times its private ``_URSolver`` as the held one,
for the before / after figures of benchmarks/README.md.
"""

from __future__ import annotations

import itertools
import os
import sys

import numpy as np

import robokin as rk

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _timing import fmt, goal, per_call_interleaved  # noqa: E402

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


def main():
    goals = per_call_figures([])
    return goals


if __name__ == "__main__":
    main()
