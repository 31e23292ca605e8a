"""Signals and full disks: a headless run stopped by SIGINT, SIGTERM or SIGHUP exits within a
second with status 128 + N and finishes its files as esc does (the log with every row so far, the
recording closed and readable), named on one line; a signal before the outputs are open writes
nothing; a SIGKILL's temporary files are removed by the next run of the same output (and only
those; a log's rows are kept aside, test_sim_killed_log.py); an output that cannot be written is one line naming the file and exit status 1, and a file
that was there keeps its content."""

import csv
import glob
import os
import resource
import signal
import subprocess
import sys
import time

import imageio.v3 as iio
import numpy as np
import pytest
import robokin as rk

from robokin_sim.signals import Stopped, deferred, requested, stop_on_signals

LIMIT = 60.0


def _env():
    env = {k: v for k, v in os.environ.items() if not k.startswith("SDL_") and k != "DISPLAY"}
    env["PYTHONUNBUFFERED"] = "1"
    env["PYGAME_HIDE_SUPPORT_PROMPT"] = "1"
    return env


def _sim(*args, **kwargs):
    return subprocess.Popen([sys.executable, "-m", "robokin_sim", *args], env=_env(), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **kwargs)


def _wait_for_temporaries(directory, pid, count):
    deadline = time.monotonic() + LIMIT
    while len(glob.glob(os.path.join(directory, f".*.{pid}.*.part.*"))) < count:
        assert time.monotonic() < deadline, "the run did not start writing"
        time.sleep(0.05)


def check_serial_log(path, chain):
    """The log of a serial arm: every step from 1 on, once, complete rows, and each row's tool
    position the forward model's at its joints. Returns the number of rows."""
    with open(path, newline="") as f:
        text = f.read()
    assert text.endswith("\n")
    rows = list(csv.DictReader(text.splitlines()))
    assert rows and [int(r["step"]) for r in rows] == list(range(1, len(rows) + 1))
    q = np.array([[float(r[f"q_{i}"]) for i in range(chain.dof)] for r in rows])
    xyz = np.array([[float(r[c]) for c in "xyz"] for r in rows])
    assert np.allclose(chain.fk(q)[:, :3, 3], xyz, rtol=0, atol=1e-12)
    return len(rows)


def test_timeout_stops_a_headless_run_and_keeps_its_files(tmp_path):
    """`timeout 5 robokin-sim --headless ...` exits within a few seconds with status 124, its log
    and its MP4 whole."""
    started = time.monotonic()
    out = subprocess.run(["timeout", "5", sys.executable, "-m", "robokin_sim", "--headless", "--robot", "ur5",
                          "--mode", "circle", "--frames", "100000000", "--log", "c.csv", "--record", "c.mp4"],
                         cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=LIMIT)
    elapsed = time.monotonic() - started
    assert out.returncode == 124, out.stderr
    assert elapsed < 8.0, f"{elapsed:.2f} s"
    assert sorted(os.listdir(tmp_path)) == ["c.csv", "c.mp4"]
    steps = check_serial_log(tmp_path / "c.csv", rk.robots.ur5())
    assert len(iio.imread(tmp_path / "c.mp4")) == steps  # one frame per step
    assert "Traceback" not in out.stderr


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_each_signal_stops_a_headless_run_and_finishes_its_files(tmp_path, sig):
    (tmp_path / "c.csv").write_text("an older log\n")  # replaced by the run's
    proc = _sim("--headless", "--robot", "puma560", "--mode", "circle", "--frames", "100000000", "--log", "c.csv",
                "--record", "c.gif", "--screenshot", "c.png", cwd=tmp_path)
    try:
        _wait_for_temporaries(tmp_path, proc.pid, 2)
        time.sleep(0.5)
        sent = time.monotonic()
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=LIMIT)
        elapsed = time.monotonic() - sent
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 128 + sig, err
    assert elapsed < 3.0, f"{elapsed:.2f} s"  # within a second on an idle machine
    assert sorted(os.listdir(tmp_path)) == ["c.csv", "c.gif", "c.png"]  # no temporary left
    steps = check_serial_log(tmp_path / "c.csv", rk.robots.puma560())
    frames = iio.imread(tmp_path / "c.gif", index=None, mode="RGB")
    assert len(frames) == (steps + 1) // 2 and frames.shape[1:3] == (480, 480)  # one frame in 2 steps
    assert iio.imread(tmp_path / "c.png").shape == (800, 800, 3)
    assert err.strip().splitlines() == [f"robokin-sim: stopped by {signal.Signals(sig).name} after {steps} steps; "
                                        "log: c.csv, recording: c.gif, screenshot: c.png"]
    assert out == ""


def test_ctrl_c_in_a_terminal_keeps_the_mp4_whole(tmp_path):
    """Ctrl-C signals the terminal's whole process group, ffmpeg included: the encoder must not
    die with the run's video unfinished."""
    proc = _sim("--headless", "--robot", "ur5", "--mode", "line", "--frames", "100000000", "--log", "c.csv",
                "--record", "c.mp4", cwd=tmp_path, start_new_session=True)
    try:
        _wait_for_temporaries(tmp_path, proc.pid, 2)
        time.sleep(0.5)
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=LIMIT)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130, err
    steps = check_serial_log(tmp_path / "c.csv", rk.robots.ur5())
    assert len(iio.imread(tmp_path / "c.mp4")) == steps
    assert sorted(os.listdir(tmp_path)) == ["c.csv", "c.mp4"]


def test_a_signal_is_raised_at_once_outside_the_deferred_part_and_noted_inside():
    with stop_on_signals():
        with pytest.raises(Stopped) as info:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(1)  # the handler runs between two bytecodes
        assert info.value.status == 128 + signal.SIGTERM
    with stop_on_signals():
        assert requested() is None
        with deferred():
            os.kill(os.getpid(), signal.SIGHUP)
            time.sleep(0.05)
            assert requested() == signal.SIGHUP
            os.kill(os.getpid(), signal.SIGINT)  # later signals are ignored while the run finishes
            time.sleep(0.05)
            assert requested() == signal.SIGHUP
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler and requested() is None


def test_a_signal_before_the_outputs_are_open_writes_nothing(tmp_path):
    """Stopped while the scene is made (the 3-RRR's paths and maps take a while): nothing had been
    written, and nothing is."""
    code = ("import os, signal, sys; import robokin_sim.scenes as s; from robokin_sim.__main__ import main; "
            "e = s.SCENES['rrr3']; "
            "stop = lambda config: os.kill(os.getpid(), signal.SIGTERM); "
            "s.SCENES['rrr3'] = e.__class__(**{**e.__dict__, 'scene': stop}); "
            "sys.exit(main(sys.argv[1:]))")
    out = subprocess.run([sys.executable, "-c", code, "--headless", "--frames", "5", "--log", "c.csv", "--record",
                          "c.gif"], cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=LIMIT)
    assert out.returncode == 128 + signal.SIGTERM, out.stderr
    assert os.listdir(tmp_path) == []
    assert out.stderr.strip().splitlines() == ["robokin-sim: stopped by SIGTERM; c.csv, c.gif not written"]


def test_a_later_run_removes_what_sigkill_left_and_only_that(tmp_path):
    proc = _sim("--headless", "--frames", "100000000", "--log", "c.csv", cwd=tmp_path)
    _wait_for_temporaries(tmp_path, proc.pid, 1)
    proc.kill()
    proc.communicate()
    left = glob.glob(str(tmp_path / f".c.{proc.pid}.*.part.csv"))
    assert len(left) == 1  # SIGKILL cannot be caught
    # Temporary files that are not this run's to remove: another target's, a live process's.
    others = [tmp_path / f".d.{proc.pid}.abc_12.part.csv", tmp_path / f".c.{os.getpid()}.abc_12.part.csv",
              tmp_path / f".c.{proc.pid}.abc_12.part.gif", tmp_path / "c.notes"]
    for path in others:
        path.write_text("x")
    out = subprocess.run([sys.executable, "-m", "robokin_sim", "--headless", "--frames", "5", "--log", "c.csv"],
                         cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=LIMIT)
    assert out.returncode == 0, out.stderr
    left = set(os.listdir(tmp_path)) - {"c.partial.csv"}  # the killed run's rows, if any had reached the disk
    assert sorted(left) == sorted(["c.csv", *(p.name for p in others)])


def _limit_file_size():
    # A file system that is full after 2 kB: writes beyond it fail (EFBIG) instead of killing the
    # process (SIGXFSZ ignored, for ffmpeg too).
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (2048, 2048))


@pytest.mark.parametrize("option,name", [("--log", "big.csv"), ("--record", "big.mp4"), ("--record", "big.gif"),
                                         ("--screenshot", "big.png")])
def test_a_full_disk_is_one_line_naming_the_file(tmp_path, option, name):
    (tmp_path / name).write_bytes(b"the previous file")
    out = subprocess.run([sys.executable, "-m", "robokin_sim", "--headless", "--mode", "clover", "--frames", "60",
                          option, name], cwd=tmp_path, env=_env(), capture_output=True,
                         text=True, timeout=LIMIT * 2, preexec_fn=_limit_file_size)
    assert out.returncode == 1, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"robokin-sim: error: cannot write {name}: "), out.stderr
    assert os.listdir(tmp_path) == [name] and (tmp_path / name).read_bytes() == b"the previous file"
