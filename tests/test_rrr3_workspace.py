"""3-RRR workspace maps and the design study, against reachability and determinants computed here."""

import pickle

import numpy as np
import pytest

import robokin as rk
import robokin.rrr3_design as design

from rrr3_truth import base, platform, seed_jacobians


@pytest.fixture(scope="module")
def robot():
    return rk.RRR3()


@pytest.fixture(scope="module")
def ws(robot):
    return robot.workspace(phi=0.1, mode=(1, 1, 1), n=120)


def test_reachable_cells_are_the_reachable_poses(robot, ws):
    xx, yy = np.meshgrid(ws.x, ws.y)  # row j at y[j], column i at x[i]
    reach = np.ones(xx.shape, bool)
    for i in range(3):
        bx = xx + robot.platform_radius * np.cos(np.radians(-90 + 120 * i) + 0.1)
        by = yy + robot.platform_radius * np.sin(np.radians(-90 + 120 * i) + 0.1)
        r = np.hypot(bx - base(robot)[i, 0], by - base(robot)[i, 1])
        reach &= (r <= robot.l1 + robot.l2) & (r > 0)
    assert reach.sum() > 1000
    np.testing.assert_array_equal(ws.cells > 0, reach)
    assert not reach[0].any() and not reach[-1].any() and not reach[:, 0].any() and not reach[:, -1].any()
    assert ws.reachable_area == pytest.approx(reach.sum() * ws.cell_size**2)


def test_reachable_area_converges_to_the_intersection_of_disks(robot):
    # Monte Carlo estimate of the intersection of the three reach disks (an independent estimate).
    rng = np.random.default_rng(1)
    pts = rng.uniform(-0.3, 0.3, (400_000, 2))
    inside = np.ones(len(pts), bool)
    for i in range(3):
        c = base(robot)[i] - platform(robot, np.zeros(3))[i]
        inside &= np.linalg.norm(pts - c, axis=1) <= robot.l1 + robot.l2
    mc = inside.mean() * 0.36
    assert robot.workspace(phi=0.0, mode=(1, 1, 1), n=400).reachable_area == pytest.approx(mc, rel=0.02)


def test_singular_cells(robot, ws):
    """Red cells sit on det A = 0: small |det A| or a sign change to a neighbour; others keep a sign."""
    mode = (1, 1, 1)
    det = np.full(ws.cells.shape, np.nan)
    for j, i in zip(*np.nonzero(ws.cells > 0)):
        pose = np.array([ws.x[i], ws.y[j], 0.1])
        det[j, i] = np.linalg.det(seed_jacobians(robot, pose, robot.ik(pose, mode))[0]) / robot.platform_radius
    sign = np.sign(det)
    flips = np.zeros(det.shape, bool)
    for axis in (0, 1):
        d = np.abs(np.diff(sign, axis=axis)) == 2
        sl_a = [slice(None)] * 2
        sl_b = [slice(None)] * 2
        sl_a[axis], sl_b[axis] = slice(None, -1), slice(1, None)
        flips[tuple(sl_a)] |= d
        flips[tuple(sl_b)] |= d
    red = ws.cells == 2
    assert red.sum() > 50
    assert np.all(flips[red] | (np.abs(det[red]) < 1e-3))
    # Every sign change between neighbours has a red (or serial) cell on one side.
    for axis in (0, 1):
        a = np.moveaxis(sign, axis, 0)
        c = np.moveaxis(ws.cells, axis, 0)
        change = np.abs(a[1:] - a[:-1]) == 2
        assert np.all(((c[1:] >= 2) | (c[:-1] >= 2))[change])
    assert ws.area <= ws.regular_area <= ws.reachable_area


def largest_region(regular):
    """Cells of the largest 4-connected region of True cells (a flood fill written here)."""
    seen = np.zeros(regular.shape, bool)
    best = 0
    for start in zip(*np.nonzero(regular)):
        if seen[start]:
            continue
        seen[start], stack, size = True, [start], 0
        while stack:
            j, i = stack.pop()
            size += 1
            for nb in ((j + 1, i), (j - 1, i), (j, i + 1), (j, i - 1)):
                if 0 <= nb[0] < regular.shape[0] and 0 <= nb[1] < regular.shape[1] and regular[nb] and not seen[nb]:
                    seen[nb] = True
                    stack.append(nb)
        best = max(best, size)
    return best


def test_areas_are_the_cells_counted(ws):
    """The areas are cell counts times the cell's area: reachable, regular, and the largest
    singularity-free region (several regions here: the largest is not all of the regular area)."""
    cells = np.asarray(ws.cells)
    cell = ws.cell_size**2
    assert ws.reachable_area == pytest.approx(np.count_nonzero(cells > 0) * cell, rel=1e-12)
    assert ws.regular_area == pytest.approx(np.count_nonzero(cells == 1) * cell, rel=1e-12)
    largest = largest_region(cells == 1)
    assert largest < np.count_nonzero(cells == 1)
    assert ws.area == pytest.approx(largest * cell, rel=1e-12)
    assert ws.regular_area == pytest.approx(np.sum(ws.cells == 1) * ws.cell_size**2)


def test_workspace_bad_input(robot):
    with pytest.raises(ValueError, match="n"):
        robot.workspace(n=1)
    with pytest.raises(ValueError, match="n"):
        robot.workspace(n=100_000)
    with pytest.raises(ValueError, match="mode"):
        robot.workspace(mode=(1, 1, 2))
    with pytest.raises(ValueError, match="phi"):
        robot.workspace(phi=float("nan"))
    with pytest.raises(ValueError, match="platform_radii"):
        design.area_vs_platform_radius([0.05, -0.1])
    with pytest.raises(ValueError, match="robots"):
        rk._core.rrr3_region_areas(np.array([[0.15, 0.05, 0.1, 0.0]]))


def test_design_study_matches_the_workspace_maps():
    radii = np.array([0.04, 0.08, 0.12])
    curve = design.area_vs_platform_radius(radii, n=80)
    for r, a in zip(radii, curve.area):
        assert a == pytest.approx(rk.RRR3(0.15, r, 0.10, 0.10).workspace(phi=0.0, mode=(1, 1, 1), n=80).area)
    assert curve.best in radii
    best = design.best_l2([0.08, 0.12], np.linspace(0.04, 0.2, 9), n=60)
    assert best.area.shape == (2, 9)
    np.testing.assert_allclose(best.index, best.area / (np.pi * (best.l1[:, None] + best.l2[None, :]) ** 2))
    for k in range(2):
        assert best.index[k].max() == best.index[k][list(best.l2).index(best.best_l2[k])]


def segments(ax):
    """Every two-point line of the axes as ((x0, y0), (x1, y1))."""
    return [tuple(map(tuple, np.asarray(line.get_xydata()))) for line in ax.lines if len(line.get_xydata()) == 2]


def test_plots_draw_the_model(robot):
    """The figures are checked by what they draw: the legs where DESIGN.md's geometry puts them
    (elbows from the core's inverse model), the map's cells in their colours, the design curves."""
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    import robokin.plots_rrr3 as plots

    pose = np.array([0.02, 0.01, 0.2])
    clover = rk.paths.clover(100)
    fig, ax = plots.plot_robot(robot, pose, path=clover)
    o, b = base(robot), platform(robot, pose)
    alpha = robot.ik(pose)
    a = o + robot.l1 * np.column_stack((np.cos(alpha), np.sin(alpha)))
    np.testing.assert_allclose(np.linalg.norm(b - a, axis=1), robot.l2, atol=1e-12)  # the loops close
    drawn = segments(ax)
    for i in range(3):
        for p, q in ((o[i], a[i]), (a[i], b[i])):
            assert any(np.allclose(seg, (p, q), atol=1e-12) for seg in drawn), (i, p, q)
    assert any(np.array_equal(line.get_xydata(), clover) for line in ax.lines)  # the path as given
    np.testing.assert_allclose(ax.patches[-1].get_xy()[:3], b, atol=1e-12)  # the platform's triangle
    fig, ax, w = plots.plot_workspace(robot, phi=0.1, n=80)
    np.testing.assert_array_equal(ax.images[0].get_array(), plots.CELL_COLOURS[np.asarray(w.cells)])
    assert tuple(ax.images[0].get_extent()) == tuple(w.extent)
    curve = design.area_vs_platform_radius(np.linspace(0.03, 0.12, 4), n=40)
    best = design.best_l2([0.08, 0.1], [0.05, 0.1, 0.15], n=40)
    fig, (ax1, ax2) = plots.plot_design(curve, best)
    np.testing.assert_array_equal(ax1.lines[0].get_xydata(), np.column_stack((curve.values * 100, curve.area * 1e4)))
    np.testing.assert_array_equal(ax2.lines[0].get_xydata(), np.column_stack((best.l1 * 100, best.best_l2 * 100)))
    plt.close("all")


def test_map_cells_agree_with_singularity_everywhere(robot):
    # The map's determinants come from the robot's own inverse model and Jacobians (one
    # implementation): every reachable cell is classified as RRR3.singularity classifies its centre,
    # apart from cells marked for a sign change of det A with a neighbour.
    rng = np.random.default_rng(5)
    for phi, mode in [(0.0, (1, 1, 1)), (0.4, (1, -1, 1)), (-1.0, (-1, -1, -1))]:
        w = robot.workspace(phi=phi, mode=mode, n=90, tol=1e-2)
        cells = np.asarray(w.cells)
        code = {"none": 1, "parallel": 2, "serial": 3}
        checked = 0
        for j, i in zip(rng.integers(0, 90, 1500), rng.integers(0, 90, 1500)):
            pose = np.array([w.x[i], w.y[j], phi])
            try:
                s = robot.singularity(pose, mode, tol=1e-2)
            except rk.UnreachableError:
                assert cells[j, i] == 0
                continue
            checked += 1
            if cells[j, i] == 2 and s.kind == "none":
                continue  # a sign change of det A with a neighbour
            assert cells[j, i] == code[s.kind], (phi, mode, pose)
        assert checked > 300


def test_base_joints_from_the_core(robot):
    o = robot.base_joints
    assert o.shape == (3, 2)
    np.testing.assert_allclose(o, base(robot), atol=1e-15)
    np.testing.assert_allclose(o, robot.points([0.0, 0.0, 0.0])["O"], atol=1e-15)
    with pytest.raises(ValueError):
        o[0, 0] = 1.0  # read-only
    assert rk.RRR3(0.2, 0.05, 0.1, 0.1).base_joints[0, 1] == pytest.approx(-0.2)


def test_plot_design_titles_follow_the_curve(tmp_path):
    mpl = pytest.importorskip("matplotlib")
    mpl.use("Agg")
    import matplotlib.pyplot as plt

    import robokin.plots_rrr3 as plots

    curve = design.area_vs_platform_radius(np.linspace(0.03, 0.1, 3), base_radius=0.2, l1=0.12, l2=0.08, n=30)
    assert (curve.base_radius, curve.l1, curve.l2) == (0.2, 0.12, 0.08)
    best = design.best_l2([0.08, 0.1], [0.05, 0.1], base_radius=0.18, platform_radius=0.06, n=30)
    fig, (ax1, ax2) = plots.plot_design(curve, best)
    assert "R_b = 20 cm" in ax1.get_title() and "l1 = 12 cm, l2 = 8 cm" in ax1.get_title()
    assert "15 cm" not in ax1.get_title()
    assert "R_b = 18 cm" in ax2.get_title() and "R_e = 6 cm" in ax2.get_title()
    plt.close("all")
    fig, (ax1, _) = plots.plot_design(design.area_vs_platform_radius(np.linspace(0.03, 0.12, 3), n=30),
                                      design.best_l2([0.1], [0.1], n=30))
    assert "R_b = 15 cm, l1 = l2 = 10 cm" in ax1.get_title()
    plt.close("all")


def test_map_grid_and_pickle(robot, ws):
    """x, y and extent (computed in the core) describe the same grid as x0, y0, cell_size; a pickled
    map comes back equal, and so does a state written with the cells as bytes (the earlier layout)."""
    h = ws.cell_size
    np.testing.assert_allclose(ws.x, ws.x0 + (np.arange(ws.n) + 0.5) * h, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ws.y, ws.y0 + (np.arange(ws.n) + 0.5) * h, rtol=0, atol=1e-15)
    assert ws.extent == pytest.approx((ws.x0, ws.x0 + ws.n * h, ws.y0, ws.y0 + ws.n * h), abs=1e-15)
    assert ws.cells.shape == (ws.n, ws.n) and ws.cells.dtype == np.uint8
    copy = pickle.loads(pickle.dumps(ws))
    assert repr(copy) == repr(ws) and np.array_equal(copy.cells, ws.cells)
    cls, state = type(ws), list(ws.__getstate__())
    state[5] = ws.cells.tobytes()
    old = cls.__new__(cls)
    old.__setstate__(tuple(state))
    assert repr(old) == repr(ws) and np.array_equal(old.cells, ws.cells)
    state[5] = ws.cells.tobytes()[:-1]
    with pytest.raises(ValueError, match="cells: n \\* n cell codes expected"):
        cls.__new__(cls).__setstate__(tuple(state))
