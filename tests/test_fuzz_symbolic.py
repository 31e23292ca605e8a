"""Property tests of robokin.symbolic: any DH chain (standard or modified, revolute and prismatic
rows, angles on and off the multiples of pi/12, a tool) gives matrices equal to the numeric chain's
FK and Jacobian at any configuration; any wrong argument raises TypeError / ValueError naming it.
Few examples: sympy is slow."""

import math

import numpy as np
import sympy as sp
from fuzz import check_call
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import robokin as rk
from robokin import symbolic

COVERS = {"symbolic.fk", "symbolic.jacobian", "symbolic.table"}

FEW = settings(max_examples=max(5, settings.default.max_examples // 10), deadline=None,
               suppress_health_check=[HealthCheck.too_slow])

angles = st.one_of(st.sampled_from([k * math.pi / 12 for k in range(-12, 13)]), st.floats(-math.pi, math.pi))
lengths = st.one_of(st.just(0.0), st.floats(-2.0, 2.0))
rows = st.tuples(lengths, angles, lengths, angles, st.sampled_from("RP"))


@FEW
@given(table=st.lists(rows, min_size=1, max_size=4), modified=st.booleans(), rpy=st.lists(angles, min_size=3, max_size=3),
       data=st.data())
def test_symbolic_matrices_are_the_chains(table, modified, rpy, data):
    tool = rk.pose.from_rpy(rpy, position=[0.1, -0.2, 0.3])
    chain = rk.Chain.from_dh(table, modified=modified, tool=tool)
    q = data.draw(st.lists(st.floats(-3.0, 3.0), min_size=chain.dof, max_size=chain.dof))
    T = symbolic.fk(chain, q, simplify=False)
    J = symbolic.jacobian(chain, q, task="pose", simplify=False)
    assert np.allclose(np.array(T.evalf(), dtype=float), chain.fk(q), atol=1e-9)
    assert np.allclose(np.array(J.evalf(), dtype=float), chain.jacobian(q, task="pose"), atol=1e-9)
    assert symbolic.table(chain).shape == (chain.dof, 4)


wild = st.one_of(st.none(), st.text(max_size=3), st.integers(-3, 3), st.floats(allow_nan=True, allow_infinity=True),
                 st.complex_numbers(max_magnitude=2), st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=4),
                 st.sampled_from(["pose", "xy", "symbols", "values", [1j, 0, 0], (1, 2, 3), b"xy"]))


@FEW
@given(chain=st.sampled_from([rk.robots.prr(), rk.robots.rpr(), rk.robots.planar_3r(), "prr", None]),
       q=wild, task=wild, lengths=wild)
def test_wrong_arguments_are_named(chain, q, task, lengths):
    for call in (lambda: symbolic.fk(chain, q, lengths, False),
                 lambda: symbolic.jacobian(chain, q, task, lengths, False),
                 lambda: symbolic.table(chain, lengths)):
        out = check_call(call, "chain", "q", "task", "lengths")
        if out is not None:
            assert not out.has(sp.nan, sp.zoo, sp.oo, -sp.oo)
