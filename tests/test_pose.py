"""robokin.pose against closed forms (elementary rotations multiplied out, the quaternion of a
rotation about one axis, screw motions, the matrix exponential's series), round trips, and a second
method for quaternions (Bar-Itzhack's eigenvector; scipy is not a dependency)."""

import math

import numpy as np
import pytest

from robokin import pose

RNG_SEED = 11  # conftest restarts RNG from it for each test
RNG = np.random.default_rng(RNG_SEED)


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def random_rotations(n):
    q = RNG.normal(size=(n, 4))
    return pose.from_quaternion(q)


def test_rpy_is_rz_ry_rx_and_round_trips():
    for _ in range(50):
        r, p, y = RNG.uniform(-math.pi, math.pi), RNG.uniform(-1.5, 1.5), RNG.uniform(-math.pi, math.pi)
        T = pose.from_rpy([r, p, y], position=[1, 2, 3])
        np.testing.assert_allclose(T[:3, :3], rz(y) @ ry(p) @ rx(r), atol=1e-15)
        np.testing.assert_array_equal(T[:3, 3], [1, 2, 3])
        np.testing.assert_allclose(pose.rpy(T), [r, p, y], atol=1e-12)
        np.testing.assert_allclose(pose.rpy(T[:3, :3]), [r, p, y], atol=1e-12)
    batch = RNG.uniform(-1, 1, (30, 3))
    np.testing.assert_allclose(pose.rpy(pose.from_rpy(batch)), batch, atol=1e-12)


def test_rpy_at_gimbal_lock_keeps_the_rotation():
    for pitch in (math.pi / 2, -math.pi / 2):
        T = pose.from_rpy([0.4, pitch, 1.1])
        r, p, y = pose.rpy(T)
        assert r == 0.0 and p == pytest.approx(pitch)
        np.testing.assert_allclose(pose.from_rpy([r, p, y]), T, atol=1e-12)


def test_quaternion_of_a_rotation_about_one_axis():
    for _ in range(20):
        axis = RNG.normal(size=3)
        axis /= np.linalg.norm(axis)
        angle = RNG.uniform(0, math.pi)
        T = pose.from_axis_angle(axis, angle)
        np.testing.assert_allclose(pose.quaternion(T), np.r_[math.cos(angle / 2), math.sin(angle / 2) * axis], atol=1e-14)
        # Rodrigues, multiplied out: R = I + sin a K + (1 - cos a) K^2.
        K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        np.testing.assert_allclose(T[:3, :3], np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K, atol=1e-15)
        got_axis, got_angle = pose.axis_angle(T)
        assert got_angle == pytest.approx(angle, abs=1e-13)
        np.testing.assert_allclose(got_axis, axis, atol=1e-12)


def test_quaternion_round_trips_and_sign():
    R = random_rotations(200)
    q = pose.quaternion(R)
    assert np.all(q[:, 0] >= 0)
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-15)
    np.testing.assert_allclose(pose.from_quaternion(q), R, atol=1e-14)
    # Near 180 degrees (w ~ 0): Shepperd's branches.
    for axis in np.eye(3):
        T = pose.from_axis_angle(axis, math.pi)
        np.testing.assert_allclose(np.abs(pose.quaternion(T)), np.r_[0.0, axis], atol=1e-15)
    # Normalised first; scale and sign do not matter.
    np.testing.assert_allclose(pose.from_quaternion(-3 * q[0]), R[0], atol=1e-14)
    with pytest.raises(ValueError, match="quaternion"):
        pose.from_quaternion([0, 0, 0, 0])


def test_axis_angle_batch_and_zero_angle():
    axis, angle = pose.axis_angle(np.stack([np.eye(4), pose.from_rpy([0, 0, 0.5])]))
    np.testing.assert_allclose(axis, [[0, 0, 1], [0, 0, 1]], atol=1e-15)
    np.testing.assert_allclose(angle, [0, 0.5], atol=1e-15)
    T = pose.from_axis_angle(RNG.normal(size=(5, 3)), RNG.uniform(-3, 3, 5), position=RNG.normal(size=(5, 3)))
    a, t = pose.axis_angle(T)
    np.testing.assert_allclose(pose.from_axis_angle(a, t, position=T[:, :3, 3]), T, atol=1e-13)
    with pytest.raises(ValueError, match="axis"):
        pose.from_axis_angle([0, 0, 0], 1.0)


def test_se3_exp_closed_forms_and_log_round_trip():
    # A screw about z: rotation by a, translation along z by h, moving along v_x turns a circle.
    a = 0.7
    T = pose.exp([0, 0, 0.3, 0, 0, a])
    np.testing.assert_allclose(T[:3, :3], rz(a), atol=1e-15)
    np.testing.assert_allclose(T[:3, 3], [0, 0, 0.3], atol=1e-15)
    T = pose.exp([1.0, 0, 0, 0, 0, a])  # v = (1, 0, 0), w = a z: p = V v, V = I + (1-c)/a^2 W + (a-s)/a^3 W^2
    np.testing.assert_allclose(T[:3, 3], [math.sin(a) / a, (1 - math.cos(a)) / a, 0], atol=1e-15)
    np.testing.assert_allclose(pose.exp([1, 2, 3, 0, 0, 0]), np.r_[np.c_[np.eye(3), [1, 2, 3]], [[0, 0, 0, 1]]])
    xi = np.c_[RNG.normal(size=(100, 3)), RNG.normal(size=(100, 3))]
    xi[:, 3:] *= (RNG.uniform(0, 3.1, 100) / np.linalg.norm(xi[:, 3:], axis=1))[:, None]
    xi[:5, 3:] *= 1e-6  # the series branch
    np.testing.assert_allclose(pose.log(pose.exp(xi)), xi, atol=1e-12)
    # exp(log(T)) = T for any frame; log of a product of commuting screws adds.
    T = pose.from_quaternion(RNG.normal(size=(50, 4)), position=RNG.normal(size=(50, 3)))
    np.testing.assert_allclose(pose.exp(pose.log(T)), T, atol=1e-13)
    np.testing.assert_allclose(pose.log(pose.exp([0, 0, 1, 0, 0, 0.4]) @ pose.exp([0, 0, 2, 0, 0, 0.5])),
                               [0, 0, 3, 0, 0, 0.9], atol=1e-15)


def test_exp_matches_a_matrix_exponential_series():
    xi = np.array([0.3, -0.2, 0.5, 0.4, -0.6, 0.9])
    X = np.zeros((4, 4))
    w = xi[3:]
    X[:3, :3] = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]
    X[:3, 3] = xi[:3]
    series, term = np.eye(4), np.eye(4)
    for k in range(1, 30):
        term = term @ X / k
        series = series + term
    np.testing.assert_allclose(pose.exp(xi), series, atol=1e-14)


def test_error_is_the_iks_pose_error():
    target = pose.from_rpy([0.1, 0.2, 0.3], position=[1, 2, 3])
    current = pose.from_rpy([0.1, 0.2, 0.0], position=[1, 2.5, 3])
    e = pose.error(target, current)
    np.testing.assert_allclose(e[:3], [0, -0.5, 0])
    # R_t R^T is a rotation by 0.3 about the world z axis here (yaw is the outermost factor).
    np.testing.assert_allclose(e[3:], [0, 0, 0.3], atol=1e-15)
    T = pose.from_quaternion(RNG.normal(size=(10, 4)), position=RNG.normal(size=(10, 3)))
    batch = pose.error(T, current)
    np.testing.assert_allclose(batch[3], pose.error(T[3], current))
    np.testing.assert_allclose(np.linalg.norm(batch[:, 3:], axis=1),
                               pose.axis_angle(T[:, :3, :3] @ current[:3, :3].T)[1], atol=1e-13)
    with pytest.raises(ValueError, match="target, current"):
        pose.error(T, T[:3])


def test_frames_from_objects_with_A_or___array__():
    class SE3Like:
        def __init__(self, m):
            self.A = m

    class Many:
        A = [np.eye(4), pose.from_rpy([0, 0, 1.0])]

    class ArrayLike:
        def __array__(self, dtype=None, copy=None):
            return pose.from_rpy([0, 0, 1.0])

    T = pose.from_rpy([0.1, 0.2, 0.3], position=[1, 2, 3])
    np.testing.assert_array_equal(pose.rpy(SE3Like(T)), pose.rpy(T))
    np.testing.assert_allclose(pose.rpy(Many()), [[0, 0, 0], [0, 0, 1.0]], atol=1e-15)
    np.testing.assert_allclose(pose.log(ArrayLike()), [0, 0, 0, 0, 0, 1.0], atol=1e-15)
    np.testing.assert_allclose(pose.error(SE3Like(T), ArrayLike())[:3], [1, 2, 3])


def test_rejects_what_is_not_a_rotation():
    with pytest.raises(ValueError, match="T: not a rotation"):
        pose.rpy(2 * np.eye(4) - np.diag([0, 0, 0, 1]))
    with pytest.raises(ValueError, match="T: expected"):
        pose.log(np.eye(3))
    with pytest.raises(ValueError, match="rpy: expected shape"):
        pose.from_rpy([1, 2])
    with pytest.raises(ValueError, match="position"):
        pose.from_rpy([1, 2, 3], position=[np.nan, 0, 0])


def test_quaternion_against_a_second_method():
    # Bar-Itzhack: the quaternion is the eigenvector of a symmetric 4x4 matrix built from R for its
    # largest eigenvalue (numpy's eigh), an algorithm unrelated to Shepperd's branches.
    R = random_rotations(100)[:, :3, :3]
    for Rk, qk in zip(R, pose.quaternion(R)):
        (a, b, c), (d, e, f), (g, h, i) = Rk
        K = np.array([[a - e - i, d + b, g + c, h - f],
                      [d + b, e - a - i, h + f, c - g],
                      [g + c, h + f, i - a - e, d - b],
                      [h - f, c - g, d - b, a + e + i]]) / 3.0
        vals, vecs = np.linalg.eigh(K)
        x, y, z, w = vecs[:, -1]
        ref = np.array([w, x, y, z]) * (1.0 if w >= 0 else -1.0)
        np.testing.assert_allclose(qk, ref, atol=1e-12)


def test_empty_batches_give_empty_results():
    empty = np.zeros((0, 4, 4))
    assert pose.error(empty, empty).shape == (0, 6) and pose.error(np.eye(4), empty).shape == (0, 6)
    assert pose.from_rpy(np.zeros((0, 3))).shape == (0, 4, 4) and pose.exp(np.zeros((0, 6))).shape == (0, 4, 4)
    assert pose.rpy(empty).shape == (0, 3) and pose.log(empty).shape == (0, 6)
    assert pose.from_quaternion(np.zeros((0, 4))).shape == (0, 4, 4)
