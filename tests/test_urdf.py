"""Chains from URDF (urdfdom parses, robokin builds the KDL tree as kdl_parser did): forward
kinematics against hand-written transforms and against the DH catalogue; joint limits read from the
file."""

import math

import numpy as np
import pytest

import robokin as rk

SMALL = """<?xml version="1.0"?>
<robot name="small">
  <link name="base_link"/><link name="link1"/><link name="link2"/><link name="link3"/><link name="tool"/>
  <joint name="j1" type="revolute">
    <parent link="base_link"/><child link="link1"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1.0" upper="1.0" effort="10" velocity="1"/>
  </joint>
  <joint name="j2" type="prismatic">
    <parent link="link1"/><child link="link2"/>
    <origin xyz="0.5 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0.0" upper="0.3" effort="10" velocity="1"/>
  </joint>
  <joint name="j3" type="continuous">
    <parent link="link2"/><child link="link3"/>
    <origin xyz="0.2 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="tool_joint" type="fixed">
    <parent link="link3"/><child link="tool"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
  </joint>
</robot>
"""


def tz(d):
    m = np.eye(4)
    m[2, 3] = d
    return m


def tx(a):
    m = np.eye(4)
    m[0, 3] = a
    return m


def rz(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def ry(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1.0]])


def small_fk(q):
    return tz(0.1) @ rz(q[0]) @ tx(0.5) @ tx(q[1]) @ tx(0.2) @ ry(q[2]) @ tz(0.1)


def urdf_from_dh(name, rows, lower, upper):
    """A URDF whose joint i has the fixed part Tz(d) Tx(a) Rx(alpha) of DH row i - 1 as its origin."""
    links = "".join(f'<link name="l{i}"/>' for i in range(len(rows) + 1)) + '<link name="tool"/>'
    joints, xyz, rpy = [], "0 0 0", "0 0 0"
    for i, (a, alpha, d) in enumerate(rows):
        joints.append(
            f'<joint name="j{i + 1}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
            f'<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="0 0 1"/>'
            f'<limit lower="{float(lower[i])!r}" upper="{float(upper[i])!r}" effort="1" velocity="1"/></joint>'
        )
        xyz, rpy = f"{a!r} 0 {d!r}", f"{alpha!r} 0 0"
    joints.append(
        f'<joint name="flange" type="fixed"><parent link="l{len(rows)}"/><child link="tool"/>'
        f'<origin xyz="{xyz}" rpy="{rpy}"/></joint>'
    )
    return f'<?xml version="1.0"?><robot name="{name}">{links}{"".join(joints)}</robot>'


UR5_DH = [(0.0, math.pi / 2, 0.089159), (-0.425, 0.0, 0.0), (-0.39225, 0.0, 0.0), (0.0, math.pi / 2, 0.10915),
          (0.0, -math.pi / 2, 0.09465), (0.0, 0.0, 0.0823)]
PUMA_DH = [(0.0, math.pi / 2, 0.0), (0.4318, 0.0, 0.0), (0.0203, -math.pi / 2, 0.15005), (0.0, math.pi / 2, 0.4318),
           (0.0, -math.pi / 2, 0.0), (0.0, 0.0, 0.0)]


def test_small_urdf_fk_and_limits(tmp_path):
    chain = rk.Chain.from_urdf(SMALL, "base_link", "tool")
    assert chain.dof == 3 and chain.joint_types == "RPR"
    lo, hi = chain.limits
    assert np.allclose(lo[:2], [-1.0, 0.0]) and np.allclose(hi[:2], [1.0, 0.3])
    assert lo[2] == -math.inf and hi[2] == math.inf  # continuous
    rng = np.random.default_rng(0)
    for _ in range(20):
        q = rng.uniform([-1, 0, -3], [1, 0.3, 3])
        assert np.allclose(chain.fk(q), small_fk(q), atol=1e-12)
    # the same from a file, and a sub-chain
    path = tmp_path / "small.urdf"
    path.write_text(SMALL)
    assert np.allclose(rk.Chain.from_urdf(path, "base_link", "tool").fk([0.3, 0.1, 0.2]), small_fk([0.3, 0.1, 0.2]))
    assert np.allclose(rk.Chain.from_urdf(str(path), "base_link", "tool").fk([0.3, 0.1, 0.2]), small_fk([0.3, 0.1, 0.2]))
    sub = rk.Chain.from_urdf(SMALL, "link1", "link2")
    assert sub.dof == 1 and sub.joint_types == "P"


@pytest.mark.parametrize("name", ["ur5", "puma560"])
def test_urdf_written_from_the_dh_table_matches_the_catalogue(name):
    ref = getattr(rk.robots, name)()
    lo, hi = ref.limits
    rows = UR5_DH if name == "ur5" else PUMA_DH
    chain = rk.Chain.from_urdf(urdf_from_dh(name, rows, lo, hi), "l0", "tool")
    assert chain.dof == 6
    assert np.allclose(chain.limits[0], lo) and np.allclose(chain.limits[1], hi)
    q = np.random.default_rng(1).uniform(lo, hi, (50, 6))
    assert np.allclose(chain.fk(q), ref.fk(q), atol=1e-12)
    assert np.allclose(chain.jacobian(q[0]), ref.jacobian(q[0]), atol=1e-12)
    # and IK works on it
    r = rk.ik(chain, ref.fk(q[0]), np.zeros(6), restarts=20, seed=0)
    assert r.success and np.allclose(ref.fk(r.q), ref.fk(q[0]), atol=1e-9)


def test_bad_urdf_input():
    with pytest.raises(ValueError, match="path_or_string"):
        rk.Chain.from_urdf("<robot", "a", "b")
    with pytest.raises(ValueError, match="path_or_string"):
        rk.Chain.from_urdf("/no/such/file.urdf", "a", "b")
    with pytest.raises(TypeError, match="path_or_string"):
        rk.Chain.from_urdf(42, "a", "b")
    with pytest.raises(ValueError, match="base"):
        rk.Chain.from_urdf(SMALL, "nowhere", "tool")
    with pytest.raises(ValueError, match="tip"):
        rk.Chain.from_urdf(SMALL, "base_link", "nowhere")
    with pytest.raises(ValueError, match="base, tip"):
        rk.Chain.from_urdf(SMALL, "tool", "tool")


def test_fast_path_equals_kdl_with_joint_origins(rng):
    """URDF joints get a non-zero KDL origin, as kdl_parser gave them (pose(q) = Frame(Rot(axis, q), origin)): the
    specialised evaluation path must agree with KDL's solvers on such chains too."""
    ur5 = rk.robots.ur5()
    for xml, base in ((SMALL, "base_link"), (urdf_from_dh("ur5", UR5_DH, *ur5.limits), "l0")):
        chain = rk.Chain.from_urdf(xml, base, "tool")
        for q in rng.uniform(-1, 1, size=(20, chain.dof)):
            np.testing.assert_allclose(chain.fk(q), chain._fk_kdl(q), atol=1e-12)
            np.testing.assert_allclose(chain.jacobian(q), chain._jacobian_kdl(q), atol=1e-12)
