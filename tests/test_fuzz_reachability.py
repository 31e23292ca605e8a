"""Property tests of the reachability maps, their figure and robokin.dask: every argument arbitrary;
a call returns a well-formed finite result (the index a fraction of the orientations, the Dask
calls the one-machine bits) or raises ValueError / TypeError naming an argument."""

import math
import sys

import dask
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import robokin as rk
import robokin.dask as rkd
from fuzz import arrays, check_call, wild_floats
from robokin import rrr3_design
from robokin.plots_reachability import plot_reachability

R = sys.modules["robokin.reachability"]

COVERS = {"reachability", "reachability.grid", "reachability.plan", "reachability.reachability", "plots_reachability.plot_reachability",
          "dask.fk", "dask.ik_batch", "dask.reachability", "dask.region_areas", "dask.best_l2",
          "dask.area_vs_platform_radius"}

CHAINS = [rk.robots.planar_3r(), rk.robots.ur5(), rk.robots.rpr()]
NAMES = ("bounds", "resolution", "orientations", "seed", "task", "q0", "ik_options", "chain")
small = st.one_of(wild_floats, st.floats(0.05, 2.0), st.sampled_from([None, "1", [0.5], True]))
bounds = st.one_of(arrays([(3, 2), (2, 2), (3,), (1, 2), (4, 2)], elements=st.floats(-1.5, 1.5)),
                   arrays([(3, 2), (2, 2)]))
ints = st.one_of(st.integers(-2, 6), st.sampled_from([2**64, -(2**63), 2.5, None, "3", True]))
tasks = st.sampled_from(["pose", "position", "xy", "xyphi", "bad", None])


@pytest.fixture(autouse=True)
def synchronous_dask():
    with dask.config.set(scheduler="synchronous"):
        yield


@settings(max_examples=60, deadline=None)
@given(chain=st.sampled_from(CHAINS), bounds=bounds, resolution=small, orientations=ints, seed=ints, task=tasks)
def test_reachability_with_arbitrary_arguments(chain, bounds, resolution, orientations, seed, task):
    axes = check_call(lambda: R.grid(bounds, resolution), "bounds", "resolution")
    if axes is None:
        return
    assert all(np.all(np.isfinite(a)) and np.all(np.diff(a) > 0) for a in axes)
    k = orientations if isinstance(orientations, int) and not isinstance(orientations, bool) else 1
    assume(math.prod(len(a) for a in axes) * max(k, 1) <= 150)
    m = check_call(lambda: rk.reachability(chain, bounds, resolution, orientations=orientations, seed=seed, task=task,
                                           restarts=1, max_iter=20), *NAMES)
    if m is None:
        return
    assert m.index.shape == tuple(len(a) for a in axes)
    assert np.all((m.index >= 0) & (m.index <= 1)) and np.all(np.isfinite(m.manipulability))
    assert np.all(m.manipulability >= 0) and np.all((m.manipulability > 0) <= (m.index > 0))
    assert np.allclose(m.index * m.orientations, np.round(m.index * m.orientations))
    # Dask, one chunk per voxel: the same bits.
    d = rkd.reachability(chain, bounds, resolution, orientations=orientations, seed=seed, task=task, restarts=1,
                         max_iter=20, chunks=1)
    assert d.index.tobytes() == m.index.tobytes() and d.manipulability.tobytes() == m.manipulability.tobytes()
    # The plan's blocks, three voxels each, computed last block first: the same bits.
    p = R.plan(chain, bounds, resolution, orientations=orientations, seed=seed, task=task, restarts=1, max_iter=20)
    index, manip = np.empty(p.voxels), np.empty(p.voxels)
    for first in reversed(range(0, p.voxels, 3)):
        count = min(3, p.voxels - first)
        index[first:first + count], manip[first:first + count] = p.block(first, count)
    b = p.result(index, manip)
    assert b.index.tobytes() == m.index.tobytes() and b.manipulability.tobytes() == m.manipulability.tobytes()


MAP = rk.reachability(rk.robots.ur5(), ((-0.8, 0.8), (-0.8, 0.8), (0.0, 0.4)), 0.4, orientations=2, restarts=1)


@settings(max_examples=20, deadline=None)
@given(axis=st.sampled_from(["x", "y", "z", "w", None, 2]),
       slices=st.one_of(st.none(), arrays([(1,), (3,), (0,), (20,)], elements=st.floats(-1, 1)), arrays([(2,)])))
def test_plot_with_arbitrary_arguments(axis, slices):
    fig = check_call(lambda: plot_reachability(MAP, axis=axis, slices=slices), "axis", "slices")
    if fig is not None:
        assert len(fig.axes) >= 3


@settings(max_examples=40, deadline=None)
@given(chain=st.sampled_from(CHAINS), q=arrays([(5, 3), (5, 6), (0, 3), (3,), (4, 2)]),
       chunks=st.sampled_from([1, 2, 100]))
def test_dask_fk_with_arbitrary_arrays(chain, q, chunks):
    out = check_call(lambda: rkd.fk(chain, q, chunks=chunks).compute(), "q")
    if out is not None:
        np.testing.assert_array_equal(out, chain.fk(np.asarray(q, dtype=float)))


@settings(max_examples=40, deadline=None)
@given(targets=arrays([(3, 4, 4), (3, 2), (3, 3), (0, 4, 4), (4,)], elements=st.floats(-1, 1)),
       task=st.sampled_from(["pose", "xy", "position", "bad"]), seed=ints, chunks=st.sampled_from([1, 2, 100]),
       restarts=st.sampled_from([0, 1, -1]))
def test_dask_ik_batch_with_arbitrary_arguments(targets, task, seed, chunks, restarts):
    chain = rk.robots.ur5() if task == "pose" else rk.robots.planar_3r()
    names = ("targets", "task", "seed", "restarts", "q0")
    got = check_call(lambda: rkd.ik_batch(chain, targets, np.zeros(chain.dof), task=task, seed=seed, chunks=chunks,
                                          restarts=restarts, max_iter=20).compute(), *names)
    if got is None:
        return
    ref = rk.ik_batch(chain, np.asarray(targets, dtype=float), np.zeros(chain.dof), task=task, seed=seed,
                      restarts=restarts, max_iter=20)
    assert np.array_equal(got.q, ref.q) and np.array_equal(got.success, ref.success)


@settings(max_examples=30, deadline=None)
@given(robots=arrays([(2, 4), (1, 4), (2, 3), (0, 4)], elements=st.floats(0.01, 0.2)), n=st.sampled_from([10, 0, -1]),
       chunks=st.sampled_from([1, 3]))
def test_dask_region_areas_with_arbitrary_robots(robots, n, chunks):
    got = check_call(lambda: rkd.region_areas(robots, n=n, chunks=chunks).compute(), "robots", "n")
    if got is not None:
        np.testing.assert_array_equal(got, rk._core.rrr3_region_areas(np.asarray(robots, dtype=float), n=n))


@settings(max_examples=20, deadline=None)
@given(values=arrays([(2,), (1,), (0,)], elements=st.floats(-0.1, 0.15)), n=st.sampled_from([10, 0]))
def test_dask_design_sweeps_with_arbitrary_values(values, n):
    names = ("l1_values", "l2_values", "platform_radii", "n")
    got = check_call(lambda: rkd.best_l2(values, values, n=n, chunks=1), *names)
    if got is not None:
        assert np.array_equal(got.area, rrr3_design.best_l2(values, values, n=n).area)
    curve = check_call(lambda: rkd.area_vs_platform_radius(values, n=n, chunks=1), *names)
    if curve is not None:
        assert np.array_equal(curve.area, rrr3_design.area_vs_platform_radius(values, n=n).area)
