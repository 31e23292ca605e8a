"""Random well-formed serial chains for the property tests of chains, Reach and the numerical IK
(test_fuzz_chain.py, test_fuzz_reach.py, test_fuzz_ik.py), and the independent forward model they
are checked against (tests/dh_reference.py)."""

import math

import numpy as np
from hypothesis import strategies as st

import robokin as rk
from dh_reference import fk_dh

PI = math.pi
INF = math.inf

_lengths = st.one_of(st.just(0.0), st.floats(-1.0, 1.0, allow_subnormal=False))
_angles = st.one_of(st.sampled_from([0.0, PI / 2, -PI / 2, PI]), st.floats(-PI, PI, allow_subnormal=False))


@st.composite
def dh_chains(draw, min_dof=1, max_dof=7, prismatic=True, limits=True):
    """A dict ``rows``, ``modified``, ``limits`` (None or (lower, upper), some bounds infinite) and
    the ``chain`` built from them: 1-7 joints, moderate lengths (|a|, |d| <= 1), revolute and
    prismatic joints."""
    n = draw(st.integers(min_dof, max_dof))
    kinds = st.sampled_from("RP") if prismatic else st.just("R")
    rows = [draw(st.tuples(_lengths, _angles, _lengths, _angles, kinds)) for _ in range(n)]
    modified = draw(st.booleans())
    lim = None
    if limits and draw(st.booleans()):
        lower, upper = [], []
        for _ in range(n):
            lo = draw(st.one_of(st.just(-INF), st.floats(-3.0, 1.0)))
            hi = draw(st.one_of(st.just(INF), st.floats(0.0, 3.0).map(lambda w, lo=lo: (lo if math.isfinite(lo) else -1.0) + w)))
            lower.append(lo)
            upper.append(hi)
        lim = (np.array(lower), np.array(upper))
    chain = rk.Chain.from_dh(rows, modified=modified, limits=lim)
    return {"rows": rows, "modified": modified, "limits": lim, "chain": chain}


def reference_fk(case, q):
    """The tool pose of a dh_chains case by the numpy DH product (independent of the core)."""
    return fk_dh(case["rows"], q, modified=case["modified"])


def q_within(case, values):
    """Joints from ``values`` (at least dof numbers) clipped into the case's limits."""
    chain = case["chain"]
    lo, hi = chain.limits
    return np.clip(np.asarray(values[: chain.dof], dtype=float), lo, hi)


def rotation_angle(R):
    """The angle of the rotation R (0..pi), robust near 0 and pi."""
    s = np.linalg.norm([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2.0
    return math.atan2(s, (np.trace(R) - 1.0) / 2.0)


def planar_angle(T):
    return math.atan2(T[1, 0], T[0, 0])


def task_target(T, task):
    """The target of ``task`` that the pose T reaches exactly."""
    if task == "pose":
        return T
    if task == "position":
        return T[:3, 3].copy()
    if task == "xy":
        return T[:2, 3].copy()
    return np.array([T[0, 3], T[1, 3], planar_angle(T)])


def task_errors(F, target, task):
    """(position error, orientation error) of the tool pose F for a target of ``task``."""
    if task == "pose":
        return float(np.linalg.norm(F[:3, 3] - target[:3, 3])), rotation_angle(F[:3, :3].T @ target[:3, :3])
    if task == "position":
        return float(np.linalg.norm(F[:3, 3] - target)), 0.0
    ep = math.hypot(F[0, 3] - target[0], F[1, 3] - target[1])
    if task == "xy":
        return ep, 0.0
    return ep, abs(math.remainder(target[2] - planar_angle(F), 2 * PI))
