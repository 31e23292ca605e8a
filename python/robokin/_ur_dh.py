"""The Universal Robots arms' standard DH table, shared by the catalogue (robokin.robots) and the
UR closed form's arms given as a table (robokin.closed.ur with a dict)."""

from __future__ import annotations

import math


def ur_dh_rows(d1: float, a2: float, a3: float, d4: float, d5: float, d6: float) -> list:
    """Standard DH rows a = (0, a2, a3, 0, 0, 0), d = (d1, 0, 0, d4, d5, d6),
    alpha = (pi/2, 0, 0, pi/2, -pi/2, 0), six revolute joints with no theta offsets."""
    p = math.pi
    return [(0.0, p / 2, d1, 0.0, "R"), (a2, 0.0, 0.0, 0.0, "R"), (a3, 0.0, 0.0, 0.0, "R"),
            (0.0, p / 2, d4, 0.0, "R"), (0.0, -p / 2, d5, 0.0, "R"), (0.0, 0.0, d6, 0.0, "R")]
