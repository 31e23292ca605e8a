"""_core.track_postures: track_postures' dynamic programme over the layers of inverse solutions.

Truth: a small reference programme written here with numpy, on random layers. Its rules are the
core's, stated once: a step from row a of waypoint k to row b of waypoint l (the next waypoint with
solutions; q0 is waypoint -1) is a reconfiguration when some joint i moves more than
qdot_max[i] * dt * (l - k) * (1 + 1e-9), continuous joints the short way round
(remainder(d + pi, 2 pi) - pi); its motion is the square root of the squared changes summed over the
joints in order. The plan minimises (reconfigurations, motion) lexicographically; ties go to the
lowest row, for each row's predecessor and for the last waypoint's row. Layers of small whole
numbers make exact ties common, so the tie rule is tested, not only the optimum.
"""

import math

import numpy as np
import pytest

from robokin import _core


def plan(*args):
    """The core's plan as (pick, reconfigured, motion)."""
    p = _core.track_postures(*args)
    return p.pick, p.reconfigured, p.motion


def reference(sets, vmax, dt, cont, q0=None):
    """(pick, reconfigured waypoints, motion) by the rules above, with numpy."""
    n = len(vmax)
    reached = [k for k, s in enumerate(sets) if len(s)]
    pick = np.full(len(sets), -1)
    if not reached:
        return pick, [], 0.0

    def step(a, b, steps):
        d = b[None, :, :] - a[:, None, :]
        d = np.where(cont, np.remainder(d + math.pi, 2 * math.pi) - math.pi, d)
        jump = np.any(np.abs(d) > vmax * dt * steps * (1 + 1e-9), axis=2).astype(int)
        sq = d * d
        total = sq[..., 0]
        for i in range(1, n):
            total = total + sq[..., i]
        return jump, np.sqrt(total)

    first = reached[0]
    if q0 is None:
        costs = [(0, 0.0)] * len(sets[first])
    else:
        j, m = step(np.asarray(q0, float)[None, :], sets[first], first + 1)
        costs = [(int(j[0, b]), float(m[0, b])) for b in range(len(sets[first]))]
    back = {}
    for prev, k in zip(reached[:-1], reached[1:]):
        j, m = step(sets[prev], sets[k], k - prev)
        new, back[k] = [], []
        for b in range(len(sets[k])):
            r, mm, a = min((costs[a][0] + int(j[a, b]), costs[a][1] + float(m[a, b]), a) for a in range(len(sets[prev])))
            new.append((r, mm))
            back[k].append(a)
        costs = new
    r, m, row = min((c[0], c[1], b) for b, c in enumerate(costs))
    for k in reversed(reached):
        pick[k] = row
        if k != first:
            row = back[k][row]
    # The waypoints the chosen rows enter by a jump (from q0 or the previous waypoint reached).
    previous = None if q0 is None else (-1, np.asarray(q0, float))
    reconfigured = []
    for k in reached:
        row_q = sets[k][pick[k]]
        if previous is not None and step(previous[1][None, :], row_q[None, :], k - previous[0])[0][0, 0]:
            reconfigured.append(k)
        previous = (k, row_q)
    assert len(reconfigured) == r
    return pick, reconfigured, m


def random_layers(rng, whole_numbers):
    n = int(rng.integers(1, 4)) if whole_numbers else 6
    K = int(rng.integers(1, 9))
    sets = []
    for _ in range(K):
        m = int(rng.integers(0, 5))
        if whole_numbers:
            sets.append(rng.integers(-2, 3, (m, n)).astype(float))
        else:
            sets.append(rng.uniform(-4.0, 4.0, (m, n)))
    vmax = rng.choice([0.5, 1.0, 2.0], n) if whole_numbers else rng.uniform(0.5, 20.0, n)
    cont = rng.random(n) < 0.5
    q0 = None if rng.random() < 0.5 else (rng.integers(-2, 3, n).astype(float) if whole_numbers else rng.uniform(-4, 4, n))
    return sets, vmax, 1.0 if whole_numbers else float(rng.uniform(0.05, 0.5)), cont, q0


@pytest.mark.parametrize("whole_numbers", [True, False])
def test_the_core_agrees_with_the_reference_programme(whole_numbers, rng):
    ties = jumps = 0
    for trial in range(300):
        sets, vmax, dt, cont, q0 = random_layers(rng, whole_numbers)
        pick, r, m = plan(sets, vmax, dt, cont, q0)
        ref_pick, ref_r, ref_m = reference(sets, vmax, dt, cont, q0)
        np.testing.assert_array_equal(pick, ref_pick, err_msg=str(trial))
        assert (list(r), m) == (ref_r, ref_m), trial
        jumps += len(r)
        ties += whole_numbers and sum(len(np.unique(s, axis=0)) < len(s) for s in sets)
    assert not whole_numbers or ties > 50  # duplicate rows: exact ties in motion and reconfigurations
    assert jumps > 50  # plans with reconfigurations, their waypoints compared


def reference_joint_path(sets, pick, q0, cont, lower, upper):
    """The plan's joint path by its rules (postures.hpp), with numpy: the picked rows, continuous
    joints shifted by whole turns towards the joints before them within the limits, gaps filled."""
    K, n = len(sets), len(cont)
    q = np.zeros((K, n))
    last = None if q0 is None else np.asarray(q0, float)
    for k in range(K):
        if pick[k] >= 0:
            v = sets[k][pick[k]].copy()
            if last is not None:
                shifted = v + 2 * math.pi * np.round((last - v) / (2 * math.pi))
                v = np.where(cont & (shifted >= lower) & (shifted <= upper), shifted, v)
            q[k] = last = v
        elif last is not None:
            q[k] = last
    reached = np.flatnonzero(pick >= 0)
    first = reached[0] if len(reached) else K
    q[:first] = (q[first] if first < K else 0.0) if q0 is None else q0
    return q


@pytest.mark.parametrize("limited", [False, True])
def test_the_joint_path_follows_its_rules(limited, rng):
    """Rows shifted by whole turns (far-off q0 and rows, so that turns are taken), some kept by the
    limits, gaps before, between and after the solutions, no solution at all: as the reference."""
    shifted = kept = 0
    for trial in range(300):
        sets, vmax, dt, cont, q0 = random_layers(rng, False)
        n = len(cont)
        sets = [s + 2 * math.pi * rng.integers(-3, 4, s.shape) for s in sets]
        lower, upper = (-rng.uniform(4, 25, n), rng.uniform(4, 25, n)) if limited else (np.full(n, -np.inf), np.full(n, np.inf))
        p = _core.track_postures(sets, vmax, dt, cont, q0, (lower, upper) if limited else None)
        expected = reference_joint_path(sets, p.pick, q0, cont, lower, upper)
        np.testing.assert_array_equal(p.q, expected, err_msg=str(trial))
        picked = np.array([sets[k][r] for k, r in enumerate(p.pick) if r >= 0]).reshape(-1, n)
        moved = np.array([p.q[k] for k, r in enumerate(p.pick) if r >= 0]).reshape(-1, n) != picked
        shifted += moved.sum()
        # the limits refused some shift: the path differs from the one without limits
        free = reference_joint_path(sets, p.pick, q0, cont, np.full(n, -np.inf), np.full(n, np.inf))
        kept += limited and not np.array_equal(free, expected)
    assert shifted > 100 and (not limited or kept > 20)


def test_ties_go_to_the_lowest_row():
    # Two identical rows everywhere: every choice ties; the lowest rows are taken.
    same = np.array([[0.0, 1.0], [0.0, 1.0]])
    pick, r, m = plan([same, same, same], [1.0, 1.0], 0.1, [False, False])
    assert list(pick) == [0, 0, 0] and (list(r), m) == ([], 0.0)
    # Equal motion both ways (1 to the left, 1 to the right): the lower row.
    pick, _, m = plan([np.array([[0.0]]), np.array([[1.0], [-1.0]])], [5.0], 1.0, [False])
    assert list(pick) == [0, 0] and m == 1.0
    # Fewer reconfigurations beat less motion.
    sets = [np.array([[0.0]]), np.array([[0.3], [0.2]]), np.array([[0.6], [10.0]])]
    pick, r, _ = plan(sets, [0.35], 1.0, [False])
    assert list(pick) == [0, 0, 0] and len(r) == 0


def test_gaps_q0_and_continuous_joints():
    # An empty waypoint: the step over the gap has two intervals' allowance.
    sets = [np.array([[0.0]]), np.zeros((0, 1)), np.array([[1.5], [-0.1]])]
    pick, r, _ = plan(sets, [1.0], 1.0, [False])
    assert list(pick) == [0, -1, 1] and len(r) == 0
    # q0 is waypoint -1: the first step counts.
    pick, r, _ = plan([np.array([[3.0], [0.5]])], [1.0], 1.0, [False], np.array([0.0]))
    assert list(pick) == [1] and len(r) == 0
    # A jump over a gap is marked at the waypoint it enters.
    pick, r, _ = plan([np.array([[0.0]]), np.zeros((0, 1)), np.array([[2.5]])], [1.0], 1.0, [False])
    assert list(pick) == [0, -1, 0] and list(r) == [2]
    # A continuous joint goes the short way round: 3 to -3 is a step of 2 pi - 6.
    pick, r, m = plan([np.array([[3.0]]), np.array([[-3.0]])], [0.5], 1.0, [True])
    assert len(r) == 0 and m == pytest.approx(2 * math.pi - 6)
    pick, r, _ = plan([np.array([[3.0]]), np.array([[-3.0]])], [0.5], 1.0, [False])
    assert list(r) == [1]
    # No solution anywhere, and no waypoint at all.
    pick, r, m = plan([np.zeros((0, 2))] * 3, [1.0, 1.0], 0.1, [False, False])
    assert list(pick) == [-1, -1, -1] and (len(r), m) == (0, 0.0)
    assert len(plan([], [1.0], 0.1, [False])[0]) == 0


@pytest.mark.parametrize("args, error, name", [
    (dict(sets=5), TypeError, "sets"),
    (dict(sets="abc"), TypeError, "sets"),
    (dict(sets=[np.zeros((1, 2)), np.zeros((1, 3))]), ValueError, r"sets\[1\]"),
    (dict(sets=[np.full((1, 2), np.nan)]), ValueError, r"sets\[0\]"),
    (dict(sets=[np.zeros(2)]), ValueError, r"sets\[0\]"),
    (dict(sets=[["a", "b"]]), TypeError, r"sets\[0\]"),
    (dict(qdot_max=[1.0, -1.0]), ValueError, "qdot_max"),
    (dict(qdot_max=[1.0, np.inf]), ValueError, "qdot_max"),
    (dict(qdot_max=[]), ValueError, "qdot_max"),
    (dict(dt=0.0), ValueError, "dt"),
    (dict(dt=np.nan), ValueError, "dt"),
    (dict(continuous=[True]), ValueError, "continuous"),
    (dict(q0=[0.0]), ValueError, "q0"),
    (dict(q0=[0.0, np.nan]), ValueError, "q0"),
    (dict(limits=([0.0] * 3, [1.0] * 3)), ValueError, "limits"),
    (dict(limits=([np.nan, 0.0], [1.0, 1.0])), ValueError, "limits"),
    (dict(limits=([0.0, 0.0],)), ValueError, "limits"),
    (dict(limits=5), TypeError, "limits"),
])
def test_bad_arguments_name_themselves(args, error, name):
    call = dict(sets=[np.zeros((1, 2))], qdot_max=[1.0, 1.0], dt=0.1, continuous=[False, False], q0=None)
    call.update(args)
    with pytest.raises(error, match=name):
        _core.track_postures(**call)
