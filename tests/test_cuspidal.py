"""rk.cuspidal: the aspects, cusps and posture changes of 3R arms.

Truth: the forward model (KDL's, chain._fk_kdl), the chain's Jacobian for the singular curve and
det J's sign, and the definitions themselves: at a cusp the image of the singular curve turns
back (the workspace point moves as the square of the distance along the curve, not linearly),
and a cuspidal arm has points with two solutions in one aspect (a non-cuspidal one never has).

Literature:
- Seed 003 (after P. Wenger and D. Chablat, "Robots cuspidaux : theorie et applications",
  Techniques de l'Ingenieur, 2021): a 3R arm whose first two or last two axes are parallel or
  intersect is not cuspidal.
- Orthogonal 3R arms in the parametrisation of M. Baili, P. Wenger, D. Chablat, "A classification of
  3R orthogonal manipulators by the topology of their workspace", ICRA 2004 (Craig's modified DH,
  alpha = (0, -90, 90) deg, link lengths d2, d3, d4, offsets r2, r3): the arm d2 = 1, d3 = 2,
  d4 = 1.5, r2 = 1, r3 = 0, the example of P. Wenger, "Cuspidal and noncuspidal robot
  manipulators", Robotica 25(6), 2007, is cuspidal (four cusps on its singular curves). The
  parameters are quoted from memory of that paper (its text was not at hand): the test does not
  rest on the citation alone but checks each cusp and the posture change from their definitions.
- D. H. Salunkhe, C. Spartalis, J. Capco, D. Chablat, P. Wenger, "Necessary and sufficient condition
  for a generic 3R serial manipulator to be cuspidal", Mechanism and Machine Theory 171, 2022: a
  cusp point exists if and only if the arm is cuspidal.
"""

import math

import numpy as np
import pytest

import robokin as rk
from arms_3r import P, WENGER_CUSPIDAL, orthogonal, random_arm, wrapped


@pytest.mark.parametrize("condition", ["first parallel", "first intersect", "last parallel", "last intersect"])
def test_seed_conditions_are_not_cuspidal(condition, rng):
    for _ in range(3):
        chain = random_arm(rng, condition)
        c = rk.cuspidal(chain, resolution=128)
        assert not c.cuspidal, (condition, c.cusps)
        assert len(c.cusps) == 0 and c.path is None
        assert "no cusp" in c.evidence


def aspect_of(c, q):
    """The aspect of the grid cell of q, or None when a neighbouring cell is in another one (q too
    near a singular curve for the grid to tell)."""
    n = len(c.grid)
    h = 2 * P / n
    i = int(round((np.remainder(q[1] + P, 2 * P) - 0.37 * h) / h)) % n
    j = int(round((np.remainder(q[2] + P, 2 * P) - 0.37 * h) / h)) % n
    around = {c.label[(i + a) % n, (j + b) % n] for a in (-1, 0, 1) for b in (-1, 0, 1)}
    return c.label[i, j] if len(around) == 1 else None


def two_in_one_aspect(chain, c, rng, samples=150):
    """Some point with two solutions in the same aspect (solutions away from the singular curves)."""
    for q in rng.uniform(-P, P, (samples, 3)):
        s = rk.closed.general_3r(chain.fk(q)[:3, 3], chain, limits=None)
        labs = [aspect_of(c, r) for r in s.q]
        labs = [a for a in labs if a is not None]
        if len(labs) != len(set(labs)):
            return True
    return False


def test_wenger_orthogonal_arm_is_cuspidal_with_cusps_and_a_nonsingular_posture_change(rng):
    chain = orthogonal(**WENGER_CUSPIDAL)
    c = rk.cuspidal(chain, resolution=256)
    assert c.cuspidal
    assert len(c.cusps) == 4  # Wenger (2007): four cusps on the inner singular curve
    # Each cusp: on the singular curve (KDL's Jacobian), and the curve's image turns back there.
    for q2, q3, rho, z in c.cusps:
        q = np.array([0.0, q2, q3])
        J = chain.jacobian(q, task="position")
        assert abs(np.linalg.det(J)) < 1e-7
        p = chain._fk_kdl(q)[:3, 3]
        assert math.hypot(p[0], p[1]) == pytest.approx(rho, abs=1e-9) and p[2] == pytest.approx(z, abs=1e-9)
        # points on the curve at distance e and 2e along it: their images move ~ e^2 (a cusp), not ~ e
        grad = np.array([np.linalg.det(chain.jacobian([0, q2 + s2, q3 + s3], task="position"))
                         for s2, s3 in ((1e-6, 0), (-1e-6, 0), (0, 1e-6), (0, -1e-6))])
        g = np.array([grad[0] - grad[1], grad[2] - grad[3]])
        tau = np.array([-g[1], g[0]]) / np.linalg.norm(g)

        def on_curve(e):
            x = np.array([q2, q3]) + e * tau
            for _ in range(20):
                f = np.linalg.det(chain.jacobian([0, *x], task="position"))
                h = 1e-7
                gx = np.array([np.linalg.det(chain.jacobian([0, x[0] + h, x[1]], task="position")) - f,
                               np.linalg.det(chain.jacobian([0, x[0], x[1] + h], task="position")) - f]) / h
                x = x - f * gx / (gx @ gx)
            pe = chain._fk_kdl([0, *x])[:3, 3]
            return np.array([math.hypot(pe[0], pe[1]) - rho, pe[2] - z])

        d1, d2 = np.linalg.norm(on_curve(1e-3)), np.linalg.norm(on_curve(2e-3))
        assert 3.0 < d2 / d1 < 5.0  # quadratic: ratio 4 (a fold would give 2)
    # The evidence path: two solutions of one point, det J of one sign along the whole path.
    assert c.path is not None and c.point is not None
    start, end = c.path[0], c.path[-1]
    assert wrapped(start, end) > 1e-3
    for q in (start, end):
        assert np.linalg.norm(chain._fk_kdl(q)[:3, 3] - c.point) < 1e-9
    # det J keeps its sign on the whole path, between its configurations too (checked densely here:
    # a path that crosses the singular curve between two of them is no evidence).
    dense = np.concatenate([a + np.linspace(0, 1, 40, endpoint=False)[:, None] * (b - a)
                            for a, b in zip(c.path[:-1], c.path[1:])] + [c.path[-1:]])
    dets = np.linalg.det(chain.jacobian(dense, task="position"))
    assert np.all(np.sign(dets) == np.sign(dets[0]))
    # and such points exist elsewhere too (an independent sample)
    assert two_in_one_aspect(chain, c, rng)


def test_non_cuspidal_arms_never_have_two_solutions_in_one_aspect(rng):
    for condition in ("first intersect", "last parallel"):
        chain = random_arm(rng, condition)
        c = rk.cuspidal(chain, resolution=128)
        assert not c.cuspidal
        assert not two_in_one_aspect(chain, c, rng, samples=60)


def test_bad_arguments():
    with pytest.raises(ValueError, match="chain"):
        rk.cuspidal(rk.robots.ur5())
    with pytest.raises(TypeError, match="chain: expected a robokin.Chain, got str"):
        rk.cuspidal("arm")
    with pytest.raises(ValueError, match=r"^resolution: expected an int in \[16, 4096\] \(grid points per joint\), got 3$"):
        rk.cuspidal(orthogonal(**WENGER_CUSPIDAL), resolution=3)
    with pytest.raises(TypeError, match="^resolution: expected int, got str$"):
        rk.cuspidal(orthogonal(**WENGER_CUSPIDAL), resolution="fine")
    with pytest.raises(TypeError):
        rk.cuspidal(orthogonal(**WENGER_CUSPIDAL), 64)  # an option: keyword-only


def test_a_state_whose_evidence_has_the_wrong_shape_is_refused():
    """The posture change is None or an array (point (3,), path (m, 3)); unpickling checks which."""
    c = rk.cuspidal(orthogonal(**WENGER_CUSPIDAL), resolution=64)
    state = c.__getstate__()
    point, path = len(state) - 2, len(state) - 1
    for index, value, field in ((point, np.zeros(2), "point"), (path, np.zeros((4, 2)), "path"),
                                (path, "along", "path")):
        bad = list(state)
        bad[index] = value
        copied = type(c).__new__(type(c))
        with pytest.raises(ValueError, match=f"^Cuspidality state: {field} is not None or an array of the result's shape$"):
            copied.__setstate__(tuple(bad))
    none = list(state)
    none[point] = none[path] = None
    copied = type(c).__new__(type(c))
    copied.__setstate__(tuple(none))
    assert copied.point is None and copied.path is None and copied.cuspidal


def test_the_posture_change_is_found_for_random_cuspidal_arms_and_each_one_holds():
    """Beyond Wenger's arm: over random 3R arms, the search around the cusps finds a posture change
    for nearly every cuspidal one (it may miss one: no claim of completeness), and every path it
    returns joins two solutions of its point (KDL's forward model) with det J of one sign, checked
    densely."""
    cuspidal = found = 0
    for seed in range(60):
        chain = random_arm(np.random.default_rng(seed))
        c = rk.cuspidal(chain, resolution=64)
        if not c.cuspidal:
            assert c.point is None and c.path is None
            continue
        cuspidal += 1
        if c.path is None:
            continue
        found += 1
        for q in (c.path[0], c.path[-1]):
            assert np.linalg.norm(chain._fk_kdl(q)[:3, 3] - c.point) < 1e-9
        assert wrapped(c.path[0], c.path[-1]) > 1e-3
        dense = np.concatenate([a + np.linspace(0, 1, 20, endpoint=False)[:, None] * (b - a)
                                for a, b in zip(c.path[:-1], c.path[1:])] + [c.path[-1:]])
        dets = np.linalg.det(chain.jacobian(dense, task="position"))
        assert np.all(np.sign(dets) == np.sign(dets[0])), seed
    assert cuspidal >= 40 and found >= 0.9 * cuspidal, (found, cuspidal)
