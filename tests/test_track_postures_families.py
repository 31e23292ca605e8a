"""rk.track_postures(method="closed") on arms whose closed form is read from their geometry (the
UR5 from its URDF, the ABB IRB 120): every waypoint of a path made from known joints is reached
(the chain's own forward model), with the same plan as on the UR5's DH table where the two arms are
the same."""

import numpy as np
from ur_urdf import UR5_URDF

import robokin as rk


def path(chain, rng, count=40):
    q = np.linspace(rng.uniform(-1, 1, 6), rng.uniform(-1, 1, 6), count)
    return chain.fk(q)


def test_the_ur5_urdf_is_tracked_as_its_dh_table(rng):
    urdf, dh = rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), rk.robots.ur5()
    poses = path(dh, rng)
    a = rk.track_postures(urdf, poses, 0.05, qdot_max=2.0, method="closed")
    b = rk.track_postures(dh, poses, 0.05, qdot_max=2.0, method="closed")
    assert np.all(a.success) and np.allclose(urdf.fk(a.q), poses, atol=1e-9)
    assert a.postures == b.postures and np.max(np.abs(a.q - b.q)) < 1e-6


def test_a_spherical_wrist_arm_is_tracked_in_closed_form(rng):
    irb = rk.robots.irb120()
    poses = path(irb, rng)
    r = rk.track_postures(irb, poses, 0.05, qdot_max=2.0, method="closed")
    assert np.all(r.success) and np.allclose(irb.fk(r.q), poses, atol=1e-9)
    assert all(p.startswith("shoulder") for p in r.postures)
