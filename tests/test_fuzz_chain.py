"""Property tests of the serial chains: Chain.from_dh / from_segments / from_urdf with arbitrary
definitions, FK, Jacobians, frames and points with arbitrary arrays, joint_limit_cost, the robot
catalogue and the RPR self-motion set. Every call returns finite, correctly shaped results (checked
against the numpy DH product where the input is well formed) or raises ValueError / TypeError
naming the argument."""

import math
import os
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import robokin as rk
from dh_reference import fk_dh
from fuzz import arrays, assert_finite, check_call, finite_arrays, wild_floats
from fuzz_chains import dh_chains

COVERS = {
    "Chain.table",
    "Chain.from_dh",
    "Chain.from_segments",
    "Chain.from_urdf",
    "Chain.dof",
    "Chain.joint_types",
    "Chain.natural_task",
    "Chain.limits",
    "Chain.fk",
    "Chain.jacobian",
    "Chain.frames",
    "Chain.point_in_frame",
    "joint_limit_cost",
    "robots.rpr",
    "robots.prr",
    "robots.planar_3r",
    "robots.rp",
    "robots.ur5",
    "robots.puma560",
    "robots.rpr_self_motion",
}

PI = math.pi
INF = math.inf
TASK_ROWS = {"pose": [0, 1, 2, 3, 4, 5], "position": [0, 1, 2], "xy": [0, 1], "xyphi": [0, 1, 5]}
tasks = st.one_of(st.sampled_from([*TASK_ROWS, "bad", "", "POSE"]), st.sampled_from([None, 1, b"pose", ["xy"]]))
CHAINS = [
    rk.robots.rpr(),
    rk.robots.ur5(),
    rk.robots.planar_3r(),
    rk.robots.rp(),
    rk.Chain.from_dh([(0.0, 0.0, 0.0, 0.0, "P")]),
    rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True),
]


def is_rigid(T, tol=1e-9):
    R = T[..., :3, :3]
    eye = np.broadcast_to(np.eye(3), R.shape)
    assert np.allclose(np.swapaxes(R, -1, -2) @ R, eye, rtol=0, atol=tol), T
    assert np.all(T[..., 3, :] == [0.0, 0.0, 0.0, 1.0]), T
    return True


def assert_table(chain, header_lines):
    """chain.table() (and str) of any chain: text with the header, a row per joint by its name."""
    text = chain.table()
    assert isinstance(text, str) and str(chain) == text and text.isascii()
    lines = text.splitlines()
    rows = [line.split()[0] for line in lines[header_lines:] if line.split() and line.split()[0] in chain.joint_names]
    assert rows == list(chain.joint_names)


def q_shape(q):
    """The shape numpy sees in q, or None when it is no rectangular array."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", np.exceptions.ComplexWarning)
            return np.asarray(q, dtype=float).shape
    except (TypeError, ValueError):
        return None


# --- Chain.from_dh ---------------------------------------------------------------------------

cells = st.one_of(wild_floats, st.integers(-5, 5), st.sampled_from(["R", "P", "1.0", None, [1.0], np.float32(2.0)]))
kinds = st.one_of(st.sampled_from(["R", "P", "r", "p", "F", "X", "RP", "", " R", "revolute"]), st.sampled_from([None, 1, b"R"]))
rows_strategy = st.one_of(
    # well-shaped rows with arbitrary numbers and joint types
    st.lists(st.tuples(cells, cells, cells, cells, kinds), min_size=0, max_size=8),
    # rows of any length
    st.lists(st.lists(st.one_of(cells, kinds), min_size=0, max_size=7), min_size=0, max_size=4),
    st.sampled_from([None, "RPR", 3, [None], [[]], np.zeros((2, 5))]),
)
tools = st.one_of(st.none(), arrays([(4, 4), (3, 3), (4,), (1, 4, 4)]),
                  st.sampled_from([np.eye(4), 2 * np.eye(4), np.diag([1.0, 1.0, -1.0, 1.0])]))
limit_vectors = st.one_of(arrays([(0,), (1,), (2,), (3,), (7,), (2, 2)]), st.sampled_from([[0.0, -INF], [INF], [np.nan]]))
limits_strategy = st.one_of(st.none(), st.tuples(limit_vectors, limit_vectors),
                            st.sampled_from([(), ([0.0],), "limits", ([0.0], [1.0], [2.0]), 3.0]))
modified_strategy = st.one_of(st.booleans(), st.sampled_from([None, 0, 1, "yes", 2.5]))


@given(rows=rows_strategy, modified=modified_strategy, tool=tools, limits=limits_strategy)
def test_from_dh_with_arbitrary_definitions(rows, modified, tool, limits):
    chain = check_call(lambda: rk.Chain.from_dh(rows, modified=modified, tool=tool, limits=limits),
                       "rows", "modified", "tool", "limits")
    if chain is None:
        return
    n = len(rows)
    assert chain.dof == n
    assert chain.joint_types == "".join(str(r[4]).upper() for r in rows)
    lo, hi = chain.limits
    assert lo.shape == hi.shape == (n,) and not np.any(np.isnan(lo)) and np.all(lo <= hi)
    assert np.all(lo < INF) and np.all(hi > -INF)
    assert_table(chain, 3)
    q = np.clip(np.zeros(n), lo, hi)
    T = check_call(lambda: chain.fk(q), "q")
    if T is not None:
        assert T.shape == (4, 4)
        assert_finite(T)


@given(case=dh_chains(), values=finite_arrays((7,), -7.0, 7.0), batch=st.integers(0, 4),
       tool=st.one_of(st.none(), st.tuples(finite_arrays((3,), -1, 1), finite_arrays((3,), -PI, PI))))
def test_dh_chain_equals_the_numpy_dh_product(case, values, batch, tool):
    """Random well-formed chains: FK is the DH product (times the tool), a rigid transform; the batch
    gives the single results bit for bit; the Jacobian is KDL's; the frames are the partial
    products; point_in_frame maps through them."""
    rows, modified, n = case["rows"], case["modified"], case["chain"].dof
    T_tool = np.eye(4)
    if tool is not None:
        T_tool = rk.robots.ur5().fk(tool[1].tolist() * 2)  # some rigid transform
        T_tool[:3, 3] = tool[0]
    chain = rk.Chain.from_dh(rows, modified=modified, tool=T_tool if tool is not None else None, limits=case["limits"])
    q = values[:n]
    T = chain.fk(q)
    assert T.shape == (4, 4) and is_rigid(T)
    np.testing.assert_allclose(T, fk_dh(rows, q, modified) @ T_tool, rtol=0, atol=1e-9)
    Q = np.tile(q, (batch, 1)) + np.arange(batch)[:, None] * 0.1
    TB = chain.fk(Q)
    assert TB.shape == (batch, 4, 4)
    for k in range(batch):
        np.testing.assert_array_equal(TB[k], chain.fk(Q[k]))
    J6 = chain._jacobian_kdl(q)
    for task, rows_of in TASK_ROWS.items():
        J = chain.jacobian(q, task=task)
        assert J.shape == (len(rows_of), n)
        np.testing.assert_allclose(J, J6[rows_of], rtol=0, atol=1e-9)
        assert chain.jacobian(Q, task=task).shape == (batch, len(rows_of), n)
    F = chain.frames(q)
    assert F.shape == (n + 1, 4, 4) and is_rigid(F)
    np.testing.assert_allclose(F[0], np.eye(4), atol=1e-12)
    for i in range(1, n + 1):
        np.testing.assert_allclose(F[i], fk_dh(rows[:i], q[:i], modified) @ (T_tool if i == n else np.eye(4)),
                                   rtol=0, atol=1e-9)
    point = values[:3] / 7
    for frame, in_frame in ((n, 0), (0, n), (n // 2, n)):
        p = chain.point_in_frame(q, point, frame, in_frame)
        expected = np.linalg.solve(F[in_frame], F[frame] @ np.append(point, 1.0))[:3]
        assert p.shape == (3,)
        np.testing.assert_allclose(p, expected, rtol=0, atol=1e-9)


@given(case=dh_chains(), data=st.data())
def test_natural_task_is_the_rule_on_the_jacobians_rows(case, data):
    """A planar arm (rows v_z, w_x, w_y of KDL's Jacobian zero, here at a random q: the core reads
    q = 0) controls "xyphi" with three revolute joints or more, "xy" with fewer; another arm "pose"
    with six joints or more, "position" with fewer."""
    chain = case["chain"]
    q = np.array(data.draw(st.lists(st.floats(-PI, PI), min_size=chain.dof, max_size=chain.dof)))
    J = chain._jacobian_kdl(q)
    off = np.max(np.abs(J[2:5])) / max(1.0, np.max(np.abs(J)))
    assume(not 1e-11 < off < 1e-7)  # clearly planar or clearly not
    revolute = chain.joint_types.count("R")
    expected = ("xyphi" if revolute >= 3 else "xy") if off <= 1e-11 else ("pose" if chain.dof >= 6 else "position")
    assert chain.natural_task == expected, (case["rows"], off)


# --- FK, Jacobian, frames, point_in_frame with arbitrary arrays ------------------------------

chains = st.sampled_from(CHAINS)


@given(chain=chains, q=arrays(), task=tasks)
def test_fk_jacobian_frames_with_arbitrary_q(chain, q, task):
    n = chain.dof
    shape = q_shape(q)
    T = check_call(lambda: chain.fk(q), "q")
    if T is not None:
        assert shape in ((n,), (shape[0], n)) if shape is not None and len(shape) == 2 else shape == (n,)
        assert T.shape == shape[:-1] + (4, 4)
        assert_finite(T)
        is_rigid(T, tol=1e-6)
    J = check_call(lambda: chain.jacobian(q, task=task), "q", "task")
    if J is not None:
        assert J.shape == shape[:-1] + (len(TASK_ROWS[task if task is not None else chain.natural_task]), n)
        assert_finite(J)
    F = check_call(lambda: chain.frames(q), "q")
    if F is not None:
        assert shape == (n,) and F.shape == (n + 1, 4, 4)
        assert_finite(F)


@given(chain=chains, q=arrays([(3,), (6,), (7,), (1,), (2, 3)], elements=st.floats(-1e6, 1e6)), data=st.data())
def test_fk_matches_kdl_for_any_finite_q(chain, q, data):
    """Any layout of a right-sized q gives KDL's answer (within the rounding of large angles)."""
    T = check_call(lambda: chain.fk(q), "q")
    if T is None:
        return
    qa = np.asarray(q, dtype=float)
    for k, Tk in enumerate(T.reshape(-1, 4, 4)):
        qk = qa.reshape(-1, chain.dof)[k]
        scale = 1e-9 * (1 + np.abs(qk).max())
        np.testing.assert_allclose(Tk, chain._fk_kdl(qk), rtol=0, atol=scale)


frame_ints = st.one_of(st.integers(-3, 9), st.sampled_from([2**31, -(2**31) - 1, 2**63, -(2**70)]),
                       st.sampled_from([1.5, None, "0", np.int64(1), True]))


@given(chain=chains, q=arrays([(3,), (6,), (7,), (1,), (2, 3)]), point=arrays([(3,), (2,), (4,), (1, 3)]),
       frame=frame_ints, in_frame=frame_ints)
def test_point_in_frame_with_arbitrary_arguments(chain, q, point, frame, in_frame):
    p = check_call(lambda: chain.point_in_frame(q, point, frame, in_frame), "q", "point", "frame", "in_frame")
    if p is None:
        return
    assert p.shape == (3,)
    assert_finite(p)
    F = chain.frames(q)
    expected = np.linalg.solve(F[int(in_frame)], F[int(frame)] @ np.append(np.asarray(point, dtype=float), 1.0))[:3]
    np.testing.assert_allclose(p, expected, rtol=1e-9, atol=1e-9 * (1 + np.abs(expected).max()))


@given(chain=chains, q=arrays())
def test_joint_limit_cost_with_arbitrary_q(chain, q):
    z = check_call(lambda: rk.joint_limit_cost(chain, q), "q")
    if z is None:
        return
    shape = q_shape(q)
    lo, hi = chain.limits
    w = np.where(np.isfinite(hi - lo) & (hi > lo), 1.0 / np.where(hi > lo, hi - lo, 1.0), 0.0)
    with np.errstate(invalid="ignore"):
        mid = np.where(np.isfinite(lo + hi), (lo + hi) / 2, 0.0)
    with np.errstate(over="ignore"):
        expected = 0.5 * np.sum((w * (mid - np.asarray(q, dtype=float))) ** 2, axis=-1)
    if shape == (chain.dof,):
        assert isinstance(z, float)
    else:
        assert z.shape == (shape[0],)
    assert_finite(z)
    np.testing.assert_allclose(z, expected, rtol=1e-12, atol=0)


# --- Chain.from_segments ---------------------------------------------------------------------

segment = st.tuples(
    st.one_of(st.sampled_from(["R", "P", "F", "f", "X", ""]), st.sampled_from([None, 0])),
    st.one_of(arrays([(3,), (2,)]), st.sampled_from([(0, 0, 1), (1e-300, 0, 0), (0, 0, 0), (1e308, 1e308, 0)])),
    st.one_of(arrays([(4, 4), (3, 4)]), st.just(np.eye(4))),
)
segments_strategy = st.one_of(
    st.lists(segment, min_size=0, max_size=5),
    st.lists(st.lists(st.sampled_from(["R", (0, 0, 1), np.eye(4), None]), max_size=4), max_size=3),
    st.sampled_from([None, "R", 1]),
)


@given(segments=segments_strategy, tool=tools, limits=limits_strategy)
def test_from_segments_with_arbitrary_definitions(segments, tool, limits):
    chain = check_call(lambda: rk.Chain.from_segments(segments, tool=tool, limits=limits), "segments", "tool", "limits")
    if chain is None:
        return
    kinds = "".join(str(s[0]).upper() for s in segments)
    assert chain.joint_types == kinds.replace("F", "") and chain.dof == len(chain.joint_types)
    assert_table(chain, 4)
    q = np.clip(np.zeros(chain.dof), *chain.limits)
    T = check_call(lambda: chain.fk(q), "q")
    if T is not None:
        assert T.shape == (4, 4)
        assert_finite(T)
        is_rigid(T, tol=1e-6)
    J = check_call(lambda: chain.jacobian(q), "q")
    if J is not None:
        assert J.shape == (6, chain.dof)
        assert_finite(J)


# --- Chain.from_urdf -------------------------------------------------------------------------

URDF = """<?xml version="1.0"?>
<robot name="fuzz">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="tool"/>
  <joint name="j1" type="{t1}">
    <parent link="base"/><child link="l1"/>
    <origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/>
    <limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="{t2}">
    <parent link="l1"/><child link="l2"/>
    <origin xyz="0.5 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/>
  </joint>
  <joint name="flange" type="fixed">
    <parent link="l2"/><child link="tool"/><origin xyz="{xyz}" rpy="0 0 0"/>
  </joint>
</robot>
"""
number_text = st.one_of(st.floats(-3, 3).map(repr), st.sampled_from(
    ["nan", "inf", "-inf", "1e308", "-1e308", "1e400", "abc", "", "1 2", "0x10", "1e-320"]))
triple_text = st.one_of(st.tuples(number_text, number_text, number_text).map(" ".join),
                        st.sampled_from(["0 0 0", "0 0 1", "1 0", "0 0 1 0", "", "nan nan nan", "1e-300 0 0"]))
joint_kinds = st.sampled_from(["revolute", "continuous", "prismatic", "fixed", "floating", "planar", "spherical", "x"])
good_urdfs = st.builds(lambda t1, t2, xyz, rpy, axis, lower, upper: URDF.format(
    t1=t1, t2=t2, xyz=xyz, rpy=rpy, axis=axis, lower=lower, upper=upper),
    joint_kinds, joint_kinds, triple_text, triple_text, triple_text, number_text, number_text)


@st.composite
def mangled(draw, urdfs):
    """A URDF cut short or with a character replaced: malformed XML."""
    text = draw(urdfs)
    cut = draw(st.integers(0, len(text)))
    how = draw(st.sampled_from(["cut", "replace", "none"]))
    if how == "cut":
        return text[:cut]
    if how == "replace":
        return text[:cut] + draw(st.sampled_from(["<", ">", '"', "&", "\x00", "é", "/"])) + text[cut + 1:]
    return text


names = st.one_of(st.sampled_from(["base", "l1", "l2", "tool", "nowhere", "", "j1"]), st.text(max_size=5),
                  st.sampled_from([None, 3, b"base"]))
sources = st.one_of(mangled(good_urdfs), st.text(max_size=30),
                    st.sampled_from(["/no/such/file.urdf", "/", ".", "", "<", "<robot/>", None, 42, b"<robot/>"]))


@given(source=sources, base=names, tip=names)
def test_from_urdf_with_arbitrary_documents(source, base, tip):
    chain = check_call(lambda: rk.Chain.from_urdf(source, base, tip), "path_or_string", "base", "tip")
    if chain is None:
        return
    n = chain.dof
    assert n >= 1 and len(chain.joint_types) == n and set(chain.joint_types) <= {"R", "P"}
    lo, hi = chain.limits
    assert lo.shape == hi.shape == (n,) and not np.any(np.isnan(lo) | np.isnan(hi)) and np.all(lo <= hi)
    q = np.clip(np.zeros(n), lo, hi)
    for call, shape in ((lambda: chain.fk(q), (4, 4)), (lambda: chain.jacobian(q), (6, n)),
                        (lambda: chain.frames(q), (n + 1, 4, 4))):
        out = check_call(call, "q")
        if out is not None:
            assert out.shape == shape
            assert_finite(out)
        else:
            assert "e308" in source  # only lengths near the largest double overflow


def test_from_urdf_file_and_path_like(tmp_path):
    text = URDF.format(t1="revolute", t2="prismatic", xyz="0 0 0.1", rpy="0 0 0", axis="0 0 1", lower="-1", upper="1")
    path = tmp_path / "fuzz.urdf"
    path.write_text(text)
    for source in (text, path, str(path), os.fsencode(str(path)).decode()):
        chain = rk.Chain.from_urdf(source, "base", "tool")
        assert chain.dof == 2 and chain.joint_types == "RP"
    with pytest.raises(ValueError, match="path_or_string"):
        rk.Chain.from_urdf(tmp_path, "base", "tool")  # a directory


# --- the catalogue ---------------------------------------------------------------------------

lengths = st.one_of(wild_floats, st.sampled_from([0, 1, -1, True, "1", None, [1.0], np.float32(0.5)]))


@given(name=st.sampled_from(["prr", "planar_3r", "rp"]), args=st.lists(lengths, max_size=4))
def test_robot_factories_with_arbitrary_arguments(name, args):
    factory = getattr(rk.robots, name)
    argnames = {"prr": ("a2", "a3"), "planar_3r": ("a1", "a2", "a3"), "rp": ("stroke",)}[name]
    chain = check_call(lambda: factory(*args), *argnames, "positional argument")
    if chain is None:
        return
    assert len(args) <= len(argnames)
    assert chain.joint_types == {"prr": "PRR", "planar_3r": "RRR", "rp": "RP"}[name]
    q = np.clip(np.full(chain.dof, 0.3), *chain.limits)
    T = check_call(lambda: chain.fk(q), "q")  # lengths near 1e308 overflow
    if T is not None:
        assert T.shape == (4, 4)
        assert_finite(T)
        is_rigid(T)


@pytest.mark.parametrize("name, kinds", [("rpr", "RPR"), ("ur5", "RRRRRR"), ("puma560", "RRRRRR"), ("prr", "PRR"),
                                         ("planar_3r", "RRR"), ("rp", "RP")])
def test_robot_factories_build_their_chains(name, kinds):
    chain = getattr(rk.robots, name)()
    assert chain.joint_types == kinds and chain.dof == len(kinds)
    lo, hi = chain.limits
    q = np.clip(np.linspace(-1, 1, chain.dof), lo, hi)
    assert is_rigid(chain.fk(q))
    with pytest.raises(TypeError):
        getattr(rk.robots, name)(1, 2, 3, 4)


def rpr_tip(q):
    t1, t2, t3 = q
    r = rk.robots.RPR_L1 + t2
    return np.array([r * math.cos(t1) + rk.robots.RPR_L3 * math.cos(t1 + t3),
                     r * math.sin(t1) + rk.robots.RPR_L3 * math.sin(t1 + t3)])


@given(point=st.one_of(arrays([(2,), (3,), (1, 2)]), finite_arrays((2,), -3.0, 3.0)),
       t1=st.one_of(st.none(), arrays([(0,), (1,), (5,), (2, 2)]), finite_arrays((4,), -1.0, 3.0)),
       num=st.one_of(st.integers(-2, 50), st.sampled_from([1.5, None, "3", 2**70, True])))
def test_rpr_self_motion_with_arbitrary_arguments(point, t1, num):
    out = check_call(lambda: rk.robots.rpr_self_motion(point, t1, num=num), "point", "t1", "num")
    if out is None:
        return
    k = num if t1 is None else len(t1)
    assert out.shape == (2, k, 3)
    lo, hi = rk.robots.RPR_LIMITS
    for q in out.reshape(-1, 3):
        if np.all(np.isnan(q)):
            continue
        assert_finite(q)  # a row is all NaN (no solution) or a solution
        assert np.all(q >= lo) and np.all(q <= hi)
        p = np.asarray(point, dtype=float)
        np.testing.assert_allclose(rpr_tip(q), p, rtol=0, atol=1e-9 * (1 + np.abs(p).max()))


# --- regressions: the cases the fuzzing found ------------------------------------------------


def test_urdf_zero_axis_is_rejected():
    """<axis xyz="0 0 0"> (or shorter than KDL's 1e-6) gave a chain whose every pose was NaN."""
    for axis in ("0 0 0", "1e-7 0 0"):
        text = URDF.format(t1="revolute", t2="prismatic", xyz="0 0 0.1", rpy="0 0 0", axis=axis, lower="-1", upper="1")
        with pytest.raises(ValueError, match="path_or_string: joint 'j1' has a zero axis"):
            rk.Chain.from_urdf(text, "base", "tool")


def test_overflowing_results_raise_naming_q():
    """Lengths or prismatic joints near 1e308 made fk, jacobian, frames and point_in_frame return inf
    or NaN, and joint_limit_cost inf."""
    huge = rk.Chain.from_dh([(1e308, 0, 0, 0, "R")] * 2)
    for call in (lambda: huge.fk([0.0, 0.0]), lambda: huge.fk([[0.0, 0.0]]), lambda: huge.jacobian([0.0, 0.0]),
                 lambda: huge.frames([0.0, 0.0])):
        with pytest.raises(ValueError, match="q: the result is not finite"):
            call()
    with pytest.raises(ValueError, match="q, point: the result is not finite"):
        rk.robots.planar_3r().point_in_frame([PI / 4, 0, 0], [1.5e308, 1.5e308, 0], 3, 0)
    prismatic = rk.Chain.from_dh([(0, 0, 1e308, 0, "P")])
    with pytest.raises(ValueError, match="q: the result is not finite"):
        prismatic.fk([1e308])
    with pytest.raises(ValueError, match="q: the cost is not finite"):
        rk.joint_limit_cost(rk.robots.rp(), [0.0, 1e300])
    assert math.isfinite(rk.joint_limit_cost(rk.robots.rp(), [0.0, 1e100]))


def test_robot_factories_name_their_arguments():
    """rk.robots.planar_3r("1") said "rows[0] a: expected a number", rp(-1) "limits: joint 1 ...",
    rpr_self_motion(p, num=-1) or num=1.5 numpy's messages: none named the argument."""
    with pytest.raises(TypeError, match="a1: expected a number"):
        rk.robots.planar_3r("1")
    with pytest.raises(ValueError, match="a3: must be a finite number"):
        rk.robots.prr(1.0, math.nan)
    with pytest.raises(ValueError, match="stroke: must be a finite number >= 0"):
        rk.robots.rp(-1)
    with pytest.raises(ValueError, match="num: expected an int in"):
        rk.robots.rpr_self_motion([1.0, 1.0], num=-1)
    with pytest.raises(TypeError, match="num: expected an int"):
        rk.robots.rpr_self_motion([1.0, 1.0], num=1.5)
    assert rk.robots.planar_3r(np.float32(0.5), 1, -1.0).dof == 3


@given(case=dh_chains(), q=arrays([(7,), (3, 7), (40, 7), (2, 3)]),
       part=st.one_of(st.sampled_from(["frame", "position"]), st.sampled_from(["Position", "", None, 0, b"frame"])))
def test_fk_part_position_is_the_frames_last_column(case, q, part):
    """Any chain, any array, any ``part``: "position" gives (3,) or (N, 3), the frames' last column
    bit for bit, within 1e-9 of KDL; otherwise a ValueError / TypeError naming part or q."""
    chain, n = case["chain"], case["chain"].dof
    if isinstance(q, np.ndarray) and q.ndim >= 1 and q.shape[-1] >= n:
        q = q[..., :n]  # mostly the right width, sometimes not
    P = check_call(lambda: chain.fk(q, part=part), "part", "q")
    if P is None:
        return
    F = chain.fk(q)
    assert_finite(P)
    if part == "frame":
        np.testing.assert_array_equal(P, F)
        return
    assert P.shape == F.shape[:-2] + (3,)
    np.testing.assert_array_equal(P, F[..., :3, 3])
    if P.size:
        first = np.asarray(q, dtype=float).reshape(-1, n)[0]
        np.testing.assert_allclose(P.reshape(-1, 3)[0], chain._fk_kdl(first)[:3, 3], rtol=0, atol=1e-9 * (1 + np.abs(P).max()))
