"""Shared helpers of the simulator tests: headless in-process runs and reading the CSV logs."""

import csv
import os

os.environ["SDL_VIDEODRIVER"] = "dummy"  # before anything imports pygame's display
os.environ["SDL_AUDIODRIVER"] = "dummy"

from robokin_sim.config import parse_args  # noqa: E402
from robokin_sim.loop import run  # noqa: E402


def run_sim(*args, render=True):
    """Runs ``robokin-sim --headless ARGS`` in this process and returns its RunResult."""
    return run(parse_args(["--headless", *args]), render=render)


def read_log(path):
    """The CSV log as a list of dicts (numbers still strings)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
