"""A run killed outright (SIGKILL) keeps what it wrote: the next run writing the same log keeps the
killed run's complete rows (header intact, a trailing partial row dropped) as NAME.partial.csv,
never overwriting one already there, says so on one line of stderr, and writes its own NAME.
Recording parts (which cannot be valid cut short) are removed as before; a live run's are left."""

import csv
import glob
import os
import subprocess
import sys
import time

from robokin.files import keep_stale

LIMIT = 60.0


def _env():
    env = {k: v for k, v in os.environ.items() if not k.startswith("SDL_") and k != "DISPLAY"}
    env.update(PYTHONUNBUFFERED="1", PYGAME_HIDE_SUPPORT_PROMPT="1")
    return env


def _killed_run(directory, name, size=20000):
    """A headless run logging to ``name``, SIGKILLed once ``size`` bytes of rows are on disk;
    returns the bytes its temporary file held."""
    proc = subprocess.Popen([sys.executable, "-m", "robokin_sim", "--headless", "--frames", "100000000", "--log",
                             name], cwd=directory, env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    stem = os.path.splitext(name)[0]
    deadline = time.monotonic() + LIMIT
    try:
        while True:
            parts = glob.glob(os.path.join(directory, f".{stem}.{proc.pid}.*.part.csv"))
            if parts and os.path.getsize(parts[0]) >= size:
                break
            assert time.monotonic() < deadline and proc.poll() is None, "the run did not write its rows"
            time.sleep(0.02)
    finally:
        proc.kill()
        proc.wait()
    with open(parts[0], "rb") as f:
        return f.read()


def _run(directory, name, frames=5):
    return subprocess.run([sys.executable, "-m", "robokin_sim", "--headless", "--frames", str(frames), "--log", name],
                          cwd=directory, env=_env(), capture_output=True, text=True, timeout=LIMIT)


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def test_the_next_run_keeps_the_rows_a_killed_run_wrote(tmp_path):
    left = _killed_run(tmp_path, "c.csv")
    out = _run(tmp_path, "c.csv")
    assert out.returncode == 0, out.stderr
    assert sorted(os.listdir(tmp_path)) == ["c.csv", "c.partial.csv"]
    kept = (tmp_path / "c.partial.csv").read_bytes()
    assert kept == left[:left.rfind(b"\n") + 1]  # every complete row, byte for byte; no partial one
    rows = _rows(tmp_path / "c.partial.csv")
    assert rows[0] == _rows(tmp_path / "c.csv")[0]  # the header, whole
    assert len(rows) > 50 and all(len(r) == len(rows[0]) for r in rows)
    assert [int(r[0]) for r in rows[1:]] == list(range(1, len(rows)))
    assert len(_rows(tmp_path / "c.csv")) == 6  # the new run's own log: header and 5 rows
    said = [line for line in out.stderr.splitlines() if "partial" in line]
    assert said == ["robokin-sim: kept the rows a killed run had written for c.csv in "
                    f"{tmp_path / 'c.partial.csv'}"]


def test_a_kept_file_is_never_overwritten(tmp_path):
    (tmp_path / "c.partial.csv").write_text("an earlier one\n")
    left = _killed_run(tmp_path, "c.csv", size=9000)
    assert _run(tmp_path, "c.csv").returncode == 0
    assert (tmp_path / "c.partial.csv").read_text() == "an earlier one\n"
    assert (tmp_path / "c.partial.2.csv").read_bytes() == left[:left.rfind(b"\n") + 1]


def test_keep_stale_takes_dead_writers_complete_lines_only(tmp_path):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    (tmp_path / f".a.{dead}.x1.part.csv").write_bytes(b"h1,h2\n1,2\n3,4\n5,")   # rows and half a row
    (tmp_path / f".a.{dead}.x2.part.csv").write_bytes(b"h1,h2\n")              # a header alone: no data
    (tmp_path / f".a.{os.getpid()}.x3.part.csv").write_bytes(b"h1,h2\n1,2\n")  # a live writer's
    (tmp_path / f".b.{dead}.x4.part.csv").write_bytes(b"h1,h2\n1,2\n")         # another target's
    kept = keep_stale(tmp_path / "a.csv")
    assert kept == [str(tmp_path / "a.partial.csv")]
    assert (tmp_path / "a.partial.csv").read_bytes() == b"h1,h2\n1,2\n3,4\n"
    assert sorted(os.listdir(tmp_path)) == sorted(["a.partial.csv", f".a.{os.getpid()}.x3.part.csv",
                                                   f".b.{dead}.x4.part.csv"])
