"""Chain.manipulability and Chain.ellipsoid against closed forms (the planar 2R's
|a1 a2 sin q2|, a stretched UR5) and numpy's SVD of the Jacobian the chain reports."""

import math

import numpy as np
import pytest

import robokin as rk

RNG_SEED = 7  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)
A1, A2 = 0.4, 0.3
ARM = rk.Chain.from_dh([(A1, 0, 0, 0, "R"), (A2, 0, 0, 0, "R")])


def test_planar_2r_yoshikawa_closed_form():
    q = RNG.uniform(-math.pi, math.pi, (200, 2))
    expected = np.abs(A1 * A2 * np.sin(q[:, 1]))
    np.testing.assert_allclose(ARM.manipulability(q, task="xy"), expected, rtol=1e-12, atol=1e-16)
    for qk, ek in zip(q[:5], expected[:5]):
        assert ARM.manipulability(qk, task="xy") == pytest.approx(ek, rel=1e-12, abs=1e-16)
    assert ARM.manipulability([0.3, 0.0], task="xy") == pytest.approx(0.0, abs=1e-16)


def test_planar_2r_singular_values_closed_form():
    # J J^T has trace a1^2 + a2^2 + 2 a1 a2 cos q2 + a2^2 and determinant (a1 a2 sin q2)^2.
    q = RNG.uniform(-3, 3, (50, 2))
    tr = A1**2 + 2 * A2**2 + 2 * A1 * A2 * np.cos(q[:, 1])
    det = (A1 * A2 * np.sin(q[:, 1])) ** 2
    disc = np.sqrt(np.maximum(tr**2 / 4 - det, 0))
    smax, smin = np.sqrt(tr / 2 + disc), np.sqrt(np.maximum(tr / 2 - disc, 0))
    np.testing.assert_allclose(ARM.manipulability(q, "min_singular", task="xy"), smin, atol=1e-12)
    np.testing.assert_allclose(ARM.manipulability(q, "condition", task="xy"), smin / smax, atol=1e-11)


@pytest.mark.parametrize("task", ["pose", "position", "xy", "xyphi"])
def test_against_numpy_svd(task):
    for chain in (rk.robots.ur5(), rk.robots.puma560(), rk.robots.rpr(),
                  rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True)):
        q = RNG.uniform(-2, 2, (20, chain.dof))
        s = np.linalg.svd(chain.jacobian(q, task=task), compute_uv=False)
        np.testing.assert_allclose(chain.manipulability(q, "yoshikawa", task), np.prod(s, axis=1), rtol=1e-10, atol=1e-14)
        np.testing.assert_allclose(chain.manipulability(q, "min_singular", task), s[:, -1], rtol=1e-10, atol=1e-14)
        np.testing.assert_allclose(chain.manipulability(q, "condition", task), s[:, -1] / s[:, 0], rtol=1e-9, atol=1e-14)
        assert chain.manipulability(q[3], "yoshikawa", task) == pytest.approx(np.prod(s[3]), rel=1e-10, abs=1e-14)


def test_yoshikawa_is_sqrt_det_jjt_for_a_redundant_arm():
    chain = rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True)
    q = RNG.uniform(-2, 2, 7)
    J = chain.jacobian(q)
    assert chain.manipulability(q) == pytest.approx(math.sqrt(np.linalg.det(J @ J.T)), rel=1e-10)


def test_ur5_stretched_elbow_is_singular():
    ur5 = rk.robots.ur5()
    q = np.array([0.3, -1.0, 0.0, 0.4, 0.5, 0.6])  # q3 = 0: upper arm and forearm aligned
    assert ur5.manipulability(q) < 1e-12
    assert ur5.manipulability(q, "condition") < 1e-10
    assert ur5.manipulability(q + [0, 0, 0.5, 0, 0, 0]) > 1e-3


def test_ellipsoid_axes_and_lengths_from_the_svd():
    ur5 = rk.robots.ur5()
    for _ in range(10):
        q = RNG.uniform(-2, 2, 6)
        J = ur5.jacobian(q)
        for part, rows in (("translation", J[:3]), ("rotation", J[3:])):
            axes, lengths = ur5.ellipsoid(q, part=part)
            np.testing.assert_allclose(lengths, np.linalg.svd(rows, compute_uv=False), rtol=1e-10)
            np.testing.assert_allclose(axes.T @ axes, np.eye(3), atol=1e-12)
            assert np.linalg.det(axes) == pytest.approx(1.0)
            # J J^T = U diag(s^2) U^T: the ellipsoid {J qd : |qd| <= 1}.
            np.testing.assert_allclose(axes @ np.diag(lengths**2) @ axes.T, rows @ rows.T, atol=1e-12)


def test_ellipsoid_of_a_planar_arm_has_zero_lengths_out_of_plane():
    axes, lengths = ARM.ellipsoid([0.2, 1.0])
    assert lengths[2] == 0.0 and lengths[1] == pytest.approx(abs(A1 * A2 * math.sin(1.0)) / lengths[0])
    np.testing.assert_allclose(np.abs(axes[:, 2]), [0, 0, 1], atol=1e-15)


def test_bad_arguments_name_themselves():
    ur5 = rk.robots.ur5()
    with pytest.raises(ValueError, match="measure"):
        ur5.manipulability(np.zeros(6), measure="volume")
    with pytest.raises(ValueError, match="task"):
        ur5.manipulability(np.zeros(6), task="xyz")
    with pytest.raises(ValueError, match="q: expected shape"):
        ur5.manipulability(np.zeros(5))
    with pytest.raises(ValueError, match="part"):
        ur5.ellipsoid(np.zeros(6), part="both")
    with pytest.raises(ValueError, match="q: contains NaN"):
        ur5.manipulability(np.full(6, np.nan))


def test_near_singular_configurations_agree_with_numpy():
    # Close to the UR5's elbow singularity the product of the singular values is tiny, and its
    # evaluation switches from the Cholesky factor of J J^T to the SVD: both agree with numpy.
    ur5 = rk.robots.ur5()
    for q3 in (1e-1, 1e-2, 1e-3, 1e-5, 1e-7):
        q = np.array([0.3, -1.0, q3, 0.4, 0.5, 0.6])
        s = np.linalg.svd(ur5.jacobian(q), compute_uv=False)
        assert ur5.manipulability(q) == pytest.approx(np.prod(s), rel=1e-6)
        assert ur5.manipulability(q, "min_singular") == pytest.approx(s[-1], rel=1e-6, abs=1e-15)
