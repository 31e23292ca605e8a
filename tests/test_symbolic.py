"""robokin.symbolic against independent truth: the DH exercise's position of the PRR arm and the
RPR study's hand Jacobian, exactly (sympy says the difference is 0), and the numeric chain (KDL's
FK and Jacobian) at random configurations, standard and modified DH."""

import math
import pathlib

import numpy as np
import pytest
import sympy as sp

import robokin as rk
from robokin import symbolic

d1, theta2, theta3, a2, a3 = sp.symbols("d1 theta2 theta3 a2 a3", real=True)
q1, q2, q3 = sp.symbols("q1:4", real=True)

# The RPR study's arm as a standard DH table (rk.robots.rpr() is built from joints and frames):
# frame 1's z along link 1 (theta offset pi/2, alpha pi/2), the slide d = L1 + t2 along it, then
# frame 2's z back to the base's z (alpha -pi/2) with its x a quarter turn ahead of link 1 (theta3
# offset -pi/2), and link 3 of length L3.
RPR_DH = [(0.0, math.pi / 2, 0.0, math.pi / 2, "R"), (0.0, -math.pi / 2, rk.robots.RPR_L1, 0.0, "P"),
          (rk.robots.RPR_L3, 0.0, 0.0, -math.pi / 2, "R")]


def test_the_dh_exercise_position_of_the_prr_arm():
    T = symbolic.fk(rk.robots.prr(), lengths="symbols")
    position = T[:3, 3].subs({q1: d1, q2: theta2, q3: theta3})
    expected = sp.Matrix([a3 * sp.cos(theta2 + theta3) + a2 * sp.cos(theta2), 0,
                          a3 * sp.sin(theta2 + theta3) + d1 + a2 * sp.sin(theta2)])
    assert sp.simplify(position - expected) == sp.zeros(3, 1)
    assert T[3, :] == sp.Matrix([[0, 0, 0, 1]])


def test_the_prr_table_is_exact():
    table = symbolic.table(rk.robots.prr(), lengths="symbols")
    assert table == sp.Matrix([[0, sp.pi / 2, q1, 0], [a2, 0, 0, q2], [a3, 0, 0, q3]])
    values = symbolic.table(rk.robots.prr(a2=0.4318, a3=0.25))
    assert values[1, 0] == sp.Rational(2159, 5000) and values[2, 0] == sp.Rational(1, 4)


def test_the_rpr_study_jacobian():
    chain = rk.Chain.from_dh(RPR_DH)
    rng = np.random.default_rng(1)
    for q in rng.uniform([0, 0, 0], [math.pi / 2, 1.5, math.pi], (5, 3)):  # the DH table is the study's arm
        assert np.allclose(chain.fk(q)[:2, 3], rk.robots.rpr().fk(q)[:2, 3], atol=1e-12)
    t1, t2, t3 = q1, q2, q3
    L1, L3 = sp.Rational(3, 2), sp.Integer(1)
    hand = sp.Matrix([[-(L1 + t2) * sp.sin(t1) - L3 * sp.sin(t1 + t3), sp.cos(t1), -L3 * sp.sin(t1 + t3)],
                      [(L1 + t2) * sp.cos(t1) + L3 * sp.cos(t1 + t3), sp.sin(t1), L3 * sp.cos(t1 + t3)]])
    J = symbolic.jacobian(chain, task="xy")
    assert J.shape == (2, 3)
    assert sp.simplify(J - hand) == sp.zeros(2, 3)
    # The whole geometric Jacobian: no z motion, the revolute joints turn about the base's z.
    full = symbolic.jacobian(chain, task="pose")
    assert full[2, :] == sp.zeros(1, 3) and full[3:, :] == sp.Matrix([[0, 0, 0], [0, 0, 0], [1, 0, 1]])


def _random_dh(rng, n, modified):
    rows = []
    for _ in range(n):
        alpha = rng.choice([0.0, math.pi / 2, -math.pi / 2, rng.uniform(-3, 3)])
        rows.append((float(rng.uniform(-1, 1)), float(alpha), float(rng.uniform(-1, 1)), float(rng.uniform(-3, 3)),
                     "P" if rng.random() < 0.3 else "R"))
    tool = rk.pose.from_rpy(rng.uniform(-1, 1, 3), position=rng.uniform(-0.2, 0.2, 3))
    return rk.Chain.from_dh(rows, modified=modified, tool=tool)


@pytest.mark.parametrize("modified", [False, True])
def test_the_numeric_chain_at_random_q(modified):
    rng = np.random.default_rng(7 + modified)
    for n in (1, 3, 4):
        chain = _random_dh(rng, n, modified)
        T, J = symbolic.fk(chain, simplify=False), symbolic.jacobian(chain, task="pose", simplify=False)
        qs = sp.symbols(f"q1:{n + 1}", real=True)
        fT, fJ = sp.lambdify(qs, T, "numpy"), sp.lambdify(qs, J, "numpy")
        for q in rng.uniform(-2, 2, (4, n)):
            assert np.allclose(np.array(fT(*q), dtype=float), chain.fk(q), atol=1e-9)
            assert np.allclose(np.array(fJ(*q), dtype=float), chain.jacobian(q, task="pose"), atol=1e-9)


def test_numeric_q_and_the_ur5_against_the_chain():
    ur5 = rk.robots.ur5()
    q = [0.3, -1.0, 1.2, 0.4, 0.5, 0.6]
    T = symbolic.fk(ur5, q, simplify=False)
    assert np.allclose(np.array(T.evalf(), dtype=float), ur5.fk(q), atol=1e-12)
    J = symbolic.jacobian(ur5, [sp.Rational(1, 2)] * 6, task="position", simplify=False)
    assert np.allclose(np.array(J.evalf(), dtype=float), ur5.jacobian([0.5] * 6, task="position"), atol=1e-12)


def test_the_default_task_is_the_chains_own():
    planar = rk.robots.planar_3r()
    assert symbolic.jacobian(planar).shape == (3, 3)  # natural task "xyphi"
    assert symbolic.jacobian(planar)[:, 2] == sp.Matrix([-sp.sin(q1 + q2 + q3), sp.cos(q1 + q2 + q3), 1])


def test_a_chain_without_a_dh_table_is_refused_by_name():
    with pytest.raises(ValueError, match="chain: has no DH table"):
        symbolic.fk(rk.robots.rpr())
    urdf = rk.Chain.from_urdf(pathlib.Path(__file__).resolve().parents[1] / "examples" / "arm.urdf")
    for call in (symbolic.fk, symbolic.jacobian, symbolic.table):
        with pytest.raises(ValueError, match="chain: has no DH table"):
            call(urdf)


@pytest.mark.parametrize("call, kwargs, error, name", [
    (symbolic.fk, {"q": [1, 2]}, ValueError, "q"),
    (symbolic.fk, {"q": [1, 2, float("nan")]}, ValueError, "q"),
    (symbolic.fk, {"q": [1, 2, 1j]}, TypeError, "q"),
    (symbolic.fk, {"q": "abc"}, TypeError, "q"),
    (symbolic.fk, {"q": 3}, TypeError, "q"),
    (symbolic.fk, {"lengths": "letters"}, ValueError, "lengths"),
    (symbolic.jacobian, {"task": "xyz"}, ValueError, "task"),
    (symbolic.jacobian, {"task": 2}, TypeError, "task"),
    (symbolic.table, {"lengths": None}, TypeError, "lengths"),
])
def test_bad_arguments_are_named(call, kwargs, error, name):
    with pytest.raises(error, match=f"^{name}:"):
        call(rk.robots.prr(), **kwargs)
    with pytest.raises(TypeError, match="^chain:"):
        call("prr")
