"""Files are written whole or not at all (robokin.files.AtomicPath): an interrupted write, or an
interrupted simulator run, leaves neither a truncated file under the requested name nor a
temporary file behind; an interrupted overwrite keeps the old file."""

import csv
import os

import pytest
import sim_helpers  # noqa: F401  (SDL dummy drivers before pygame is imported)
from sim_helpers import run_sim

import robokin.demo
from robokin.files import AtomicPath
from robokin_sim import __main__ as sim_main
from robokin_sim.csvlog import CsvLog
from robokin_sim.recording import Recorder
from robokin_sim.scene_rrr3 import Rrr3Scene


def files(directory):
    return sorted(os.path.relpath(os.path.join(d, f), directory) for d, _, fs in os.walk(directory) for f in fs)


def test_atomic_path_commits_or_leaves_nothing(tmp_path):
    target = tmp_path / "sub" / "a.txt"
    with AtomicPath(target) as tmp:
        assert tmp.endswith(".txt") and os.path.dirname(tmp) == str(target.parent)
        open(tmp, "w").write("whole")
    assert files(tmp_path) == ["sub/a.txt"] and target.read_text() == "whole"
    with pytest.raises(KeyboardInterrupt):
        with AtomicPath(target) as tmp:
            open(tmp, "w").write("half")
            raise KeyboardInterrupt
    assert files(tmp_path) == ["sub/a.txt"] and target.read_text() == "whole"  # the old file is kept


def _half_then_interrupt(*args, **kwargs):
    raise KeyboardInterrupt


def test_gif_writer_interrupted(tmp_path, monkeypatch):
    """Frames stream to the temporary file: a frame or the end interrupted leaves nothing."""
    from PIL import GifImagePlugin

    from robokin.gif import GifWriter

    frame = __import__("numpy").zeros((20, 30, 3), dtype="uint8")
    rec = Recorder(str(tmp_path / "a.gif"), every=1)
    rec.add(frame)
    with monkeypatch.context() as patch:
        patch.setattr(GifImagePlugin, "getdata", _half_then_interrupt)
        with pytest.raises(KeyboardInterrupt):
            rec.add(frame + 1)
    rec.discard()  # what the run does on an exception
    assert files(tmp_path) == []
    rec = Recorder(str(tmp_path / "a.gif"), every=1)
    rec.add(frame)
    monkeypatch.setattr(GifWriter, "close", _half_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        rec.close()
    assert files(tmp_path) == []


def test_csv_log_interrupted(tmp_path, monkeypatch):
    log = CsvLog(str(tmp_path / "a.csv"), ("a", "b"))
    log.write((1, 2))

    class Writer:
        def writerow(self, row):
            log._file.write("1,")  # half a row
            raise KeyboardInterrupt

    monkeypatch.setattr(log, "_writer", Writer())
    with pytest.raises(KeyboardInterrupt):
        log.write((3, 4))
    log.discard()
    assert files(tmp_path) == [] and log.close() is None


def test_demo_figure_interrupted(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    monkeypatch.setattr(Figure, "savefig", lambda self, path, **kwargs: _half_then_interrupt(path))
    with pytest.raises(KeyboardInterrupt):
        robokin.demo.main(["--out", str(tmp_path / "fig.png"), "--step", "0.2"])
    assert files(tmp_path) == []


@pytest.fixture
def interrupt_after(monkeypatch):
    """Makes the 3-RRR scene raise KeyboardInterrupt (Ctrl-C) on step n."""

    def arm(n):
        step = Rrr3Scene.step

        def interrupted(self, held):
            if self.steps >= n:
                raise KeyboardInterrupt
            step(self, held)

        monkeypatch.setattr(Rrr3Scene, "step", interrupted)

    return arm


@pytest.mark.parametrize("ext", [".gif", ".mp4"])
def test_interrupted_sim_run_leaves_no_truncated_files(tmp_path, interrupt_after, ext):
    interrupt_after(12)
    outputs = ["--record", str(tmp_path / f"run{ext}"), "--log", str(tmp_path / "run.csv"),
               "--screenshot", str(tmp_path / "run.png")]
    with pytest.raises(KeyboardInterrupt):
        run_sim("--mode", "clover", "--frames", "40", "--size", "200x200", *outputs)
    assert files(tmp_path) == []
    # the command line: exit status 130, and still nothing written
    assert sim_main.main(["--headless", "--frames", "40", "--size", "200x200", *outputs]) == 130
    assert files(tmp_path) == []


def test_uninterrupted_sim_run_writes_every_file(tmp_path, interrupt_after):
    interrupt_after(10**9)
    res = run_sim("--frames", "12", "--size", "200x200", "--record", str(tmp_path / "run.gif"),
                  "--log", str(tmp_path / "run.csv"), "--screenshot", str(tmp_path / "run.png"))
    assert files(tmp_path) == ["run.csv", "run.gif", "run.png"] and res.frames == 12
    with open(tmp_path / "run.csv", newline="") as f:
        assert len(list(csv.DictReader(f))) == 12
