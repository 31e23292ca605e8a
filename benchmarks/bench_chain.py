"""Serial-chain benchmarks: single fk / jacobian latency, batch FK (frames and positions), a Reach path.

Every figure is printed with its reference, measured in the same run, and the ratio
robokin / reference (lower is better). References:

- PyKDL (Debian's python3-pykdl) for single fk / jacobian: it is built for /usr/bin/python3, so it
  runs in a subprocess (benchmarks/_pykdl_worker.py) with the same timing code; its FK includes the
  list -> JntArray conversion, as a PyKDL user writes it.
- a numpy closed form for single fk / jacobian (RPR: the RPR study's eqs. 1 and 9; UR5: the product of
  its DH matrices), and the numpy vectorised closed form of the RPR for the batch FK;
- Pinocchio (``pip install pin``) for single fk / jacobian: the UR5 (and the RPR) built as a
  pinocchio Model with the same joint placements; its fastest natural FK call with a numpy 4x4 out;
- the RPR study's Algorithm 1 written literally in plain numpy, one Reach per path point.

Every reference is checked against robokin before it is timed. Times: best of several repeats
(median also shown) on a shared machine; batch FK single-threaded (ROBOKIN_NUM_THREADS=1) like
numpy, with the default thread count shown for information.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

import robokin as rk  # noqa: E402
from _timing import fmt, goal, once, once_interleaved, per_call, ratio_line  # noqa: E402

L1, L3 = rk.robots.RPR_L1, rk.robots.RPR_L3
LOWER, UPPER = rk.robots.RPR_LIMITS
UR5_DH = [  # (a, alpha, d, theta), as robokin.robots.ur5()
    (0.0, math.pi / 2, 0.089159, 0.0),
    (-0.425, 0.0, 0.0, 0.0),
    (-0.39225, 0.0, 0.0, 0.0),
    (0.0, math.pi / 2, 0.10915, 0.0),
    (0.0, -math.pi / 2, 0.09465, 0.0),
    (0.0, 0.0, 0.0823, 0.0),
]
BATCH = 1_000_000
PATH_POINTS = 10_000
SINGLE_FK = "one fk call from Python, UR5 (6 joints), 4x4 out, vs Pinocchio's fastest FK call"
SINGLE_JAC = "one jacobian call from Python, UR5, 6x6 out, vs Pinocchio's computeFrameJacobian"

goals: list[dict] = []


def line(*args, **kwargs) -> None:
    ratio_line(goals, *args, **kwargs)


def check(name: str, ours, ref, atol: float = 1e-12) -> None:
    ours, ref = np.asarray(ours, float), np.asarray(ref, float)
    if ours.shape != ref.shape or not np.allclose(ours, ref, rtol=0, atol=atol):
        err = np.max(np.abs(ours - ref)) if ours.shape == ref.shape else f"shapes {ours.shape} {ref.shape}"
        raise AssertionError(f"{name}: reference disagrees with robokin ({err})")


# --------------------------------------------------------------------------- numpy references
def dh_matrix(a, alpha, d, theta):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1.0]])


def rpr_fk_np(q):
    """Seed 000, eq. (1), as the 4x4 tool frame (rotation t1 + t3 about z)."""
    t1, t2, t3 = q
    c1, s1, c13, s13 = np.cos(t1), np.sin(t1), np.cos(t1 + t3), np.sin(t1 + t3)
    return np.array([[c13, -s13, 0.0, (L1 + t2) * c1 + L3 * c13],
                     [s13, c13, 0.0, (L1 + t2) * s1 + L3 * s13],
                     [0.0, 0.0, 1.0, 0.0],
                     [0.0, 0.0, 0.0, 1.0]])


def rpr_jacobian_np(q):
    """Seed 000, eq. (9), as the 6x3 geometric Jacobian (planar: rows vx, vy and wz)."""
    t1, t2, t3 = q
    s1, c1, s13, c13 = np.sin(t1), np.cos(t1), np.sin(t1 + t3), np.cos(t1 + t3)
    J = np.zeros((6, 3))
    J[0] = (-(L1 + t2) * s1 - L3 * s13, c1, -L3 * s13)
    J[1] = ((L1 + t2) * c1 + L3 * c13, s1, L3 * c13)
    J[5] = (1.0, 0.0, 1.0)
    return J


def rpr_fk_batch_np(Q):
    """The vectorised closed form of eq. (1): (N, 3) -> (N, 4, 4)."""
    t1, t2, t3 = Q[:, 0], Q[:, 1], Q[:, 2]
    c1, s1 = np.cos(t1), np.sin(t1)
    t13 = t1 + t3
    c13, s13 = np.cos(t13), np.sin(t13)
    r = L1 + t2
    out = np.zeros((len(Q), 4, 4))
    out[:, 0, 0] = c13
    out[:, 0, 1] = -s13
    out[:, 1, 0] = s13
    out[:, 1, 1] = c13
    out[:, 2, 2] = 1.0
    out[:, 3, 3] = 1.0
    out[:, 0, 3] = r * c1 + L3 * c13
    out[:, 1, 3] = r * s1 + L3 * s13
    return out


def rpr_position_batch_np(Q):
    """The tool points alone, eq. (1) vectorised: (N, 3) -> (N, 3)."""
    t1, t2, t13 = Q[:, 0], Q[:, 1], Q[:, 0] + Q[:, 2]
    r = L1 + t2
    out = np.zeros((len(Q), 3))
    out[:, 0] = r * np.cos(t1) + L3 * np.cos(t13)
    out[:, 1] = r * np.sin(t1) + L3 * np.sin(t13)
    return out


_UR5_ALPHA = [(math.cos(al), math.sin(al)) for _, al, _, _ in UR5_DH]


def ur5_fk_np(q):
    """Product of the UR5's standard DH matrices, in numpy."""
    T = np.eye(4)
    for (a, _, d, theta), (ca, sa), qi in zip(UR5_DH, _UR5_ALPHA, q):
        ct, st = np.cos(theta + qi), np.sin(theta + qi)
        T = T @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1.0]])
    return T


def ur5_jacobian_np(q):
    """Geometric Jacobian of the UR5 from its DH frames: columns [z x (p - o); z]."""
    T = np.eye(4)
    zs, os_ = [], []
    for (a, _, d, theta), (ca, sa), qi in zip(UR5_DH, _UR5_ALPHA, q):
        zs.append(T[:3, 2])
        os_.append(T[:3, 3])
        ct, st = np.cos(theta + qi), np.sin(theta + qi)
        T = T @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1.0]])
    z, o = np.array(zs), np.array(os_)
    return np.vstack((np.cross(z, T[:3, 3] - o).T, z.T))


def reach_literal(p_target, theta):
    """Seed 000, Algorithm 1, line by line (with J^p = J^T (J J^T)^-1 and eq. (1), (9))."""
    n, delta = 25, 1e-5
    d, dt = 0.75, 0.025

    def forward_kinematic(t):
        return np.array([(L1 + t[1]) * np.cos(t[0]) + L3 * np.cos(t[0] + t[2]),
                         (L1 + t[1]) * np.sin(t[0]) + L3 * np.sin(t[0] + t[2])])

    def jacobian(t):
        s1, c1, s13, c13 = np.sin(t[0]), np.cos(t[0]), np.sin(t[0] + t[2]), np.cos(t[0] + t[2])
        return np.array([[-(L1 + t[1]) * s1 - L3 * s13, c1, -L3 * s13],
                         [(L1 + t[1]) * c1 + L3 * c13, s1, L3 * c13]])

    p = forward_kinematic(theta)
    while True:
        dp = d * (p_target - p) / dt
        J = jacobian(theta)
        dtheta_m = J.T @ np.linalg.inv(J @ J.T) @ dp
        theta = np.clip(theta + dt * dtheta_m, LOWER, UPPER)
        p = forward_kinematic(theta)
        n = n - 1
        if n == 0 or np.linalg.norm(p_target - p) < delta:
            break
    return theta


def track_literal(points, q0):
    out = np.empty((len(points), 3))
    q = np.asarray(q0, float)
    for k, p in enumerate(points):
        q = reach_literal(p, q)
        out[k] = q
    return out


# --------------------------------------------------------------------------- the chains as segments
def rpr_segments():
    tx = lambda length: [[1, 0, 0, length], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]  # noqa: E731
    return [["R", [0, 0, 1], tx(L1)], ["P", [1, 0, 0], tx(0.0)], ["R", [0, 0, 1], tx(L3)]]


def ur5_segments():
    return [["RZ", [0, 0, 1], dh_matrix(*row).tolist()] for row in UR5_DH]


# --------------------------------------------------------------------------- PyKDL (subprocess)
def pykdl_reference(qs: dict):
    python = shutil.which("python3", path="/usr/bin") or "/usr/bin/python3"
    request = {"robots": {"UR5": {"segments": ur5_segments(), "q": qs["UR5"].tolist()},
                          "RPR": {"segments": rpr_segments(), "q": qs["RPR"].tolist()}}}
    proc = subprocess.run([python, str(HERE / "_pykdl_worker.py")], input=json.dumps(request),
                          capture_output=True, text=True, cwd=HERE)
    if proc.returncode != 0:
        print(f"  PyKDL reference unavailable under {python}: {proc.stderr.strip().splitlines()[-1:]}")
        return None
    return json.loads(proc.stdout)["robots"]


# --------------------------------------------------------------------------- Pinocchio
def pinocchio_models():
    try:
        import pinocchio as pin
    except ImportError as exc:
        print(f"  Pinocchio unavailable ({exc}); `pip install pin` (make bench does it)")
        return None, None

    def build(joints, tool):
        """joints: [(joint model, placement 4x4 in the parent joint frame)], tool: 4x4 after the last."""
        model = pin.Model()
        parent = 0
        for i, (joint, placement) in enumerate(joints):
            parent = model.addJoint(parent, joint, pin.SE3(np.asarray(placement, float)), f"joint{i + 1}")
        placement = pin.SE3(np.asarray(tool, float))
        try:
            frame = pin.Frame("tool", parent, placement, pin.FrameType.OP_FRAME)
        except TypeError:
            frame = pin.Frame("tool", parent, 0, placement, pin.FrameType.OP_FRAME)
        fid = model.addFrame(frame)
        return model, model.createData(), fid

    # Standard DH: T = Rz(q1) A1 Rz(q2) A2 ... Rz(q6) A6, so joint i sits at A_{i-1} in joint i-1.
    A = [dh_matrix(*row) for row in UR5_DH]
    ur5 = build([(pin.JointModelRZ(), np.eye(4) if i == 0 else A[i - 1]) for i in range(6)], A[5])
    tx = lambda length: np.array([[1, 0, 0, length], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])  # noqa: E731
    rpr = build([(pin.JointModelRZ(), np.eye(4)), (pin.JointModelPX(), tx(L1)), (pin.JointModelRZ(), np.eye(4))], tx(L3))
    return pin, {"UR5": ur5, "RPR": rpr}


# --------------------------------------------------------------------------- the benchmarks
def bench_single(rng):
    chains = {"UR5": rk.robots.ur5(), "RPR": rk.robots.rpr()}
    qs = {"UR5": rng.uniform(-math.pi, math.pi, 6),
          "RPR": rng.uniform(LOWER, UPPER)}
    numpy_fk = {"UR5": ur5_fk_np, "RPR": rpr_fk_np}
    numpy_jac = {"UR5": ur5_jacobian_np, "RPR": rpr_jacobian_np}
    kdl = pykdl_reference(qs)
    pin, pin_models = pinocchio_models()

    for name, chain in chains.items():
        q = qs[name]
        T, J = chain.fk(q), chain.jacobian(q)
        check(f"{name} fk vs KDL", T, chain._fk_kdl(q))
        check(f"{name} jacobian vs KDL", J, chain._jacobian_kdl(q))
        ns = {"chain": chain, "q": q, "fk_np": numpy_fk[name], "jac_np": numpy_jac[name]}
        ours_fk = per_call("chain.fk(q)", ns)
        ours_jac = per_call("chain.jacobian(q)", ns)
        print(f"single call from Python, {name} ({chain.dof} joints), float64 numpy q:")
        goal_fk = 0.7 if name == "UR5" else None
        goal_jac = 0.8 if name == "UR5" else None

        if pin_models is not None:
            model, data, fid = pin_models[name]
            pin.forwardKinematics(model, data, q)
            check(f"{name} Pinocchio fk", pin.updateFramePlacement(model, data, fid).homogeneous, T)
            pin.framesForwardKinematics(model, data, q)
            check(f"{name} Pinocchio fk (frames)", data.oMf[fid].homogeneous, T)
            world = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
            check(f"{name} Pinocchio jacobian", pin.computeFrameJacobian(model, data, q, fid, world), J)
            pns = {"pin": pin, "model": model, "data": data, "fid": fid, "q": q, "world": world}
            # Pinocchio's fastest natural way to a numpy 4x4 of the tool: the better of two.
            pin_fk = min(per_call("pin.forwardKinematics(model, data, q); "
                                  "pin.updateFramePlacement(model, data, fid).homogeneous", pns),
                         per_call("pin.framesForwardKinematics(model, data, q); data.oMf[fid].homogeneous", pns))
            pin_jac = per_call("pin.computeFrameJacobian(model, data, q, fid, world)", pns)
            line(f"fk {name}", ours_fk, "Pinocchio", pin_fk, goal_fk, name=SINGLE_FK)
            line(f"jacobian {name}", ours_jac, "Pinocchio", pin_jac, goal_jac, name=SINGLE_JAC)
        elif goal_fk:
            for what, limit in ((SINGLE_FK, goal_fk), (SINGLE_JAC, goal_jac)):
                goal(goals, what, float("nan"), "x", limit, "Pinocchio: not installed, so not measured")

        if kdl is not None:
            check(f"{name} PyKDL fk", kdl[name]["fk_value"], T)
            check(f"{name} PyKDL jacobian", kdl[name]["jacobian_value"], J)
            line(f"fk {name}", ours_fk, "PyKDL", kdl[name]["fk"], note="(PyKDL incl. list -> JntArray)")
            line(f"jacobian {name}", ours_jac, "PyKDL", kdl[name]["jacobian"], note="(PyKDL incl. list -> JntArray)")

        check(f"{name} numpy fk", numpy_fk[name](q), T)
        check(f"{name} numpy jacobian", numpy_jac[name](q), J)
        line(f"fk {name}", ours_fk, "numpy", per_call("fk_np(q)", ns))
        line(f"jacobian {name}", ours_jac, "numpy", per_call("jac_np(q)", ns))


def touched(shape) -> None:
    """A new array with one value written per 4 KB page: the page faults and the kernel's zeroing of
    a fresh output, without its stores."""
    np.empty(shape).reshape(-1)[::512] = 0.0


def one_thread_floor(Q, ref_best: float, positions: float) -> float:
    """What one thread cannot go below for the (N, 4, 4) frames of Q, from figures measured in this
    run (seconds; printed with their ratios to numpy's FK, ref_best), the larger of:

    - memory: the frames written once and Q read once, at the copy bandwidth of arrays of the
      output's size;
    - computation: robokin's own, taken as the positions-only call (its best time, `positions`,
      repeated calls: its output written into memory kept from the one before, no page faults):
      the frames take at least the positions' sines, cosines and products.

    The two overlap (the caches write back while the core computes), so the larger is the floor.
    Printed beside it: a fresh output's page faults and zeroing by the kernel (a new array touched
    once per page), which run on the calling thread too, and numpy's fill of a fresh array. (Their
    sum with the computation is no floor: robokin's call measured below it.)"""
    n = len(Q)
    src = np.ones(16 * n)
    dst = np.empty_like(src)
    dst.fill(0.0)  # pages in: a copy between two warm arrays is pure memory bandwidth
    copy = once(lambda: np.copyto(dst, src), repeat=5)[0]
    bandwidth = 2 * src.nbytes / copy  # bytes read + written per second
    del src, dst
    zero = once(lambda: touched((n, 4, 4)), repeat=5)[0]
    filled = once(lambda: np.empty((n, 4, 4)).fill(0.0), repeat=5)[0]
    memory = (16 * 8 * n + Q.nbytes) / bandwidth
    compute = positions
    floor = max(memory, compute)
    r = lambda t: f"{t * 1e3:.1f} ms = {t / ref_best:.3f} x"  # noqa: E731
    print(f"  memory: copy bandwidth {bandwidth / 1e9:.1f} GB/s; the frames written once and Q read once {r(memory)}\n"
          f"  computation: the positions-only call {r(compute)}\n"
          f"  one-thread floor, the larger of the two: {r(floor)}\n"
          f"  (information) a fresh (N, 4, 4) array's page faults and zeroing {r(zero)}; zeroed and written once "
          f"(numpy's fill) {r(filled)}", flush=True)
    return floor


def fresh_output(chain, Q):
    """(best, median) seconds of ``chain.fk(Q)`` into a new array, which the kernel faults in and
    zeroes as the call writes it: a call without ``out=``."""
    return once(lambda: chain.fk(Q), repeat=5)


def bench_batch(rng):
    chain = rk.robots.rpr()
    Q = rng.uniform(LOWER, UPPER, size=(BATCH, 3))
    print(f"batch FK, RPR, {BATCH:,} configurations (N, 3) -> (N, 4, 4), and -> (N, 3) with part='position':")
    ref_out = rpr_fk_batch_np(Q)
    for k in rng.integers(0, BATCH, 20):
        check("batch fk vs KDL", ref_out[k], chain._fk_kdl(Q[k]))
    saved = os.environ.get("ROBOKIN_NUM_THREADS")
    try:
        os.environ["ROBOKIN_NUM_THREADS"] = "1"
        check("numpy batch fk", ref_out, chain.fk(Q))
        check("numpy batch fk, positions", ref_out[:, :3, 3], chain.fk(Q, part="position"))
        del ref_out
        # Repeated calls into the caller's array (out=), as a loop that reuses its buffer does.
        out = np.empty((BATCH, 4, 4))
        ours, ref = once_interleaved([lambda: chain.fk(Q, out=out), lambda: rpr_fk_batch_np(Q)], repeat=5)
        per = lambda t: (t[0] / BATCH, t[1] / BATCH)  # noqa: E731
        line("batch fk RPR, 1 thread", ours, "numpy", ref, 0.15,
             note=f"per configuration: {fmt(per(ours)[0]).strip()} vs {fmt(per(ref)[0]).strip()}",
             name=f"batch FK of {BATCH:,} RPR configurations, (N, 4, 4) out, 1 thread, repeated calls (out=), vs "
                  "numpy's vectorised closed form (the RPR study, eq. 1)")
        g = goals[-1]
        fresh = fresh_output(chain, Q)
        line("batch fk RPR, 1 thread, new output", fresh, "numpy", ref,
             note="(information: without out=, the output faulted in and zeroed by the kernel)")
        positions_out = np.empty((BATCH, 3))
        positions = once(lambda: chain.fk(Q, part="position", out=positions_out), repeat=5)
        floor = one_thread_floor(Q, ref[0], positions[0]) / ref[0]
        g["note"] = (f"each call writes into the caller's array (out=); into a new array "
                     f"{fresh[0] / ref[0]:.3f} x. One-thread floor here {floor:.3f} x (the larger of the memory "
                     "traffic at the copy bandwidth and robokin's computation of the positions, measured in this run)"
                     + ("; above the goal, so it cannot be met on one thread on this machine with this computation"
                        if floor > g["limit"]
                        else "" if g["met"]
                        else "; below the goal: the miss is the time the thread spends beyond the floor, in "
                             "robokin's stores"))
        ref_pos = once(lambda: rpr_position_batch_np(Q), repeat=5)
        line("batch fk RPR positions, 1 thread", positions, "numpy", ref_pos,
             note="(information: part='position', (N, 3), vs numpy's closed form of the point)")
        if saved is None:
            del os.environ["ROBOKIN_NUM_THREADS"]
        else:
            os.environ["ROBOKIN_NUM_THREADS"] = saved
        threads = once(lambda: chain.fk(Q, out=out), repeat=5)
        line(f"batch fk RPR, {saved or 'all'} threads", threads, "numpy", ref,
             note=f"(information; {os.cpu_count()} cores, shared)")
    finally:
        if saved is None:
            os.environ.pop("ROBOKIN_NUM_THREADS", None)
        else:
            os.environ["ROBOKIN_NUM_THREADS"] = saved


def bench_reach():
    chain = rk.robots.rpr()
    # Seed 000's Figure 2 setting: from a point on the boundary (t1 = pi/2) along a straight line.
    q0 = np.array([math.pi / 2, 0.5, math.pi / 2])
    p1 = chain.fk(q0)[:2, 3]
    p2 = np.array([1.5, 1.0])
    dist = float(np.linalg.norm(p2 - p1))
    points = rk.paths.line(p1, p2, dist / (PATH_POINTS - 1) * (1 + 1e-12))
    if len(points) != PATH_POINTS:
        points = p1 + np.linspace(0, 1, PATH_POINTS)[:, None] * (p2 - p1)
    print(f"Reach path, RPR, straight line {np.round(p1, 3)} -> {p2}, {len(points):,} points, seed defaults:")
    tr = rk.track(chain, points, q0)
    literal = track_literal(points, q0)
    check("Reach path vs the literal seed algorithm", tr.q, literal, atol=1e-9)
    ours = once(lambda: rk.track(chain, points, q0), repeat=5)
    ref = once(lambda: track_literal(points, q0), repeat=3)
    per = lambda t: t[0] / len(points)  # noqa: E731
    line("Reach path RPR", ours, "numpy", ref, 0.01,
         name=f"Reach path, RPR, {len(points):,} points, seed defaults, vs the RPR study's Algorithm 1 in plain numpy",
         note=f"per point: {fmt(per(ours)).strip()} vs {fmt(per(ref)).strip()}; "
              f"{int(tr.converged.sum())}/{len(points)} converged, "
              f"{tr.iterations.mean():.2f} iterations per point")


def main():
    goals.clear()
    rng = np.random.default_rng(2)
    print(f"robokin {rk.__version__}, numpy {np.__version__}, Python {sys.version.split()[0]}")
    bench_single(rng)
    bench_batch(rng)
    bench_reach()
    return list(goals)


if __name__ == "__main__":
    results = main()
    sys.exit(0 if all(g["met"] for g in results) else 1)
