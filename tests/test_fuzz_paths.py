"""Property tests of the sampled paths (robokin.paths), the figures (robokin.plots,
robokin.plots_rrr3) and the RPR demo's command line (robokin.demo.main).

Paths: any arguments give finite points of the documented shape that lie on the curve, or a
ValueError / TypeError naming the argument; a count that would allocate gigabytes is refused.
Figures (few examples: matplotlib is slow): bad poses, modes, paths and counts raise by name.
"""

import math
import os

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from fuzz import arrays, assert_finite, check_call, finite_arrays, wild_floats  # noqa: E402
from hypothesis import HealthCheck, assume, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import robokin as rk  # noqa: E402
import robokin.demo  # noqa: E402
from robokin import plots, plots_rrr3, rrr3_design  # noqa: E402
from robokin.reach import track  # noqa: E402

COVERS = {
    "paths.line", "paths.circle", "paths.clover",
    "plots.draw_planar_chain", "plots.rpr_line_figure",
    "plots_rrr3.plot_robot", "plots_rrr3.plot_workspace", "plots_rrr3.plot_design",
    "demo.main",
}

#: Figures are slow: a twentieth of the profile's examples.
FEW = settings(max_examples=max(5, settings.default.max_examples // 20),
               suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])

counts = st.one_of(st.integers(-3, 2000), st.sampled_from([rk.paths.MAX_POINTS + 1, 2**63, 10**30, np.int64(7)]),
                   st.sampled_from([0.0, 5.0, math.nan, True, None, "10", [3]]))
numbers = st.one_of(wild_floats, st.floats(1e-3, 10.0), st.sampled_from([None, "0.1", 1j, [0.1], np.float32(0.2), -1]))
points = st.one_of(finite_arrays((2,)), finite_arrays((3,)), arrays([(2,), (3,), (4,), (1,), (2, 1), ()]))


# --- paths ---------------------------------------------------------------------------------

@given(p1=points, p2=points, step=numbers)
def test_line(p1, p2, step):
    a, b = (np.asarray(v, dtype=float) if isinstance(v, np.ndarray) and v.dtype.kind in "fiub" else None
            for v in (p1, p2))
    if a is not None and b is not None and a.shape == b.shape and isinstance(step, float) and step > 0:
        # A count of points the test can afford; beyond MAX_POINTS the call must refuse.
        with np.errstate(over="ignore"):
            k = math.hypot(*(b - a)) / step if a.ndim == 1 and np.all(np.isfinite(b - a)) else 0.0
        assume(not 1e5 < k <= rk.paths.MAX_POINTS)
    out = check_call(lambda: rk.paths.line(p1, p2, step), "p1", "p2", "step")
    if out is None:
        return
    a, b = np.asarray(p1, dtype=float), np.asarray(p2, dtype=float)
    assert out.ndim == 2 and out.shape[1] == a.shape[0] and 2 <= len(out) <= rk.paths.MAX_POINTS
    assert_finite(out)
    assert np.array_equal(out[0], a)
    assert np.allclose(out[-1], b, rtol=1e-12, atol=1e-12 * np.abs(a).max(initial=0))
    gaps = np.linalg.norm(np.diff(out, axis=0), axis=1)
    assert gaps.max() <= step * (1 + 1e-9) + 1e-12 * np.abs(out).max()
    # every point on the segment: collinear with the ends
    d = b - a
    if np.linalg.norm(d) > 0:
        off = (out - a) - np.outer((out - a) @ d / (d @ d), d)
        assert np.abs(off).max() <= 1e-9 * (np.abs(a).max() + np.abs(b).max())


@given(n=counts, size=numbers, center=st.one_of(finite_arrays((2,)), arrays([(2,), (3,), (1,)])),
       which=st.sampled_from(["circle", "clover"]))
def test_circle_and_clover(n, size, center, which):
    if which == "circle":
        out = check_call(lambda: rk.paths.circle(n, radius=size, center=center), "n", "radius", "center")
    else:
        out = check_call(lambda: rk.paths.clover(n, k=size, center=center), "n", "k", "center")
    if out is None:
        return
    assert out.shape == (int(n), 2) and out.dtype == np.float64
    assert_finite(out)
    c, size = np.asarray(center, dtype=float), float(size)
    # In units of the largest input, so that nothing overflows near 1e308 (the tolerance stays finite).
    unit = max(abs(float(size)), float(np.abs(c).max())) or 1.0
    rel = out / unit - c / unit
    r = np.hypot(rel[:, 0], rel[:, 1])
    t = 2 * np.pi * np.arange(int(n)) / int(n)
    expected = size / unit * (1.0 if which == "circle" else 1.0 + np.cos(4 * t) + 2.0 * np.sin(4 * t) ** 2)
    # A subnormal size (below 2.2e-308) keeps only a few significant bits: one unit of 5e-324 each.
    assert np.allclose(r, expected, rtol=1e-9, atol=5e-12 + 4 * 5e-324 / unit)


@pytest.mark.parametrize("call, match", [
    (lambda: rk.paths.circle(10**12), r"n: expected an int in \[1, 10000000\] \(points\), got 1000000000000"),
    (lambda: rk.paths.clover(2**63), r"n: expected an int in \[1, 10000000\] \(points\)"),
    (lambda: rk.paths.line([0, 0], [1, 0], 1e-300), "step: "),
    (lambda: rk.paths.line([-1e308, 0], [1e308, 0], 1.0), "p1, p2: too far apart"),
    (lambda: rk.paths.circle(10, radius=1e308, center=(1e308, 0)), "radius, center: the points overflow"),
    (lambda: rk.paths.line(None, [1, 0], 0.1), "p1: expected real numbers"),
    (lambda: rk.paths.line([0, 0], [1j, 0], 0.1), "p2: expected real numbers"),
    (lambda: rk.paths.line([0, 0], [1, 0], "abc"), "step: expected a number, got str"),
    (lambda: rk.paths.circle(5, center=[[0.0], [1.0, 2.0]]), "center: expected real numbers"),
])
def test_bad_paths_regressions(call, match):
    """Each was an allocation of terabytes (MemoryError), an OverflowError, inf in the points, or a
    TypeError / ValueError from numpy naming no argument."""
    with pytest.raises((ValueError, TypeError), match=match):
        call()


# --- figures -------------------------------------------------------------------------------

RPR = rk.robots.rpr()
LINE = rk.paths.line(RPR.fk(rk.robots.RPR_LINE_Q1)[:2, 3], rk.robots.RPR_LINE_P2, 0.1)
TRACK = track(RPR, LINE, rk.robots.RPR_LINE_Q1)
ROBOT = rk.RRR3()


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@FEW
@given(q=arrays([(3,), (2,), (4,)]), chain=st.sampled_from([RPR, rk.robots.planar_3r(), rk.robots.rp()]))
def test_draw_planar_chain(q, chain):
    ax = Figure().add_subplot()
    check_call(lambda: plots.draw_planar_chain(ax, chain, q), "q")
    if check_call(lambda: chain.fk(q), "q") is not None:
        assert len(ax.lines) == 2
        assert np.allclose(ax.lines[0].get_xydata()[-1], chain.fk(q)[:2, 3])


@FEW
@given(points=st.one_of(st.just(LINE), st.just(LINE[:3]), arrays([(len(LINE), 2), (0, 2), (3,)])),
       tracks=st.sampled_from([{"a": TRACK}, {"a": TRACK, "b": TRACK}, {}, {"a": None}, [TRACK], None]),
       surface_samples=counts, snapshots=counts, title=st.sampled_from([None, "t", 3]))
def test_rpr_line_figure(points, tracks, surface_samples, snapshots, title):
    fig = check_call(lambda: plots.rpr_line_figure(points, tracks, surface_samples, snapshots, title),
                     "points", "tracks", "surface_samples", "snapshots", "title")
    if fig is not None:
        assert isinstance(fig, Figure) and len(fig.axes) >= 3


modes = st.one_of(st.tuples(*[st.sampled_from([1, -1])] * 3), arrays([(3,), (2,)]), st.sampled_from([(1, 0, 1), "abc"]))


@FEW
@given(pose=st.one_of(finite_arrays((3,), -0.1, 0.1), arrays([(3,), (2,)])), mode=modes,
       path=st.one_of(st.none(), finite_arrays((5, 2), -0.1, 0.1), arrays([(5, 2), (5,), (0, 2)])))
def test_plot_robot(pose, mode, path):
    out = check_call(lambda: plots_rrr3.plot_robot(ROBOT, pose, mode, path=path), "pose", "mode", "path")
    if out is not None:
        fig, ax = out
        assert ax.figure is fig and len(ax.lines) > 6


@FEW
@given(phi=st.one_of(st.floats(-3, 3), wild_floats, st.sampled_from([None, "0"])), mode=modes,
       n=st.one_of(st.integers(-2, 40), st.sampled_from([10**9, 2**63, 2.5, None])),
       tol=st.one_of(st.just(1e-3), wild_floats))
def test_plot_workspace(phi, mode, n, tol):
    out = check_call(lambda: plots_rrr3.plot_workspace(ROBOT, phi=phi, mode=mode, n=n, tol=tol), "phi", "mode", "n", "tol")
    if out is not None:
        fig, ax, w = out
        assert w.cells.shape == (n, n) and len(ax.images) == 1


CURVE = rrr3_design.area_vs_platform_radius(np.array([0.03, 0.06]), n=20)
BEST = rrr3_design.best_l2(np.array([0.08, 0.1]), np.array([0.05, 0.1]), n=20)


@FEW
@given(curve=st.sampled_from([CURVE, BEST, "x", 1.0, np.zeros(3)]), best=st.sampled_from([BEST, CURVE, [], "y"]))
def test_plot_design(curve, best):
    out = check_call(lambda: plots_rrr3.plot_design(curve, best), "curve", "best")
    if out is not None:
        fig, (ax1, ax2) = out
        assert np.allclose(ax1.lines[0].get_xdata(), CURVE.values * 100)


# --- the demo's command line ---------------------------------------------------------------

tokens = st.one_of(
    st.sampled_from(["--step", "--step", "--out", "--out", "-h", "--help", "--steps", "--step=0.5", "-x", "--", "1"]),
    st.sampled_from(["nan", "inf", "-1", "0", "1e-300", "1e9", "0.4", "abc", ""]),
    st.sampled_from(["fig.png", "sub/dir/fig.svg", "fig.xyz", "fig", "fig.PNG", "dir/", "."]),
    st.text(max_size=6).filter(lambda t: not t.startswith("-")),
)


@settings(max_examples=max(5, settings.default.max_examples // 30),
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(argv=st.lists(tokens, max_size=5))
def test_demo_main_any_argv(argv, tmp_path_factory, capsys):
    """Any command line: a figure written whole, or argparse's exit (status 0 for --help, 2 for a
    usage error, with a message), never a traceback. Runs in a fresh temporary directory."""
    where = tmp_path_factory.mktemp("demo")
    old = os.getcwd()
    os.chdir(where)
    try:
        status = robokin.demo.main(argv)
    except SystemExit as exc:
        assert exc.code in (0, 2), exc.code
        if exc.code == 2:
            assert "error:" in capsys.readouterr().err
        status = None
    finally:
        os.chdir(old)
    if status is not None:
        assert status == 0
        written = [os.path.join(d, f) for d, _, files in os.walk(where) for f in files]
        assert len(written) == 1 and ".part" not in written[0] and os.path.getsize(written[0]) > 1000


def test_demo_rejects_a_step_that_would_take_hours(capsys):
    """--step 1e-9: ten million points tracked and drawn (hours, gigabytes); now a usage error."""
    with pytest.raises(SystemExit) as exc:
        robokin.demo.main(["--step", "1e-9", "--out", "never.png"])
    assert exc.value.code == 2 and "--step" in capsys.readouterr().err
    assert not os.path.exists("never.png")
