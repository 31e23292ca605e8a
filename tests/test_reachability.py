"""Reachability maps: the index of a planar 3R against the closed-form reachable set
(the IK course's wrist point) for the very orientations sampled, and against a brute-force estimate from
forward kinematics alone; zero outside the reach sphere; the same bits for any thread count and
any block size; ValueErrors naming the argument; the figure."""

import math
import os
import sys

import numpy as np
import pytest

import robokin as rk
from robokin.plots_reachability import plot_reachability

R = sys.modules["robokin.reachability"]  # the module (rk.reachability is the function)
A = (1.0, 0.8, 0.5)
BOUNDS = ((-2.4, 2.4), (-2.4, 2.4))


@pytest.fixture(scope="module")
def planar_map():
    return rk.reachability(rk.robots.planar_3r(*A), BOUNDS, 0.4, orientations=32, task="xyphi", seed=1)


def test_index_is_the_closed_form_reachable_fraction_of_the_sampled_orientations(planar_map):
    # Seed 003: (x, y, phi) is reachable iff the wrist p - a3 (cos phi, sin phi) is at a distance
    # in [|a1 - a2|, a1 + a2] from the base (no joint limits). The orientations are the map's own.
    m = planar_map
    K = m.orientations
    u = R._uniforms(m.seed, 0, m.index.size * K, 3)
    phi = (2 * u[:, 0] - 1) * np.pi
    X, Y = np.meshgrid(*m.axes, indexing="ij")
    wx = np.repeat(X.ravel(), K) - A[2] * np.cos(phi)
    wy = np.repeat(Y.ravel(), K) - A[2] * np.sin(phi)
    w = np.hypot(wx, wy)
    truth = ((w >= abs(A[0] - A[1]) + 1e-9) & (w <= A[0] + A[1] - 1e-9)).reshape(-1, K).mean(axis=1)
    edge = ((np.abs(w - abs(A[0] - A[1])) < 1e-6) | (np.abs(w - A[0] - A[1]) < 1e-6)).reshape(-1, K).any(axis=1)
    np.testing.assert_array_equal(m.index.ravel()[~edge], truth[~edge])
    assert 0.2 < m.index.mean() < 0.8  # neither empty nor full: the comparison means something


def test_index_agrees_with_a_brute_force_fk_estimate(planar_map):
    # FK only: sample the joints, bin the tool orientations of the samples that land near each voxel
    # centre; the share of orientation bins hit estimates the reachable fraction of orientations.
    m = planar_map
    chain = rk.robots.planar_3r(*A)
    x, y = m.axes
    bins, radius = 32, 0.06
    hit = np.zeros((len(x), len(y), bins), bool)
    rng = np.random.default_rng(0)
    for _ in range(15):
        T = chain.fk(rng.uniform(-np.pi, np.pi, (200_000, 3)))
        px, py, phi = T[:, 0, 3], T[:, 1, 3], np.arctan2(T[:, 1, 0], T[:, 0, 0])
        i, j = np.rint((px - x[0]) / m.resolution).astype(int), np.rint((py - y[0]) / m.resolution).astype(int)
        ok = (i >= 0) & (i < len(x)) & (j >= 0) & (j < len(y))
        i, j, px, py, phi = i[ok], j[ok], px[ok], py[ok], phi[ok]
        near = (px - x[i]) ** 2 + (py - y[j]) ** 2 < radius**2
        hit[i[near], j[near], ((phi[near] + np.pi) / (2 * np.pi) * bins).astype(int) % bins] = True
    estimate = hit.mean(axis=2)
    assert np.abs(m.index - estimate).mean() < 0.08
    assert np.all(m.index[estimate == 0] == 0)  # nothing reached where FK never lands
    assert np.all(m.index[estimate == 1] >= 0.75)  # dexterous voxels are (nearly) fully reached


def test_manipulability_is_the_best_among_the_solutions(planar_map):
    m = planar_map
    assert np.all((m.manipulability > 0) == (m.index > 0))
    # At a reachable (x, y, phi) both elbows have |sin q2| from the wrist distance w,
    # cos q2 = (w^2 - a1^2 - a2^2) / (2 a1 a2), and the xyphi manipulability a1 a2 |sin q2|: the map
    # holds the best of it over the voxel's sampled orientations (the map's own).
    K = m.orientations
    u = R._uniforms(m.seed, 0, m.index.size * K, 3)
    phi = (2 * u[:, 0] - 1) * np.pi
    X, Y = np.meshgrid(*m.axes, indexing="ij")
    w = np.hypot(np.repeat(X.ravel(), K) - A[2] * np.cos(phi), np.repeat(Y.ravel(), K) - A[2] * np.sin(phi))
    c2 = np.clip((w**2 - A[0] ** 2 - A[1] ** 2) / (2 * A[0] * A[1]), -1, 1)
    reachable = (w >= abs(A[0] - A[1]) + 1e-9) & (w <= A[0] + A[1] - 1e-9)
    best = np.where(reachable, A[0] * A[1] * np.sqrt(1 - c2**2), 0.0).reshape(-1, K).max(axis=1)
    edge = ((np.abs(w - abs(A[0] - A[1])) < 1e-6) | (np.abs(w - A[0] - A[1]) < 1e-6)).reshape(-1, K).any(axis=1)
    # (the IK stops within 1e-6: near a stretched or folded elbow |sin q2| moves by ~1e-5)
    np.testing.assert_allclose(m.manipulability.ravel()[~edge], best[~edge], rtol=0, atol=1e-4)
    # The 3R's xyphi manipulability is a1 a2 |sin q2|: at most a1 a2.
    assert m.manipulability.max() <= A[0] * A[1] + 1e-12 and m.manipulability.max() > 0.9 * A[0] * A[1]


def test_a_voxel_outside_the_reach_sphere_is_zero():
    chain = rk.robots.ur5()
    reach = 0.089159 + 0.425 + 0.39225 + 0.10915 + 0.09465 + 0.0823  # sum of |a| and |d|: an upper bound
    m = rk.reachability(chain, ((-0.3, 1.5), (-0.3, 0.3), (-0.3, 0.3)), 0.3, orientations=4, seed=2,
                        restarts=3)
    X, Y, Z = np.meshgrid(*m.axes, indexing="ij")
    outside = np.sqrt(X**2 + Y**2 + Z**2) > reach
    assert outside.any() and (~outside).any()
    assert np.all(m.index[outside] == 0) and np.all(m.manipulability[outside] == 0)
    assert m.index[~outside].max() > 0


def test_the_same_bits_whatever_the_threads_and_blocks(monkeypatch):
    chain = rk.robots.ur5()
    args = (chain, ((0.1, 0.5), (-0.2, 0.2), (0.0, 0.3)), 0.1)
    kw = dict(orientations=5, seed=123, restarts=2)
    monkeypatch.setenv("ROBOKIN_NUM_THREADS", "1")
    one = rk.reachability(*args, **kw)
    monkeypatch.setenv("ROBOKIN_NUM_THREADS", "3")
    monkeypatch.setattr(R, "BLOCK", 7)
    other = rk.reachability(*args, **kw)
    assert one.index.tobytes() == other.index.tobytes()
    assert one.manipulability.tobytes() == other.manipulability.tobytes()
    assert 0 < one.index.mean() < 1
    # Another seed draws other orientations.
    assert rk.reachability(*args, **{**kw, "seed": 124}).index.tobytes() != one.index.tobytes()


def test_orientations_are_uniform_rotations():
    u = R._uniforms(5, 0, 20000, 3)
    frames = R._targets("pose", np.zeros((20000, 3)), u)
    # A uniform rotation has E[R] = 0 and E[trace R] = 0 (Haar measure).
    assert np.abs(frames[:, :3, :3].mean(axis=0)).max() < 0.02
    np.testing.assert_allclose(np.einsum("nij,nkj->nik", frames[:, :3, :3], frames[:, :3, :3]),
                               np.broadcast_to(np.eye(3), (20000, 3, 3)), atol=1e-12)
    # Counter-based: the uniforms of targets 100..199 do not depend on where the block starts.
    assert np.array_equal(R._uniforms(5, 100, 100, 3), R._uniforms(5, 0, 200, 3)[100:])


@pytest.mark.parametrize("kwargs, name", [
    (dict(bounds=((0, 1), (0, 1), (1, 0))), "bounds"),
    (dict(bounds=((0, 1), (0, np.nan), (0, 1))), "bounds"),
    (dict(bounds=((0, 1),)), "bounds"),
    (dict(bounds="box"), "bounds"),
    (dict(bounds=((0, 1), (0, 1))), "bounds"),  # 2-D bounds for the pose task
    (dict(resolution=0.0), "resolution"),
    (dict(resolution=-1.0), "resolution"),
    (dict(resolution=math.inf), "resolution"),
    (dict(resolution="1"), "resolution"),
    (dict(resolution=1e-6), "resolution"),  # too many voxels
    (dict(orientations=0), "orientations"),
    (dict(orientations=2.5), "orientations"),
    (dict(orientations=True), "orientations"),
    (dict(orientations=3, task="position"), "orientations"),
    (dict(seed=-1), "seed"),
    (dict(seed=2**64), "seed"),
    (dict(task="full"), "task"),
    (dict(timeout=-1.0), "timeout"),
    (dict(stall_window=-1), "stall_window"),
    (dict(q0=np.zeros(5)), "q0"),
    (dict(q0=np.full(6, np.nan)), r"q0: contains NaN or inf"),
])
def test_bad_arguments_are_errors_naming_them(kwargs, name):
    args = dict(bounds=((0, 0.5), (0, 0.5), (0, 0.5)), resolution=0.25)
    args.update(kwargs)
    # A value of the wrong kind is a TypeError, one out of range a ValueError.
    wrong_kind = (isinstance(kwargs.get("bounds"), str) or isinstance(kwargs.get("resolution"), str)
                  or isinstance(kwargs.get("orientations"), (float, bool)))
    error = TypeError if wrong_kind else ValueError
    with pytest.raises(error, match=name):
        rk.reachability(rk.robots.ur5(), **args)


def test_figure_slices_and_projection(tmp_path, planar_map):
    m3 = rk.reachability(rk.robots.ur5(), ((-0.9, 0.9), (-0.9, 0.9), (-0.3, 0.6)), 0.3, orientations=3, seed=1,
                         restarts=2)
    path = tmp_path / "map.png"
    fig = plot_reachability(m3, path, axis="z")
    assert len(fig.axes) == 5  # three slices, the projection, the colorbar
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert os.listdir(tmp_path) == ["map.png"]  # written atomically: no temporary file left
    fig2 = plot_reachability(planar_map, tmp_path / "planar.png")
    assert len(fig2.axes) == 2  # one panel and its colorbar
    with pytest.raises(ValueError, match=r"^axis: expected one of \('z',\), got 'x'$"):
        plot_reachability(planar_map, axis="x")  # a planar map has its z panel only
    with pytest.raises(TypeError, match=r"^axis: expected one of \('x', 'y', 'z'\), got int$"):
        plot_reachability(m3, axis=2)
    with pytest.raises(ValueError, match="^slices: contains NaN or inf$"):
        plot_reachability(m3, slices=[np.nan])
    with pytest.raises(ValueError, match=r"^slices: expected a \(K,\) array, 1 <= K <= 12, got shape \(13,\)$"):
        plot_reachability(m3, slices=np.zeros(13))
    with pytest.raises(TypeError, match="^slices: expected real numbers"):
        plot_reachability(m3, slices=["a"])


def test_an_arm_with_a_closed_form_is_mapped_by_it():
    # The UR5's map is made with its closed form: every target the numerical batch IK solves (a
    # solution checked by FK) the closed form solves too, with a manipulability at least as good (to
    # the IK's 1e-6 tolerance), and at most a few more (the restarts' misses).
    import dataclasses

    chain = rk.robots.ur5()
    p = R.plan(chain, ((-0.9, 0.9), (-0.9, 0.9), (0.0, 0.6)), 0.3, orientations=12, seed=5)
    assert p.closed is not None and p.closed.family == "three parallel axes 2, 3, 4"
    closed = rk.reachability(chain, ((-0.9, 0.9), (-0.9, 0.9), (0.0, 0.6)), 0.3, orientations=12, seed=5)
    numeric = dataclasses.replace(p, closed=None)
    ik = numeric.result(*numeric.block(0, numeric.voxels))
    assert np.all(ik.index <= closed.index) and np.abs(ik.index - closed.index).mean() < 0.02
    both = (ik.index > 0) & (closed.index > 0)
    assert both.sum() > 10 and np.all(ik.manipulability[both] <= closed.manipulability[both] + 1e-5)
    assert np.all((closed.manipulability > 0) == (closed.index > 0))
    # Arms without one, and the other tasks, keep the IK.
    assert R.plan(rk.robots.panda(), ((0, 0.2),) * 3, 0.1).closed is None
    assert R.plan(chain, ((0, 0.2),) * 3, 0.1, task="position").closed is None
