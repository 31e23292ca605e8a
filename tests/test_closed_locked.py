"""rk.closed.family / solve / ClosedSolver with one joint of a 7-joint arm held (locked=).

Truth: the arms' published geometry (which axes meet or line up: the iiwa's spherical shoulder and
wrist, the Panda's 88 mm flange offset, the Gen3's 11.8 and 12.8 mm offsets), the configuration a
pose was made from, the chain's own forward model, and a damped Newton iteration written here
(on chain.fk and chain.jacobian, the held joint's column dropped) from random starts."""

import math
import pickle

import numpy as np
import pytest

import robokin as rk
from closed_helpers import angle_distance, newton_held, newton_steps, random_q

P = math.pi
ARMS = {"iiwa14": rk.robots.iiwa14(), "panda": rk.robots.panda(), "gen3": rk.robots.gen3()}
# The locks (0-based joint indices) that leave a 6R with a closed form, at a generic value.
SOLVABLE = {"iiwa14": [0, 1, 2, 4, 5, 6], "panda": [3, 5, 6], "gen3": [0, 1, 2, 3]}
CASES = [(name, j) for name, locks in SOLVABLE.items() for j in locks]


@pytest.mark.parametrize("name", ARMS)
def test_which_locks_leave_a_closed_form(name):
    chain = ARMS[name]
    assert not rk.closed.family(chain).solvable
    solvable = [j for j in range(7) if rk.closed.family(chain, locked={j: 0.3}).solvable]
    assert solvable == SOLVABLE[name]


@pytest.mark.parametrize("name,locks", [("iiwa14", [0, 2, 4, 6]), ("panda", [6]), ("gen3", [0, 1, 2, 3])])
def test_locks_that_hold_at_any_value(name, locks):
    for j in locks:
        for v in (0.0, 1e-9, 0.3, P / 2, -2.5):
            assert rk.closed.family(ARMS[name], locked={j: v}).solvable, (j, v)


def test_locks_that_fail_where_axes_line_up():
    iiwa, panda = ARMS["iiwa14"], ARMS["panda"]
    for j, v in [(1, 0.0), (1, P), (5, 0.0), (5, -P)]:
        assert not rk.closed.family(iiwa, locked={j: v}).solvable
    assert not rk.closed.family(panda, locked={5: 0.0}).solvable and rk.closed.family(panda, locked={5: 3.0}).solvable
    # The Panda's elbow at 0 (beyond its limit of -0.07 rad): axis 5 through the shoulder's point.
    assert "axis 5 passes through the wrist centre" in rk.closed.family(panda, locked={3: 0.0}).reason
    assert all(rk.closed.family(panda, locked={3: v}).solvable for v in (-0.07, -1.2, -3.07, 1.0, P))


def test_the_families_the_locks_leave():
    iiwa, panda, gen3 = ARMS["iiwa14"], ARMS["panda"], ARMS["gen3"]
    assert rk.closed.family(iiwa, locked={2: 0.3}).name == "spherical wrist, axes 1, 2 meet"
    # Held at 0, the iiwa's joint 3 leaves axes 2 and 4 parallel: the PUMA's family.
    assert rk.closed.family(iiwa, locked={2: 0.0}).name == "spherical wrist, axes 2, 4 parallel"
    assert rk.closed.family(iiwa, locked={6: 0.3}).name == "spherical shoulder, axes 5, 6 meet"
    assert rk.closed.family(panda, locked={6: 0.3}).name == "spherical shoulder, axes 5, 6 meet"
    assert rk.closed.family(gen3, locked={3: 0.3}).name == "spherical wrist, axes 1, 2 meet"
    # The iiwa's elbow: shoulder and wrist both spherical, their distance fixed by the elbow alone.
    assert "the distance between the two points is the same for every posture" in rk.closed.family(
        iiwa, locked={3: 0.3}).reason
    # Axes that line up at 0: the iiwa's 1 and 3, the Panda's 5 and 7.
    assert "axes 1, 3 are parallel" in rk.closed.family(iiwa, locked={1: 0.0}).reason
    assert not rk.closed.family(panda, locked={5: 0.0}).solvable
    # The Panda's elbow held: its shoulder spherical, axes 5, 6 meeting, axis 7 88 mm from them.
    assert rk.closed.family(panda, locked={3: -1.2}).name == "spherical shoulder, axes 5, 6 meet before axis 7"
    # The Gen3's shoulder offset (axes 1, 2 and 2, 3 meet 11.8 mm apart along axis 2): with joint 2
    # held, axes 3, 4 meet 11.8 mm off axis 1; with joint 5 held, no spherical shoulder.
    assert rk.closed.family(gen3, locked={1: 0.3}).name == "spherical wrist, axes 3, 4 meet after axis 1"
    assert "axes 1, 2, 3 do not meet: 11.8 mm apart" in rk.closed.family(gen3, locked={4: 0.3}).reason


@pytest.mark.parametrize("name,j", CASES)
def test_every_solution_reaches_and_the_source_is_among_them(name, j):
    chain = ARMS[name]
    rng = np.random.default_rng(100 + 7 * j + len(name))
    for q in random_q(chain, rng, 40):
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, locked={j: q[j]})
        assert s.q.shape[1] == 7 and 1 <= len(s) <= 8
        assert np.all(s.q[:, j] == q[j])
        assert np.abs(chain.fk(s.q) - T).max() <= 1e-9
        assert angle_distance(s.q, q).min() < 1e-6
        assert len(set(s.postures)) == len(s)  # one label per solution


@pytest.mark.parametrize("name,j", CASES)
def test_numerical_ik_finds_nothing_the_closed_form_misses(name, j):
    chain = ARMS[name]
    rng = np.random.default_rng(200 + 7 * j + len(name))
    found = 0
    for q in random_q(chain, rng, 2):
        T = chain.fk(q)
        s = rk.closed.solve(T, chain, limits=None, locked={j: q[j]})
        starts = random_q(chain, rng, 48)
        if (name, j) == ("gen3", 3):
            # The Gen3's elbow held: only the 11.8 mm shoulder offset changes the wrist centre's
            # distance from the shoulder, and Newton converges only from near a solution.
            starts = q + rng.normal(0.0, 0.05, (48, 7))
        starts[:, j] = q[j]
        ends, errors = newton_held(chain, T, starts, j, iterations=newton_steps(name, j))
        for qn in ends[errors < 1e-10]:
            found += 1
            assert angle_distance(s.q, qn).min() < 1e-6
    assert found >= 20  # the starts do converge: the check compares something


def test_a_sweep_of_the_held_joint_is_the_self_motion():
    # The iiwa's joint 3 held at each value of a sweep: every solution reaches the pose, and the
    # generating posture's solutions move continuously with the held value (the self-motion).
    chain = ARMS["iiwa14"]
    q = np.array([0.4, 0.7, -0.2, -1.1, 0.5, 0.9, -0.3])
    T = chain.fk(q)
    values = q[2] + np.linspace(-0.6, 0.6, 121)
    path = [q]
    for v in values[values > q[2]]:
        s = rk.closed.solve(T, chain, locked={2: v})
        assert len(s) and np.abs(chain.fk(s.q) - T).max() <= 1e-9
        step = angle_distance(s.q, path[-1])
        assert step.min() < 0.15  # a neighbour of the previous point: one branch, followed
        path.append(s.q[np.argmin(step)])
    path = np.array(path)
    assert np.ptp(path[:, 2]) > 0.5 and np.ptp(path[:, 0]) > 0.01  # the other joints move with it


@pytest.mark.parametrize("name,j", [("iiwa14", 2), ("panda", 6), ("gen3", 0)])
def test_solver_batch_and_pickle(name, j):
    chain = ARMS[name]
    Q = random_q(chain, np.random.default_rng(3), 30)
    Q[:, j] = Q[0, j]
    solver = rk.closed.ClosedSolver(chain, locked={j: Q[0, j]})
    assert solver.locked == {j: Q[0, j]} and solver.family == rk.closed.family(chain, locked={j: Q[0, j]}).name
    q8, singular, within = solver.solve_batch(chain.fk(Q))
    assert q8.shape == (30, 8, 7) and within.shape == (30, 8)
    for k in range(30):
        s = solver.solve(chain.fk(Q[k]))
        rows = q8[k][~np.isnan(q8[k, :, 0])]
        assert len(rows) == len(s) and sorted(map(tuple, rows)) == sorted(map(tuple, s.q))
        assert within[k].sum() == s.within_limits.sum() and bool(singular[k]) == s.singular
    back = pickle.loads(pickle.dumps(solver))
    assert back.locked == solver.locked and back.family == solver.family
    assert np.array_equal(back.solve(chain.fk(Q[1])).q, solver.solve(chain.fk(Q[1])).q)
    solver.locked[j] = 0.0  # a copy: the solver's own stays
    assert solver.locked == {j: Q[0, j]}
    assert rk.closed.ClosedSolver(rk.robots.ur5()).locked is None


def test_limits_and_labels():
    chain = ARMS["iiwa14"]
    q = np.array([0.4, 0.7, -0.2, -1.1, 0.5, 0.9, -0.3])
    s = rk.closed.solve(chain.fk(q), chain, locked={2: q[2]})
    lo, hi = chain.limits
    assert np.array_equal(s.within_limits, np.all((s.q >= lo) & (s.q <= hi), axis=1))
    none = rk.closed.solve(chain.fk(q), chain, limits=None, locked={2: q[2]})
    assert none.within_limits.all() and len(none) == len(s)
    for label in s.postures:
        shoulder, elbow, wrist = label.split(", ")
        assert shoulder in ("shoulder left", "shoulder right") and elbow in ("elbow up", "elbow down")
        assert wrist in ("wrist no flip", "wrist flip")


def test_bad_locks():
    iiwa = ARMS["iiwa14"]
    T = iiwa.fk(np.zeros(7))
    with pytest.raises(ValueError, match=r"locked: joint index 7 out of range .* 7 joints"):
        rk.closed.solve(T, iiwa, locked={7: 0.1})
    with pytest.raises(ValueError, match=r"locked: q\[2\] = 3.5 is outside the joint's limits"):
        rk.closed.solve(T, iiwa, locked={2: 3.5})
    q35 = np.array([0.4, 0.7, 3.5, -1.1, 0.5, 0.9, -0.3])  # q[2] beyond its limit of 2.97 rad
    s = rk.closed.solve(iiwa.fk(q35), iiwa, limits=None, locked={2: 3.5})  # no limits: any value
    assert len(s) and np.all(s.q[:, 2] == 3.5) and angle_distance(s.q, q35).min() < 1e-6
    assert np.abs(iiwa.fk(s.q) - iiwa.fk(q35)).max() < 1e-9
    with pytest.raises(ValueError, match="locked: the held value must be finite"):
        rk.closed.solve(T, iiwa, locked={2: math.nan})
    with pytest.raises(ValueError, match=r"locked: joint index -1 out of range .* \(indices 0 to 6\)"):
        rk.closed.solve(T, iiwa, locked={-1: 0.1})
    for index in (1, 6):  # the chain's size is the first thing wrong, whatever the index
        with pytest.raises(ValueError, match="locked: holding a joint needs a chain of 7 joints.*this one has 6"):
            rk.closed.solve(T, rk.robots.ur5(), locked={index: 0.1})
    with pytest.raises(ValueError, match="locked: holding a joint needs a chain of 7 joints"):
        rk.closed.family(rk.robots.ur5(), locked={1: 0.1})
    with pytest.raises(ValueError, match=r"locked: no closed form for this arm with q\[3\] held \(.*continuum"):
        rk.closed.solve(T, iiwa, locked={3: 0.5})
    with pytest.raises(ValueError, match="locked: expected one joint"):
        rk.closed.ClosedSolver(iiwa, locked={1: 0.1, 2: 0.2})
    for bad in ([2, 0.1], "x", 3):
        with pytest.raises(TypeError, match="locked: expected None or a dict"):
            rk.closed.solve(T, iiwa, locked=bad)
    for bad in ({2.0: 0.1}, {True: 0.1}, {"2": 0.1}):
        with pytest.raises(TypeError, match="locked: the key must be a joint index"):
            rk.closed.family(iiwa, locked=bad)
    with pytest.raises(TypeError, match="locked: the held value must be a real number"):
        rk.closed.solve(T, iiwa, locked={2: "0.1"})
    assert rk.closed.family(iiwa, locked={np.int64(2): np.float32(0.25)}).solvable  # numpy scalars


@pytest.mark.parametrize("shape", ["wrist, axes 1, 2 meet", "shoulder, axes 5, 6 meet"])
def test_random_arms_of_the_new_families(shape):
    # Random 6R arms whose DH table makes the family (a_i = 0: z_{i-1} and z_i meet; with d_i = 0
    # as well, z_{i-2}, z_{i-1}, z_i meet in one point), lengths and twists otherwise random.
    rng = np.random.default_rng(len(shape))
    length = lambda: rng.uniform(0.05, 0.5) * rng.choice([-1, 1])  # noqa: E731
    twist = lambda: rng.uniform(0.3, P - 0.3) * rng.choice([-1, 1])  # noqa: E731
    for _ in range(40):
        rows = [[length(), twist(), length(), rng.uniform(-P, P), "R"] for _ in range(6)]
        zero = [(0, 0), (3, 0), (4, 0), (4, 2)] if shape.startswith("wrist") else [(0, 0), (1, 0), (1, 2), (4, 0)]
        for i, k in zero:
            rows[i][k] = 0.0
        chain = rk.Chain.from_dh([tuple(r) for r in rows])
        assert rk.closed.family(chain).name == "spherical " + shape
        for q in rng.uniform(-P, P, (5, 6)):
            T = chain.fk(q)
            s = rk.closed.solve(T, chain, limits=None)
            assert np.abs(chain.fk(s.q) - T).max() <= 1e-9
            assert angle_distance(s.q, q).min() < 1e-6 and len(set(s.postures)) == len(s)


def test_the_held_value_stays_as_given():
    # Beyond pi (the Panda's joint 6 turns to 3.75 rad) and without limits: not wrapped.
    panda = ARMS["panda"]
    q = np.array([0.3, -0.4, 0.2, -2.0, 0.5, 3.5, 0.7])
    for limits in ("default", None):
        s = rk.closed.solve(panda.fk(q), panda, limits=limits, locked={5: 3.5})
        assert len(s) and np.all(s.q[:, 5] == 3.5) and angle_distance(s.q, q).min() < 1e-6


def test_a_family_read_from_the_tool_serves_the_ik_restarts():
    # The Panda's first six joints (its flange joint's frame as the tool): a spherical shoulder,
    # axes 5, 6 meeting. rk.ik's restarts start from its closed-form solutions (reversed axes).
    rows = [(0.0, 0.0, 0.333, 0.0, "R"), (0.0, -P / 2, 0.0, 0.0, "R"), (0.0, P / 2, 0.316, 0.0, "R"),
            (0.0825, P / 2, 0.0, 0.0, "R"), (-0.0825, -P / 2, 0.384, 0.0, "R"), (0.0, P / 2, 0.0, 0.0, "R")]
    tool = np.eye(4)
    tool[0, 3] = 0.088
    chain = rk.Chain.from_dh(rows, modified=True, tool=tool)
    assert rk.closed.family(chain).name == "spherical shoulder, axes 5, 6 meet"
    rng = np.random.default_rng(9)
    for q in rng.uniform(-2.5, 2.5, (20, 6)):
        T = chain.fk(q)
        r = rk.ik(chain, T, np.zeros(6), seed=1)
        assert r.success and np.abs(chain.fk(r.q) - T).max() < 1e-8
        s = rk.closed.solve(T, chain, limits=None)
        assert angle_distance(s.q, q).min() < 1e-6 and angle_distance(s.q, r.q).min() < 1e-5
        # One iteration from a far start cannot reach T; the one restart can, only from an exact start.
        far = np.full(6, 2.9)
        assert not rk.ik(chain, T, far, restarts=0, max_iter=1).success
        one = rk.ik(chain, T, far, restarts=1, max_iter=1)
        assert one.success and one.attempts == 2 and angle_distance(s.q, one.q).min() < 1e-9
