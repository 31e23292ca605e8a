"""3-RRR benchmarks: ik_batch against the same formula vectorised in numpy (same process),
fk_all per call, a 400 x 400 workspace map, and the avoidance numbers of the seed's paths.

Goals: ik_batch <= 0.2 x numpy (1e6 poses, one thread each: numpy's is single-threaded, robokin's
runs with ROBOKIN_NUM_THREADS=1 here); fk_all <= 10 us per call and the 400 x 400 map <= 50 ms
(absolute times: no other implementation of either to run beside them).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

import robokin as rk

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import NO_REFERENCE, goal  # noqa: E402


def best_time(fn, repeat: int = 5) -> float:
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def ik_numpy(robot: rk.RRR3, poses: np.ndarray, mode) -> np.ndarray:
    """DESIGN.md's formula, vectorised: alpha_i = atan2(B_i - O_i) - m_i acos(...)."""
    t = np.radians(-90.0 + 120.0 * np.arange(3))
    x, y, phi = poses[:, 0:1], poses[:, 1:2], poses[:, 2:3]
    bx = x + robot.platform_radius * np.cos(phi + t) - robot.base_radius * np.cos(t)
    by = y + robot.platform_radius * np.sin(phi + t) - robot.base_radius * np.sin(t)
    r2 = bx * bx + by * by
    r = np.sqrt(r2)
    c = (robot.l1**2 + r2 - robot.l2**2) / (2 * robot.l1 * r)
    with np.errstate(invalid="ignore"):
        return np.arctan2(by, bx) - np.asarray(mode) * np.arccos(c)


def main() -> list:
    goals: list[dict] = []
    robot = rk.RRR3()
    rng = np.random.default_rng(0)
    n = 1_000_000
    poses = np.column_stack((rng.uniform(-0.08, 0.08, (n, 2)), rng.uniform(-0.5, 0.5, n)))
    mode = (1, -1, 1)
    ours = robot.ik_batch(poses, mode)
    ref = ik_numpy(robot, poses, mode)
    ok = ~np.isnan(ours[:, 0])
    assert np.array_equal(ok, ~np.isnan(ref).any(axis=1))
    assert np.abs(np.angle(np.exp(1j * (ours[ok] - ref[ok])))).max() < 1e-9
    saved = os.environ.get("ROBOKIN_NUM_THREADS")
    os.environ["ROBOKIN_NUM_THREADS"] = "1"
    try:
        t_core = best_time(lambda: robot.ik_batch(poses, mode))
    finally:
        if saved is None:
            os.environ.pop("ROBOKIN_NUM_THREADS")
        else:
            os.environ["ROBOKIN_NUM_THREADS"] = saved
    t_numpy = best_time(lambda: ik_numpy(robot, poses, mode))
    t_all = best_time(lambda: robot.ik_batch(poses, mode))
    g = goal(goals, f"RRR3.ik_batch, {n:,} poses, 1 thread, vs the same formula vectorised in numpy",
             t_core / t_numpy, "x", 0.2, "numpy (DESIGN.md's formula), same run")
    print(f"ik_batch, {n:,} poses: core {t_core * 1e3:.1f} ms (1 thread; every core {t_all * 1e3:.1f} ms), numpy "
          f"{t_numpy * 1e3:.1f} ms, ratio {g['figure']:.3f} (goal <= 0.2: {'met' if g['met'] else 'MISSED'})")

    alphas = [robot.ik(p, (1, 1, 1)) for p in poses[ok][:2000:4]]
    count = 0

    def run_fk():
        nonlocal count
        count = sum(len(robot.fk_all(a)) for a in alphas)

    t_fk = best_time(run_fk) / len(alphas)
    g = goal(goals, f"RRR3.fk_all (every assembly mode), time per call from Python, {len(alphas)} actuations",
             t_fk * 1e6, "us", 10.0, NO_REFERENCE, note="best of 5 loops")
    print(f"fk_all: {t_fk * 1e6:.2f} us per call from Python ({count / len(alphas):.2f} assembly modes on average, "
          f"goal <= 10 us: {'met' if g['met'] else 'MISSED'})")

    t_ws = best_time(lambda: robot.workspace(phi=0.0, mode=(1, 1, 1), n=400), repeat=10)
    g = goal(goals, "RRR3.workspace, a 400 x 400 map at phi = 0, mode (1, 1, 1)", t_ws * 1e3, "ms", 50.0,
             NO_REFERENCE, note="best of 10, every core")
    print(f"workspace 400 x 400: {t_ws * 1e3:.1f} ms (goal <= 50 ms: {'met' if g['met'] else 'MISSED'})")

    for name, pts in [("circle r=0.1", rk.paths.circle(629, 0.1)), ("clover", rk.paths.clover(629))]:
        plain = robot.plan(pts, phi=0.0, mode=(1, 1, 1), avoid=False)
        t_plan = best_time(lambda: robot.plan(pts, phi=0.0, mode=(1, 1, 1)), repeat=3)
        avoid = robot.plan(pts, phi=0.0, mode=(1, 1, 1))
        d0, d1 = np.abs(plain.det_a_norm), np.abs(avoid.det_a_norm)
        print(f"{name}, {len(pts)} points, mode (1,1,1), phi = 0: min |det A| without avoidance "
              f"{d0.min() * robot.platform_radius:.2e} (det A / R_e {d0.min():.4f}), with avoidance "
              f"{d1.min() * robot.platform_radius:.2e} ({d1.min():.4f}); det A sign changes "
              f"{np.sum(np.diff(np.sign(plain.det_a_norm)) != 0)} -> {np.sum(np.diff(np.sign(avoid.det_a_norm)) != 0)}; "
              f"max |phi| {np.abs(avoid.poses[:, 2]).max():.3f} rad; plan {t_plan * 1e3:.0f} ms")
    return goals


if __name__ == "__main__":
    main()
