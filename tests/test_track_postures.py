"""rk.track_postures: fewest reconfigurations, then least motion (IKLink's objective).

Truth: an exhaustive search over every sequence of solutions on short paths (the dynamic
programme must find the same optimum), the greedy closed-form tracker closed.puma560_path (never
better than the plan), and the forward model (every chosen row reaches its pose).
"""

import itertools
import math

import numpy as np
import pytest

import robokin as rk

P = math.pi


def line_poses(chain, q_start, direction, length, count):
    """Tool frames along a straight line from fk(q_start), the orientation kept."""
    T0 = chain.fk(q_start)
    out = np.repeat(T0[None], count, axis=0)
    s = np.linspace(0.0, length, count)
    out[:, :3, 3] += s[:, None] * np.asarray(direction, float)[None, :]
    return out


def brute_force(sets, dt, vmax, cont, q0=None):
    """(reconfigurations, motion) of the best sequence, by enumeration."""
    best = None
    for choice in itertools.product(*[range(len(s)) for s in sets]):
        path = [s[c] for s, c in zip(sets, choice)]
        if q0 is not None:
            path = [q0] + path
        r, m = 0, 0.0
        for a, b in zip(path[:-1], path[1:]):
            d = b - a
            d = np.where(cont, np.remainder(d + P, 2 * P) - P, d)
            r += int(np.any(np.abs(d) > vmax * dt * (1 + 1e-9)))
            m += float(np.linalg.norm(d))
        if best is None or (r, m) < best:
            best = (r, m)
    return best


def test_count_reconfigurations_takes_continuous_joints_the_short_way():
    # Every UR5 joint spans 4 pi: continuous. Joint 1 turns 3.13 rad, then 0.02 rad across +-pi.
    q = np.zeros((3, 6))
    q[1, 0], q[2, 0] = P - 0.01, -P + 0.01
    assert list(rk.count_reconfigurations(q, 0.1, 1.0, chain=rk.robots.ur5())) == [1]
    assert list(rk.count_reconfigurations(q, 0.1, 1.0)) == [1, 2]  # without a chain no joint is continuous


def test_count_reconfigurations_is_the_rule_step_by_step(rng):
    """Against the rule written out with numpy: a step k - 1 -> k (q0 -> 0) is a reconfiguration
    when some joint moves more than qdot_max * dt (1 + 1e-9), the short way round on the chain's
    continuous joint (the PUMA 560's joint 6, the one whose limits span a turn). Steps are drawn
    near the limit (just under and just over) and across the +-pi seam."""
    chain = rk.robots.puma560()
    cont = np.array([False] * 5 + [True])
    assert np.array_equal(cont, np.diff(np.array(chain.limits), axis=0)[0] >= 2 * P)
    vmax, dt = rng.uniform(0.5, 2.0, 6), 0.1
    for _ in range(20):
        steps = vmax * dt * rng.choice([0.5, 1.0 - 1e-12, 1.0 + 1e-6, 1.5], (30, 6), p=[0.7, 0.2, 0.05, 0.05]) * rng.choice([-1, 1], (30, 6))
        steps += 2 * P * rng.integers(-1, 2, (30, 6)) * cont  # a whole turn on a continuous joint is no move
        q0 = rng.uniform(-P, P, 6)
        q = q0 + np.cumsum(steps, axis=0)
        for start in (q0, None):
            path = q if start is None else np.vstack([start, q])
            d = np.diff(path, axis=0)
            d = np.where(cont, np.remainder(d + P, 2 * P) - P, d)
            want = np.nonzero(np.any(np.abs(d) > vmax * dt * (1 + 1e-9), axis=1))[0] + (start is None)
            got = rk.count_reconfigurations(q, dt, vmax, q0=start, chain=chain)
            assert got.dtype == np.int64 and np.array_equal(got, want)
            assert 0 < len(got) < len(q)


@pytest.mark.parametrize("robot", ["ur5", "puma560"])
def test_dynamic_programme_matches_exhaustive_search(robot, rng):
    chain = getattr(rk.robots, robot)()
    cont = np.array([(hi - lo) >= 2 * P for lo, hi in zip(*chain.limits)])
    compared = 0
    for trial in range(16):
        q_start = rng.uniform(-1.0, 1.0, 6)
        poses = line_poses(chain, q_start, rng.normal(size=3) * 0.15, 1.0, 4)
        q0 = q_start if trial % 2 else None
        # Two speed limits: with the slower one the plan with the least motion often has more
        # reconfigurations than the best plan (the objective's order then matters).
        for vmax in (2.0, 1.0):
            res = rk.track_postures(chain, poses, dt=0.1, qdot_max=vmax, q0=q0)
            sets = [s for s in res.solutions if len(s)]
            if len(sets) < len(poses) or np.prod([len(s) for s in sets]) > 5000:
                continue
            r, m = brute_force(sets, 0.1, vmax, cont, q0)
            assert len(res.reconfigurations) == r, (trial, vmax)
            assert res.motion == pytest.approx(m, abs=1e-9), (trial, vmax)
            # The waypoints marked are where the returned joint path jumps (counted on its own).
            np.testing.assert_array_equal(res.reconfigurations,
                                          rk.count_reconfigurations(res.q, 0.1, vmax, q0=q0, chain=chain))
            for T, q in zip(poses, res.q):
                assert np.allclose(chain.fk(q), T, atol=1e-9)
            compared += 1
    assert compared >= 10


def test_never_worse_than_greedy_on_puma_lines(rng):
    chain = rk.robots.puma560()
    lo, hi = chain.limits
    compared = fewer = 0
    for _ in range(25):
        q_start = rng.uniform(lo * 0.8, hi * 0.8)
        poses = line_poses(chain, q_start, rng.normal(size=3), rng.uniform(0.2, 0.8), 60)
        for dt, vmax in ((0.05, 2.0), (0.02, 1.0)):
            plan = rk.track_postures(chain, poses, dt=dt, qdot_max=vmax, q0=q_start)
            qg, ok, _ = rk.closed.puma560_path(poses, q_start)
            assert np.array_equal(ok, plan.success)
            greedy = rk.count_reconfigurations(qg, dt, vmax, q0=q_start, chain=chain)
            assert len(plan.reconfigurations) <= len(greedy)
            compared += 1
            fewer += len(plan.reconfigurations) < len(greedy)
            for T, q, s in zip(poses, plan.q, plan.success):
                if s:
                    assert np.allclose(chain.fk(q), T, atol=1e-9)
    assert compared == 50


def test_demo_line_greedy_reconfigures_more():
    from robokin.demo_postures import demo_line

    chain, poses, q0, dt, vmax = demo_line()
    plan = rk.track_postures(chain, poses, dt=dt, qdot_max=vmax, q0=q0)
    qg, ok, _ = rk.closed.puma560_path(poses, q0)
    greedy = rk.count_reconfigurations(qg, dt, vmax, q0=q0, chain=chain)
    assert np.all(plan.success)
    assert len(plan.reconfigurations) < len(greedy)


def test_numerical_method_agrees_with_closed_on_ur5(rng):
    chain = rk.robots.ur5()
    q_start = np.array([0.4, -1.2, 1.5, -0.8, 1.1, 0.3])
    poses = line_poses(chain, q_start, (0.0, 0.1, -0.05), 1.0, 8)
    a = rk.track_postures(chain, poses, dt=0.1, qdot_max=1.5, q0=q_start)
    b = rk.track_postures(chain, poses, dt=0.1, qdot_max=1.5, q0=q_start, method="numerical", starts=64)
    assert np.all(a.success) and np.all(b.success)
    assert len(b.reconfigurations) >= len(a.reconfigurations)
    for T, q in zip(poses, b.q):
        assert np.allclose(chain.fk(q), T, atol=1e-8)
    # the numerical sets are subsets of the closed-form ones
    for sa, sb in zip(a.solutions, b.solutions):
        for q in sb:
            d = np.remainder(sa - q + P, 2 * P) - P
            assert np.min(np.max(np.abs(d), axis=1)) < 1e-6


def test_unreachable_waypoints_are_reported():
    chain = rk.robots.ur5()
    q_start = np.array([0.4, -1.2, 1.5, -0.8, 1.1, 0.3])
    poses = line_poses(chain, q_start, (0.0, 0.1, 0.0), 0.1, 5)
    poses[2, 0, 3] = 5.0
    res = rk.track_postures(chain, poses, dt=0.1)
    assert list(res.success) == [True, True, False, True, True]
    assert np.array_equal(res.q[2], res.q[1])
    # The result's arrays are the caller's (the core's plan is read-only; the result holds copies).
    assert res.q.flags.writeable and res.reconfigurations.flags.writeable
    assert res.q.dtype == np.float64 and res.reconfigurations.dtype == np.int64


def test_bad_arguments():
    chain = rk.robots.ur5()
    poses = np.repeat(chain.fk(np.zeros(6))[None], 3, axis=0)
    for kwargs, name in ((dict(dt=0.0), "dt"), (dict(dt=0.1, qdot_max=-1.0), "qdot_max"),
                         (dict(dt=0.1, method="x"), "method"), (dict(dt=0.1, q0=[0.0]), "q0"),
                         (dict(dt=0.1, starts=0, method="numerical"), "starts")):
        with pytest.raises(ValueError, match=name):
            rk.track_postures(chain, poses, **kwargs)
    with pytest.raises(ValueError, match="poses"):
        rk.track_postures(chain, np.zeros((3, 3, 3)), 0.1)
    with pytest.raises(ValueError, match="method"):
        rk.track_postures(rk.robots.planar_3r(1, 1, 1), np.zeros((1, 4, 4)), 0.1)
    with pytest.raises(TypeError, match="chain: expected a robokin.Chain, got str"):
        rk.track_postures("ur5", poses, 0.1)


def test_demo_writes_both_figures_atomically(tmp_path, capsys):
    from robokin import demo_postures

    line, aspects = tmp_path / "line.png", tmp_path / "sub" / "aspects.png"
    assert demo_postures.main(["--out", str(line), "--aspects-out", str(aspects)]) == 0
    for f in (line, aspects):
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == ["aspects.png", "line.png"]
    out = capsys.readouterr().out
    assert "greedy (nearest solution): 19 reconfiguration(s)" in out and "cuspidal = True" in out
    with pytest.raises(SystemExit):
        demo_postures.main(["--out", str(tmp_path / "x.nope")])


def test_numerical_sets_keep_one_row_per_posture(rng):
    """The numerical method's de-duplication (the core's distinct_rows) against the plain rule, one
    row at a time: keep a found row unless an earlier kept row is within 1e-6 on every joint, the
    short way round on continuous joints. Near copies are planted, some across the +-pi seam."""
    K, S, n = 40, 12, 4
    cont = np.array([True, False, True, False])
    q = rng.uniform(-P, P, (K, S, n))
    for k in range(K):
        for i in rng.choice(np.arange(1, S), 6, replace=False):
            j = rng.integers(0, i)
            q[k, i] = q[k, j] + rng.uniform(-2e-6, 2e-6, n) * rng.integers(0, 2)
            if rng.random() < 0.3:
                q[k, i, 0] += 2 * P * rng.choice([-1, 1])  # the same angle a turn away: a copy
    q[0, 1] = q[0, 0] + np.array([0, 2 * P, 0, 0])  # a turn away on a bounded joint: not a copy
    q[1, 1] = q[1, 0] + 0.8e-6  # a copy of row 0; row 2 is near row 1 only, so it is kept
    q[1, 2] = q[1, 0] + 1.6e-6
    q[1, 3:] += 1.0  # nothing else near them
    found = rng.random((K, S)) < 0.8
    found[0, :2] = True
    found[1, :3] = True
    got = rk._core.distinct_solutions(q, found, cont)
    planted = 0
    for k in range(K):
        kept = []
        for i in range(S):
            if not found[k, i]:
                continue
            d = q[k, i] - np.array(kept).reshape(-1, n)
            d = np.where(cont, np.remainder(d + P, 2 * P) - P, d)
            if kept and np.min(np.max(np.abs(d), axis=1)) <= 1e-6:
                planted += 1
                continue
            kept.append(q[k, i])
        np.testing.assert_array_equal(got[k], np.array(kept).reshape(-1, n))
    assert planted > K  # the rule dropped copies: the test sees both outcomes
    assert len(got[0]) >= 2 and np.array_equal(got[0][1], q[0, 1])
    assert np.array_equal(got[1][:2], q[1, [0, 2]])
