"""Property tests of what URDF chains know of their names: robokin.urdf_tree on arbitrary documents
(consistent with the chain Chain.from_urdf builds by default), joint_names / link_names of URDF and
DH chains, q_from with arbitrary mappings and defaults (checked against the mapping, read here),
q_dict with arbitrary arrays, and the catalogue's named configurations with arbitrary names. Every
call returns a consistent result or raises ValueError / TypeError naming the argument."""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

import robokin as rk
from fuzz import arrays, assert_finite, check_call, wild_floats
from fuzz_chains import dh_chains
from test_fuzz_chain import sources
from test_urdf import SMALL

COVERS = {"urdf_tree", "Chain.joint_names", "Chain.link_names", "Chain.q_from", "Chain.q_dict",
          "robots.configurations"}

CHAINS = [rk.Chain.from_urdf(SMALL), rk.Chain.from_urdf(SMALL, "link1", "link2"), rk.robots.ur5(), rk.robots.rpr()]
keys = st.one_of(st.sampled_from(["j1", "j2", "j3", "q1", "q2", "", "J1", "tool"]), st.text(max_size=3),
                 st.sampled_from([1, None, b"j1", 2.5, ("j1",)]))
values = st.one_of(wild_floats, st.integers(-(2**1100), 2**1100),
                   st.sampled_from([True, "1", None, [1.0], np.float32(0.5), np.array(2.0), 1 + 2j, np.int64(3)]))
mappings = st.one_of(st.dictionaries(keys, values, max_size=5), st.sampled_from([[("j1", 1.0)], None, "j1", 3]))


@given(source=sources)
def test_urdf_tree_with_arbitrary_documents(source):
    tree = check_call(lambda: rk.urdf_tree(source), "path_or_string")
    if tree is None:
        return
    assert tree.links[0] == tree.root == tree.base and isinstance(repr(tree), str)
    assert len(set(tree.links)) == len(tree.links) == len(tree.joints) + 1
    assert [j.child for j in tree.joints] == tree.links[1:]
    assert all(tree.links.index(j.parent) < tree.links.index(j.child) for j in tree.joints)  # parents first
    assert tree.tips == sorted(tree.tips) and set(tree.tips) <= set(tree.links)
    assert (tree.tip is None) == (len(tree.tips) != 1) and (tree.movable == 0) == (not tree.tips)
    chain = check_call(lambda: rk.Chain.from_urdf(source), "path_or_string", "base", "tip")
    if tree.tip is None:
        assert chain is None
    elif chain is not None:
        assert chain.link_names[0] == tree.root and chain.link_names[-1] == tree.tip and chain.dof == tree.movable
        movable = [j.name for j in tree.joints if j.type in ("revolute", "continuous", "prismatic")]
        assert set(chain.joint_names) <= set(movable) and len(set(chain.joint_names)) == chain.dof


@given(source=sources)
def test_names_of_chains_from_arbitrary_documents(source):
    chain = check_call(lambda: rk.Chain.from_urdf(source, "base", "tool"), "path_or_string", "base", "tip")
    if chain is None:
        return
    assert len(chain.joint_names) == chain.dof and len(chain.link_names) == chain.dof + 1
    assert chain.link_names[0] == "base" and chain.link_names[-1] == "tool"
    assert all(isinstance(n, str) for n in chain.joint_names + chain.link_names) and isinstance(repr(chain), str)


@given(spec=dh_chains())
def test_dh_chains_are_numbered(spec):
    chain = spec["chain"]
    n = chain.dof
    assert chain.joint_names == tuple(f"q{i}" for i in range(1, n + 1))
    assert chain.link_names == ("base",) + tuple(f"link{i}" for i in range(1, n + 1))


def expected_default(default, n):
    """default as q_from reads it, or None when it must be refused."""
    if default is None:
        return np.full(n, math.nan)
    try:
        a = np.asarray(default)
    except (TypeError, ValueError):
        return None
    if a.dtype.kind not in "biuf" or a.shape not in ((), (n,)):
        return None
    a = np.broadcast_to(a.astype(float), (n,))
    return a if np.all(np.isfinite(a)) else None


@given(chain=st.sampled_from(CHAINS), mapping=mappings,
       default=st.one_of(st.none(), wild_floats, arrays([(), (1,), (3,), (6,), (2, 3)]), st.sampled_from(["0", [0.0]])))
def test_q_from_with_arbitrary_mappings(chain, mapping, default):
    q = check_call(lambda: chain.q_from(mapping, default=default), "mapping", "default")
    if q is None:
        return
    n, names = chain.dof, chain.joint_names
    assert isinstance(mapping, dict) and set(mapping) <= set(names)
    fallback = expected_default(default, n)
    assert fallback is not None
    assert q.shape == (n,) and q.dtype == np.float64
    assert_finite(q)
    for i, name in enumerate(names):
        assert q[i] == (float(mapping[name]) if name in mapping else fallback[i])


@given(chain=st.sampled_from(CHAINS), q=arrays([(1,), (3,), (6,), (2, 3)]))
def test_q_dict_with_arbitrary_arrays(chain, q):
    out = check_call(lambda: chain.q_dict(q), "q")
    if out is None:
        return
    assert list(out) == list(chain.joint_names)
    np.testing.assert_array_equal(list(out.values()), np.asarray(q, dtype=float))
    np.testing.assert_array_equal(chain.q_from(out), np.asarray(q, dtype=float))


@given(name=st.one_of(st.sampled_from(rk.robots.names()), st.text(max_size=6), st.sampled_from([None, 3, b"ur5"])))
def test_configurations_with_arbitrary_names(name):
    named = check_call(lambda: rk.robots.configurations(name), "name")
    if named is None:
        return
    chain = rk.robots.get(name)
    lower, upper = chain.limits
    assert "zero" in named
    for q in named.values():
        assert q.shape == (chain.dof,) and np.all((lower <= q) & (q <= upper))
