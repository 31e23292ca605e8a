"""Property tests of the posture calls: rk.closed.ur / ur_batch, rk.track_postures,
rk.count_reconfigurations, rk.closed.general_3r, rk.cuspidal.

Rules. (1) Any arguments: a result whose every number is finite (NaN only as the batch's "no
solution" rows), or ValueError / TypeError naming an argument. (2) Reported success equals verified
success: every returned UR solution reaches its target by the textbook DH product, within the
limits; a target made from random joints is reached by one of them.
"""

import math

import numpy as np
from fuzz import arrays, assert_finite, check_call, finite_arrays, wild_floats
from hypothesis import given, settings
from hypothesis import strategies as st

import robokin as rk
from dh_reference import fk_dh

COVERS = {"closed.ur", "closed.ur_batch", "track_postures", "count_reconfigurations", "closed.general_3r", "cuspidal"}

P = math.pi
UR5 = rk.robots.ur5()
UR5_ROWS = [(0.0, P / 2, 0.089159, 0.0, "R"), (-0.425, 0.0, 0.0, 0.0, "R"), (-0.39225, 0.0, 0.0, 0.0, "R"),
            (0.0, P / 2, 0.10915, 0.0, "R"), (0.0, -P / 2, 0.09465, 0.0, "R"), (0.0, 0.0, 0.0823, 0.0, "R")]

joints = finite_arrays((6,), -2 * P, 2 * P)
special = st.sampled_from([0.0, P / 2, -P / 2, P, 1e-9, -1e-12])


@st.composite
def ur_joints(draw):
    """Random joints, some pinned to the singular values (q3, q5 = 0 or pi, ...)."""
    q = np.array(draw(joints))
    for i in draw(st.lists(st.integers(0, 5), max_size=3)):
        q[i] = draw(special)
    return q


geometry = st.fixed_dictionaries({k: st.one_of(st.floats(-1.0, 1.0), wild_floats)
                                  for k in ("d1", "a2", "a3", "d4", "d5", "d6")})


@settings(max_examples=150)
@given(ur_joints())
def test_ur_every_solution_reaches_and_the_source_is_found(q):
    T = fk_dh(UR5_ROWS, q)
    s = rk.closed.ur(T, UR5, limits=None)
    assert len(s) >= 1
    assert_finite(s.q)
    for row in s.q:
        F = fk_dh(UR5_ROWS, row)
        assert np.linalg.norm(F[:3, 3] - T[:3, 3]) < 1e-8
        assert np.max(np.abs(F[:3, :3] - T[:3, :3])) < 1e-7
    if not s.singular:
        d = np.remainder(s.q - q + P, 2 * P) - P
        assert np.min(np.max(np.abs(d), axis=1)) < 1e-6


def ur_rows(g):
    """The UR table of a geometry dict as standard DH rows (rk.closed.ur's docstring)."""
    return [(0.0, P / 2, g["d1"], 0.0, "R"), (g["a2"], 0.0, 0.0, 0.0, "R"), (g["a3"], 0.0, 0.0, 0.0, "R"),
            (0.0, P / 2, g["d4"], 0.0, "R"), (0.0, -P / 2, g["d5"], 0.0, "R"), (0.0, 0.0, g["d6"], 0.0, "R")]


def assert_ur_solutions_reach(g, s, T):
    """Every solution puts the arm g's tool on T by the textbook DH product, within the core's
    verified tolerance (1e-9 of the arm's size in position, 1e-8 in the rotation's entries) and the
    reference's own rounding."""
    size = sum(abs(float(g[k])) for k in ("d1", "a2", "a3", "d4", "d5", "d6"))
    for row in s.q:
        F = fk_dh(ur_rows(g), row)
        miss = math.hypot(*(F[:3, 3] - T[:3, 3]))
        assert miss <= 4e-9 * size + 1e-12, (g, row, miss)
        assert np.max(np.abs(F[:3, :3] - T[:3, :3])) <= 4e-8, (g, row)


@settings(max_examples=100)
@given(geometry, ur_joints(), st.one_of(st.none(), st.just("default"), st.tuples(joints, joints), wild_floats))
def test_ur_any_geometry_and_limits(g, q, limits):
    s = check_call(lambda: rk.closed.ur(UR5.fk(q), g, limits=limits), "robot", "limits", "target")
    if s is not None:
        assert_finite(s.q)
        assert_ur_solutions_reach(g, s, UR5.fk(q))
    b = check_call(lambda: rk.closed.ur_batch(UR5.fk(q)[None], UR5, limits=limits), "limits", "targets")
    if b is not None:
        assert b.q.shape == (1, 8, 6)


@settings(max_examples=100)
@given(arrays(), st.sampled_from([None, "default"]))
def test_ur_any_target(target, limits):
    check_call(lambda: rk.closed.ur(target, UR5, limits), "target")
    check_call(lambda: rk.closed.ur_batch(target, UR5, limits), "targets")


@settings(max_examples=40)
@given(st.one_of(arrays(), st.just(None)), wild_floats, st.one_of(wild_floats, arrays()),
       st.sampled_from(["closed", "numerical", "x"]), st.one_of(st.none(), arrays()))
def test_track_postures_any_arguments(poses, dt, qdot_max, method, q0):
    r = check_call(lambda: rk.track_postures(UR5, poses, dt, qdot_max=qdot_max, method=method, q0=q0, starts=2),
                   "poses", "dt", "qdot_max", "method", "q0")
    if r is not None:
        assert_finite(r.q, r.motion)


@settings(max_examples=30)
@given(st.lists(ur_joints(), min_size=1, max_size=5), st.floats(0.01, 1.0), st.floats(0.1, 5.0))
def test_track_postures_reaches_every_successful_waypoint(qs, dt, vmax):
    poses = UR5.fk(np.array(qs))
    r = rk.track_postures(UR5, poses, dt, qdot_max=vmax)
    assert np.all(r.success)
    for T, q in zip(poses, r.q):
        assert np.allclose(UR5.fk(q), T, atol=1e-8)
    again = rk.count_reconfigurations(r.q, dt, vmax, chain=UR5)
    assert np.array_equal(again, r.reconfigurations)


@settings(max_examples=100)
@given(arrays(), wild_floats, st.one_of(wild_floats, arrays()), st.one_of(st.none(), arrays()))
def test_count_reconfigurations_any_arguments(q, dt, vmax, q0):
    r = check_call(lambda: rk.count_reconfigurations(q, dt, vmax, q0=q0), "q", "dt", "qdot_max", "q0")
    if r is not None:
        assert r.dtype.kind == "i"


dh_rows3 = st.lists(st.tuples(st.floats(-2, 2), st.floats(-4, 4), st.floats(-2, 2), st.floats(-4, 4)),
                    min_size=3, max_size=3)


@settings(max_examples=60)
@given(dh_rows3, finite_arrays((3,), -4.0, 4.0), st.one_of(arrays(), finite_arrays((3,), -4.0, 4.0)))
def test_general_3r_any_geometry_and_target(rows, q, target):
    chain = rk.Chain.from_dh([r + ("R",) for r in rows])
    for p in (chain.fk(np.asarray(q))[:3, 3], target):
        s = check_call(lambda: rk.closed.general_3r(p, chain, limits=None), "chain", "target")
        if s is None:
            continue
        assert_finite(s.q)
        assert len(s) <= 4 or s.singular
        for row in s.q:
            assert np.linalg.norm(chain._fk_kdl(row)[:3, 3] - np.asarray(p, float)) <= 1e-8 * (1 + sum(
                abs(v) for r in rows for v in (r[0], r[2])))


@settings(max_examples=15)
@given(dh_rows3, st.one_of(st.integers(-5, 40), st.just(2.5), st.none()))
def test_cuspidal_any_geometry(rows, resolution):
    chain = rk.Chain.from_dh([r + ("R",) for r in rows])
    c = check_call(lambda: rk.cuspidal(chain, resolution=resolution), "chain", "resolution")
    if c is not None:
        assert_finite(c.cusps)
        assert c.cuspidal == (len(c.cusps) > 0) and c.aspects >= 0
