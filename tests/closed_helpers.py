"""What the closed-form tests share: configurations drawn inside the limits, the distance of joint
vectors modulo 2 pi, and a damped Newton with one joint held (an independent numerical IK)."""

import math

import numpy as np

P = math.pi


def random_q(chain, rng, count, margin=0.05):
    """count configurations uniform within the limits less `margin` of each range at both ends (an
    unlimited joint within [-pi, pi])."""
    lo, hi = chain.limits
    lo, hi = np.where(np.isfinite(lo), lo, -P), np.where(np.isfinite(hi), hi, P)
    return rng.uniform(lo + margin * (hi - lo), hi - margin * (hi - lo), (count, chain.dof))


def angle_distance(a, b):
    """Largest joint difference, angles compared modulo 2 pi."""
    return np.max(np.abs(np.remainder(a - b + P, 2 * P) - P), axis=-1)


def newton_held(chain, T, starts, j, iterations=80):
    """Damped Newton from each start (rows), joint j held (None: none): the pose error on the other
    joints. Returns the end points and each one's largest deviation of fk from T."""
    q = starts.copy()
    # Orientation error: half the sum of the columns' cross products (both operands 3-D, so that
    # axis 1 is the column's rows in each).
    free = [i for i in range(chain.dof) if i != j]
    for _ in range(iterations):
        F = chain.fk(q)
        e = np.concatenate([T[:3, 3] - F[:, :3, 3], 0.5 * np.cross(F[:, :3, :3], T[None, :3, :3], axis=1).sum(axis=2)],
                           axis=1)
        J = chain.jacobian(q)[:, :, free]
        step = np.linalg.solve(J @ J.transpose(0, 2, 1) + 1e-9 * np.eye(6), e[:, :, None])
        q[:, free] += (J.transpose(0, 2, 1) @ step)[:, :, 0]
    return q, np.abs(chain.fk(q) - T).max(axis=(1, 2))


def newton_steps(name, j):
    """Newton's iterations for the catalogue arm `name` with joint j held: the Panda's elbow held
    keeps the wrist's point (axes 5, 6) a fixed distance from the shoulder's, and from a random
    start Newton mostly creeps along that constraint (800 steps converge about as often as 80 do
    elsewhere)."""
    return 800 if (name, j) == ("panda", 3) else 80
