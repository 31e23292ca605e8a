"""What the closed-form tests share: configurations drawn inside the limits, the distance of joint
vectors modulo 2 pi, a damped Newton with one joint held (an independent numerical IK) and its
check of a closed form's completeness, the check of every solution of random poses, the labels
against their geometric definitions, a configuration on a singularity found along one joint,
random DH rows of a given shape, a bisection, and EAIK's robot of a chain (a peer library, when
installed)."""

import math

import numpy as np

import robokin as rk

P = math.pi


def random_q(chain, rng, count, margin=0.05):
    """count configurations uniform within the limits less `margin` of each range at both ends (an
    unlimited joint within [-pi, pi])."""
    lo, hi = chain.limits
    lo, hi = np.where(np.isfinite(lo), lo, -P), np.where(np.isfinite(hi), hi, P)
    return rng.uniform(lo + margin * (hi - lo), hi - margin * (hi - lo), (count, chain.dof))


def angle_distance(a, b):
    """Largest joint difference, angles compared modulo 2 pi."""
    return np.max(np.abs(np.remainder(a - b + P, 2 * P) - P), axis=-1)


def newton_held(chain, T, starts, j, iterations=80):
    """Damped Newton from each start (rows), joint j held (None: none): the pose error on the other
    joints. Returns the end points and each one's largest deviation of fk from T."""
    q = starts.copy()
    # Orientation error: half the sum of the columns' cross products (both operands 3-D, so that
    # axis 1 is the column's rows in each).
    free = [i for i in range(chain.dof) if i != j]
    for _ in range(iterations):
        F = chain.fk(q)
        e = np.concatenate([T[:3, 3] - F[:, :3, 3], 0.5 * np.cross(F[:, :3, :3], T[None, :3, :3], axis=1).sum(axis=2)],
                           axis=1)
        J = chain.jacobian(q)[:, :, free]
        step = np.linalg.solve(J @ J.transpose(0, 2, 1) + 1e-9 * np.eye(6), e[:, :, None])
        q[:, free] += (J.transpose(0, 2, 1) @ step)[:, :, 0]
    return q, np.abs(chain.fk(q) - T).max(axis=(1, 2))


def newton_agrees(arms, rng, poses=3, starts=64):
    """Numerical IK (newton_held, no joint held) from `starts` random starts on `poses` random poses
    of each arm: every converged end (1e-11) is one of rk.closed.solve's solutions (1e-6). Returns
    how many converged, for the caller to check that the comparison compared something."""
    found = 0
    for chain in arms:
        for q in rng.uniform(-P, P, (poses, 6)):
            T = chain.fk(q)
            s = rk.closed.solve(T, chain, limits=None)
            ends, errors = newton_held(chain, T, rng.uniform(-P, P, (starts, 6)), None)
            for qn in ends[errors < 1e-11]:
                found += 1
                assert angle_distance(s.q, qn).min() < 1e-6, (q, qn)
    return found


def arm_size(chain, locked=None):
    """The arm's size as closed_family measures it (its distance tolerance over the default tol)."""
    return rk.closed.family(chain, locked=locked).tol_distance / 1e-6


def check_poses(chain, Q, locked=None):
    """Every solution reaches its pose (1e-9 x the arm's size; rotation entries 1e-9), the
    generating q is among them (1e-6), one label per solution. Returns the solutions."""
    size = arm_size(chain, None if locked is None else {locked: 0.0})
    out = []
    for q in Q:
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, limits=None, locked=None if locked is None else {locked: q[locked]})
        F = chain.fk(s.q)
        assert len(s) >= 1 and np.abs(F[:, :3, 3] - T[:3, 3]).max() <= 1e-9 * size, q
        assert np.abs(F[:, :3, :3] - T[:3, :3]).max() <= 1e-9, q
        assert s.singular or angle_distance(s.q, q).min() < 1e-6, (q, s)
        assert len(set(s.postures)) == len(s)
        out.append(s)
    return out


def family_solves(arms, name, rng, poses=10):
    """Each arm is of the family `name` (solvable, no reason) and check_poses holds on `poses`
    random poses of it; returns the solution counts."""
    counts = []
    for chain in arms:
        f = rk.closed.family(chain)
        assert f.name == name and f.solvable and f.reason == ""
        counts += [len(s) for s in check_poses(chain, rng.uniform(-P, P, (poses, 6)))]
    return counts


def labels_agree(arms, rng, label_of, poses=10):
    """rk.closed.solve's postures on `poses` random poses of each arm are label_of(chain, q) of
    their solutions (the labels' geometric definitions); returns the set of labels seen."""
    seen = set()
    for chain in arms:
        for q in rng.uniform(-P, P, (poses, 6)):
            s = rk.closed.solve(chain.fk(q), chain, limits=None)
            for qk, posture in zip(s.q, s.postures):
                assert posture == label_of(chain, qk)
                seen.add(posture)
    return seen


def zero_along(condition, joint, rng):
    """A random configuration with q[joint] moved onto a zero of condition(q): a sign change among
    13 values across [-pi, pi], then bisection (a singularity crossed along that joint)."""
    while True:
        q = rng.uniform(-P, P, 6)
        grid = np.linspace(-P, P, 13)
        f = lambda t: condition(np.r_[q[:joint], t, q[joint + 1:]])  # noqa: E731
        values = [f(t) for t in grid]
        for k in range(12):
            if values[k] * values[k + 1] < 0:
                q[joint] = bisect(f, grid[k], grid[k + 1])
                return q


def newton_steps(name, j):
    """Newton's iterations for the catalogue arm `name` with joint j held: the Panda's elbow held
    keeps the wrist's point (axes 5, 6) a fixed distance from the shoulder's, and from a random
    start Newton mostly creeps along that constraint (800 steps converge about as often as 80 do
    elsewhere)."""
    return 800 if (name, j) == ("panda", 3) else 80


def random_rows(rng, zero, parallel=()):
    """Standard DH rows [a, alpha, d, theta, "R"] x 6 with random lengths (0.05 to 0.5 m, either
    sign) and twists (0.3 to pi - 0.3 rad, either sign), the (row, column) entries of `zero` set to 0
    (a_i = 0: axes i and i + 1 meet; with d_i = 0 too, axes i - 1, i and i + 1 meet in one point)
    and the twists of the rows in `parallel` to 0 (axes i and i + 1 parallel)."""
    length = lambda: rng.uniform(0.05, 0.5) * rng.choice([-1, 1])  # noqa: E731
    twist = lambda: rng.uniform(0.3, P - 0.3) * rng.choice([-1, 1])  # noqa: E731
    rows = [[length(), twist(), length(), rng.uniform(-P, P), "R"] for _ in range(6)]
    for i, k in zero:
        rows[i][k] = 0.0
    for i in parallel:
        rows[i][1] = 0.0
    return rows


def bisect(f, lo, hi):
    """A root of f between lo and hi (f(lo), f(hi) of opposite signs), to rounding."""
    flo = f(lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if (f(mid) > 0) == (flo > 0):
            lo, flo = mid, f(mid)
        else:
            hi = mid
    return lo


def eaik_robot(chain, locked=None):
    """EAIK's robot (pip's eaik; the test is skipped without it) of the chain's joint lines at q = 0
    (rk.plots.joint_axes: read from the Jacobian, not from closed_family) with the tool's
    orientation; locked={j: value} holds joint j."""
    import pytest

    EAIK = pytest.importorskip("eaik.pybindings.EAIK")
    zero = np.zeros(chain.dof)
    lines, tool = rk.plots.joint_axes(chain, zero), chain.fk(zero)
    offsets = np.diff(np.vstack([np.zeros(3), lines[:, 0], tool[:3, 3]]), axis=0)
    fixed = [] if locked is None else [(j, float(value)) for j, value in locked.items()]
    return EAIK.Robot(np.ascontiguousarray(lines[:, 1].T), np.ascontiguousarray(offsets.T), tool[:3, :3], fixed, True)


def eaik_solutions(robot, T):
    """EAIK's exact solutions of T (its least-squares ones dropped), (k, n)."""
    e = robot.calculate_IK(T)
    if not e.num_solutions():
        return np.zeros((0, 0))
    return np.atleast_2d(np.asarray(e.Q, float))[~np.asarray(e.is_LS, bool)]
