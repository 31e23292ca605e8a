"""Property tests of the robot catalogue by name (rk.robots.names / get) and of its real arms:
arbitrary names give a chain or a ValueError / TypeError naming ``name``; every arm's FK at arbitrary
joints within its limits is rigid and equals KDL's; the default IK on a pose of the arm claims
success only for a pose KDL's FK confirms."""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import robokin as rk
from fuzz import check_call

COVERS = {
    "robots.names", "robots.get",
    "robots.ur3", "robots.ur10", "robots.ur3e", "robots.ur5e", "robots.ur10e", "robots.ur16e",
    "robots.panda", "robots.iiwa14", "robots.irb120", "robots.gen3",
}

ARMS = {name: rk.robots.get(name) for name in ("ur3", "ur10", "ur3e", "ur5e", "ur10e", "ur16e", "panda", "iiwa14",
                                                "irb120", "gen3")}
names_any = st.one_of(st.sampled_from(rk.robots.names()), st.text(max_size=12),
                      st.sampled_from([None, 5, b"panda", ["ur5"], "PANDA", " panda", "ur5\x00"]))


@given(name=names_any)
def test_get_with_arbitrary_names(name):
    chain = check_call(lambda: rk.robots.get(name), "name")
    if chain is None:
        assert name not in rk.robots.names()
        return
    assert name in rk.robots.names() and isinstance(chain, rk.Chain) and chain.dof >= 1


@given(name=st.sampled_from(sorted(ARMS)), u=st.lists(st.floats(0, 1), min_size=7, max_size=7))
def test_arms_fk_and_default_ik(name, u):
    chain = ARMS[name]
    assert rk.robots.names().count(name) == 1
    lo, hi = chain.limits
    lo, hi = np.where(np.isfinite(lo), lo, -math.pi), np.where(np.isfinite(hi), hi, math.pi)
    q = lo + np.asarray(u[: chain.dof]) * (hi - lo)
    T = chain.fk(q)
    np.testing.assert_allclose(T[:3, :3].T @ T[:3, :3], np.eye(3), atol=1e-12)
    np.testing.assert_allclose(T, chain._fk_kdl(q), atol=1e-12)
    r = rk.ik(chain, T, (lo + hi) / 2, seed=0)
    assert np.all(r.q >= chain.limits[0]) and np.all(r.q <= chain.limits[1])
    F = chain._fk_kdl(r.q)
    R = F[:3, :3].T @ T[:3, :3]
    ep = np.linalg.norm(F[:3, 3] - T[:3, 3])
    er = math.atan2(np.linalg.norm([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2, (np.trace(R) - 1) / 2)
    tol = rk.IK_DEFAULTS["tol_p"]
    if r.success:  # what the solver claims, KDL's FK confirms (to rounding)
        assert ep < tol * (1 + 1e-6) and er < tol * (1 + 1e-6), (ep, er)
    else:
        assert ep > tol * (1 - 1e-6) or er > tol * (1 - 1e-6), (ep, er)
