"""`make run`'s RPR demo: it tracks the line both ways, every point within tolerance, and writes its
figure, which draws the joint paths it tracked."""

import re

import numpy as np

import robokin as rk
import robokin.demo
import robokin.plots


def test_demo_writes_the_figure(tmp_path, capsys, monkeypatch):
    drawn = {}

    def figure(points, tracks, **kwargs):
        drawn["points"], drawn["tracks"] = points, tracks
        drawn["figure"] = fig = rpr_line_figure(points, tracks, **kwargs)
        return fig

    rpr_line_figure = robokin.plots.rpr_line_figure
    monkeypatch.setattr(robokin.plots, "rpr_line_figure", figure)
    out = tmp_path / "fig.png"
    assert robokin.demo.main(["--out", str(out), "--step", "0.01"]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    text = capsys.readouterr().out
    counts = re.findall(r"converged (\d+)/(\d+)", text)
    assert len(counts) == 2 and all(a == b for a, b in counts)
    assert str(out) in text
    # The tracks put the tool on the line's points (forward model of the tracked joints) ...
    chain = rk.robots.rpr()
    points, tracks = drawn["points"], drawn["tracks"]
    assert len(tracks) == 2
    for tr in tracks.values():
        np.testing.assert_allclose(chain.fk(tr.q)[:, :2, 3], points, rtol=0, atol=1e-5)
    # ... and panel (a) draws each joint path as it was tracked.
    ax = drawn["figure"].axes[0]
    paths = [np.array(line.get_data_3d()).T for line in ax.lines if line.get_linewidth() == 2.5]
    assert len(paths) == 2
    for path, tr in zip(paths, tracks.values()):
        np.testing.assert_array_equal(path, tr.q)
