"""Soak: resident memory of long headless simulator runs, sampled through the run.

Two runs of the 3-RRR clover, each a child process (``python -m robokin_sim --headless``): one with
the CSV log and an MP4 recording, one with a GIF recording. The child's resident memory (VmRSS in
/proc/PID/status) is sampled every second; the slope of a least-squares line through the samples
after the first 20 % of the run (start-up and the first frames excluded) is printed in MB per
minute. A run whose outputs stream to disk has a slope near 0; the ratio line compares the GIF
run's slope with the MP4 run's (goal: no more than the MP4's plus 1 MB/min).

Defaults finish in about two minutes; ``--full`` runs the long sizes (10^6 steps with log and MP4,
the MP4 keeping one frame in 10 so that the run takes tens of minutes rather than hours; 10^5 steps
with GIF). ``--python`` runs another installation's simulator (e.g. a checkout before a change).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np


def _rss_mb(pid: int):
    """The process's resident memory in MB (None once it is gone)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        return None
    return None


def soak(python: str, steps: int, outputs: list, every: float = 1.0) -> dict:
    """Runs ``steps`` headless clover steps writing ``outputs`` (simulator options) and samples
    the child's resident memory every ``every`` seconds. Returns the samples, seconds and slope."""
    with tempfile.TemporaryDirectory() as directory:
        env = {k: v for k, v in os.environ.items() if not k.startswith("SDL_")}
        env["PYGAME_HIDE_SUPPORT_PROMPT"] = "1"
        command = [python, "-m", "robokin_sim", "--headless", "--mode", "clover", "--frames", str(steps), *outputs]
        started = time.monotonic()
        proc = subprocess.Popen(command, cwd=directory, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        samples = []
        while proc.poll() is None:
            rss = _rss_mb(proc.pid)
            if rss:  # 0 or None: the process is ending
                samples.append((time.monotonic() - started, rss))
            time.sleep(every)
        err = proc.stderr.read().decode(errors="replace")
        proc.stderr.close()
        if proc.returncode != 0:
            raise RuntimeError(f"{' '.join(command)} ended with {proc.returncode}: {err.strip()}")
        sizes = {name: os.path.getsize(os.path.join(directory, name)) for name in os.listdir(directory)}
    return {"seconds": time.monotonic() - started, "samples": samples, "slope": _slope(samples), "sizes": sizes}


def _slope(samples) -> float:
    """MB per minute of a least-squares line through the samples after the first 20 % of the run."""
    if len(samples) < 3:
        return float("nan")
    t = np.array([s[0] for s in samples])
    m = np.array([s[1] for s in samples])
    keep = t >= t[-1] * 0.2
    if keep.sum() < 2:
        keep[:] = True
    return float(np.polyfit(t[keep], m[keep], 1)[0] * 60.0)


def _report(what: str, steps: int, result: dict) -> None:
    rss = [s[1] for s in result["samples"]]
    files = ", ".join(f"{name} {size / 1e6:.1f} MB" for name, size in sorted(result["sizes"].items()))
    print(f"  {what:<14}{steps:>10,} steps in {result['seconds']:6.1f} s  RSS {min(rss):6.1f} .. {max(rss):6.1f} MB "
          f"(last {rss[-1]:.1f})  slope {result['slope']:+7.2f} MB/min  [{files}]")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="10^6 steps with log and MP4, 10^5 with GIF")
    parser.add_argument("--mp4-steps", type=int, default=None, help="steps of the log + MP4 run")
    parser.add_argument("--gif-steps", type=int, default=None, help="steps of the GIF run")
    parser.add_argument("--mp4-every", type=int, default=None, help="the MP4 keeps one frame in this many")
    parser.add_argument("--python", default=sys.executable, help="the interpreter whose robokin_sim runs")
    args, _ = parser.parse_known_args(sys.argv[1:] if argv is None and __name__ == "__main__" else (argv or []))
    mp4_steps = args.mp4_steps or (1_000_000 if args.full else 3_000)
    gif_steps = args.gif_steps or (100_000 if args.full else 12_000)
    mp4_every = args.mp4_every or (10 if args.full else 1)
    print(f"robokin-sim soak: resident memory of headless clover runs, sampled every second ({args.python})")
    mp4 = soak(args.python, mp4_steps, ["--log", "soak.csv", "--record", "soak.mp4", "--record-every", str(mp4_every)])
    _report(f"log + MP4/{mp4_every}", mp4_steps, mp4)
    gif = soak(args.python, gif_steps, ["--record", "soak.gif"])
    _report("GIF", gif_steps, gif)
    gap = gif["slope"] - mp4["slope"]
    verdict = "met" if gap <= 1.0 else "MISSED"
    print(f"  GIF slope - MP4 slope: {gap:+.2f} MB/min  goal <= +1.00 MB/min (memory flat as MP4's): {verdict}")


if __name__ == "__main__":
    main()
