"""Serial-arm toolkit benchmarks: manipulability and trajectory evaluation.

Each figure is printed beside its reference measured in the same run, with the ratio
robokin / reference (lower is better):

- ``Chain.manipulability(q)`` (one call: Jacobian + JacobiSVD of its rows + the measure) against
  ``Chain.jacobian(q)`` (one call: the Jacobian alone) on the same chain: the goal is within 1.5x,
  i.e. the SVD and the measure cost at most half a Jacobian call on top of it. UR5 (6 joints) and
  a 7-joint arm.
- ``robokin.traj.quintic`` evaluated at 1e6 sample times (6 joints: positions, velocities and
  accelerations) against numpy's vectorised polynomial (Horner in s for the three shapes, then
  outer products with q1 - q0), single-threaded (ROBOKIN_NUM_THREADS=1) like numpy; the default
  thread count shown for information. Goal: no slower than numpy. Beside it, for information, the
  same call writing into the arrays of an earlier result (``out=``, single-threaded): the fresh
  pages of three new 48 MB arrays are what it saves.

Every reference is checked against robokin before it is timed. Times: best of several repeats
(median also shown) on a shared machine.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

import robokin as rk  # noqa: E402
from _timing import fmt, once, per_call, per_call_interleaved, ratio_line  # noqa: E402

SAMPLES = 1_000_000
goals: list[dict] = []


def line(*args, **kwargs) -> None:
    ratio_line(goals, *args, **kwargs)


def bench_manipulability(rng) -> None:
    print("manipulability, one call (q as a float64 array):")
    arms = {"UR5": rk.robots.ur5(), "7R arm": rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True)}
    for name, chain in arms.items():
        q = rng.uniform(-2, 2, chain.dof)
        s = np.linalg.svd(chain.jacobian(q), compute_uv=False)
        if not np.isclose(chain.manipulability(q), np.prod(s), rtol=1e-10):
            raise AssertionError(f"{name}: manipulability disagrees with numpy's SVD")
        ns = {"chain": chain, "q": q}
        measures = ("yoshikawa", "condition")
        ref, *ours = per_call_interleaved(["chain.jacobian(q)"] + [f"chain.manipulability(q, {m!r})" for m in measures],
                                          ns)
        for measure, t in zip(measures, ours):
            line(f"{name} manipulability {measure}", t, "jacobian", ref, 1.5 if measure == "yoshikawa" else None,
                 name=f"one Chain.manipulability call (Yoshikawa), {name}, vs one Chain.jacobian call")
        ns_np = {"np": np, "J": chain.jacobian(q)}
        svd = per_call("np.linalg.svd(J, compute_uv=False)", ns_np)
        print(f"    (for scale: numpy's SVD of that 6x{chain.dof} Jacobian alone takes {fmt(svd[0]).strip()})")


def numpy_quintic(q0, q1, t):
    """The quintic with zero end velocities and accelerations, vectorised in numpy."""
    T = t[-1] - t[0]
    s = (t - t[0]) / T
    d = q1 - q0
    s2 = s * s
    shape = s2 * s * (10.0 + s * (-15.0 + 6.0 * s))
    dshape = s2 * (30.0 + s * (-60.0 + 30.0 * s)) / T
    ddshape = s * (60.0 + s * (-180.0 + 120.0 * s)) / (T * T)
    return q0 + np.outer(shape, d), np.outer(dshape, d), np.outer(ddshape, d)


def bench_traj(rng) -> None:
    print(f"quintic trajectory, {SAMPLES:,} samples x 6 joints (q, qd, qdd):")
    q0, q1 = rng.uniform(-2, 2, 6), rng.uniform(-2, 2, 6)
    t = np.linspace(0.0, 3.0, SAMPLES)
    tr = rk.traj.quintic(q0, q1, t)
    ref = numpy_quintic(q0, q1, t)
    for ours, theirs, what in zip((tr.q, tr.qd, tr.qdd), ref, ("q", "qd", "qdd")):
        if not np.allclose(ours, theirs, rtol=0, atol=1e-12):
            raise AssertionError(f"quintic {what}: numpy's polynomial disagrees with robokin")
    ref_bits = [a.copy() for a in (tr.q, tr.qd, tr.qdd)]
    saved = os.environ.get("ROBOKIN_NUM_THREADS")
    try:
        os.environ["ROBOKIN_NUM_THREADS"] = "1"
        ours = once(lambda: rk.traj.quintic(q0, q1, t), repeat=7)
        theirs = once(lambda: numpy_quintic(q0, q1, t), repeat=7)
        line("quintic 1e6 samples, 1 thread", ours, "numpy", theirs, 1.0,
             name="rk.traj.quintic, 1e6 samples x 6 joints, 1 thread, vs numpy's vectorised polynomial")
        reused = rk.traj.quintic(q0, q1, t, out=tr)  # tr's arrays, their pages already touched
        if not all(np.array_equal(a, b) for a, b in zip((reused.q, reused.qd, reused.qdd), ref_bits)):
            raise AssertionError("quintic out=: the samples differ from a new trajectory's")
        ours_out = once(lambda: rk.traj.quintic(q0, q1, t, out=tr), repeat=7)
        line("quintic 1e6 samples out=, 1 thread", ours_out, "numpy", theirs, None)
        os.environ.pop("ROBOKIN_NUM_THREADS")
        ours_all = once(lambda: rk.traj.quintic(q0, q1, t), repeat=7)
        line(f"quintic 1e6 samples, {os.cpu_count()} threads", ours_all, "numpy", theirs, None)
    finally:
        if saved is None:
            os.environ.pop("ROBOKIN_NUM_THREADS", None)
        else:
            os.environ["ROBOKIN_NUM_THREADS"] = saved
    trap = once(lambda: rk.traj.trapezoidal(q0, q1, vmax=1.0, amax=2.0, dt=1e-5), repeat=3)
    k = len(rk.traj.trapezoidal(q0, q1, vmax=1.0, amax=2.0, dt=1e-5))
    print(f"  (for information: trapezoidal, {k:,} samples: {fmt(trap[0]).strip()})")


def main():
    goals.clear()
    rng = np.random.default_rng(13)
    print(f"robokin {rk.__version__}, numpy {np.__version__}, Python {sys.version.split()[0]}")
    bench_manipulability(rng)
    bench_traj(rng)
    return list(goals)


if __name__ == "__main__":
    results = main()
    sys.exit(0 if all(g["met"] for g in results) else 1)
