"""`make run`'s RPR demo: it tracks the line both ways, every point within tolerance, and writes its figure."""

import re

import robokin.demo


def test_demo_writes_the_figure(tmp_path, capsys):
    out = tmp_path / "fig.png"
    assert robokin.demo.main(["--out", str(out), "--step", "0.01"]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 20_000
    text = capsys.readouterr().out
    counts = re.findall(r"converged (\d+)/(\d+)", text)
    assert len(counts) == 2 and all(a == b for a, b in counts)
    assert str(out) in text
