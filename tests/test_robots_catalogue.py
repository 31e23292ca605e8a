"""The catalogue's real arms: each against a URDF written here from the same published numbers
(loaded by rk.Chain.from_urdf, whose joints are general frames, not DH rows), against KDL's own
solvers, and against positions worked out by hand from the published dimensions; names() / get().

The numbers below are typed again from the makers' tables (not imported from robokin.robots), so a
typo on either side fails the comparison.
"""

import math

import numpy as np
import pytest

import robokin as rk
from dh_reference import rot_x as rx, rot_z as rz, trans

P = math.pi
INF = math.inf
DEG = P / 180


def ur_spec(d1, a2, a3, d4, d5, d6, wrist3_unlimited=False):
    rows = [(0.0, P / 2, d1, 0.0), (a2, 0.0, 0.0, 0.0), (a3, 0.0, 0.0, 0.0), (0.0, P / 2, d4, 0.0),
            (0.0, -P / 2, d5, 0.0), (0.0, 0.0, d6, 0.0)]
    hi = [2 * P] * 5 + [INF if wrist3_unlimited else 2 * P]
    return dict(kind="standard", rows=rows, lower=[-h for h in hi], upper=hi)


# Universal Robots' "DH Parameters for calculations of kinematics and dynamics".
SPECS = {
    "ur3": ur_spec(0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819, True),
    "ur5": ur_spec(0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823),
    "ur10": ur_spec(0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922),
    "ur3e": ur_spec(0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921, True),
    "ur5e": ur_spec(0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996),
    "ur10e": ur_spec(0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655),
    "ur16e": ur_spec(0.1807, -0.4784, -0.36, 0.17415, 0.11985, 0.11655),
    # Franka Emika, FCI docs "Robot and interface specifications": Craig's modified DH (a, alpha, d, theta)
    # and the flange d = 0.107.
    "panda": dict(
        kind="modified",
        rows=[(0, 0, 0.333, 0), (0, -P / 2, 0, 0), (0, P / 2, 0.316, 0), (0.0825, P / 2, 0, 0),
              (-0.0825, -P / 2, 0.384, 0), (0, P / 2, 0, 0), (0.088, P / 2, 0, 0)],
        flange=0.107,
        lower=[-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973],
        upper=[2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973],
    ),
    # KUKA LBR iiwa 14 R820: 360 / 420 / 400 / 126 mm; +-170, 120, 170, 120, 170, 120, 175 deg.
    "iiwa14": dict(
        kind="standard",
        rows=[(0, -P / 2, 0.36, 0), (0, P / 2, 0, 0), (0, P / 2, 0.42, 0), (0, -P / 2, 0, 0),
              (0, -P / 2, 0.4, 0), (0, P / 2, 0, 0), (0, 0, 0.126, 0)],
        lower=[-170 * DEG, -120 * DEG, -170 * DEG, -120 * DEG, -170 * DEG, -120 * DEG, -175 * DEG],
        upper=[170 * DEG, 120 * DEG, 170 * DEG, 120 * DEG, 170 * DEG, 120 * DEG, 175 * DEG],
    ),
    # ABB IRB 120 product specification: 290 / 270 / 70 / 302 / 72 mm.
    "irb120": dict(
        kind="standard",
        rows=[(0, -P / 2, 0.29, 0), (0.27, 0, 0, -P / 2), (0.07, -P / 2, 0, 0), (0, P / 2, 0.302, 0),
              (0, -P / 2, 0, 0), (0, 0, 0.072, P)],
        lower=[-165 * DEG, -110 * DEG, -110 * DEG, -160 * DEG, -120 * DEG, -400 * DEG],
        upper=[165 * DEG, 110 * DEG, 70 * DEG, 160 * DEG, 120 * DEG, 400 * DEG],
    ),
    # Kinova Gen3 User Guide, classic DH of the 7-DoF arm (base frame Rx(pi)).
    "gen3": dict(
        kind="standard",
        base=P,
        rows=[(0, P / 2, -(0.1564 + 0.1284), 0), (0, P / 2, -(0.0054 + 0.0064), P),
              (0, P / 2, -(0.2104 + 0.2104), P), (0, P / 2, -(0.0064 + 0.0064), P),
              (0, P / 2, -(0.2084 + 0.1059), P), (0, P / 2, 0, P), (0, P, -(0.1059 + 0.0615), P)],
        lower=[-INF, -128.9 * DEG, -INF, -147.8 * DEG, -INF, -120.3 * DEG, -INF],
        upper=[INF, 128.9 * DEG, INF, 147.8 * DEG, INF, 120.3 * DEG, INF],
    ),
}

NEW_ARMS = sorted(SPECS)
OLD = ["planar_3r", "prr", "puma560", "rp", "rpr"]


def rpy_of(R):
    """URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
    if abs(math.cos(pitch)) < 1e-12:  # gimbal lock: put it all in roll
        return math.atan2(-R[1, 2], R[1, 1]), pitch, 0.0
    return math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])


def joint_origins(spec):
    """The frame before each joint (parent link to joint, revolute about its z) and the flange,
    composed from the DH numbers: standard A_i = Rz(theta_i + q) Tz(d) Tx(a) Rx(alpha), modified
    A_i = Rx(alpha) Tx(a) Rz(theta_i + q) Tz(d)."""
    origins, before = [], rx(spec.get("base", 0.0))
    for a, alpha, d, theta in spec["rows"]:
        if spec["kind"] == "standard":
            origins.append(before @ rz(theta))
            before = trans(0, 0, d) @ trans(a, 0, 0) @ rx(alpha)
        else:
            origins.append(before @ rx(alpha) @ trans(a, 0, 0) @ rz(theta))
            before = trans(0, 0, d)
    return origins, before @ trans(0, 0, spec.get("flange", 0.0))


def urdf_of(name, spec):
    origins, flange = joint_origins(spec)
    n = len(origins)

    def origin(m):
        values = [float(v) for v in (m[0, 3], m[1, 3], m[2, 3], *rpy_of(m[:3, :3]))]
        return '<origin xyz="{!r} {!r} {!r}" rpy="{!r} {!r} {!r}"/>'.format(*values)

    parts = [f'<?xml version="1.0"?><robot name="{name}">']
    parts += [f'<link name="link{i}"/>' for i in range(n + 1)] + ['<link name="flange"/>']
    for i, m in enumerate(origins):
        lo, hi = spec["lower"][i], spec["upper"][i]
        kind = "continuous" if math.isinf(hi) else "revolute"
        limit = "" if kind == "continuous" else f'<limit lower="{lo!r}" upper="{hi!r}" effort="1" velocity="1"/>'
        parts.append(f'<joint name="joint{i + 1}" type="{kind}"><parent link="link{i}"/><child link="link{i + 1}"/>'
                     f'{origin(m)}<axis xyz="0 0 1"/>{limit}</joint>')
    parts.append(f'<joint name="flange_joint" type="fixed"><parent link="link{n}"/><child link="flange"/>'
                 f'{origin(flange)}</joint></robot>')
    return "".join(parts)


def sample(chain, count, rng):
    lo, hi = chain.limits
    lo, hi = np.where(np.isfinite(lo), lo, -P), np.where(np.isfinite(hi), hi, P)
    return rng.uniform(lo, hi, (count, chain.dof))


@pytest.mark.parametrize("name", NEW_ARMS)
def test_arm_matches_a_urdf_of_the_published_numbers(name, rng):
    spec = SPECS[name]
    arm = rk.robots.get(name)
    assert arm.dof == len(spec["rows"]) and arm.joint_types == "R" * arm.dof
    np.testing.assert_allclose(arm.limits[0], spec["lower"], rtol=1e-12, atol=0)
    np.testing.assert_allclose(arm.limits[1], spec["upper"], rtol=1e-12, atol=0)
    urdf = rk.Chain.from_urdf(urdf_of(name, spec), "link0", "flange")
    np.testing.assert_array_equal(urdf.limits[0], arm.limits[0])
    np.testing.assert_array_equal(urdf.limits[1], arm.limits[1])
    q = sample(arm, 200, rng)
    np.testing.assert_allclose(arm.fk(q), urdf.fk(q), atol=1e-12)
    for k in range(5):  # and KDL's own solvers on both chains
        np.testing.assert_allclose(arm.fk(q[k]), arm._fk_kdl(q[k]), atol=1e-12)
        np.testing.assert_allclose(arm.jacobian(q[k]), urdf._jacobian_kdl(q[k]), atol=1e-12)


@pytest.mark.parametrize(
    "name, position",
    [
        # By hand from the published dimensions, at q = 0:
        ("panda", (0.088, 0.0, 0.333 + 0.316 + 0.384 - 0.107)),  # flange pointing down
        ("iiwa14", (0.0, 0.0, 0.36 + 0.42 + 0.4 + 0.126)),  # straight up
        ("irb120", (0.302 + 0.072, 0.0, 0.29 + 0.27 + 0.07)),  # ABB's calibration position
        ("gen3", (0.0, -(0.0054 + 0.0064 + 0.0064 + 0.0064),
                  0.1564 + 0.1284 + 0.2104 + 0.2104 + 0.2084 + 0.1059 + 0.1059 + 0.0615)),
        # UR: (a2 + a3, -(d4 + d6), d1 - d5)
        ("ur5", (-0.425 - 0.39225, -(0.10915 + 0.0823), 0.089159 - 0.09465)),
        ("ur10e", (-0.6127 - 0.57155, -(0.17415 + 0.11655), 0.1807 - 0.11985)),
        ("ur3", (-0.24365 - 0.21325, -(0.11235 + 0.0819), 0.1519 - 0.08535)),
    ],
)
def test_zero_pose_by_hand(name, position):
    T = rk.robots.get(name).fk(np.zeros(rk.robots.get(name).dof))
    np.testing.assert_allclose(T[:3, 3], position, atol=1e-12)


def test_zero_pose_orientations_by_hand():
    # Panda: flange z down, x along base x (rotation pi about x); IRB 120: flange z along +x;
    # Gen3: the tool frame is the base frame; iiwa14: identity.
    np.testing.assert_allclose(rk.robots.panda().fk(np.zeros(7))[:3, :3], np.diag([1.0, -1.0, -1.0]), atol=1e-12)
    np.testing.assert_allclose(rk.robots.irb120().fk(np.zeros(6))[:3, 2], [1.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(rk.robots.gen3().fk(np.zeros(7))[:3, :3], np.eye(3), atol=1e-12)
    np.testing.assert_allclose(rk.robots.iiwa14().fk(np.zeros(7))[:3, :3], np.eye(3), atol=1e-12)


def test_irb120_axes_turn_as_abb_defines_them():
    """ABB: axis 2 positive leans the arm forward (+x), axis 3 positive lowers the forearm."""
    arm = rk.robots.irb120()
    home = arm.fk(np.zeros(6))[:3, 3]
    assert arm.fk([0, 0.1, 0, 0, 0, 0])[0, 3] > home[0]
    assert arm.fk([0, 0, 0.1, 0, 0, 0])[2, 3] < home[2]


def test_names_and_get():
    names = rk.robots.names()
    assert names == sorted(names) and len(set(names)) == len(names)
    assert set(NEW_ARMS) | set(OLD) == set(names)
    for name in names:
        chain = rk.robots.get(name)
        assert isinstance(chain, rk.Chain)
        if hasattr(rk.robots, name):
            np.testing.assert_array_equal(chain.fk(np.full(chain.dof, 0.1)), getattr(rk.robots, name)().fk(np.full(chain.dof, 0.1)))
    with pytest.raises(ValueError, match=r"name: no robot named 'kr16'.*valid names: gen3, iiwa14"):
        rk.robots.get("kr16")
    with pytest.raises(ValueError, match="name: no robot named ''"):
        rk.robots.get("")
    with pytest.raises(TypeError, match="name: expected a str"):
        rk.robots.get(5)


# Named configurations: the arms whose documented home is singular (an arm upright or stretched out,
# or a wrist with joint 5 at 0), as robokin.robots.configurations says.
SINGULAR_HOMES = {"ur3", "ur3e", "ur5", "ur5e", "ur10", "ur10e", "ur16e", "iiwa14", "irb120", "puma560"}


def yoshikawa(chain, q):
    """sqrt(det(J J^T)) from numpy's singular values (not the core's manipulability)."""
    return float(np.prod(np.linalg.svd(chain.jacobian(q), compute_uv=False)))


@pytest.mark.parametrize("name", rk.robots.names())
def test_named_configurations_lie_within_the_limits(name):
    chain, named = rk.robots.get(name), rk.robots.configurations(name)
    lower, upper = chain.limits
    np.testing.assert_array_equal(named["zero"], np.clip(np.zeros(chain.dof), lower, upper))
    if name in NEW_ARMS or name == "puma560":
        assert {"zero", "home"} <= set(named) and ("ready" in named) == (name != "irb120")
    else:
        assert set(named) == {"zero"}  # the seeds' arms
    for key, q in named.items():
        assert q.shape == (chain.dof,) and q.dtype == np.float64, key
        assert np.all((lower <= q) & (q <= upper)), (name, key, q)
    # fresh arrays at each call
    named["zero"][0] = 99.0
    assert rk.robots.configurations(name)["zero"][0] != 99.0


@pytest.mark.parametrize("name", sorted(set(NEW_ARMS) | {"puma560"}))
def test_ready_is_clear_of_singularities_and_home_as_documented(name):
    chain, named = rk.robots.get(name), rk.robots.configurations(name)
    if name != "irb120":  # no published ready posture
        assert yoshikawa(chain, named["ready"]) > 1e-3, name
    home = yoshikawa(chain, named["home"])
    if name in SINGULAR_HOMES:
        assert home < 1e-12, name
    else:
        assert home > 1e-2, name
    if "up" in named:
        assert yoshikawa(chain, named["up"]) < 1e-12


def test_named_configurations_are_the_published_numbers():
    # The Robotics Toolbox's Panda qr; franka_ros's start pose.
    panda = rk.robots.configurations("panda")
    np.testing.assert_array_equal(panda["ready"], [0, -0.3, 0, -2.2, 0, 2.0, P / 4])
    np.testing.assert_array_equal(panda["home"], [0, -P / 4, 0, -3 * P / 4, 0, P / 2, P / 4])
    np.testing.assert_array_equal(panda["zero"], [0, 0, 0, -0.0698, 0, 0, 0])
    # Universal Robots' MoveIt configuration, for every size of arm.
    for name in ("ur3", "ur5e", "ur16e"):
        ur = rk.robots.configurations(name)
        np.testing.assert_array_equal(ur["home"], [0, -P / 2, 0, 0, 0, 0])
        np.testing.assert_array_equal(ur["up"], [0, -P / 2, 0, -P / 2, 0, 0])
        np.testing.assert_array_equal(ur["ready"], [1.54, -1.62, 1.4, -1.2, -1.6, -0.11])
    # Kinova's Home (joint 4's 230 deg is -130 deg); the PUMA's qr and qn (joint 3's pi is -pi).
    np.testing.assert_allclose(rk.robots.configurations("gen3")["home"], np.radians([0, 15, 180, -130, 0, 55, 90]))
    puma = rk.robots.configurations("puma560")
    np.testing.assert_array_equal(puma["home"], [0, P / 2, -P / 2, 0, 0, 0])
    np.testing.assert_array_equal(puma["ready"], [0, P / 4, -P, 0, P / 4, 0])
    chain = rk.robots.puma560()
    np.testing.assert_allclose(chain.fk(puma["ready"]), chain.fk([0, P / 4, P, 0, P / 4, 0]), atol=1e-12)


def test_configurations_of_an_unknown_name():
    with pytest.raises(ValueError, match="name: no robot named 'kr16'"):
        rk.robots.configurations("kr16")
    with pytest.raises(TypeError, match="name: expected a str"):
        rk.robots.configurations(None)
