"""Command line, scripted keys, recordings and the entry points."""

import os
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image
from sim_helpers import read_log, run_sim

from robokin_sim.config import parse_args
from robokin_sim.loop import run
from robokin_sim.keys import parse_script


def test_key_script_parsing():
    script = parse_script("right*20, down*10,l*10,space,Escape*2")
    assert script.items == (("right", 20), ("down", 10), ("l", 10), ("space", 1), ("esc", 2))
    assert script.frames == 43
    inputs = list(parse_script("l*3,l*2").inputs())
    assert [bool(i.pressed) for i in inputs] == [True, False, False, True, False]
    assert all(i.held == {"l"} for i in inputs)
    for bad in ("jump*3", "right*x", "right*0", "right*-2"):
        with pytest.raises(ValueError, match="--keys"):
            parse_script(bad)


def test_bad_command_lines_exit_with_usage(capsys):
    for argv in (["--robot", "rpr", "--mode", "clover"], ["--frames", "0"], ["--record", "x.avi"],
                 ["--keys", "fly*2"], ["--size", "10x10"]):
        with pytest.raises(SystemExit) as exc:
            parse_args(argv)
        assert exc.value.code == 2
    assert "robokin-sim --help" in capsys.readouterr().err


def test_defaults():
    assert parse_args([]).mode == "free" and parse_args(["--robot", "rpr"]).mode == "line"
    gif = parse_args(["--record", "a.gif"])
    assert gif.record_every == 2 and gif.record_width == 480
    assert parse_args(["--record", "a.mp4"]).record_every == 1


def test_mp4_recording(tmp_path):
    out = tmp_path / "clover.mp4"
    res = run_sim("--mode", "clover", "--frames", "40", "--record", str(out), "--size", "320x240")
    assert res.record == str(out) and out.stat().st_size > 1000
    assert out.read_bytes()[4:8] == b"ftyp"
    assert [p.name for p in tmp_path.iterdir()] == ["clover.mp4"]  # the temporary file was renamed


def test_gif_recording_frames(tmp_path):
    out = tmp_path / "free.gif"
    run_sim("--frames", "30", "--keys", "right*30", "--record", str(out), "--record-every", "3", "--record-width", "200")
    with Image.open(out) as im:
        assert im.n_frames == 10 and im.size == (200, 200)
        im.seek(9)
        first_last = np.asarray(im.convert("RGB"))
    assert first_last.std() > 0


def test_headless_defaults_to_the_script_length(tmp_path):
    log = tmp_path / "a.csv"
    res = run_sim("--keys", "up*7,k*5", "--log", str(log), render=False)
    assert res.frames == 12 and len(read_log(log)) == 12


def test_esc_quits():
    res = run_sim("--keys", "right*5,esc,right*5", "--frames", "100", render=False)
    assert res.frames == 5 and res.steps == 5


@pytest.mark.parametrize("entry", [["-m", "robokin_sim"], ["-c", "from robokin_sim.__main__ import main; main()"]])
def test_entry_points(tmp_path, entry):
    log = tmp_path / "run.csv"
    env = dict(os.environ, SDL_VIDEODRIVER="dummy")
    out = subprocess.run([sys.executable, *entry, "--headless", "--robot", "rpr", "--frames", "20", "--log", str(log)],
                         capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    assert f"log: {log}" in out.stdout and len(read_log(log)) == 20


def test_window_path_runs_with_the_dummy_driver(tmp_path):
    """The windowed loop (events, flip, 60 fps pacing) on SDL's dummy driver."""
    res = run(parse_args(["--frames", "12", "--keys", "right*3,h,o*8", "--fps", "120"]))
    assert res.frames == 12 and res.steps == 12
    assert res.seconds >= 11 / 120 * 0.8  # paced, not flat out


def test_console_script_is_installed():
    script = os.path.join(os.path.dirname(sys.executable), "robokin-sim")
    out = subprocess.run([script, "--help"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and "--no-avoid" in out.stdout


def test_demo_without_a_display_records_the_clover(tmp_path, monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.setattr(sys, "platform", "linux")
    config = parse_args(["--demo", "--frames", "30", "--record", str(tmp_path / "d.gif")])
    assert config.headless and config.mode == "clover" and config.log == os.path.join("out", "robokin-sim-rrr3-clover.csv")
    monkeypatch.setenv("DISPLAY", ":0")
    assert not parse_args(["--demo"]).headless


def test_unwritable_output_is_a_clean_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    env = dict(os.environ, SDL_VIDEODRIVER="dummy")
    out = subprocess.run([sys.executable, "-m", "robokin_sim", "--headless", "--frames", "3", "--log",
                          str(blocker / "sub" / "x.csv")], capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 1 and "robokin-sim: error:" in out.stderr and "Traceback" not in out.stderr


@pytest.mark.parametrize("argv", [
    ["--record-width", "20000"], ["--record-width", "100000"], ["--record-width", "99"], ["--log", ""],
    ["--log", "  "], ["--record", ""], ["--screenshot", ""], ["--keys", "right*"], ["--keys", "right*1e9"],
    ["--frames", "1" * 30], ["--frames", "1000000001"], ["--fps", "100000"], ["--record-every", "99999999"],
    ["--record", "a.gif", "--record-every", "1"], ["--log", "."],
])
def test_out_of_range_options_are_one_line_and_exit_2(argv, capsys):
    with pytest.raises(SystemExit) as exc:
        parse_args(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and err.startswith("robokin-sim: error: "), err


def test_bounds_that_are_accepted():
    assert parse_args(["--frames", "1000000000"]).frames == 10**9
    assert parse_args(["--record", "a.mp4", "--record-width", "4096"]).record_width == 4096
    assert parse_args(["--record", "a.gif"]).record_width == 480


def _mp4_frames_and_seconds(path):
    import imageio_ffmpeg

    reader = imageio_ffmpeg.read_frames(str(path))
    meta = next(reader)
    frames = sum(1 for _ in reader)
    return frames, meta["fps"], meta["duration"]


@pytest.mark.parametrize("every", [1, 3])
def test_mp4_plays_in_simulated_time(tmp_path, every):
    """N steps of 1/60 s last N/60 s of video, pauses excluded, whatever the frames per second."""
    out = tmp_path / "run.mp4"
    # 91 steps: 20, the frame of the second space, 30 and 40; the 15 paused frames record nothing.
    run_sim("--keys", "right*20,space,up*14,space,left*30,k*40", "--record", str(out), "--record-every",
            str(every), "--size", "200x200", "--fps", "7")
    frames, fps, duration = _mp4_frames_and_seconds(out)
    steps = 20 + 1 + 30 + 40
    assert frames == -(-steps // every)  # one frame kept in every, the first one included
    assert fps == pytest.approx(60 / every)
    assert frames / fps == pytest.approx(steps / 60, abs=every / 60)
    assert duration == pytest.approx(steps / 60, abs=every / 60 + 1e-9)


def test_gif_plays_in_simulated_time(tmp_path):
    out = tmp_path / "run.gif"
    run_sim("--frames", "300", "--mode", "circle", "--record", str(out), "--record-every", "2")
    with Image.open(out) as im:
        durations = []
        for k in range(im.n_frames):
            im.seek(k)
            durations.append(im.info["duration"])
    assert len(durations) == 150 and min(durations) >= 20
    assert sum(durations) == pytest.approx(300 / 60 * 1000, abs=10)


def test_recorded_frames_are_drawn_at_their_size_without_fps_or_rec(tmp_path):
    """The recording has its own renderer: a 480 px frame with the HUD at full size, no fps row,
    no REC mark; the window's frame has both."""
    import pygame

    from robokin_sim import theme
    from robokin_sim.render_common import Hud
    from robokin_sim.render_rrr3 import Rrr3Renderer
    from robokin_sim.scene_rrr3 import Rrr3Scene

    out = tmp_path / "run.gif"
    res = run_sim("--frames", "4", "--record", str(out), "--size", "800x600")
    with Image.open(out) as im:
        assert im.size == (480, 360)
        im.seek(1)
        recorded = np.asarray(im.convert("RGB")).astype(int)
    scene = Rrr3Scene("free")
    for _ in range(4):
        scene.step(frozenset())
    surface = pygame.Surface((480, 360))
    Rrr3Renderer((480, 360)).draw(surface, scene.state(), Hud(fps=None))
    direct = pygame.surfarray.array3d(surface).swapaxes(0, 1).astype(int)
    # The same picture as drawn directly at 480 x 360 without an fps row (up to the GIF palette).
    assert np.mean(np.abs(recorded - direct).max(axis=2) <= 40) > 0.995
    with_fps = pygame.Surface((480, 360))
    Rrr3Renderer((480, 360)).draw(with_fps, scene.state(), Hud(fps=60.0, recording=True))
    window = pygame.surfarray.array3d(with_fps).swapaxes(0, 1).astype(int)
    assert np.mean(np.abs(recorded - window).max(axis=2) > 40) > 0.001  # the fps row and REC differ
    red = np.all(np.abs(window[5:35, 400:475] - np.array(theme.SINGULAR)) < 30, axis=2)
    assert red.sum() > 30  # the REC mark, in the window only
    assert res.record == str(out)


def test_a_truncated_mp4_is_told_from_a_whole_one(tmp_path):
    """ffmpeg may end with status 0 after a full disk cut its file short: the recorder checks the
    file's boxes before renaming it into place."""
    from robokin_sim.recording import mp4_complete

    out = tmp_path / "whole.mp4"
    run_sim("--frames", "10", "--record", str(out), "--size", "200x200")
    data = out.read_bytes()
    assert mp4_complete(str(out))
    for cut in (len(data) - 1, len(data) // 2, 2048, 7):
        part = tmp_path / f"cut{cut}.mp4"
        part.write_bytes(data[:cut])
        assert not mp4_complete(str(part)), cut
