"""The Paden-Kahan subproblems (cpp/src/subproblems.cpp) against cases built from known angles:
random axes and vectors, the data made by rotating with scipy-free Rodrigues matrices written here
(numpy only); every returned angle satisfies its equation, the generating angle is among them, and
data that admit no solution give none."""

import math

import numpy as np
import pytest

import robokin  # noqa: F401  (robokin._testing needs the core's types)
from robokin import _testing as t


def rot(k, theta):
    """Rodrigues: the rotation by theta about the unit vector k."""
    k = np.asarray(k, float) / np.linalg.norm(k)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(theta) * K + (1 - math.cos(theta)) * K @ K


def unit(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def angle_gap(a, b):
    return abs(math.remainder(a - b, 2 * math.pi))


@pytest.fixture
def cases(rng):
    return [(unit(rng), rng.normal(size=3) * rng.uniform(0.1, 3), rng.uniform(-math.pi, math.pi)) for _ in range(300)]


def test_subproblem1_finds_the_angle(cases):
    for k, p, theta in cases:
        (angles, singular) = t.subproblem1(k, p, rot(k, theta) @ p)
        assert not singular and len(angles) == 1 and angle_gap(angles[0], theta) < 1e-9


def test_subproblem1_on_the_axis_is_a_continuum():
    angles, singular = t.subproblem1([0, 0, 1], [0, 0, 2.0], [0, 0, 2.0])
    assert singular and angles == [0.0]


def test_subproblem2_finds_both_pairs(rng):
    for _ in range(300):
        k1, k2, p = unit(rng), unit(rng), rng.normal(size=3)
        a, b = rng.uniform(-math.pi, math.pi, 2)
        q = rot(k1, a) @ rot(k2, b) @ p
        (t1, _), (t2, _) = t.subproblem2(k1, k2, p, q)
        assert 1 <= len(t1) == len(t2) <= 2
        for x, y in zip(t1, t2):
            assert np.linalg.norm(rot(k1, x) @ rot(k2, y) @ p - q) < 1e-9 * (1 + np.linalg.norm(p))
        assert min(max(angle_gap(x, a), angle_gap(y, b)) for x, y in zip(t1, t2)) < 1e-6


def test_subproblem3_every_angle_has_the_distance(cases, rng):
    for k, p, theta in cases:
        q = rng.normal(size=3)
        d = np.linalg.norm(rot(k, theta) @ p - q)
        angles, singular = t.subproblem3(k, p, q, d)
        assert angles and min(angle_gap(a, theta) for a in angles) < 1e-6
        for a in angles:
            assert abs(np.linalg.norm(rot(k, a) @ p - q) - d) < 1e-9 * (1 + d)


def test_subproblem3_out_of_reach_has_none():
    # |R p - q| for p = (1, 0, 0) about z and q = (3, 0, 0) ranges over [2, 4].
    assert t.subproblem3([0, 0, 1], [1, 0, 0], [3, 0, 0], 4.5)[0] == []
    assert t.subproblem3([0, 0, 1], [1, 0, 0], [3, 0, 0], 1.5)[0] == []
    angles, singular = t.subproblem3([0, 0, 1], [1, 0, 0], [3, 0, 0], 4.0)
    assert singular and len(angles) == 1 and angle_gap(angles[0], math.pi) < 1e-9


def test_subproblem4_every_angle_has_the_projection(cases, rng):
    for k, p, theta in cases:
        h = unit(rng)
        d = h @ rot(k, theta) @ p
        angles, _ = t.subproblem4(h, k, p, d)
        assert angles and min(angle_gap(a, theta) for a in angles) < 1e-6
        for a in angles:
            assert abs(h @ rot(k, a) @ p - d) < 1e-9 * (1 + np.linalg.norm(p))


def test_subproblem4_beyond_its_range_has_none():
    # h . R p for h = x, p = x about z: cos theta, in [-1, 1].
    assert t.subproblem4([1, 0, 0], [0, 0, 1], [1, 0, 0], 1.5)[0] == []
    angles, singular = t.subproblem4([1, 0, 0], [0, 0, 1], [1, 0, 0], 0.5)
    assert not singular and sorted(abs(a) for a in angles) == pytest.approx([math.pi / 3] * 2)
