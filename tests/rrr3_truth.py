"""Independent truth for the 3-RRR tests: DESIGN.md's geometry and the seed's formulas in numpy."""

import math

import numpy as np

import robokin as rk

T = np.radians(-90.0 + 120.0 * np.arange(3))
U = np.column_stack((np.cos(T), np.sin(T)))


def u(a):
    return np.array([math.cos(a), math.sin(a)])


def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def rot(phi):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


def base(robot):
    return robot.base_radius * U


def platform(robot, pose):
    """B_i from DESIGN.md: E + R_e R(phi) u(t_i)."""
    return pose[:2] + robot.platform_radius * U @ rot(pose[2]).T


def elbows(robot, alpha):
    """A_i = O_i + l1 u(alpha_i): each leg's forward chain up to the elbow."""
    return base(robot) + robot.l1 * np.column_stack((np.cos(alpha), np.sin(alpha)))


def random_poses(robot, rng, count, mode=(1, 1, 1)):
    """Reachable poses well inside the workspace and away from singularities in the given mode."""
    out = []
    while len(out) < count:
        p = np.array([*rng.uniform(-0.06, 0.06, 2), rng.uniform(-0.6, 0.6)])
        try:
            s = robot.singularity(p, mode)
        except rk.UnreachableError:
            continue
        if abs(s.det_a_norm) > 0.05 and abs(s.det_b_norm) > 0.05:
            out.append(p)
    return out


def seed_jacobians(robot, pose, alpha):
    """Seed 002 eqs. (3)-(5): g_i = atan2(A_iB_i) - theta_E, d_i = A_iB_i ^ A_iE / |A_iB_i|,
    e_i = A_iB_i ^ A_iO_i / |B_iA_i|."""
    a, b, o, e = elbows(robot, alpha), platform(robot, pose), base(robot), pose[:2]
    ab = b - a
    n = np.linalg.norm(ab, axis=1)
    g = np.arctan2(ab[:, 1], ab[:, 0]) - pose[2]
    d = cross(ab, e - a) / n
    ee = cross(ab, o - a) / n
    return np.column_stack((np.cos(g), np.sin(g), d)), np.diag(ee)
