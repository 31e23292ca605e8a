"""Arbitrary arrays and numbers into the IK calls: a result or a ValueError, never a crash; and a
reported success is always a reached pose."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import robokin as rk

UR5 = rk.robots.ur5()
floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
shapes = hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=6)
arrays = st.one_of(
    hnp.arrays(np.float64, shapes, elements=floats),
    hnp.arrays(np.float64, st.sampled_from([(4, 4), (6,), (1, 4, 4), (2, 6)]), elements=st.floats(-3, 3)),
    hnp.arrays(np.int64, shapes, elements=st.integers(-5, 5)),
)


@settings(max_examples=150, deadline=None)
@given(target=arrays, q0=arrays, method=st.sampled_from(["lm", "gn", "nr", "halley", "?"]),
       task=st.sampled_from(["pose", "position", "xy", "xyphi", "?"]), tol=floats,
       max_iter=st.integers(-2, 20), restarts=st.integers(-1, 3))
def test_ik_returns_or_raises(target, q0, method, task, tol, max_iter, restarts):
    try:
        r = rk.ik(UR5, target, q0, method=method, task=task, tol_p=tol, tol_r=tol, max_iter=max_iter,
                  restarts=restarts, seed=0)
    except ValueError:
        return
    assert np.all(np.isfinite(r.q)) and np.isfinite(r.error_p) and np.isfinite(r.error_r)
    assert r.success == (r.error_p < tol and (task not in ("pose", "xyphi") or r.error_r < tol))


@settings(max_examples=100, deadline=None)
@given(targets=arrays, q0=arrays, path=st.booleans())
def test_ik_batch_returns_or_raises(targets, q0, path):
    try:
        r = rk.ik_batch(UR5, targets, q0, max_iter=10, path=path, seed=0)
    except ValueError:
        return
    assert r.q.shape == (len(r), 6) and np.all(np.isfinite(r.q))


@settings(max_examples=150, deadline=None)
@given(target=arrays, a=st.tuples(floats, floats, floats), method=st.sampled_from(["algebraic", "geometric"]))
def test_closed_forms_return_or_raise(target, a, method):
    calls = [
        lambda: rk.closed.planar_rp(target),
        lambda: rk.closed.planar_2r(target, a[0], a[1]),
        lambda: rk.closed.planar_3r(target, *a, method=method),
        lambda: rk.closed.anthropomorphic(target, a[0], a[1], a[2]),
        lambda: rk.closed.puma560(target),
        lambda: rk.closed.spherical_wrist_6r(target, 0.4, 0.02, 0.1, 0.4, d6=a[0]),
    ]
    for call in calls:
        try:
            s = call()
        except ValueError:
            continue
        assert np.all(np.isfinite(s.q)) and len(s.postures) == len(s)
