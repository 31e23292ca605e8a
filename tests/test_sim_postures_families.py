"""The simulator's `n` key on arms whose closed form is read from their geometry (the ABB IRB 120,
the UR5 and the KUKA KR 16 from their URDFs): it cycles through every closed-form posture within the limits of the
current tool pose (rk.closed.solve's), each reached with the tool where it was."""

import numpy as np
import pytest
from kr16_urdf import KR16_URDF
from ur_urdf import UR5_URDF

import robokin as rk
from robokin_sim.scene_serial import SerialScene


@pytest.mark.parametrize("name", ["irb120", "ur5 urdf", "kr16 urdf"])
def test_n_visits_every_posture_within_the_limits(name):
    if name == "irb120":
        chain, scene_name, q0 = rk.robots.irb120(), "irb120", np.radians([10, 20, -30, 40, 50, 60])
    elif name == "ur5 urdf":
        chain, scene_name, q0 = rk.Chain.from_urdf(UR5_URDF, "base", "tool0"), "urdf", np.array([0.3, -1.2, 1.4, 0.2, 1.1, 0.4])
    else:
        chain, scene_name, q0 = rk.Chain.from_urdf(KR16_URDF), "urdf", np.radians([10, -70, 90, 20, 50, 30])
    scene = SerialScene(chain, name=scene_name, q0=q0)
    T0 = chain.fk(scene.q)
    expected = rk.closed.solve(T0, chain).only_within_limits()
    assert len(expected) >= 2  # the IRB 120's limits keep 2 of its 8 here
    labels = set()
    for _ in range(len(expected)):
        scene.press("n")
        assert scene.mode == "posture", scene.message
        while scene.mode == "posture":
            scene.step(frozenset())
        labels.add(scene.posture.split(": ", 1)[1])
        assert np.allclose(chain.fk(scene.q), T0, rtol=0, atol=1e-9)
    assert labels == set(expected.postures)
