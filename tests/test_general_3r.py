"""rk.closed.general_3r: every position solution of a 3R arm of any geometry.

Truth: the forward model (KDL's, chain._fk_kdl), numerical IK from many random starts (every
distinct solution it finds must be in the closed-form set) and the sign of det J (KDL's Jacobian)
for the labels.
"""

import numpy as np
import pytest

import robokin as rk
from arms_3r import P, WENGER_CUSPIDAL, orthogonal, random_arm, wrapped


@pytest.mark.parametrize("condition", [None, "first parallel", "first intersect", "last parallel", "last intersect"])
def test_every_solution_reaches_and_numerical_ik_finds_no_other(condition, rng):
    for _ in range(4):
        chain = random_arm(rng, condition)
        Q = rng.uniform(-P, P, (6, 3))
        for q in Q:
            p = chain.fk(q)[:3, 3]
            s = rk.closed.general_3r(p, chain, limits=None)
            assert 1 <= len(s) <= 4
            for row in s.q:
                assert np.linalg.norm(chain._fk_kdl(row)[:3, 3] - p) < 1e-9
            assert np.min(wrapped(s.q, q)) < 1e-7
            starts = rng.uniform(-P, P, (24, 3))
            res = rk.ik_batch(chain, np.repeat(p[None], 24, axis=0), starts, task="position", max_iter=200)
            for qn in res.q[res.success]:
                if abs(np.linalg.det(chain.jacobian(qn, task="position"))) < 1e-6:
                    continue  # a near-singular solution (two roots merging): closed-form rounding
                assert np.min(wrapped(s.q, qn)) < 1e-5, (condition, q, qn, s)


def test_solutions_are_polished_to_the_forward_models_rounding():
    """general_3r's roots are polished by Newton's method on the forward model (its docstring): each
    solution puts the tool within 1e-14 of the arm's size of the target by KDL's FK (unpolished
    eigenvalue roots miss by up to ~1e-13 and a few are dropped by the 1e-9 check)."""
    rng = np.random.default_rng(0)
    worst = 0.0
    for _ in range(400):
        rows = [(rng.uniform(-2, 2), rng.uniform(-4, 4), rng.uniform(-2, 2), rng.uniform(-4, 4), "R") for _ in range(3)]
        chain = rk.Chain.from_dh(rows)
        size = 1 + sum(abs(r[0]) + abs(r[2]) for r in rows)
        p = chain._fk_kdl(rng.uniform(-np.pi, np.pi, 3))[:3, 3]
        s = rk.closed.general_3r(p, chain, limits=None)
        assert len(s) >= 1
        for q in s.q:
            worst = max(worst, np.linalg.norm(chain._fk_kdl(q)[:3, 3] - p) / size)
    assert worst < 1e-14


def test_four_solutions_somewhere_and_labels_follow_det_j(rng):
    chain = orthogonal(**WENGER_CUSPIDAL)
    counts = []
    for q in rng.uniform(-P, P, (60, 3)):
        s = rk.closed.general_3r(chain.fk(q)[:3, 3], chain, limits=None)
        counts.append(len(s))
        for row, label in zip(s.q, s.postures):
            d = np.linalg.det(chain.jacobian(row, task="position"))
            assert label == ("det J > 0" if d > 0 else "det J < 0") or label == "singular"
    assert max(counts) == 4 and min(counts) == 2


def test_bad_arguments():
    with pytest.raises(ValueError, match="target"):
        rk.closed.general_3r([0, 0], orthogonal(**WENGER_CUSPIDAL))
    with pytest.raises(ValueError, match="chain"):
        rk.closed.general_3r([0, 0, 0], rk.robots.ur5())
