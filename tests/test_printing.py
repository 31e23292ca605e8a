"""Text for people: chain.table() / print(chain) for a standard-DH arm (the PUMA 560's published
table), a modified-DH arm with a prismatic joint and a tool, and a URDF chain with names (each
against text written here by hand from the parameters, and the URDF rows against the file's own
<origin>, <axis> and <limit>); repr unchanged; results' str() one field per line."""

import math
import pathlib
import pickle
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import robokin as rk

ARM = pathlib.Path(__file__).resolve().parent.parent / "examples" / "arm.urdf"
D = math.pi / 180

# The PUMA 560 in standard DH as Corke publishes it (a, alpha, d, theta), joint limits in degrees.
PUMA_ROWS = [(0, 90 * D, 0, 0, "R"), (0.4318, 0, 0, 0, "R"), (0.0203, -90 * D, 0.15005, 0, "R"),
             (0, 90 * D, 0.4318, 0, "R"), (0, -90 * D, 0, 0, "R"), (0, 0, 0, 0, "R")]
PUMA_LIMITS = np.array([(-160, 160), (-110, 110), (-135, 135), (-266, 266), (-100, 100), (-266, 266)]) * D

PUMA_TABLE = """\
Chain: 6 joints (RRRRRR), standard DH: A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha)
joint   a (m)  alpha (deg)    d (m)  theta (deg)  type     lower    upper
-----  ------  -----------  -------  -----------  ----  --------  -------
q1          0           90        0           q1  R     -160 deg  160 deg
q2     0.4318            0        0           q2  R     -110 deg  110 deg
q3     0.0203          -90  0.15005           q3  R     -135 deg  135 deg
q4          0           90   0.4318           q4  R     -266 deg  266 deg
q5          0          -90        0           q5  R     -100 deg  100 deg
q6          0            0        0           q6  R     -266 deg  266 deg"""

# A modified-DH arm: a prismatic joint with an offset, a revolute one with a negative offset, a tool;
# the second joint unlimited.
CRAIG_TABLE = """\
Chain: 3 joints (RPR), modified DH (Craig): A_i = Rx(alpha) Tx(a) Rz(theta) Tz(d)
joint  a (m)  alpha (deg)     d (m)  theta (deg)  type    lower   upper
-----  -----  -----------  --------  -----------  ----  -------  ------
q1         0            0      0.25      q1 + 30  R     -90 deg  90 deg
q2       0.1          -90  q2 + 0.2          -45  P       0.1 m   0.6 m
q3      0.35           90         0      q3 - 15  R        -inf     inf
tool: xyz (0, 0, 0.12) m, rpy (0, 0, 90) deg"""

UR5_TABLE = """\
Chain: 6 joints (RRRRRR), base 'base_link', tip 'tool0'
xyz, rpy: the frame after the joint at q = 0 in the one before (URDF <origin>); axis: in that frame
joint                      type   xyz (m)           rpy (deg)    axis          lower    upper
-------------------------  -----  ----------------  -----------  ---------  --------  -------
shoulder_pan_joint         R      (0, 0, 0)         (0, 0, 0)    (0, 0, 1)  -360 deg  360 deg
shoulder_lift_joint        R      (0, 0, 0.08916)   (90, 0, 0)   (0, 0, 1)  -360 deg  360 deg
elbow_joint                R      (-0.425, 0, 0)    (0, 0, 0)    (0, 0, 1)  -360 deg  360 deg
wrist_1_joint              R      (-0.39225, 0, 0)  (0, 0, 0)    (0, 0, 1)  -360 deg  360 deg
wrist_2_joint              R      (0, 0, 0.10915)   (90, 0, 0)   (0, 0, 1)  -360 deg  360 deg
wrist_3_joint              R      (0, 0, 0.09465)   (-90, 0, 0)  (0, 0, 1)  -360 deg  360 deg
wrist_3-tool0_fixed_joint  fixed  (0, 0, 0.0823)    (0, 0, 0)"""


def puma():
    return rk.Chain.from_dh(PUMA_ROWS, limits=(PUMA_LIMITS[:, 0], PUMA_LIMITS[:, 1]))


def craig():
    tool = np.array([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0.12], [0, 0, 0, 1]], dtype=float)
    rows = [(0, 0, 0.25, 30 * D, "R"), (0.1, -90 * D, 0.2, -45 * D, "P"), (0.35, 90 * D, 0, -15 * D, "R")]
    return rk.Chain.from_dh(rows, modified=True, tool=tool,
                            limits=([-90 * D, 0.1, -math.inf], [90 * D, 0.6, math.inf]))


def test_a_standard_dh_arm_prints_its_table():
    chain = puma()
    assert chain.table() == PUMA_TABLE
    assert str(chain) == PUMA_TABLE
    # The catalogue's PUMA 560 is the same table (its limits are its own).
    catalogue = rk.robots.get("puma560").table().splitlines()
    assert [line[:45] for line in catalogue[3:]] == [line[:45] for line in PUMA_TABLE.splitlines()[3:]]


def test_a_modified_dh_arm_with_a_prismatic_joint_and_a_tool_prints_its_table():
    assert craig().table() == CRAIG_TABLE


def test_a_urdf_chain_prints_its_joints_by_name():
    chain = rk.Chain.from_urdf(ARM)
    assert chain.table() == UR5_TABLE
    assert str(chain) == UR5_TABLE


def test_the_urdf_rows_are_the_files_origins_axes_and_limits():
    """Independent of the text above: every movable joint's row read back against the XML."""
    chain = rk.Chain.from_urdf(ARM)
    rows = {line.split()[0]: line for line in chain.table().splitlines()[4:]}
    joints = {j.get("name"): j for j in ET.parse(ARM).getroot().iter("joint")}
    for name in chain.joint_names:
        xml = joints[name]
        cells = rows[name].split("  ")
        cells = [c.strip() for c in cells if c.strip()]
        _, _, xyz, rpy, axis, lower, upper = cells
        parse = lambda text: np.array([float(v) for v in text.strip("()").split(",")])  # noqa: E731
        np.testing.assert_allclose(parse(xyz), [float(v) for v in xml.find("origin").get("xyz").split()], atol=1e-5)
        np.testing.assert_allclose(parse(rpy) * D, [float(v) for v in xml.find("origin").get("rpy").split()], atol=1e-6)
        np.testing.assert_allclose(parse(axis), [float(v) for v in xml.find("axis").get("xyz").split()], atol=1e-5)
        assert float(lower.split()[0]) * D == pytest.approx(float(xml.find("limit").get("lower")))
        assert float(upper.split()[0]) * D == pytest.approx(float(xml.find("limit").get("upper")))


def test_a_chain_of_joints_and_frames_without_names():
    tip = np.eye(4)
    tip[:3, 3] = (0.3, 0, 0)
    chain = rk.Chain.from_segments([("R", (0, 0, 1), tip), ("P", (1, 0, 0), np.eye(4)), ("F", (0, 0, 1), tip)])
    lines = chain.table().splitlines()
    assert lines[0] == f"Chain: 2 joints (RP), base {chain.link_names[0]!r}, tip {chain.link_names[-1]!r}"
    body = [line.split() for line in lines[4:]]
    assert body[0] == ["q1", "R", "(0.3,", "0,", "0)", "(0,", "0,", "0)", "(0,", "0,", "1)", "-inf", "inf"]
    assert body[1] == ["q2", "P", "(0,", "0,", "0)", "(0,", "0,", "0)", "(1,", "0,", "0)", "-inf", "inf"]
    assert body[2] == ["fixed", "(0.3,", "0,", "0)", "(0,", "0,", "0)"]


def test_repr_stays_short_and_unchanged():
    chain = puma()
    assert repr(chain).startswith("Chain(dof=6, joints='RRRRRR', dh=[")
    assert "deg" not in repr(chain) and repr(chain) != str(chain)
    assert repr(rk.Chain.from_urdf(ARM)).startswith("Chain(dof=6, joints='RRRRRR', base='base_link', tip='tool0'")


def test_the_table_survives_pickling():
    assert pickle.loads(pickle.dumps(craig())).table() == CRAIG_TABLE


def test_results_print_one_field_per_line():
    chain = puma()
    q = np.array([0.1, 0.2, -0.3, 0.4, 0.5, 0.6])
    res = rk.ik(chain, chain.fk(q), q + 0.05)
    lines = str(res).splitlines()
    assert lines[0] == "IKResult:"
    fields = {line.split()[0]: line.split(None, 1)[1] for line in lines[1:]}
    assert set(fields) == {"success", "iterations", "attempts", "error_p", "error_r", "q"}
    assert fields["success"] == str(res.success)
    assert fields["iterations"] == str(res.iterations)
    assert float(fields["error_p"]) == pytest.approx(res.error_p, rel=1e-3)
    np.testing.assert_allclose(np.array(eval(fields["q"])), res.q, atol=5e-5)
    assert repr(res).startswith("IKResult(success=")


def test_batch_results_print_arrays_by_shape_and_range():
    rpr = rk.robots.rpr()
    points = rk.paths.line([-1.0, 2.25], [1.5, 1.0], step=0.05)
    tr = rk.track(rpr, points, [math.pi / 2, 0.75, math.pi / 2])
    fields = {line.split()[0]: line.split(None, 1)[1] for line in str(tr).splitlines()[1:]}
    K = len(points)
    assert fields["q"] == f"({K}, 3), {tr.q.min():.4g} to {tr.q.max():.4g}"
    assert fields["converged"] == f"({K},), {int(tr.converged.sum())} of {K} true"


def test_posture_tracks_and_3rrr_plans_print_readably():
    chain = rk.robots.get("puma560")
    q = np.array([0.1, 0.2, -0.3, 0.4, 0.5, 0.6])
    poses = np.stack([chain.fk(q + s) for s in np.linspace(0, 0.1, 12)])
    result = rk.track_postures(chain, poses, 0.1, qdot_max=2.0)
    text = str(result)
    assert text.splitlines()[0] == "TrackPosturesResult:"
    assert f"  success           (12,), {int(result.success.sum())} of 12 true" in text
    assert "  solutions         list of 12" in text
    robot = rk.RRR3()
    plan = robot.plan(rk.paths.circle(40, radius=0.05))
    lines = str(plan).splitlines()
    assert lines[0] == "RRR3Plan:" and len(lines) > 2
    assert all("\n" not in line for line in lines)


def test_the_docs_page_shows_what_print_prints():
    page = (ARM.parent.parent / "docs" / "plots.md").read_text()
    assert f'>>> print(rk.robots.get("puma560"))\n{rk.robots.get("puma560")}\n```' in page
    assert f'>>> print(rk.Chain.from_urdf("examples/arm.urdf"))\n{rk.Chain.from_urdf(ARM)}\n```' in page
