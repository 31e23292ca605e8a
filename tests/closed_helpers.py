"""What the closed-form tests share: configurations drawn inside the limits and the distance of
joint vectors modulo 2 pi."""

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
