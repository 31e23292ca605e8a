"""The repr of the core's classes, written in Python (robokin._printing): the exact texts the
earlier C++ reprs gave for the cases whose format has rules (long name lists elided, a one-item
tuple, tied URDF tips, a deep tree's indentation and its cut, solutions outside the limits, %.6g
numbers, a DH table with a tool)."""

import numpy as np

import robokin as rk


def _urdf(name, links, joints):
    return f'<robot name="{name}">' + "".join(f'<link name="{n}"/>' for n in links) + "".join(joints) + "</robot>"


def _revolute(name, parent, child, kind="revolute"):
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if kind == "revolute" else ""
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<axis xyz="0 0 1"/><origin xyz="0 0 0.1"/>{limit}</joint>')


def _solutions(dof, q, postures, singular, within):
    s = rk.closed.IKSolutions.__new__(rk.closed.IKSolutions)
    s.__setstate__((1, dof, np.array(q, dtype=float).reshape(len(postures), dof), postures, singular, within))
    return s


def test_a_long_list_of_joint_names_is_elided_and_a_single_name_is_a_one_item_tuple():
    links = [f"l{i}" for i in range(15)]
    chain = rk.Chain.from_urdf(_urdf("long", links, [_revolute(f"j{i}", links[i], links[i + 1]) for i in range(14)]))
    assert repr(chain) == ("Chain(dof=14, joints='RRRRRRRRRRRRRR', base='l0', tip='l14', joint_names=('j0', 'j1', "
                           "'j2', 'j3', 'j4', 'j5', 'j6', 'j7', ..., 'j12', 'j13'))")
    one = rk.Chain.from_urdf(_urdf("one", ["a", "b"], [_revolute("j", "a", "b")]))
    assert repr(one) == "Chain(dof=1, joints='R', base='a', tip='b', joint_names=('j',))"


def test_a_dh_chain_shows_its_rows_as_written_and_says_a_tool_follows():
    tool = np.eye(4)
    tool[2, 3] = 0.1
    chain = rk.Chain.from_dh([(0.1, 0.2, 0.3, 0.4, "P"), (1.0, 0, 0, 0, "R")], modified=True, tool=tool)
    assert repr(chain) == ("Chain(dof=2, joints='PR', modified dh=[\n    (0.1, 0.2, 0.3, 0.4, 'P'),\n"
                           "    (1.0, 0.0, 0.0, 0.0, 'R')], tool)")


def test_a_urdf_tree_with_tied_tips_lists_them_and_a_deep_tree_is_cut():
    tie = rk.urdf_tree(_urdf("tie", "abc", [_revolute("j1", "a", "b"), _revolute("j2", "a", "c", "continuous")]))
    assert repr(tie) == ("UrdfTree(name='tie', root='a', base='a', tip=None, tips=['b', 'c'], 3 links, 2 joints)\n"
                         "  a -> b (j1, revolute)\n  a -> c (j2, continuous)")
    links = [f"l{i}" for i in range(206)]
    deep = rk.urdf_tree(_urdf("deep", links, [_revolute(f"j{i}", links[i], links[i + 1], "fixed") for i in range(205)]))
    lines = repr(deep).splitlines()
    assert len(lines) == 202 and lines[0] == "UrdfTree(name='deep', root='l0', base='l0', tip=None, 206 links, 205 joints)"
    assert lines[1] == "  l0 -> l1 (j0, fixed)"
    # Indented two spaces per level up to 16 levels.
    assert lines[17] == " " * 32 + "l16 -> l17 (j16, fixed)" and lines[-2] == " " * 32 + "l199 -> l200 (j199, fixed)"
    assert lines[-1] == "  ... and 5 more joints"


def test_solutions_show_their_postures_limits_and_numbers_to_six_significant_digits():
    s = _solutions(3, [[0.3, -1.0, 1e-16], [-0.0, 2.5e7, 3.14159265358979]], ("elbow up", "elbow down"), True,
                   (True, False))
    assert repr(s) == ("IKSolutions(2 solutions, 1 outside the limits, singular:\n  elbow up: [0.3, -1, 1e-16]\n"
                       "  elbow down (outside the limits): [-0, 2.5e+07, 3.14159]\n)")
    assert repr(_solutions(2, [[1.0, 2.0]], ("elbow up",), False, (True,))) == "IKSolutions(1 solution:\n  elbow up: [1, 2]\n)"
    assert repr(_solutions(2, [], (), False, ())) == "IKSolutions(0 solutions)"


def test_robots_and_solvers_show_what_builds_them_again():
    assert repr(rk.RRR3(0.3, 0.1, 0.25, 0.3)) == "RRR3(base_radius=0.3, platform_radius=0.1, l1=0.25, l2=0.3)"
    panda = rk.robots.panda()
    held = rk.closed.ClosedSolver(panda, None, locked={3: -1.2})
    assert repr(held) == (f"ClosedSolver({panda!r}, family='spherical shoulder, axes 5, 6 meet before axis 7', "
                          "limits=None, locked={3: -1.2})")
    assert repr(rk.closed.ClosedSolver(panda, locked={3: -1.2})).endswith("axis 7', locked={3: -1.2})")
    assert repr(rk.IKSolver(panda, method="gn", tol_p=1e-7)) == (
        "IKSolver(method='gn', task='pose', tol_p=1e-07, tol_r=1e-09, max_iter=100, restarts=None, timeout=None, "
        "damping=None, stall_window=None)")


def test_options_and_results_show_every_field_and_long_arrays_by_shape():
    chain = rk.robots.ur5()
    T = chain.fk(np.full(6, 0.3))
    batch = rk.ik_batch(chain, np.stack([T] * 12), np.zeros(6), seed=1)
    assert repr(batch) == ("IKBatchResult(q=<array (12, 6) float64>, success=<array (12,) bool>, "
                           "iterations=<array (12,) int32>, attempts=<array (12,) int32>, "
                           "error_p=<array (12,) float64>, error_r=<array (12,) float64>)")
    assert repr(rk.ReachOptions(tol=1e-6)) == ("ReachOptions(max_iter=25, tol=1e-06, gain=0.75, dt=0.025, "
                                                "saturate=True, damping=0.0)")
