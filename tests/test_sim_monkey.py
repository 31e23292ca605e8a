"""Monkey test: thousands of random key events in every mode never raise and never log a NaN."""

import zlib

import numpy as np
import pytest
from sim_helpers import read_log, run_sim

from robokin_sim.keys import KEYS

NUMERIC = {
    "rrr3": ["x", "y", "phi", "alpha_0", "alpha_1", "alpha_2", "det_a", "det_b"],
    "rpr": ["x", "y", "q_0", "q_1", "q_2", "error"],
}


def _script(rng, events):
    # esc would end the run: it is pressed last, once.
    keys = [k for k in KEYS if k != "esc"]
    # Movement keys are held longer (several steps), as a person does.
    items = []
    for k in rng.choice(keys, size=events):
        n = int(rng.integers(1, 40)) if k in ("left", "right", "up", "down", "k", "l") else 1
        items.append(f"{k}*{n}")
    return ",".join(items + ["esc"])


@pytest.mark.parametrize("robot,mode", [("rrr3", "free"), ("rrr3", "circle"), ("rrr3", "clover"),
                                        ("rpr", "line"), ("rpr", "free")])
def test_random_keys_never_raise_nor_log_nan(tmp_path, robot, mode):
    # Seeded from the names' CRC (str hash() changes with every interpreter: not reproducible).
    rng = np.random.default_rng(zlib.crc32(f"{robot}/{mode}".encode()))
    log = tmp_path / "monkey.csv"
    events = 5000
    res = run_sim("--robot", robot, "--mode", mode, "--keys", _script(rng, events), "--log", str(log),
                  render=False)
    rows = read_log(log)
    assert res.frames > events  # ran to the final esc
    values = np.array([[float(r[c]) for c in NUMERIC[robot]] for r in rows])
    assert len(rows) > 0 and np.all(np.isfinite(values))


def test_random_keys_while_drawing(tmp_path):
    """Same, drawing every frame (a NaN or bad coordinate would raise in pygame)."""
    rng = np.random.default_rng(7)
    for robot in ("rrr3", "rpr"):
        res = run_sim("--robot", robot, "--keys", _script(rng, 60), "--screenshot", str(tmp_path / f"{robot}.png"))
        assert res.frames > 60 and (tmp_path / f"{robot}.png").stat().st_size > 0
