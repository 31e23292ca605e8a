"""Benchmarks of the UR closed form against numerical IK, its batch, and track_postures
against greedy tracking.

- ``rk.closed.ur`` per call (all 8 solutions) against one numerical solve, ``rk.IKSolver.solve`` (LM
  with restarts, one solution), the same process; goal <= 0.2 x. The numerical solve is timed on
  the UR5 with axes 2 and 3 a microradian from parallel (the same lengths and reach, no closed
  form), its own poses: on the UR5 itself IK's restarts start from the closed form's solutions, so
  that solve is partly the closed form it is compared with (its ratio is printed too, no goal).
- ``rk.closed.ur_batch`` on 1e6 poses, every core, against 1e6 single calls' time.
- ``rk.track_postures`` on a 1,000-waypoint line of the PUMA 560 against ``closed.puma560_path``
  (greedy nearest solution): time and reconfigurations.
"""

from __future__ import annotations

import itertools
import os
import sys
import time

import numpy as np

import robokin as rk
from robokin._ur_dh import ur_dh_rows

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _timing import goal, once, per_call_interleaved  # noqa: E402


def main():
    goals = []
    ur5 = rk.robots.ur5()
    rng = np.random.default_rng(0)
    Q = rng.uniform(-np.pi, np.pi, (200, 6))
    poses = ur5.fk(Q)
    # --- per call: closed form (8 solutions) vs numerical (1 solution, restarts) ---
    # The numerical solve on its own: the UR5's table (robots.ur5) with alpha 2 = 1e-6, axes 2 and 3
    # a microradian from parallel, which no closed form takes (checked); the unbent table is
    # checked against robots.ur5.
    rows = [list(r) for r in ur_dh_rows(0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823)]
    assert np.allclose(rk.Chain.from_dh(rows).fk(Q[:20]), ur5.fk(Q[:20]), rtol=0, atol=1e-15)
    rows[1][1] = 1e-6
    bent = rk.Chain.from_dh(rows, limits=ur5.limits)
    assert not rk.closed.family(bent).solvable
    bent_poses = bent.fk(Q)
    q0 = np.zeros(6)
    numerical = rk.IKSolver(bent, restarts=20, seed=0)
    helped = rk.IKSolver(ur5, restarts=20, seed=0)
    ok = sum(numerical.solve(T, q0).success for T in bent_poses)
    found = sum(len(rk.closed.ur(T, ur5)) for T in poses)
    # Each call timed the same way, over its poses in turn: the frames made once (a list of views,
    # cycled), so that the loop's own cost is a next() (~20 ns), not an index and a new numpy view
    # per call (~100 ns, a tenth of a closed-form call). The calls' repeats are taken in turn, so
    # that all see the same spells of the shared machine's load.
    ns = {"closed": rk.closed.ur, "numerical": numerical.solve, "helped": helped.solve, "ur5": ur5, "q0": q0,
          "closed_frames": itertools.cycle(list(poses)), "numerical_frames": itertools.cycle(list(bent_poses)),
          "helped_frames": itertools.cycle(list(poses))}
    (t_closed, _), (t_num, _), (t_helped, _) = per_call_interleaved(
        ["closed(next(closed_frames), ur5)", "numerical(next(numerical_frames), q0)",
         "helped(next(helped_frames), q0)"], ns, repeat=15, budget=0.1)
    ratio = t_closed / t_num
    print(f"UR5, {len(poses)} random poses: closed.ur {1e6 * t_closed:.2f} us/call ({found / len(poses):.2f} "
          f"solutions/pose); IKSolver(lm, restarts=20) on the bent UR5 {1e6 * t_num:.2f} us/call "
          f"({ok}/{len(poses)} solved, 1 solution): ratio {ratio:.4f}; IKSolver on the UR5 itself (restarts "
          f"from the closed form) {1e6 * t_helped:.2f} us/call: ratio {t_closed / t_helped:.4f}")
    goal(goals, f"rk.closed.ur (all 8 solutions), time per call, UR5, {len(poses)} poses, vs one numerical "
         "solve (IKSolver LM, restarts)", ratio, "x", 0.2,
         "rk.IKSolver.solve on the UR5 bent a microradian (no closed form), same run")
    # All solutions numerically: LM from 48 random starts per pose (as the completeness test), in
    # one batch on every core; distinct solutions found against the closed form's.
    S = 48
    starts = rng.uniform(-np.pi, np.pi, (len(poses) * S, 6))
    rep = np.repeat(poses, S, axis=0)
    t_all, _ = once(lambda: rk.ik_batch(ur5, rep, starts, max_iter=200), repeat=2)
    res = rk.ik_batch(ur5, rep, starts, max_iter=200)
    distinct = 0
    for i in range(len(poses)):
        sols = res.q[i * S:(i + 1) * S][res.success[i * S:(i + 1) * S]]
        kept = []
        for q in sols:
            if not kept or np.min(np.max(np.abs(np.remainder(np.array(kept) - q + np.pi, 2 * np.pi) - np.pi), axis=1)) > 1e-4:
                kept.append(q)
        distinct += len(kept)
    t_closed_batch, _ = once(lambda: rk.closed.ur_batch(poses, ur5), repeat=5)
    ratio_all = t_closed_batch / t_all
    print(f"all solutions: closed.ur_batch {1e6 * t_closed_batch / len(poses):.2f} us/pose ({found / len(poses):.2f} "
          f"solutions/pose) vs ik_batch from {S} starts {1e6 * t_all / len(poses):.0f} us/pose "
          f"({distinct / len(poses):.2f} distinct solutions/pose): ratio {ratio_all:.4f}; per solution, closed.ur "
          f"{1e6 * t_closed * len(poses) / found:.2f} us vs one numerical solve {1e6 * t_num:.2f} us")
    goal(goals, f"rk.closed.ur_batch, every solution of {len(poses)} UR5 poses, vs numerical ik_batch from "
         f"{S} starts per pose", ratio_all, "x", 0.2, "rk.ik_batch on every core, same poses, same run")
    # --- batch of 1e6 poses on every core ---
    n = 1_000_000
    Qb = rng.uniform(-np.pi, np.pi, (n, 6))
    big = ur5.fk(Qb)
    t_batch, _ = once(lambda: rk.closed.ur_batch(big, ur5), repeat=2)
    q, _, _ = rk.closed.ur_batch(big[:1000], ur5)
    per_pose = np.sum(~np.isnan(q[:, :, 0])) / 1000
    print(f"closed.ur_batch, {n} poses on {os.cpu_count()} cores: {t_batch:.3f} s ({1e9 * t_batch / n:.0f} ns/pose, "
          f"{per_pose:.2f} solutions/pose); {n} single calls would take ~{n * t_closed:.1f} s "
          f"(batch/single ratio {t_batch / (n * t_closed):.4f})")
    # --- track_postures vs greedy on a 1,000-waypoint line ---
    puma = rk.robots.puma560()
    from robokin.demo_postures import LINE_DIRECTION, LINE_LENGTH, LINE_Q0

    qs = np.array(LINE_Q0, dtype=float)
    T0 = puma.fk(qs)
    K = 1000
    line = np.repeat(T0[None], K, axis=0)
    direction = np.asarray(LINE_DIRECTION) / np.linalg.norm(LINE_DIRECTION)
    line[:, :3, 3] += np.linspace(0, LINE_LENGTH, K)[:, None] * direction[None, :]
    dt, vmax = 0.004, 2.0  # the demo's line and speed, 5 x more waypoints
    t_plan, _ = once(lambda: rk.track_postures(puma, line, dt, qdot_max=vmax, q0=qs), repeat=3)
    t_greedy, _ = once(lambda: rk.closed.puma560_path(line, qs), repeat=3)
    plan = rk.track_postures(puma, line, dt, qdot_max=vmax, q0=qs)
    qg, okg, _ = rk.closed.puma560_path(line, qs)
    rg = rk.count_reconfigurations(qg, dt, vmax, q0=qs, chain=puma)
    print(f"PUMA 560, {K}-waypoint line: track_postures {1e3 * t_plan:.1f} ms, {len(plan.reconfigurations)} "
          f"reconfiguration(s), motion {plan.motion:.3f} rad; greedy puma560_path {1e3 * t_greedy:.2f} ms, "
          f"{len(rg)} reconfiguration(s); time ratio {t_plan / t_greedy:.1f}x")
    t0 = time.perf_counter()
    ur_line = np.repeat(poses[0][None], K, axis=0)
    ur_line[:, 2, 3] += np.linspace(0, 0.2, K)
    up = rk.track_postures(ur5, ur_line, dt, qdot_max=vmax)
    print(f"UR5, {K}-waypoint line: track_postures {1e3 * (time.perf_counter() - t0):.1f} ms, "
          f"{len(up.reconfigurations)} reconfiguration(s), {int(up.success.sum())}/{K} reached")
    return goals


if __name__ == "__main__":
    for g in main():
        print(g)
