"""robokin: robot kinematics with a C++ core (Eigen + Orocos KDL).

Serial chains from Denavit-Hartenberg tables, forward kinematics and Jacobians, the Reach loop
with joint-limit avoidance and path tracking. See the README for a tour.
"""

from . import closed, paths, robots
from ._core import RRR3, Chain, ReachResult, TrackResult, joint_limit_cost
from .errors import PrecisionWarning, UnreachableError
from .ik import IKBatchResult, IKResult, IKSolver, ik, ik_batch
from .reach import reach, track
from .postures import TrackPosturesResult, count_reconfigurations, track_postures
from .cuspidality import Cuspidality, cuspidal

__version__ = "0.1.0"

__all__ = [
    "Chain",
    "PrecisionWarning",
    "IKBatchResult",
    "IKResult",
    "IKSolver",
    "RRR3",
    "ReachResult",
    "TrackResult",
    "UnreachableError",
    "closed",
    "ik",
    "ik_batch",
    "joint_limit_cost",
    "paths",
    "reach",
    "robots",
    "track",
    # issue 15: postures along a path
    "TrackPosturesResult",
    "count_reconfigurations",
    "track_postures",
    "Cuspidality",
    "cuspidal",
]
