"""rk.closed.family: the decomposition read from the joint axes, whatever the chain was built from.

Truth: the published geometry of the catalogue's arms (the PUMA and the ABB IRB 120 have a
spherical wrist and parallel axes 2, 3; the UR arms three parallel axes 2, 3, 4), the same arm
written as standard DH, modified DH (Craig's PUMA table) and URDF, and a wrist offset by a known
distance."""

import dataclasses
import math

import pytest
from ur_urdf import UR5_URDF

import robokin as rk

P = math.pi
WRIST = "spherical wrist, axes 2, 3 parallel"
PARALLEL = "three parallel axes 2, 3, 4"


def puma_rows(d5=0.0):
    """The PUMA 560's standard DH table (Corke), with an offset d5 along axis 5 when given."""
    return [(0, P / 2, 0, 0, "R"), (0.4318, 0, 0, 0, "R"), (0.0203, -P / 2, 0.15005, 0, "R"),
            (0, P / 2, 0.4318, 0, "R"), (0, -P / 2, d5, 0, "R"), (0, 0, 0, 0, "R")]


@pytest.mark.parametrize("name", ["puma560", "irb120"])
def test_spherical_wrist_arms(name):
    f = rk.closed.family(rk.robots.get(name))
    assert f.name == WRIST and f.solvable and f.reason == ""
    assert (4, 5) in f.meet and (5, 6) in f.meet and (2, 3) in f.parallel


@pytest.mark.parametrize("name", ["ur3", "ur5", "ur10", "ur3e", "ur5e", "ur10e", "ur16e"])
def test_ur_arms(name):
    f = rk.closed.family(rk.robots.get(name))
    assert f.name == PARALLEL and f.solvable and f.parallel == ((2, 3), (3, 4))


def test_the_ur5_from_its_urdf_is_the_ur_family():
    chain = rk.Chain.from_urdf(UR5_URDF, "base", "tool0")
    f = rk.closed.family(chain)
    assert f.name == PARALLEL and f.solvable and f.parallel == ((2, 3), (3, 4))
    assert f == dataclasses.replace(rk.closed.family(rk.robots.ur5()), tol_distance=f.tol_distance)


def test_modified_dh_reads_as_standard_dh():
    # Craig's PUMA 560 (modified DH: alpha_{i-1}, a_{i-1}, d_i), rows as (a, alpha, d, theta).
    craig = [(0, 0, 0, 0, "R"), (0, -P / 2, 0, 0, "R"), (0.4318, 0, 0.15005, 0, "R"),
             (0.0203, -P / 2, 0.4318, 0, "R"), (0, P / 2, 0, 0, "R"), (0, -P / 2, 0, 0, "R")]
    assert rk.closed.family(rk.Chain.from_dh(craig, modified=True)).name == WRIST


def test_an_offset_wrist_says_how_far_its_axes_miss():
    f = rk.closed.family(rk.Chain.from_dh(puma_rows(d5=0.0032)))
    assert not f.solvable and f.name == "none"
    assert f.reason.startswith("axes 4, 5, 6 do not meet: 3.2 mm apart")
    assert (4, 5) in f.meet and (5, 6) in f.meet  # each pair meets, at points 3.2 mm apart
    # A tolerance coarser than the offset (relative to the arm's size, about 1.5 m) accepts it.
    assert rk.closed.family(rk.Chain.from_dh(puma_rows(d5=0.0032)), tol=0.01).name == WRIST


def test_chains_without_six_revolute_joints():
    assert rk.closed.family(rk.robots.iiwa14()).reason == (
        "6 revolute joints needed: the chain has 7 joints; hold one (locked={index: value}) to solve the 6 others")
    assert "some prismatic" in rk.closed.family(rk.robots.rpr()).reason


def test_bad_arguments():
    with pytest.raises(ValueError, match="tol"):
        rk.closed.family(rk.robots.ur5(), tol=0.0)
    with pytest.raises(TypeError, match="tol"):
        rk.closed.family(rk.robots.ur5(), tol="x")
    with pytest.raises(TypeError, match="chain"):
        rk.closed.family("ur5")
    with pytest.raises(dataclasses.FrozenInstanceError):
        rk.closed.family(rk.robots.ur5()).name = "x"
