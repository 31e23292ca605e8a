"""3R arms shared by the tests of rk.closed.general_3r and rk.cuspidal: DH tables, Baili, Wenger and
Chablat's orthogonal arms (see test_cuspidal.py for the literature) and random arms meeting a
seed condition."""

import math

import numpy as np

import robokin as rk

P = math.pi


def standard(rows):
    return rk.Chain.from_dh([tuple(r) + ("R",) for r in rows])


def orthogonal(d2, d3, d4, r2, r3):
    """Baili, Wenger and Chablat's orthogonal 3R (modified DH), tool d4 along x3."""
    tool = np.eye(4)
    tool[0, 3] = d4
    rows = [(0.0, 0.0, 0.0, 0.0, "R"), (d2, -P / 2, r2, 0.0, "R"), (d3, P / 2, r3, 0.0, "R")]
    return rk.Chain.from_dh(rows, modified=True, tool=tool)


WENGER_CUSPIDAL = dict(d2=1.0, d3=2.0, d4=1.5, r2=1.0, r3=0.0)


def random_arm(rng, condition=None):
    a = rng.uniform(0.3, 1.5, 3)
    alpha = rng.uniform(-P, P, 3)
    d = rng.uniform(-1.0, 1.0, 3)
    if condition == "first parallel":
        alpha[0] = 0.0
    elif condition == "first intersect":
        a[0] = 0.0
    elif condition == "last parallel":
        alpha[1] = 0.0
    elif condition == "last intersect":
        a[1] = 0.0
    return standard([(a[i], alpha[i], d[i], 0.0) for i in range(3)])


def wrapped(a, b):
    return np.max(np.abs(np.remainder(np.asarray(a) - np.asarray(b) + P, 2 * P) - P), axis=-1)
