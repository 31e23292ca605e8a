"""Arbitrary arrays and numbers into the IK calls: a result or a ValueError, never a crash; and a
reported success is always a reached pose. The solvers themselves are fuzzed with rigid targets
(FK of a random q, perturbed or not) on chains with finite, half-infinite and no limits."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import robokin as rk

UR5 = rk.robots.ur5()
floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
shapes = hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=6)
arrays = st.one_of(
    hnp.arrays(np.float64, shapes, elements=floats),
    hnp.arrays(np.float64, st.sampled_from([(4, 4), (6,), (1, 4, 4), (2, 6)]), elements=st.floats(-3, 3)),
    hnp.arrays(np.int64, shapes, elements=st.integers(-5, 5)),
)


@settings(max_examples=150, deadline=None)
@given(target=arrays, q0=arrays, method=st.sampled_from(["lm", "gn", "nr", "halley", "?"]),
       task=st.sampled_from(["pose", "position", "xy", "xyphi", "?"]), tol=floats,
       max_iter=st.integers(-2, 20), restarts=st.integers(-1, 3))
def test_ik_returns_or_raises(target, q0, method, task, tol, max_iter, restarts):
    try:
        r = rk.ik(UR5, target, q0, method=method, task=task, tol_p=tol, tol_r=tol, max_iter=max_iter,
                  restarts=restarts, seed=0)
    except ValueError:
        return
    assert np.all(np.isfinite(r.q)) and np.isfinite(r.error_p) and np.isfinite(r.error_r)
    assert r.success == (r.error_p < tol and (task not in ("pose", "xyphi") or r.error_r < tol))


@settings(max_examples=100, deadline=None)
@given(targets=arrays, q0=arrays, path=st.booleans())
def test_ik_batch_returns_or_raises(targets, q0, path):
    try:
        r = rk.ik_batch(UR5, targets, q0, max_iter=10, path=path, seed=0)
    except ValueError:
        return
    assert r.q.shape == (len(r), 6) and np.all(np.isfinite(r.q))


INF = math.inf
P2 = math.pi / 2
UR5_ROWS = [(0, P2, 0.089159, 0, "R"), (-0.425, 0, 0, 0, "R"), (-0.39225, 0, 0, 0, "R"),
            (0, P2, 0.10915, 0, "R"), (0, -P2, 0.09465, 0, "R"), (0, 0, 0.0823, 0, "R")]
CHAINS = [
    UR5,
    rk.robots.puma560(),
    # a UR5 geometry with half-infinite and unlimited joints
    rk.Chain.from_dh(UR5_ROWS, limits=([-INF, -1.0, -INF, -INF, 0.5, -INF], [0.5, INF, INF, 1.0, INF, INF])),
    rk.Chain.from_dh(UR5_ROWS),  # no limits at all
    rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 3, limits=([-INF, -1.0, -INF], [1.0, INF, INF])),
    rk.Chain.from_dh([(1.0, 0, 0, 0, "R")] * 2, limits=([-INF, -INF], [1.0, INF])),
    rk.Chain.from_dh([(1.0, 0, 0, 0, "R")], limits=([-INF], [1.0])),
    # prismatic joints: unlimited, and half-infinite
    rk.robots.prr(),
    rk.Chain.from_dh([(0, P2, 0, 0, "P"), (1.0, 0, 0, 0, "R"), (0.7, 0, 0, 0, "R")],
                     limits=([0.0, -INF, -2.0], [INF, 0.5, INF])),
    rk.robots.rp(),
    rk.robots.rpr(),
]


def rotation_angle(R):
    s = np.linalg.norm([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2.0
    return math.atan2(s, (np.trace(R) - 1.0) / 2.0)


def rotation(v):
    """Rodrigues: the rotation by |v| about v."""
    angle = np.linalg.norm(v)
    if angle == 0:
        return np.eye(3)
    k = v / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def task_target(T, task):
    if task == "pose":
        return T
    if task == "position":
        return T[:3, 3].copy()
    if task == "xy":
        return T[:2, 3].copy()
    return np.array([T[0, 3], T[1, 3], math.atan2(T[1, 0], T[0, 0])])


def fk_errors(chain, q, T, task):
    """(position, orientation) errors of FK(q) (KDL's recursive FK) for the target T."""
    F = chain._fk_kdl(q)
    if task == "pose":
        return np.linalg.norm(F[:3, 3] - T[:3, 3]), rotation_angle(F[:3, :3].T @ T[:3, :3])
    if task == "position":
        return np.linalg.norm(F[:3, 3] - T[:3, 3]), 0.0
    ep = math.hypot(F[0, 3] - T[0, 3], F[1, 3] - T[1, 3])
    if task == "xy":
        return ep, 0.0
    phi = math.atan2(F[1, 0], F[0, 0]) - math.atan2(T[1, 0], T[0, 0])
    return ep, abs(math.remainder(phi, 2 * math.pi))


def check(chain, q, success, error_p, error_r, T, task, tol):
    lo, hi = chain.limits
    assert q.shape == (chain.dof,) and np.all(np.isfinite(q)), q
    assert np.isfinite(error_p) and np.isfinite(error_r)
    assert np.all(q >= lo) and np.all(q <= hi), (q, lo, hi)
    ep, er = fk_errors(chain, q, T, task)
    assert abs(ep - error_p) <= 1e-9 * (1 + ep) and abs(er - error_r) <= 1e-9 * (1 + er), (ep, error_p, er, error_r)
    margin = 1e-12  # FK rounding: no verdict within it of the tolerance
    if success:
        assert ep < tol + margin and er < tol + margin, (ep, er, tol)
    else:
        assert ep >= tol - margin or er >= tol - margin, (ep, er, tol)


coords = st.floats(-7, 7, allow_nan=False)
rigid = st.fixed_dictionaries({
    "chain": st.integers(0, len(CHAINS) - 1),
    "q": st.lists(coords, min_size=6, max_size=6),
    "dp": st.one_of(st.just((0.0, 0.0, 0.0)), st.tuples(*[st.floats(-0.3, 0.3)] * 3), st.tuples(*[st.floats(-5, 5)] * 3)),
    "dr": st.one_of(st.just((0.0, 0.0, 0.0)), st.tuples(*[st.floats(-1, 1)] * 3)),
    "method": st.sampled_from(["lm", "gn", "nr", "halley"]),
    "task": st.sampled_from(["pose", "position", "xy", "xyphi"]),
    "tol": st.sampled_from([1e-9, 1e-6, 1e-3]),
})


def rigid_target(case):
    chain = CHAINS[case["chain"]]
    lo, hi = chain.limits
    q = np.clip(np.array(case["q"][: chain.dof]), lo, hi)
    T = chain.fk(q)
    T[:3, 3] += case["dp"]
    T[:3, :3] = T[:3, :3] @ rotation(np.array(case["dr"]))
    return chain, T


@settings(max_examples=400, deadline=None)
@given(case=rigid, q0=st.lists(st.floats(-20, 20), min_size=6, max_size=6), max_iter=st.integers(1, 60),
       restarts=st.integers(0, 3), seed=st.integers(0, 2**64 - 1))
def test_ik_solver_fuzzed_with_rigid_targets(case, q0, max_iter, restarts, seed):
    chain, T = rigid_target(case)
    task, tol = case["task"], case["tol"]
    r = rk.ik(chain, task_target(T, task), np.array(q0[: chain.dof]), method=case["method"], task=task,
              tol_p=tol, tol_r=tol, max_iter=max_iter, restarts=restarts, seed=seed)
    check(chain, r.q, r.success, r.error_p, r.error_r, T, task, tol)
    assert bool(r) == r.success and 1 <= r.attempts <= restarts + 1


@settings(max_examples=80, deadline=None)
@given(cases=st.lists(rigid, min_size=1, max_size=4), q0=st.lists(st.floats(-20, 20), min_size=6, max_size=6),
       chain_index=st.integers(0, len(CHAINS) - 1), method=st.sampled_from(["lm", "gn", "nr", "halley"]),
       task=st.sampled_from(["pose", "position", "xy", "xyphi"]), path=st.booleans(), restarts=st.integers(0, 3))
def test_ik_batch_fuzzed_with_rigid_targets(cases, q0, chain_index, method, task, path, restarts):
    targets = [rigid_target(dict(case, chain=chain_index))[1] for case in cases]
    chain = CHAINS[chain_index]
    res = rk.ik_batch(chain, np.array([task_target(T, task) for T in targets]), np.array(q0[: chain.dof]),
                      method=method, task=task, tol_p=1e-6, tol_r=1e-6, max_iter=40, restarts=restarts,
                      seed=7, path=path)
    for k, T in enumerate(targets):
        check(chain, res.q[k], res.success[k], res.error_p[k], res.error_r[k], T, task, 1e-6)


@settings(max_examples=150, deadline=None)
@given(target=arrays, a=st.tuples(floats, floats, floats), method=st.sampled_from(["algebraic", "geometric"]))
def test_closed_forms_return_or_raise(target, a, method):
    calls = [
        lambda: rk.closed.planar_rp(target),
        lambda: rk.closed.planar_2r(target, a[0], a[1]),
        lambda: rk.closed.planar_3r(target, *a, method=method),
        lambda: rk.closed.anthropomorphic(target, a[0], a[1], a[2]),
        lambda: rk.closed.puma560(target),
        lambda: rk.closed.spherical_wrist_6r(target, 0.4, 0.02, 0.1, 0.4, d6=a[0]),
    ]
    for call in calls:
        try:
            s = call()
        except ValueError:
            continue
        assert np.all(np.isfinite(s.q)) and len(s.postures) == len(s)
