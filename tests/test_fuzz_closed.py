"""Property tests of the closed-form inverse kinematics (robokin.closed) and its IKSolutions.

Two rules. (1) Any arguments: a call returns an IKSolutions whose every row is finite and puts the
tool on the target (checked with the numpy DH of tests/dh_reference.py), marked within the limits
exactly when whole turns can bring it within them (and then within them), or it raises ValueError /
TypeError naming an argument. (2) Reported success equals verified success: over random targets,
reachable (the forward model of random joints within the limits), too far, inside the inner hole,
and singular (stretched or folded elbow, wrist singular, on the shoulder axis), the result has a
solution within the limits exactly when the target is reachable within them, and then holds a
solution near the joints the target was made from (unless the pose is singular and that joint is
free).
"""

import math

import numpy as np
import pytest
from fuzz import arrays, assert_finite, check_call, finite_arrays, wild_floats
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import robokin as rk
from dh_reference import fk_dh
from limits_reference import turns_fit

COVERS = {
    "closed.planar_rp", "closed.planar_2r", "closed.planar_3r", "closed.anthropomorphic",
    "closed.spherical_wrist_6r", "closed.puma560", "closed.puma560_path", "robots.rpr_self_motion",
    "IKSolutions.q", "IKSolutions.postures", "IKSolutions.singular", "IKSolutions.dof", "IKSolutions.nearest",
    "IKSolutions.__repr__", "IKSolutions.__len__", "IKSolutions.within_limits", "IKSolutions.only_within_limits",
}

#: The tolerance the core verifies every solution to (cpp/src/ik_closed.cpp): tool position within
#: TOL_P x the arm's size (sum of its lengths) of the target, rotation entries within TOL_R. The
#: test's own forward model adds its rounding, hence the small margin.
TOL_P, TOL_R = 1e-9, 1e-8
MARGIN = 4.0
PUMA = rk.closed.PUMA560
PUMA_LIMITS = rk.robots.puma560().limits

lengths = st.one_of(wild_floats, st.floats(-3, 3), st.sampled_from([None, "1.0", 1j, True, np.float32(0.5), [1.0]]))
good_lengths = st.floats(0.05, 2.0)
scales = st.sampled_from([1.0, 1.0, 1e-150, 1e-6, 1e6, 1e150])


def limits_for(dof):
    """Good pairs, pairs of the wrong length or with NaN / swapped bounds, and things that are no pair."""
    lo = finite_arrays((dof,), -4.0, 0.0)
    hi = finite_arrays((dof,), 0.0, 4.0)
    good = st.tuples(lo, hi)
    bad = st.one_of(
        st.tuples(arrays([(dof,), (dof + 1,), (dof - 1,), (dof, 1)]), arrays([(dof,), (dof + 1,)])),
        st.tuples(hi.map(lambda a: a + 0.1), lo),  # lower above upper
        st.sampled_from(["default", "abc", 3.0, (), ([0.0] * dof,), ([0.0] * dof, [1.0] * dof, [2.0] * dof),
                         ([math.nan] * dof, [1.0] * dof), ([-math.inf] * dof, [math.inf] * dof)]),
    )
    return st.one_of(st.none(), good, good, bad)


# --- forward models of the closed forms' arms (numpy, tests/dh_reference.py) ------------------

def fk_rp(q):
    return q[1] * np.array([math.cos(q[0]), math.sin(q[0])])


def fk_planar(a, q):
    rows = [(ai, 0.0, 0.0, 0.0, "R") for ai in a]
    T = fk_dh(rows, q)
    return np.array([T[0, 3], T[1, 3]]), T[:2, :2]


def fk_anthropomorphic(a2, a3, d1, q):
    return fk_dh([(0.0, math.pi / 2, d1, 0.0, "R"), (a2, 0.0, 0.0, 0.0, "R"), (a3, 0.0, 0.0, 0.0, "R")], q)[:3, 3]


def fk_wrist(g, q):
    rows = [(0.0, math.pi / 2, g["d1"], 0.0, "R"), (g["a2"], 0.0, 0.0, 0.0, "R"), (g["a3"], -math.pi / 2, g["d3"], 0.0, "R"),
            (0.0, math.pi / 2, g["d4"], 0.0, "R"), (0.0, -math.pi / 2, 0.0, 0.0, "R"), (0.0, 0.0, g["d6"], 0.0, "R")]
    return fk_dh(rows, q)


def dist(u, v):
    """Euclidean distance without overflow: np.linalg.norm squares the entries, and a miss of 1e160
    (within the tolerance of a 1e170 arm) came out inf."""
    return math.hypot(*(np.asarray(u, dtype=float) - np.asarray(v, dtype=float)))


def check_solutions(s, dof, limits, reaches, prismatic=None):
    """IKSolutions invariants, the within_limits mask and the forward model of every row; returns s."""
    assert isinstance(s, rk.closed.IKSolutions)
    assert s.dof == dof and isinstance(s.singular, bool)
    q = s.q
    assert q.shape == (len(s), dof) and q.dtype == np.float64
    assert_finite(q)
    assert len(s.postures) == len(s) and all(isinstance(p, str) and p for p in s.postures)
    assert isinstance(repr(s), str) and repr(s).startswith(f"IKSolutions({len(s)} solution")
    within = s.within_limits
    assert within.shape == (len(s),) and within.dtype == np.bool_
    kept = s.only_within_limits()
    assert np.array_equal(kept.q, q[within]) and kept.postures == [p for p, w in zip(s.postures, within) if w]
    if isinstance(limits, tuple) and len(limits) == 2:
        lo, hi = (np.asarray(v, dtype=float) for v in limits)
        assert np.all(q[within] >= lo) and np.all(q[within] <= hi), (q, limits)
        for row in q[~within]:  # outside: no whole turns bring it within
            assert not turns_fit(row, lo, hi, prismatic or [False] * dof), (row, limits)
    elif limits is None:
        assert within.all()
    for row in q:
        assert reaches(row), (row, s.postures)
    return s


def check_nearest(s, q):
    k = check_call(lambda: s.nearest(q), "q")
    if k is None:
        if not s.within_limits.any():
            assert s.nearest(np.zeros(s.dof)) is None
        return
    qq = np.asarray(q, dtype=float)
    d = np.where(s.within_limits, np.sum((s.q - qq) ** 2, axis=1), np.inf)  # among those within the limits
    assert isinstance(k, int) and 0 <= k < len(s) and s.within_limits[k] and d[k] == d.min()


def wrapped(a, b):
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))).max(axis=-1)


# --- (1) any arguments -----------------------------------------------------------------------

@given(target=arrays([(2,), (3,), (1,), (2, 1), (0,)]), limits=limits_for(2), q=arrays([(2,), (3,)]))
def test_planar_rp_any_arguments(target, limits, q):
    s = check_call(lambda: rk.closed.planar_rp(target, limits=limits), "target", "limits")
    if s is not None:
        p = np.asarray(target, dtype=float)
        unit = np.abs(p).max() or 1.0  # norms in units of the target: no overflow near 1e308
        check_solutions(s, 2, limits,
                        lambda row: np.linalg.norm((fk_rp(row) - p) / unit) <= MARGIN * TOL_P * np.linalg.norm(p / unit),
                        prismatic=[False, True])
        check_nearest(s, q)


@given(target=arrays([(2,), (3,)]), a1=lengths, a2=lengths, limits=limits_for(2), q=arrays([(2,), (1,)]))
def test_planar_2r_any_arguments(target, a1, a2, limits, q):
    s = check_call(lambda: rk.closed.planar_2r(target, a1, a2, limits=limits), "target", "a1", "a2", "limits")
    if s is not None:
        p = np.asarray(target, dtype=float)
        size = a1 + a2
        check_solutions(s, 2, limits, lambda row: math.hypot(*(fk_planar((a1, a2), row)[0] - p)) <= MARGIN * TOL_P * size)
        check_nearest(s, q)


@given(target=arrays([(3,), (2,)]), a=st.tuples(lengths, lengths, lengths),
       method=st.sampled_from(["algebraic", "geometric", "Geometric", "", None, 3]), limits=limits_for(3),
       q=arrays([(3,), (2,)]))
def test_planar_3r_any_arguments(target, a, method, limits, q):
    s = check_call(lambda: rk.closed.planar_3r(target, *a, method=method, limits=limits),
                   "target", "a1", "a2", "a3", "method", "limits")
    if s is not None:
        x, y, phi = np.asarray(target, dtype=float)
        size = a[0] + a[1] + abs(a[2])

        def reaches(row):
            p, R = fk_planar(a, row)
            return (dist(p, (x, y)) <= MARGIN * TOL_P * size
                    and np.abs(R - [[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]]).max() <= MARGIN * TOL_R)

        check_solutions(s, 3, limits, reaches)
        check_nearest(s, q)


@given(target=arrays([(3,), (4,)]), a2=lengths, a3=lengths, d1=lengths, limits=limits_for(3), q=arrays([(3,)]))
def test_anthropomorphic_any_arguments(target, a2, a3, d1, limits, q):
    s = check_call(lambda: rk.closed.anthropomorphic(target, a2, a3, d1, limits=limits), "target", "a2", "a3", "d1",
                   "limits")
    if s is not None:
        p = np.asarray(target, dtype=float)
        size = abs(d1) + a2 + abs(a3)
        check_solutions(s, 3, limits, lambda row: dist(fk_anthropomorphic(a2, a3, d1, row), p) <= MARGIN * TOL_P * size)
        check_nearest(s, q)


def rotation(quaternion):
    w, x, y, z = quaternion / np.linalg.norm(quaternion)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


quaternions = finite_arrays((4,), -1.0, 1.0).filter(lambda v: np.linalg.norm(v) > 0.1)


@st.composite
def rigid(draw, reach=1.0):
    T = np.eye(4)
    T[:3, :3] = rotation(draw(quaternions))
    T[:3, 3] = draw(finite_arrays((3,), -reach, reach))
    return T


transforms = st.one_of(rigid(), rigid(), arrays([(4, 4), (3, 4), (4,)]))


def wrist_reaches(g, T):
    size = sum(abs(float(v)) for v in g.values())

    def reaches(row):
        F = fk_wrist(g, row)
        return (dist(F[:3, 3], T[:3, 3]) <= MARGIN * TOL_P * size
                and np.abs(F[:3, :3] - T[:3, :3]).max() <= MARGIN * TOL_R)

    return reaches


@given(target=transforms, g=st.tuples(lengths, lengths, lengths, lengths, lengths, lengths), limits=limits_for(6),
       q=arrays([(6,)]))
def test_spherical_wrist_6r_any_arguments(target, g, limits, q):
    a2, a3, d3, d4, d1, d6 = g
    s = check_call(lambda: rk.closed.spherical_wrist_6r(target, a2, a3, d3, d4, d1, d6, limits=limits),
                   "target", "a2", "a3", "d3", "d4", "d1", "d6", "limits")
    if s is not None:
        geometry = dict(a2=a2, a3=a3, d3=d3, d4=d4, d1=d1, d6=d6)
        check_solutions(s, 6, limits, wrist_reaches(geometry, np.asarray(target, dtype=float)))
        check_nearest(s, q)


@given(target=transforms, limits=st.one_of(st.just("default"), limits_for(6), st.just(rk.robots.puma560())))
def test_puma560_any_arguments(target, limits):
    s = check_call(lambda: rk.closed.puma560(target, limits=limits), "target", "limits")
    if s is not None:
        lim = PUMA_LIMITS if isinstance(limits, (str, rk.Chain)) else limits
        check_solutions(s, 6, lim, wrist_reaches(PUMA, np.asarray(target, dtype=float)))


@given(targets=st.one_of(st.lists(rigid(), max_size=4).map(lambda ts: np.array(ts).reshape(-1, 4, 4)),
                         arrays([(2, 4, 4), (0, 4, 4), (4, 4), (1, 3, 4)])),
       q0=arrays([(6,), (5,)]), limits=st.one_of(st.just("default"), limits_for(6)))
def test_puma560_path_any_arguments(targets, q0, limits):
    out = check_call(lambda: rk.closed.puma560_path(targets, q0, limits=limits), "targets", "q0", "limits")
    if out is None:
        return
    q, ok, reachable = out
    k = len(targets)
    assert q.shape == (k, 6) and ok.shape == (k,) and ok.dtype == np.bool_
    assert reachable.shape == (k,) and reachable.dtype == np.bool_ and not np.any(ok & ~reachable)
    assert_finite(q)
    lim = PUMA_LIMITS if isinstance(limits, str) else limits
    prev = np.asarray(q0, dtype=float)
    for i in range(k):
        if ok[i]:
            assert wrist_reaches(PUMA, targets[i])(q[i])
            if lim is not None:
                assert np.all(q[i] >= lim[0]) and np.all(q[i] <= lim[1])
        else:
            assert np.array_equal(q[i], prev)
        prev = q[i]


@given(point=arrays([(2,), (3,)]), t1=st.one_of(st.none(), arrays([(5,), (0,), (2, 2)])),
       num=st.one_of(st.integers(-3, 40), st.sampled_from([10**12, 2**70, 1.5, "9", None, True])))
def test_rpr_self_motion_any_arguments(point, t1, num):
    chain = rk.robots.rpr()
    lower, upper = chain.limits
    assert rk.closed.rpr_self_motion is rk.robots.rpr_self_motion  # one function under two names
    out = check_call(lambda: rk.robots.rpr_self_motion(point, t1, num), "point", "t1", "num")
    if out is None:
        return
    k = len(t1) if t1 is not None else num
    assert out.shape == (2, k, 3) and out.dtype == np.float64
    p = np.asarray(point, dtype=float)
    for row in out.reshape(-1, 3):
        if np.isnan(row).any():
            assert np.isnan(row).all()  # a branch without a solution: a whole NaN row
            continue
        assert_finite(row)
        assert np.all(row >= lower - 1e-12) and np.all(row <= upper + 1e-12)
        assert np.linalg.norm(chain.fk(row)[:2, 3] - p) <= 1e-9


# --- (2) reported success equals verified success --------------------------------------------

def unit_vector(angle):
    return np.array([math.cos(angle), math.sin(angle)])


@given(a1=good_lengths, a2=good_lengths, scale=scales, q=finite_arrays((2,), -math.pi, math.pi),
       kind=st.sampled_from(["fk", "fk", "stretched", "folded", "far", "hole", "random"]),
       r=st.floats(0.0, 5.0), angle=st.floats(-math.pi, math.pi))
def test_planar_2r_success_is_reachability(a1, a2, scale, q, kind, r, angle):
    a1, a2 = a1 * scale, a2 * scale
    if kind in ("stretched", "folded"):
        q = np.array([q[0], 0.0 if kind == "stretched" else math.pi])
    if kind in ("fk", "stretched", "folded"):
        p = fk_planar((a1, a2), q)[0]
    else:
        lo, hi = abs(a1 - a2), a1 + a2
        dist = {"far": hi * (1 + 1e-6 + r), "hole": lo * (1 - 1e-6) * min(r, 1.0), "random": hi * r}[kind]
        p = dist * unit_vector(angle)
    s = check_solutions(rk.closed.planar_2r(p, a1, a2), 2, None,
                        lambda row: np.linalg.norm(fk_planar((a1, a2), row)[0] - p) <= MARGIN * TOL_P * (a1 + a2))
    dist = np.linalg.norm(p)
    reachable = abs(a1 - a2) <= dist <= a1 + a2
    margin = 1e-9 * (a1 + a2)
    if abs(dist - (a1 + a2)) > margin and abs(dist - abs(a1 - a2)) > margin:
        assert (len(s) > 0) == reachable, (p, dist, a1, a2, s)
    if kind in ("fk", "stretched", "folded"):
        assert len(s) > 0
        if not s.singular:
            assert wrapped(s.q, q).min() < 1e-6, (s, q)
    if kind in ("stretched", "folded") and len(s):
        assert s.singular and len(s) == 1


@given(a=st.tuples(good_lengths, good_lengths, st.floats(-2.0, 2.0)), scale=scales,
       q=finite_arrays((3,), -math.pi, math.pi), method=st.sampled_from(["algebraic", "geometric"]),
       kind=st.sampled_from(["fk", "fk", "singular", "random"]), r=st.floats(0.0, 3.0),
       angle=st.floats(-math.pi, math.pi), turns=st.sampled_from([0, 0, 1, -3, 10**6]))
def test_planar_3r_success_is_reachability(a, scale, q, method, kind, r, angle, turns):
    a = tuple(v * scale for v in a)
    if kind == "singular":
        q[1] = 0.0 if r < 1.5 else math.pi
    if kind == "random":
        phi = angle
        p = r * (a[0] + a[1] + abs(a[2])) * unit_vector(angle * 3.0)
    else:
        p, R = fk_planar(a, q)
        phi = math.atan2(R[1, 0], R[0, 0])
    phi += 2 * math.pi * turns  # the same orientation, many turns away
    s = rk.closed.planar_3r((p[0], p[1], phi), *a, method=method)
    size = a[0] + a[1] + abs(a[2])

    def reaches(row):
        pp, RR = fk_planar(a, row)
        return (np.linalg.norm(pp - p) <= MARGIN * TOL_P * size
                and abs(math.remainder(math.atan2(RR[1, 0], RR[0, 0]) - phi, 2 * math.pi)) <= MARGIN * TOL_R)

    check_solutions(s, 3, None, reaches)
    w = np.linalg.norm(p - a[2] * unit_vector(phi))
    margin = 1e-9 * size
    if abs(w - (a[0] + a[1])) > margin and abs(w - abs(a[0] - a[1])) > margin:
        assert (len(s) > 0) == (abs(a[0] - a[1]) <= w <= a[0] + a[1]), (p, phi, a, s)
    # Many turns round phi by up to an ulp (1e-9 rad at 1e6 turns): at a stretched or folded arm
    # that moves the wrist point out of reach, or sqrt(1e-9) away in the elbow, as it should.
    if kind != "random" and not (turns and abs(math.sin(q[1])) < 1e-3):
        assert len(s) > 0
        if not s.singular:
            assert wrapped(s.q, q).min() < 1e-6, (s, q)


@given(a2=good_lengths, a3=st.floats(-2.0, 2.0).filter(lambda v: abs(v) > 0.05), d1=st.floats(-1.0, 1.0),
       scale=scales, q=finite_arrays((3,), -math.pi, math.pi),
       kind=st.sampled_from(["fk", "fk", "axis", "stretched", "random"]), r=st.floats(0.0, 3.0),
       direction=finite_arrays((3,), -1.0, 1.0).filter(lambda v: np.linalg.norm(v) > 0.1))
def test_anthropomorphic_success_is_reachability(a2, a3, d1, scale, q, kind, r, direction):
    a2, a3, d1 = a2 * scale, a3 * scale, d1 * scale
    if kind == "stretched":
        q[2] = 0.0
    if kind == "random":
        p = np.array([0, 0, d1]) + r * (a2 + abs(a3)) * direction / np.linalg.norm(direction)
    elif kind == "axis":  # on the shoulder axis: q1 is free
        p = np.array([0.0, 0.0, d1 + (r / 3.0) * (a2 + abs(a3)) * (1 if direction[0] > 0 else -1)])
    else:
        p = fk_anthropomorphic(a2, a3, d1, q)
    s = rk.closed.anthropomorphic(p, a2, a3, d1)
    size = abs(d1) + a2 + abs(a3)
    check_solutions(s, 3, None, lambda row: np.linalg.norm(fk_anthropomorphic(a2, a3, d1, row) - p) <= MARGIN * TOL_P * size)
    dist = np.linalg.norm(p - (0, 0, d1))
    lo, hi = abs(a2 - abs(a3)), a2 + abs(a3)
    if abs(dist - hi) > 1e-9 * size and abs(dist - lo) > 1e-9 * size:
        assert (len(s) > 0) == (lo <= dist <= hi), (p, a2, a3, d1, s)
    if kind == "axis" and len(s):
        assert s.singular
    if kind in ("fk", "stretched"):
        assert len(s) > 0
        if not s.singular:
            assert wrapped(s.q, q).min() < 1e-6, (s, q)


def wrist_reachable(g, T):
    """(reachable, distance to the boundary): the wrist centre within the arm's annulus. Distances
    are lengths: the horizontal one's, |p_xy| - |d3|, from rho2 over |p_xy| + |d3| (rho2 itself, a
    squared length, made a wrist centre on that boundary of a 1e150 arm, rounded 1e284 below it,
    look clearly out of reach)."""
    pw = T[:3, 3] - g["d6"] * T[:3, 2]
    L = math.hypot(g["a3"], g["d4"])
    rho2 = pw[0] ** 2 + pw[1] ** 2 - g["d3"] ** 2
    horizontal = abs(rho2) / (math.hypot(pw[0], pw[1]) + abs(g["d3"]) or 1.0)
    if rho2 < 0:
        return False, horizontal
    dist = math.sqrt(rho2 + (pw[2] - g["d1"]) ** 2)
    return abs(g["a2"] - L) <= dist <= g["a2"] + L, min(abs(dist - g["a2"] - L), abs(dist - abs(g["a2"] - L)), horizontal)


@given(geometry=st.tuples(good_lengths, st.floats(-0.5, 0.5), st.floats(-0.5, 0.5), st.floats(-1.0, 1.0),
                          st.floats(-0.5, 0.5), st.floats(-0.5, 0.5)),
       puma=st.booleans(), scale=scales, q=finite_arrays((6,), -math.pi, math.pi),
       kind=st.sampled_from(["fk", "fk", "wrist", "random"]), T=rigid(2.0), limited=st.booleans())
def test_spherical_wrist_success_is_reachability(geometry, puma, scale, q, kind, T, limited):
    if puma:
        g = dict(PUMA)
    else:
        g = dict(zip(("a2", "a3", "d3", "d4", "d1", "d6"), geometry))
        assume(math.hypot(g["a3"], g["d4"]) > 0.05)
    g = {k: v * scale for k, v in g.items()}
    limits = PUMA_LIMITS if limited else None
    if limited:
        # Strictly inside: at a limit, the rounding of a near-singular pose may put the solution
        # a hair outside, and the limit filter rightly drops it.
        q = np.clip(q, PUMA_LIMITS[0] + 1e-6, PUMA_LIMITS[1] - 1e-6)
    if kind == "wrist":
        q[4] = 0.0  # wrist singular: only q4 + q6 is determined
    if kind != "random":
        T = fk_wrist(g, q)
    else:
        T = T.copy()
        T[:3, 3] *= scale
    if puma and scale == 1.0:
        s = rk.closed.puma560(T, limits="default" if limited else None)
    else:
        s = rk.closed.spherical_wrist_6r(T, g["a2"], g["a3"], g["d3"], g["d4"], g["d1"], g["d6"], limits=limits)
    check_solutions(s, 6, limits, wrist_reaches(g, T))
    reachable, gap = wrist_reachable(g, T)
    size = sum(abs(v) for v in g.values())
    if not limited and gap > 1e-6 * size:
        assert (len(s) > 0) == reachable, (T, g, s)
    if kind != "random":
        assert len(s) > 0, (q, g)
        if abs(math.sin(q[4])) < 1e-6:
            # Wrist singular (also when q5 = 0 came from "fk"): the pose fixes only q4 + q6 (q5 = 0)
            # or q4 - q6 (q5 = pi), and a solution may carry (q4 + pi, -q5, q6 + pi). An elbow
            # within kCosEps of singular as well is returned once for its two, which differ by up
            # to ~3e-6 (elbows_apart in ik_closed.cpp).
            arm_tol = 1e-5 if s.singular else 1e-6
            assert any(wrapped(row[:3], q[:3]) < arm_tol and (wrapped(row[3] + row[5], q[3] + q[5]) < 1e-6
                                                              or wrapped(row[3] - row[5], q[3] - q[5]) < 1e-6)
                       for row in s.q), (s, q)
        elif not s.singular:
            assert wrapped(s.q, q).min() < 1e-6, (s, q)


@given(q=finite_arrays((2,), -math.pi, math.pi), stroke=st.floats(0.1, 3.0), back=st.booleans())
def test_planar_rp_success_is_reachability(q, stroke, back):
    p = fk_rp(q)
    lower = -stroke if back else 0.0
    limits = ([-math.inf, lower], [math.inf, stroke])
    s = check_solutions(rk.closed.planar_rp(p, limits=limits), 2, limits,
                        lambda row: np.linalg.norm(fk_rp(row) - p) <= MARGIN * TOL_P * np.linalg.norm(p),
                        prismatic=[False, True])
    assert len(s) == (2 if np.any(p != 0) else 1)  # both strokes, each marked (one at the origin)
    d = np.linalg.norm(p)
    if abs(d - stroke) > 1e-9:
        assert s.within_limits.any() == (d <= stroke)
    if abs(q[1]) <= stroke and (q[1] >= 0 or back) and d > 0:
        off = np.maximum(np.abs(np.angle(np.exp(1j * (s.q[:, 0] - q[0])))), np.abs(s.q[:, 1] - q[1]))
        assert off.min() < 1e-9, (s, q)


# --- regressions ----------------------------------------------------------------------------

def test_planar_3r_huge_phi_is_the_same_orientation():
    """phi = 1e300: the solutions were built from remainder(phi, 2 pi) (the double 2 pi) while the
    forward model turns by cos / sin of phi: the tool missed the target by up to 2 link lengths."""
    phi = 1e300
    target = np.array([1.2, 0.3]) + 0.5 * unit_vector(phi)  # the wrist point at (1.2, 0.3)
    s = rk.closed.planar_3r((*target, phi), 1.0, 1.0, 0.5)
    assert len(s) == 2
    for row in s.q:
        p, R = fk_planar((1.0, 1.0, 0.5), row)
        assert np.allclose(p, target, atol=1e-12)
        assert np.allclose(R, [[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]], atol=1e-12)


@pytest.mark.parametrize("scale", [1e-160, 1e160])
def test_tiny_and_huge_arms_are_solved(scale):
    """The squares of lengths underflowed (1e-160) or overflowed (1e160): a reachable target came back empty."""
    a1, a2 = 1.0 * scale, 0.7 * scale
    p = fk_planar((a1, a2), (0.3, 1.1))[0]
    s = rk.closed.planar_2r(p, a1, a2)
    assert len(s) == 2 and wrapped(s.q, (0.3, 1.1)).min() < 1e-12
    s = rk.closed.anthropomorphic(fk_anthropomorphic(a1, a2, 0.1 * scale, (0.2, 0.3, 0.4)), a1, a2, 0.1 * scale)
    assert len(s) == 4 and wrapped(s.q, (0.2, 0.3, 0.4)).min() < 1e-12


def test_planar_rp_near_the_origin_keeps_its_direction():
    """A point 1e-20 from the origin was taken for the origin (theta1 = 0), 100 % off."""
    s = rk.closed.planar_rp((0.0, 1e-20), limits=([-math.inf, 0.0], [math.inf, 1.0]))
    assert len(s) == 2 and s.within_limits.tolist() == [True, False] and not s.singular
    assert np.allclose(fk_rp(s.q[0]), (0.0, 1e-20), rtol=1e-12, atol=1e-32)


def test_a_pose_a_hair_beyond_reach_is_not_a_solution():
    """The elbow cosine is clamped within 1e-12 of 1: up to there the stretched arm is returned,
    as it reaches the target within the stated tolerance; it is verified all the same."""
    s = rk.closed.planar_2r((2.0 + 1e-13, 0.0), 1.0, 1.0)
    assert len(s) == 1 and s.singular
    assert abs(fk_planar((1.0, 1.0), s.q[0])[0][0] - 2.0) < 1e-12
    assert len(rk.closed.planar_2r((2.0 + 1e-6, 0.0), 1.0, 1.0)) == 0


def test_planar_3r_geometric_folded_elbow_with_a_shorter_first_link():
    """Elbow folded, a1 < a2: the geometric method took beta = acos(-0.9999999999999999) = pi - 1.5e-8
    (the tip 5e-9 off) where the folded arm needs beta = pi exactly."""
    a = (1.0 / 3.0, 1.0, 0.0)
    p, R = fk_planar(a, (0.0, math.pi, 0.0))
    s = rk.closed.planar_3r((p[0], p[1], math.atan2(R[1, 0], R[0, 0])), *a, method="geometric")
    assert s.postures == ["elbow folded"] and s.singular
    assert np.linalg.norm(fk_planar(a, s.q[0])[0] - p) < 1e-15


@pytest.mark.parametrize("method", ["algebraic", "geometric"])
def test_nearly_folded_equal_links_reach_a_point_near_the_first_joint(method):
    """a1 = a2 and the tip (or wrist point) 4e-8 from the first joint: the elbow cosine -1 + 8e-16,
    rounded and clamped to -1, folded the arm onto the joint, 4e-8 off; the verification rejected it
    and a reachable point came back with no solution. Both elbows are returned (singular): their
    first angles are pi apart (the elbow on either side of the joint), not one posture twice."""
    s = rk.closed.planar_2r((0.0, 4e-8), 1.0, 1.0)
    assert len(s) == 2 and s.singular and wrapped(s.q[0, 0], s.q[1, 0]) > 3.0
    for q in s.q:
        assert np.linalg.norm(fk_planar((1.0, 1.0), q)[0] - (0.0, 4e-8)) < 1e-15
    s = rk.closed.planar_3r((0.5, 4e-8, 0.0), 1.0, 1.0, 0.5, method=method)
    assert len(s) == 2 and s.singular and wrapped(s.q[0, 0], s.q[1, 0]) > 3.0
    for q in s.q:
        assert np.linalg.norm(fk_planar((1.0, 1.0, 0.5), q)[0] - (0.5, 4e-8)) < 1e-15
    p = np.array([0.0, 0.0, 3.97364299e-08])  # on the shoulder axis, too
    s = rk.closed.anthropomorphic(p, 1.0, 1.0)
    assert len(s) == 2 and s.singular
    for q in s.q:
        assert np.linalg.norm(fk_anthropomorphic(1.0, 1.0, 0.0, q) - p) < 1e-15


@pytest.mark.parametrize("limited", [False, True])
def test_folded_equal_links_near_the_shoulder_and_wrist_singularities_find_their_source(limited):
    """Found by `make fuzz`: a2 = -a3 = 0.5 (equal links, the elbow folded at q3 = 0), every joint at
    1.2e-7, the wrist centre 6e-8 from the shoulder. One elbow was returned for the singular elbow,
    the mirrored one (q2 = -pi + 2e-7): the source was not among the solutions, and with the PUMA's
    limits (which the mirrored one leaves) nothing came back."""
    g = dict(zip(("a2", "a3", "d3", "d4", "d1", "d6"), (0.5, -0.5, 0.0, 0.0, 0.0, 0.0)))
    q = np.full(6, 1.1920929e-07)
    T = fk_wrist(g, q)
    limits = PUMA_LIMITS if limited else None
    s = rk.closed.spherical_wrist_6r(T, g["a2"], g["a3"], g["d3"], g["d4"], g["d1"], g["d6"], limits=limits)
    check_solutions(s, 6, limits, wrist_reaches(g, T))
    assert s.singular and wrapped(s.q, q).min() < 1e-6


@pytest.mark.parametrize("q0", [41561584.0, 1e17, -1e300])
def test_puma560_path_from_a_far_q0_reaches_its_target(q0):
    """Shifted by whole turns towards q0 = 4.2e7 rad the angles carried 7e-9 rad of rounding, and at
    1e17 (ulp 16 rad) nothing of the angle: ok was True for joints that missed the target."""
    T = np.array([[-1.0, 0.0, 0.0, -0.54838059], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, -1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    q, ok, _ = rk.closed.puma560_path(T[None], np.full(6, q0), limits=None)
    assert ok[0] and wrist_reaches(PUMA, T)(q[0])
    assert np.all(np.abs(q[0]) <= 2.0**20) and np.all(np.abs(q[0]) > 2.0**20 - 2 * math.pi)  # as near q0 as allowed
