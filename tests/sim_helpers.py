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



def urdf_from_dh(name, rows, lower, upper, modified=False, flange=0.0):
    """A URDF of a revolute DH chain, written out here (not by robokin).

    ``rows`` are (a, alpha, d, theta): standard DH (A_i = Rz(theta + q) Tz(d) Tx(a) Rx(alpha)), or
    modified (Craig: A_i = Rx(alpha) Tx(a) Rz(q) Tz(d), theta = 0 only) followed by a fixed
    Tz(``flange``). A joint turns about z of its origin: standard DH puts row i's fixed part after
    joint i (in joint i + 1's origin: xyz (a cos theta, a sin theta, d), rpy (alpha, 0, theta), URDF's
    rpy being Rz(yaw) Ry(pitch) Rx(roll)); modified DH before it (xyz (a, -d sin alpha, d cos alpha),
    rpy (alpha, 0, 0))."""
    import math

    def origin(xyz, rpy):
        return f'<origin xyz="{" ".join(repr(float(v)) for v in xyz)}" rpy="{" ".join(repr(float(v)) for v in rpy)}"/>'

    fixed = []  # the fixed transform before each joint, then the one before the tool
    if modified:
        assert all(theta == 0 for *_, theta in rows) and flange is not None
        fixed = [((a, -d * math.sin(alpha), d * math.cos(alpha)), (alpha, 0, 0)) for a, alpha, d, _ in rows]
        fixed.append(((0, 0, flange), (0, 0, 0)))
    else:
        assert flange == 0.0
        fixed = [((0, 0, 0), (0, 0, 0))]
        fixed += [((a * math.cos(theta), a * math.sin(theta), d), (alpha, 0, theta)) for a, alpha, d, theta in rows]
    links = "".join(f'<link name="l{i}"/>' for i in range(len(rows) + 1)) + '<link name="tool"/>'
    joints = [f'<joint name="j{i + 1}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
              f'{origin(*fixed[i])}<axis xyz="0 0 1"/>'
              f'<limit lower="{float(lower[i])!r}" upper="{float(upper[i])!r}" effort="1" velocity="1"/></joint>'
              for i in range(len(rows))]
    joints.append(f'<joint name="flange" type="fixed"><parent link="l{len(rows)}"/><child link="tool"/>'
                  f'{origin(*fixed[-1])}</joint>')
    return f'<?xml version="1.0"?><robot name="{name}">{links}{"".join(joints)}</robot>'
