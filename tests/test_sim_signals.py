"""Signals and full disks: a headless run stopped by SIGINT, SIGTERM or SIGHUP exits within a
second with status 128 + N and leaves nothing behind; a SIGKILL's temporary files are removed by
the next run of the same output (and only those); an output that cannot be written is one line
naming the file and exit status 1, and a file that was there keeps its content."""

import glob
import os
import resource
import signal
import subprocess
import sys
import time

import pytest

LIMIT = 60.0


def _env():
    env = {k: v for k, v in os.environ.items() if not k.startswith("SDL_") and k != "DISPLAY"}
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


def test_timeout_stops_a_headless_run_and_leaves_nothing(tmp_path):
    """The issue's check: `timeout 5 robokin-sim --headless ...` exits within 6 s with status 124."""
    started = time.monotonic()
    out = subprocess.run(["timeout", "5", sys.executable, "-m", "robokin_sim", "--headless", "--mode", "circle",
                          "--frames", "100000000", "--log", "c.csv", "--record", "c.mp4"],
                         cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=LIMIT)
    elapsed = time.monotonic() - started
    assert out.returncode == 124, out.stderr
    assert elapsed < 6.0, f"{elapsed:.2f} s"
    assert os.listdir(tmp_path) == []
    assert "Traceback" not in out.stderr


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_each_signal_stops_a_headless_run_the_same_way(tmp_path, sig):
    (tmp_path / "c.csv").write_text("an older log\n")  # kept as it was
    proc = _sim("--headless", "--frames", "100000000", "--log", "c.csv", "--record", "c.gif", cwd=tmp_path)
    try:
        _wait_for_temporaries(tmp_path, proc.pid, 1)
        time.sleep(0.3)
        sent = time.monotonic()
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=LIMIT)
        elapsed = time.monotonic() - sent
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 128 + sig, err
    assert elapsed < 3.0, f"{elapsed:.2f} s"  # within a second on an idle machine
    assert os.listdir(tmp_path) == ["c.csv"] and (tmp_path / "c.csv").read_text() == "an older log\n"
    assert err.strip().splitlines() == [f"robokin-sim: stopped by {signal.Signals(sig).name}; c.csv, c.gif not written"]


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
    assert sorted(os.listdir(tmp_path)) == sorted(["c.csv", *(p.name for p in others)])


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
