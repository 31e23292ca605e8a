"""Chain.fk(q, part="position"): the tool points alone, (3,) or (N, 3). They are the frames' last
column bit for bit (the same evaluation path, written alone) and KDL's FK; bad `part` values and
overflowing results raise errors that name the argument."""

import math

import numpy as np
import pytest

import robokin as rk

CHAINS = {
    "rpr": rk.robots.rpr(),
    "ur5": rk.robots.ur5(),
    "puma560": rk.robots.puma560(),
    "prr": rk.robots.prr(),
    "modified 7R": rk.Chain.from_dh([(0.3, 0.5, 0.1, 0.2, "R")] * 7, modified=True),
    # prismatic joints along tilted axes, and a tool: every term of the evaluation path in use
    "segments": rk.Chain.from_segments(
        [("P", (0.0, 0.6, 0.8), np.eye(4)), ("R", (1.0, 0.0, 0.0), rk.robots.ur5().fk([0.3, -1, 0.7, 0.2, 1, 2])),
         ("P", (1.0, 1.0, 1.0), np.eye(4)), ("R", (0.0, 0.0, 1.0), np.eye(4))],
        tool=rk.robots.ur5().fk([1, 2, 3, 4, 5, 6])),
}


@pytest.mark.parametrize("name", list(CHAINS))
@pytest.mark.parametrize("count", [1, 31, 32, 33, 70000])  # the tail, one block, blocks + tail, streamed frames
def test_positions_are_the_frames_last_column_and_kdl(name, count):
    chain = CHAINS[name]
    Q = np.random.default_rng(count).uniform(-math.pi, math.pi, (count, chain.dof))
    P, F = chain.fk(Q, part="position"), chain.fk(Q, part="frame")
    assert P.shape == (count, 3) and P.dtype == np.float64 and P.flags.c_contiguous
    np.testing.assert_array_equal(P, F[:, :3, 3])
    np.testing.assert_array_equal(F, chain.fk(Q))  # "frame" is the default
    for k in np.random.default_rng(1).integers(0, count, 10):
        np.testing.assert_allclose(P[k], chain._fk_kdl(Q[k])[:3, 3], rtol=0, atol=1e-12)
        np.testing.assert_array_equal(chain.fk(Q[k], part="position"), P[k])
    assert chain.fk(Q[0], part="position").shape == (3,)


def test_empty_batch():
    assert CHAINS["ur5"].fk(np.zeros((0, 6)), part="position").shape == (0, 3)


@pytest.mark.parametrize("bad, error", [("pos", ValueError), ("FRAME", ValueError), ("", ValueError),
                                        (None, TypeError), (3, TypeError), (b"position", TypeError)])
def test_bad_part_names_the_argument(bad, error):
    with pytest.raises(error, match="part"):
        CHAINS["rpr"].fk([0.1, 0.2, 0.3], part=bad)
    with pytest.raises(error, match="part"):
        CHAINS["rpr"].fk(np.zeros((5, 3)), part=bad)


@pytest.mark.parametrize("count", [1, 40, 50000])
def test_overflowing_positions_raise(count):
    """A prismatic stroke near 1e308 overflows: a ValueError naming q, in both outputs, single and batch."""
    far = np.eye(4)
    far[0, 3] = 1e308
    chain = rk.Chain.from_segments([("P", (1.0, 0.0, 0.0), far), ("R", (0.0, 0.0, 1.0), np.eye(4))])
    Q = np.zeros((count, 2))
    Q[-1] = (1e308, 0.0)
    for part in ("position", "frame"):
        with pytest.raises(ValueError, match="q"):
            chain.fk(Q, part=part)
        with pytest.raises(ValueError, match="q"):
            chain.fk(Q[-1], part=part)
    assert np.isfinite(chain.fk(Q[:-1], part="position")).all()
