"""URDF chains that know their names: the default base and tip of Chain.from_urdf (against a
reference written here from the rule's words, on hand-made and random trees), robokin.urdf_tree,
the kinds of path accepted, joint_names / link_names of URDF and DH chains, q_from / q_dict, names
through pickling and copies, repr, and examples/arm.urdf against the catalogue arm it was written
from."""

import copy
import math
import os
import pathlib
import pickle
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import robokin as rk
from test_urdf import SMALL, small_fk, tx, tz, rz, urdf_from_dh

ARM = pathlib.Path(__file__).resolve().parent.parent / "examples" / "arm.urdf"
MOVABLE = ("revolute", "continuous", "prismatic")


def urdf(joints, name="t"):
    """A URDF of (joint name, type, parent, child) rows: every joint along z, 0.1 m from its parent."""
    links = {link for _, _, parent, child in joints for link in (parent, child)}
    out = [f'<robot name="{name}">'] + [f'<link name="{link}"/>' for link in sorted(links)]
    for joint, kind, parent, child in joints:
        limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if kind in ("revolute", "prismatic") else ""
        out.append(f'<joint name="{joint}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
                   f'<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>{limit}</joint>')
    return "".join(out) + "</robot>"


def serial(names, kinds, start="base_link", prefix="j"):
    """Joint rows of a serial run of links `names` hanging from `start`."""
    rows, parent = [], start
    for i, (link, kind) in enumerate(zip(names, kinds)):
        rows.append((f"{prefix}{i}_{link}", kind, parent, link))
        parent = link
    return rows


# A Y: one joint to a hub, then two arms of two revolute joints each.
Y_TREE = urdf([("j0", "revolute", "base_link", "hub")] + serial(["l1", "left_tip"], ["revolute"] * 2, "hub", "a")
              + serial(["r1", "right_tip"], ["revolute"] * 2, "hub", "b"))
# A UR-like arm: fixed leaves 'base' and 'base_link_inertia' off base_link, three joints, then a
# flange and tool0 after the last joint and a shorter fixed 'ee_link' beside them.
UR_LIKE = urdf([("base_fixed", "fixed", "base_link", "base"), ("inertia", "fixed", "base_link", "base_link_inertia")]
               + serial(["shoulder", "upper", "wrist"], ["revolute"] * 3)
               + serial(["flange", "tool0"], ["fixed", "fixed"], "wrist", "f")
               + [("ee_fixed", "fixed", "wrist", "ee_link")])


def reference_tips(xml, base=None):
    """The default tip's rule in words, by brute force over every link: (movable joints, ends) where
    ends are the candidates (one: the tip).

    The links below base with the most movable joints, grouped by their last movable joint; in each
    group those with the most joints; their deepest common ancestor-or-self."""
    root = ET.fromstring(xml)
    parent = {j.find("child").get("link"): (j.find("parent").get("link"), j.get("type")) for j in root.iter("joint")}
    links = [link.get("name") for link in root.iter("link")]
    if base is None:
        base = next(link for link in links if link not in parent)

    def path(link):  # [(link, joint type)] from just below base down to link; None when not below base
        out = []
        while link != base:
            if link not in parent:
                return None
            up, kind = parent[link]
            out.append((link, kind))
            link = up
        return out[::-1]

    info = {}
    for link in links:
        p = path(link)
        if p:
            movable = [i for i, (_, kind) in enumerate(p) if kind in MOVABLE]
            info[link] = (len(movable), len(p), p[movable[-1]][0] if movable else None, [name for name, _ in p])
    best = max((m for m, _, _, _ in info.values()), default=0)
    if best == 0:
        return 0, []
    groups = {}
    for link, (m, joints, last, _) in info.items():
        if m == best:
            groups.setdefault(last, []).append(link)
    ends = []
    for members in groups.values():
        most = max(info[link][1] for link in members)
        chosen = [link for link in members if info[link][1] == most]
        common = set.intersection(*(set(info[link][3]) for link in chosen))
        ends.append(max(common, key=lambda link: info[link][1]))
    return best, sorted(ends)


# --- the default base and tip --------------------------------------------------------------------

def test_defaults_on_the_suites_urdfs():
    assert rk.Chain.from_urdf(SMALL).link_names == ("base_link", "link1", "link2", "tool")
    ur5 = rk.robots.ur5()
    chain = rk.Chain.from_urdf(urdf_from_dh("ur5", [(0.0, math.pi / 2, 0.1)] * 6, *ur5.limits))
    assert chain.link_names[0] == "l0" and chain.link_names[-1] == "tool" and chain.dof == 6
    assert rk.Chain.from_urdf(SMALL) == rk.Chain.from_urdf(SMALL, "base_link", "tool")


def test_a_y_shaped_tree_asks_for_a_tip():
    with pytest.raises(ValueError) as err:
        rk.Chain.from_urdf(Y_TREE)
    assert str(err.value) == ("tip: the longest branches from 'base_link' end at 'left_tip' and 'right_tip' "
                              "(3 movable joints each): pass tip=...")
    assert rk.Chain.from_urdf(Y_TREE, tip="left_tip").joint_names == ("j0", "a0_l1", "a1_left_tip")
    # below the hub too, and from one arm's first link there is one branch
    with pytest.raises(ValueError, match="from 'hub' end at 'left_tip' and 'right_tip' .2 movable joints each"):
        rk.Chain.from_urdf(Y_TREE, base="hub")
    assert rk.Chain.from_urdf(Y_TREE, base="r1").link_names == ("r1", "right_tip")


def test_total_joints_break_ties_only_within_a_branch():
    """A fixed tool on one arm of the Y does not make that arm the longer one."""
    xml = Y_TREE.replace("</robot>", '<link name="tool"/><joint name="t" type="fixed"><parent link="left_tip"/>'
                                     '<child link="tool"/></joint></robot>')
    with pytest.raises(ValueError, match="end at 'right_tip' and 'tool' "):
        rk.Chain.from_urdf(xml)
    # one more movable joint on the right decides
    xml = Y_TREE.replace("</robot>", '<link name="far"/><joint name="f" type="continuous"><parent link="right_tip"/>'
                                     '<child link="far"/><axis xyz="1 0 0"/></joint></robot>')
    assert rk.Chain.from_urdf(xml).link_names[-1] == "far"


def test_a_ur_like_arm_ends_at_tool0():
    chain = rk.Chain.from_urdf(UR_LIKE)
    assert chain.link_names == ("base_link", "shoulder", "upper", "tool0")
    tree = rk.urdf_tree(UR_LIKE)
    assert (tree.root, tree.base, tree.tip, tree.tips, tree.movable) == ("base_link", "base_link", "tool0", ["tool0"], 3)


def test_equally_deep_leaves_after_the_last_joint_give_the_link_they_hang_from():
    xml = UR_LIKE.replace("</robot>", '<link name="camera"/><joint name="cam" type="fixed"><parent link="flange"/>'
                                      '<child link="camera"/></joint></robot>')
    assert rk.Chain.from_urdf(xml).link_names[-1] == "flange"
    assert rk.urdf_tree(xml).tip == "flange"


def test_no_movable_joint_below_the_base():
    with pytest.raises(ValueError) as err:
        rk.Chain.from_urdf(UR_LIKE, base="flange")
    assert str(err.value) == "tip: no movable joint below link 'flange': pass tip=..."
    fixed_only = urdf([("a", "fixed", "base_link", "x")])
    with pytest.raises(ValueError, match="tip: no movable joint below link 'base_link'"):
        rk.Chain.from_urdf(fixed_only)
    tree = rk.urdf_tree(fixed_only)
    assert tree.tip is None and tree.tips == [] and tree.movable == 0


def random_tree(rng, size):
    kinds = ("revolute", "fixed", "fixed", "prismatic", "continuous")
    rows = []
    for i in range(1, size):
        rows.append((f"j{i}", kinds[rng.integers(len(kinds))], f"l{rng.integers(i)}", f"l{i}"))
    return urdf(rows)


def test_the_default_tip_follows_the_rule_on_random_trees():
    rng = np.random.default_rng(7)
    ties = picks = 0
    for trial in range(400):
        xml = random_tree(rng, int(rng.integers(2, 14)))
        movable, ends = reference_tips(xml)
        tree = rk.urdf_tree(xml)
        assert (tree.movable, tree.tips) == (movable, ends), xml
        if len(ends) == 1:
            picks += 1
            assert tree.tip == ends[0]
            assert rk.Chain.from_urdf(xml).link_names[-1] == ends[0]
        elif len(ends) > 1:
            ties += 1
            assert tree.tip is None
            with pytest.raises(ValueError, match="tip: the longest branches"):
                rk.Chain.from_urdf(xml)
        # from a base inside the tree too
        base = f"l{rng.integers(1, len(tree.links))}" if len(tree.links) > 1 else "l0"
        movable, ends = reference_tips(xml, base)
        if len(ends) == 1:
            assert rk.Chain.from_urdf(xml, base=base).link_names[-1] == ends[0]
    assert ties > 20 and picks > 100  # both outcomes were exercised


# --- urdf_tree -----------------------------------------------------------------------------------

def test_urdf_tree_lists_links_and_joints_depth_first():
    tree = rk.urdf_tree(UR_LIKE)
    assert tree.name == "t"
    assert tree.links == ["base_link", "base", "base_link_inertia", "shoulder", "upper", "wrist", "ee_link",
                          "flange", "tool0"]
    joint = tree.joints[0]
    assert (joint.name, joint.type, joint.parent, joint.child) == ("base_fixed", "fixed", "base_link", "base")
    assert [j.child for j in tree.joints] == tree.links[1:]
    assert repr(joint) == "UrdfJoint('base_fixed', 'fixed', parent='base_link', child='base')"
    text = repr(tree).splitlines()
    assert text[0] == "UrdfTree(name='t', root='base_link', base='base_link', tip='tool0', 9 links, 8 joints)"
    assert text[3] == "  base_link -> shoulder (j0_shoulder, revolute)"
    assert text[-1] == "          flange -> tool0 (f1_tool0, fixed)"  # five joints deep
    y = repr(rk.urdf_tree(Y_TREE)).splitlines()[0]
    assert y == ("UrdfTree(name='t', root='base_link', base='base_link', tip=None, tips=['left_tip', 'right_tip'], "
                 "6 links, 5 joints)")


def test_urdf_tree_of_a_long_chain_is_bounded():
    rows = serial([f"l{i}" for i in range(1, 3001)], ["revolute"] * 3000, "l0")
    tree = rk.urdf_tree(urdf(rows))
    assert tree.tip == "l3000" and tree.movable == 3000 and len(tree.links) == 3001
    text = repr(tree)
    assert text.endswith("... and 2800 more joints") and len(text) < 20_000


def test_bad_documents_and_kinds_for_urdf_tree():
    with pytest.raises(ValueError, match="path_or_string: not a valid URDF document"):
        rk.urdf_tree("<robot")
    with pytest.raises(TypeError, match="path_or_string"):
        rk.urdf_tree(3.5)


# --- what path_or_string may be --------------------------------------------------------------------

class BytesPath:
    def __init__(self, path):
        self.path = path

    def __fspath__(self):
        return os.fsencode(self.path)


def test_paths_of_every_kind(tmp_path):
    path = tmp_path / "small.urdf"
    path.write_text(SMALL)
    ref = rk.Chain.from_urdf(SMALL)
    for arg in (path, str(path), os.fsencode(path), BytesPath(str(path)), SMALL.encode(), "\n  " + SMALL):
        chain = rk.Chain.from_urdf(arg)
        assert chain == ref and chain.link_names == ref.link_names, arg
    assert rk.urdf_tree(path).links == rk.urdf_tree(SMALL).links


def test_a_path_that_starts_with_a_bracket_is_read_as_a_path_only_through_pathlike(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = pathlib.Path("<odd>.urdf")
    path.write_text(SMALL)
    assert rk.Chain.from_urdf(path).dof == 3
    with pytest.raises(ValueError, match="path_or_string: not a valid URDF document"):
        rk.Chain.from_urdf(str(path))  # a str starting with '<' is a document


def test_a_document_that_is_not_unicode_text_is_a_value_error():
    message = r"^path_or_string: not a valid URDF document \(text that is not Unicode\)$"
    for call in (rk.Chain.from_urdf, rk.urdf_tree):
        with pytest.raises(ValueError, match=message):
            call(SMALL.replace("j2", "j\ud800"))  # a lone surrogate


@pytest.mark.parametrize("arg", [42, None, ["a.urdf"], 1.5, bytearray(b"<robot/>")])
def test_wrong_kinds_are_type_errors_naming_the_argument(arg):
    with pytest.raises(TypeError) as err:
        rk.Chain.from_urdf(arg)
    assert str(err.value).startswith("path_or_string: expected a URDF document or a path to one (str, bytes or "
                                     f"os.PathLike), got {type(arg).__name__}")


def test_names_are_text():
    """Any UTF-8 name loads, from str or bytes; a bytes document in another encoding is refused where
    its names are read (not later, wherever a name is shown), while other bytes do not matter."""
    name = "coude_\u00e9_\u8098_\U0001f9be"
    xml = urdf([(name, "revolute", "base_link", "a")])
    for source in (xml, xml.encode()):
        chain = rk.Chain.from_urdf(source)
        assert chain.joint_names == (name,) and name in repr(chain)
        assert pickle.loads(pickle.dumps(chain)).joint_names == (name,)
    latin = urdf([("coude_\u00e9", "revolute", "base_link", "a")]).encode("latin-1")
    with pytest.raises(ValueError) as err:
        rk.Chain.from_urdf(latin)
    assert str(err.value) == "path_or_string: the joint name 'coude_\\xe9' is not UTF-8 text"
    with pytest.raises(ValueError, match="the link name 'a\\\\xe9' is not UTF-8"):
        rk.urdf_tree(urdf([("j", "revolute", "base_link", "a\u00e9")]).encode("latin-1"))
    commented = urdf([("j", "revolute", "base_link", "a")]).replace("<robot", "<!-- caf\u00e9 --><robot")
    assert rk.Chain.from_urdf(commented.encode("latin-1")).joint_names == ("j",)


@pytest.mark.parametrize("raw", [b"\xe4\xb8\xad", b"\xf4\x8f\xbf\xbf", b"\xc3\xa9x", b"\xc0\xaf", b"\xe0\x80\xaf",
                                 b"\xed\xa0\x80", b"\xf4\x90\x80\x80", b"\xe4\xb8", b"x\xc3", b"\xbf", b"\xf8\x88\x80\x80\x80"])
def test_utf8_is_checked_as_python_decodes_it(raw):
    xml = urdf([("j", "revolute", "base_link", "a")]).encode().replace(b'"j"', b'"j' + raw + b'"')
    try:
        expected = ("j" + raw.decode("utf-8"),)
    except UnicodeDecodeError:
        expected = None
    if expected is None:
        with pytest.raises(ValueError, match="is not UTF-8 text"):
            rk.Chain.from_urdf(xml)
    else:
        assert rk.Chain.from_urdf(xml).joint_names == expected


def test_base_and_tip_must_be_names():
    with pytest.raises(TypeError, match=r"^base: expected a link name \(str\) or None, got int$"):
        rk.Chain.from_urdf(SMALL, base=3)
    with pytest.raises(TypeError, match=r"^tip: expected a link name \(str\) or None, got bytes$"):
        rk.Chain.from_urdf(SMALL, tip=b"tool")
    with pytest.raises(ValueError, match="^tip: no link named 'nowhere' in the URDF$"):
        rk.Chain.from_urdf(SMALL, tip="nowhere")


def test_missing_files_say_so(tmp_path):
    with pytest.raises(ValueError, match="path_or_string: no readable file"):
        rk.Chain.from_urdf(tmp_path / "none.urdf")
    with pytest.raises(ValueError, match="path_or_string: no readable file"):
        rk.Chain.from_urdf(os.fsencode(tmp_path / "none.urdf"))
    with pytest.raises(ValueError, match="is a directory"):
        rk.Chain.from_urdf(tmp_path)


# --- names ----------------------------------------------------------------------------------------

def test_urdf_names_follow_the_frames():
    chain = rk.Chain.from_urdf(SMALL)
    assert chain.joint_names == ("j1", "j2", "j3")
    assert chain.link_names == ("base_link", "link1", "link2", "tool")
    q = np.array([0.3, 0.1, -0.4])
    frames = chain.frames(q)
    assert len(frames) == len(chain.link_names) == chain.dof + 1
    # each frame is the named link's pose, worked out by hand from the file
    link1 = tz(0.1) @ rz(q[0])
    link2 = link1 @ tx(0.5) @ tx(q[1])
    for frame, pose in zip(frames, (np.eye(4), link1, link2, small_fk(q))):
        np.testing.assert_allclose(frame, pose, atol=1e-12)


def test_sub_and_upward_chains_name_their_own_links():
    sub = rk.Chain.from_urdf(SMALL, "link1", "link3")
    assert sub.joint_names == ("j2", "j3") and sub.link_names == ("link1", "link2", "link3")
    up = rk.Chain.from_urdf(SMALL, "link3", "base_link")
    assert up.joint_names == ("j3", "j2", "j1") and up.link_names == ("link3", "link2", "link1", "base_link")


def test_a_fixed_joint_between_movable_ones_is_skipped():
    xml = urdf(serial(["a", "b", "c", "d"], ["revolute", "fixed", "revolute", "fixed"]))
    chain = rk.Chain.from_urdf(xml)
    assert chain.joint_names == ("j0_a", "j2_c") and chain.link_names == ("base_link", "a", "d")


@pytest.mark.parametrize("name", ["ur5", "panda", "rpr", "gen3"])
def test_dh_and_segment_chains_are_numbered(name):
    chain = rk.robots.get(name)
    n = chain.dof
    assert chain.joint_names == tuple(f"q{i}" for i in range(1, n + 1))
    assert chain.link_names == ("base",) + tuple(f"link{i}" for i in range(1, n + 1))


# --- q_from / q_dict ------------------------------------------------------------------------------

def test_q_from_and_q_dict():
    chain = rk.Chain.from_urdf(SMALL)
    q = chain.q_from({"j3": 0.5, "j1": -0.25, "j2": 0.125})
    assert q.shape == (3,) and q.dtype == np.float64 and list(q) == [-0.25, 0.125, 0.5]
    assert list(chain.q_from({"j2": 0.1}, default=0.0)) == [0.0, 0.1, 0.0]
    assert list(chain.q_from({"j2": 0.1}, default=[1.0, 2.0, 3.0])) == [1.0, 0.1, 3.0]
    assert list(chain.q_from({}, default=np.float32(2.0))) == [2.0, 2.0, 2.0]
    assert chain.q_dict([1, 2, 3]) == {"j1": 1.0, "j2": 2.0, "j3": 3.0}
    assert list(chain.q_dict([1, 2, 3])) == ["j1", "j2", "j3"]
    assert np.array_equal(chain.q_from(chain.q_dict(q)), q)
    ur5 = rk.robots.ur5()
    assert list(ur5.q_from({"q2": -1.0}, default=0.0)) == [0, -1.0, 0, 0, 0, 0]


def test_q_from_errors_say_what_is_wrong():
    chain = rk.Chain.from_urdf(SMALL)
    cases = [
        ({"j1": 0.0}, None, ValueError, "mapping: no value for joints 'j2' and 'j3' (pass default= for the joints "
                                        "left out)"),
        ({"j1": 0.0, "j2": 0.0}, None, ValueError, "mapping: no value for joint 'j3' (pass default= for the joints "
                                                   "left out)"),
        ({"j1": 0.0, "shoulder": 1.0, 7: 2.0}, 0.0, ValueError,
         "mapping: unknown joint names 'shoulder' and 7; the chain's joints are 'j1', 'j2' and 'j3'"),
        ({"elbow": 1.0}, None, ValueError, "mapping: unknown joint name 'elbow'; the chain's joints are 'j1', 'j2' "
                                           "and 'j3'"),
        ({"j1": "a"}, 0.0, TypeError, "mapping['j1']: expected a number, got str"),
        ({"j1": math.nan}, 0.0, ValueError, "mapping['j1']: must be finite, got nan"),
        ([("j1", 0.0)], 0.0, TypeError, "mapping: expected a mapping {joint name: value}, got list"),
        ({}, [0.0, 1.0], ValueError, "default: expected shape (3,), got (2,)"),
        ({}, math.inf, ValueError, "default: contains NaN or inf"),
    ]
    for mapping, default, kind, message in cases:
        with pytest.raises(kind) as err:
            chain.q_from(mapping, default=default)
        assert str(err.value) == message
    with pytest.raises(ValueError, match=r"^q: expected shape \(3,\), got \(2,\)$"):
        chain.q_dict([1.0, 2.0])


def test_long_name_lists_are_cut_in_messages():
    chain = rk.Chain.from_urdf(urdf(serial([f"l{i}" for i in range(1, 41)], ["revolute"] * 40, "l0")))
    with pytest.raises(ValueError) as err:
        chain.q_from({"nope": 1.0})
    assert str(err.value).endswith("'j19_l20' and 20 more")


# --- pickling, copies, equality, repr -------------------------------------------------------------

def test_names_survive_pickling_and_copies():
    chain = rk.Chain.from_urdf(UR_LIKE)
    for other in (pickle.loads(pickle.dumps(chain)), copy.deepcopy(chain), copy.copy(chain)):
        assert other == chain and repr(other) == repr(chain)
        assert other.joint_names == chain.joint_names and other.link_names == chain.link_names


def test_equality_ignores_names():
    renamed = SMALL.replace('"j1"', '"pan"').replace("base_link", "root")
    a, b = rk.Chain.from_urdf(SMALL), rk.Chain.from_urdf(renamed)
    assert a.joint_names != b.joint_names and a.link_names != b.link_names
    assert a == b and hash(a) == hash(b)


def test_a_version_1_state_loads_without_the_base_name():
    chain = rk.Chain.from_urdf(SMALL)
    state = chain.__getstate__()
    assert state[:3] == ("robokin.Chain", 2, "segments") and state[6] == "base_link"
    old = rk.Chain.__new__(rk.Chain)
    old.__setstate__(("robokin.Chain", 1) + state[2:6])
    assert old == chain and old.joint_names == chain.joint_names
    assert old.link_names == ("base", "link1", "link2", "tool")
    with pytest.raises(ValueError, match="Chain state"):
        rk.Chain.__new__(rk.Chain).__setstate__(("robokin.Chain", 2) + state[2:6])  # version 2 has the base name


def test_repr_shows_a_urdf_chains_names():
    assert repr(rk.Chain.from_urdf(SMALL)) == ("Chain(dof=3, joints='RPR', base='base_link', tip='tool', "
                                               "joint_names=('j1', 'j2', 'j3'))")
    assert repr(rk.Chain.from_urdf(SMALL, "link1", "link2")) == ("Chain(dof=1, joints='P', base='link1', "
                                                                 "tip='link2', joint_names=('j2',))")
    assert repr(rk.robots.rpr()) == "Chain(dof=3, joints='RPR')"  # numbered names are not repeated
    long = rk.Chain.from_urdf(urdf(serial([f"l{i}" for i in range(1, 41)], ["revolute"] * 40, "l0")))
    assert repr(long).endswith("joint_names=('j0_l1', 'j1_l2', 'j2_l3', 'j3_l4', 'j4_l5', 'j5_l6', 'j6_l7', "
                               "'j7_l8', ..., 'j38_l39', 'j39_l40'))")


# --- examples/arm.urdf ----------------------------------------------------------------------------

def test_the_example_arm_is_the_catalogues_ur5():
    arm, ur5 = rk.Chain.from_urdf(ARM), rk.robots.ur5()
    assert arm.link_names[0] == "base_link" and arm.link_names[-1] == "tool0"
    assert arm.joint_names == ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
                               "wrist_2_joint", "wrist_3_joint")
    assert all(np.array_equal(a, b) for a, b in zip(arm.limits, ur5.limits))
    q = np.random.default_rng(3).uniform(*ur5.limits, size=(200, 6))
    np.testing.assert_allclose(arm.fk(q), ur5.fk(q), rtol=0, atol=1e-12)
    np.testing.assert_allclose(arm.jacobian(q[0]), ur5.jacobian(q[0]), rtol=0, atol=1e-12)
    tree = rk.urdf_tree(str(ARM))
    assert tree.name == "arm" and tree.tip == "tool0" and "base" in tree.links
