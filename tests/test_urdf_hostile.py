"""URDF loading that tells the truth: every hostile file is a ValueError saying why (or a
documented robokin.URDFWarning), never a crash, and nothing is printed to stderr behind Python's
back (urdfdom's console_bridge output is captured into the message). Each case checks fd 2 with
capfd; the long chain and the deep XML run in a subprocess, where a crash would show as a signal."""

import math
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import robokin as rk

LIMIT = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'


def joint(name, parent, child, kind="revolute", origin='xyz="0 0 0.1"', extra=LIMIT, axis='<axis xyz="0 0 1"/>'):
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin {origin}/>{axis}{extra}</joint>')


def robot(*joints, links=("a", "b", "c")):
    return '<?xml version="1.0"?><robot name="r">' + "".join(f'<link name="{l}"/>' for l in links) + "".join(joints) + "</robot>"


GOOD = robot(joint("j1", "a", "b"), joint("j2", "b", "c"))


@pytest.fixture
def quiet(capfd):
    """Asserts that the test wrote nothing to the process's stdout / stderr (file descriptors)."""
    yield
    out, err = capfd.readouterr()
    assert err == "" and out == "", f"printed behind Python's back: {err!r} {out!r}"


def load(xml, base="a", tip="c"):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning either, unless the test expects one
        return rk.Chain.from_urdf(xml, base, tip)


def test_a_good_file_loads_quietly(quiet):
    chain = load(GOOD)
    assert chain.dof == 2
    np.testing.assert_allclose(chain.fk([0.3, -0.2])[:3, 3], [0, 0, 0.2], atol=1e-15)


@pytest.mark.parametrize(
    "xml, message",
    [
        ("", "the URDF document is empty"),
        ("   \n", "the URDF document is empty"),
        ("<robot", "not a valid URDF document: .*Element"),
        ("<notxml>>>", "not a valid URDF document: .*Element"),
        ('<?xml version="1.0"?><model name="r"><link name="a"/></model>', "not a valid URDF document: .*'robot' element"),
        # a loop: every link has a parent, so there is no root
        (robot(joint("j1", "a", "b"), joint("j2", "b", "a"), links=("a", "b")), "not a valid URDF document: .*No root link found"),
        (robot(joint("j1", "a", "b", origin='xyz="0 nan 0"'), joint("j2", "b", "c")),
         r"not a valid URDF document: .*\[nan\].*joint \[j1\]"),
        (robot(joint("j1", "a", "b", extra='<limit lower="-inf" upper="1" effort="1" velocity="1"/>'),
               joint("j2", "b", "c")), r"not a valid URDF document: lower value \(-inf\) is not a valid float.*\[j1\]"),
        (robot(joint("j1", "a", "b", extra='<limit lower="-1" upper="nan" effort="1" velocity="1"/>'),
               joint("j2", "b", "c")), r"not a valid URDF document: upper value \(nan\) is not a valid float.*\[j1\]"),
        (robot(joint("j1", "a", "b", extra=""), joint("j2", "b", "c")),
         r"not a valid URDF document: Joint \[j1\] .*does not specify limits"),
        (robot(joint("j1", "a", "b", kind="wobbly"), joint("j2", "b", "c")), r"not a valid URDF document: Joint \[j1\] has no known type \[wobbly\]"),
    ],
    ids=["empty", "blank", "truncated", "not-xml", "no-robot", "loop", "nan-origin", "inf-limit", "nan-limit",
         "revolute-without-limit", "unknown-type"],
)
def test_bad_documents_say_why(xml, message, quiet):
    with pytest.raises(ValueError, match="path_or_string: " + message):
        load(xml)


def test_empty_file_and_directory(tmp_path, quiet):
    empty = tmp_path / "empty.urdf"
    empty.write_text("")
    with pytest.raises(ValueError, match="path_or_string: the URDF document is empty"):
        load(empty)
    with pytest.raises(ValueError, match="path_or_string: '.*' is a directory, not a URDF file"):
        load(tmp_path)
    binary = tmp_path / "binary.urdf"
    binary.write_bytes(b"\x00\x01garbage")
    with pytest.raises(ValueError, match="path_or_string: not a valid URDF document"):
        load(binary)


def test_lower_above_upper(quiet):
    xml = robot(joint("j1", "a", "b", extra='<limit lower="1" upper="-1" effort="1" velocity="1"/>'),
                joint("j2", "b", "c"))
    with pytest.raises(ValueError, match=r"joint 'j1' has its lower limit 1 above its upper limit -1$"):
        load(xml)


def test_equal_limits_are_unlimited_with_a_warning(quiet):
    """URDF's lower and upper default to 0: a <limit> without them gives lower == upper == 0, which
    robokin reads as 'no limits given' (documented), and says so."""
    xml = robot(joint("j1", "a", "b", extra='<limit effort="1" velocity="1"/>'), joint("j2", "b", "c"))
    with pytest.warns(rk.URDFWarning, match=r"joint 'j1' has lower == upper limit \(0\): taken as unlimited") as caught:
        chain = rk.Chain.from_urdf(xml, "a", "c")
    assert caught[0].filename == __file__  # the caller's line, not robokin's
    assert chain.limits[0][0] == -math.inf and chain.limits[1][0] == math.inf
    assert chain.limits[0][1] == -1 and chain.limits[1][1] == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error", rk.URDFWarning)
        with pytest.raises(rk.URDFWarning):
            rk.Chain.from_urdf(xml, "a", "c")


def test_link_with_two_parents(quiet):
    xml = robot(joint("j1", "a", "b"), joint("j2", "b", "c"), joint("j3", "a", "c"))
    with pytest.raises(ValueError, match=r"link 'c' has two parents \(joints '(j2' and 'j3|j3' and 'j2)'\)"):
        load(xml)


def test_mimic_joint_in_the_chain_is_refused_elsewhere_ignored(quiet):
    mimic = '<mimic joint="j1" multiplier="1" offset="0"/>'
    xml = robot(joint("j1", "a", "b"), joint("j2", "b", "c", extra=LIMIT + mimic))
    with pytest.raises(ValueError, match="joint 'j2' mimics joint 'j1': mimic joints are not supported"):
        load(xml)
    # a gripper finger on a branch off the chain does not matter to the chain a -> c
    xml = robot(joint("j1", "a", "b"), joint("j2", "b", "c"), joint("finger", "b", "d", kind="prismatic",
                                                                     extra=LIMIT + mimic), links=("a", "b", "c", "d"))
    assert load(xml).dof == 2


def test_mimic_tag_on_a_fixed_joint_in_the_chain_changes_nothing(quiet):
    """A fixed joint does not move, so a mimic tag on it (Talos' gripper in example-robot-data has
    some) is no reason to refuse the chain: it reads as the same chain without the tag."""
    mimic = '<mimic joint="j1" multiplier="1" offset="0"/>'
    fixed = joint("f", "b", "c", kind="fixed", origin='xyz="0.1 0.2 0.3" rpy="0.4 0 0"', extra="")
    tagged = joint("f", "b", "c", kind="fixed", origin='xyz="0.1 0.2 0.3" rpy="0.4 0 0"', extra=mimic)
    plain, chain = load(robot(joint("j1", "a", "b"), fixed)), load(robot(joint("j1", "a", "b"), tagged))
    assert chain.dof == 1 and chain.joint_names == ("j1",)
    for q in ([0.0], [0.7], [-1.0]):
        assert np.array_equal(chain.fk(q), plain.fk(q))
    # the tip 0.1 above the joint (j1's origin), then (0.1, 0.2, 0.3) turned by q about z
    c, s = math.cos(0.7), math.sin(0.7)
    assert np.allclose(chain.fk([0.7])[:3, 3], [0.1 * c - 0.2 * s, 0.1 * s + 0.2 * c, 0.4], atol=1e-15)


@pytest.mark.parametrize("kind", ["floating", "planar"])
def test_floating_and_planar_joints(kind, quiet):
    xml = robot(joint("j1", "a", "b"), joint("free", "b", "c", kind=kind, extra=""))
    with pytest.raises(ValueError, match=f"joint 'free' is {kind}: a serial chain has revolute, continuous, "
                                         "prismatic and fixed joints only"):
        load(xml)
    # outside the chain (a floating base above it) it does not matter
    xml = robot(joint("world_joint", "world", "a", kind=kind, extra=""), joint("j1", "a", "b"), joint("j2", "b", "c"),
                links=("world", "a", "b", "c"))
    assert load(xml).dof == 2


@pytest.mark.parametrize("value", ["1e308", "-1e10", "1e9000"])
def test_huge_origin(value, quiet):
    xml = robot(joint("j1", "a", "b", origin=f'xyz="0 {value} 0"'), joint("j2", "b", "c"))
    expected = {"1e308": r"joint 'j1' has an origin farther than 1e9 m \(1e\+308\)",
                "-1e10": r"joint 'j1' has an origin farther than 1e9 m \(-1e\+10\)",
                "1e9000": r"not a valid URDF document: .*\[1e9000\]"}[value]
    with pytest.raises(ValueError, match="path_or_string: " + expected):
        load(xml)


def test_zero_axis(quiet):
    xml = robot(joint("j1", "a", "b", axis='<axis xyz="0 0 0"/>'), joint("j2", "b", "c"))
    with pytest.raises(ValueError, match="joint 'j1' has a zero axis"):
        load(xml)


def test_root_link_with_inertia_loads_without_a_word(quiet):
    """kdl_parser printed 'The root link a has an inertia specified in the URDF, but KDL does not
    support a root link with an inertia' on every load of such arms (the IRB 120, the KR 16)."""
    inertial = '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
    xml = GOOD.replace('<link name="a"/>', f'<link name="a">{inertial}</link>')
    assert load(xml).dof == 2


def test_unknown_links_and_no_joint(quiet):
    with pytest.raises(ValueError, match="base: no link named 'x'"):
        load(GOOD, "x", "c")
    with pytest.raises(ValueError, match="tip: no link named 'x'"):
        load(GOOD, "a", "x")
    with pytest.raises(ValueError, match="base, tip: no moving joint"):
        load(GOOD, "b", "b")


def run_isolated(code):
    """Runs code in a fresh interpreter: a crash is a signal there, not the end of this test run."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=300)


def test_a_20000_joint_chain_loads(tmp_path):
    """kdl_parser's treeFromUrdfModel recursed once per link: SIGSEGV from about 10,000 joints.
    The tree is now built without recursion; the chain's FK is checked against its closed form
    (every joint about z, 1 mm apart: p = (0, 0, 20), R = Rz(sum q))."""
    n = 20_000
    links = "".join(f'<link name="l{i}"/>' for i in range(n + 1))
    joints = "".join(joint(f"j{i}", f"l{i}", f"l{i + 1}", origin='xyz="0 0 0.001"') for i in range(n))
    path = tmp_path / "long.urdf"
    path.write_text(f'<robot name="long">{links}{joints}</robot>')
    assert path.stat().st_size > 4_000_000
    result = run_isolated(f"""
        import numpy as np, robokin as rk
        chain = rk.Chain.from_urdf({str(path)!r}, "l0", "l{n}")
        q = np.random.default_rng(0).uniform(-1, 1, chain.dof)
        T = chain.fk(q)
        s = q.sum()
        assert chain.dof == {n}, chain.dof
        assert np.allclose(T[:3, 3], [0, 0, {n} * 0.001], atol=1e-9), T
        assert np.allclose(T[:2, :2], [[np.cos(s), -np.sin(s)], [np.sin(s), np.cos(s)]], atol=1e-9), T
        print("ok")
    """)
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout == "ok\n" and result.stderr == ""


def test_deeply_nested_xml_is_refused_before_parsing():
    """urdfdom's XML parser recurses per nesting level: a file of 200,000 nested elements is
    refused before it gets there."""
    depth = 200_000
    result = run_isolated(f"""
        import robokin as rk
        xml = '<robot name="r">' + '<a>' * {depth} + '</a>' * {depth} + '</robot>'
        try:
            rk.Chain.from_urdf(xml, "a", "b")
        except ValueError as e:
            print(e)
    """)
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout == "path_or_string: XML elements nested deeper than 1000 levels (not a URDF)\n"
    assert result.stderr == ""
