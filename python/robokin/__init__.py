"""robokin: robot kinematics with a C++ core (Eigen + Orocos KDL).

Serial chains from Denavit-Hartenberg tables, forward kinematics and Jacobians, the Reach loop
with joint-limit avoidance and path tracking. See the README for a tour.
"""

from . import closed, paths, robots
from . import pose, traj
from ._core import (RRR3, RRR3_DEFAULTS, Chain, ReachOptions, ReachResult, RRR3ConnectOptions, RRR3PlanOptions,
                    TrackResult, joint_limit_cost)
from ._core import RRR3LoopOptions
from ._signature import plain
from ._core import RRR3NewtonOptions, RRR3WorkspaceOptions
from .errors import NoRouteError, PrecisionWarning, UnreachableError
from .ik import IKBatchResult, IKOptions, IKResult, IKSolver, ik, ik_batch
from .reach import reach, track
from .resolved_rate import RateOptions, ServoOptions, ServoResult, resolved_rate, servo
from .postures import TrackPosturesResult, count_reconfigurations, track_postures
from .cuspidality import CuspidalOptions, Cuspidality, cuspidal

__version__ = "0.1.0"

__all__ = [
    "Chain",
    "NoRouteError",
    "PrecisionWarning",
    "IKBatchResult",
    "IKOptions",
    "IKResult",
    "IKSolver",
    "RRR3",
    "RRR3_DEFAULTS",
    "RRR3ConnectOptions",
    "RRR3LoopOptions",
    "RRR3NewtonOptions",
    "RRR3PlanOptions",
    "RRR3WorkspaceOptions",
    "ReachOptions",
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
    "RateOptions",
    "ServoOptions",
    "ServoResult",
    "pose",
    "resolved_rate",
    "servo",
    "traj",
    "TrackPosturesResult",
    "count_reconfigurations",
    "track_postures",
    "CuspidalOptions",
    "Cuspidality",
    "cuspidal",
]

# The IK defaults and URDF loading's warnings.
from .errors import URDFWarning  # noqa: E402
from .ik import IK_DEFAULTS  # noqa: E402

__all__ += ["IK_DEFAULTS", "URDFWarning"]

# A URDF's links and joints, and the chain Chain.from_urdf builds by default.
from ._core import UrdfJoint, UrdfTree  # noqa: E402
from ._urdf import urdf_tree  # noqa: E402

# help() and inspect.signature for the core's free functions as for Python's own (robokin._signature
# says why).
joint_limit_cost = plain(joint_limit_cost, "joint_limit_cost", __name__)
# Chain's methods written in Python (robokin._chain, robokin._urdf).
from . import _chain, _urdf  # noqa: E402

Chain.from_dh, Chain.from_segments = staticmethod(_chain.from_dh), staticmethod(_chain.from_segments)
Chain.from_urdf = staticmethod(_urdf.from_urdf)
Chain.q_from, Chain.q_dict = _chain.q_from, _chain.q_dict

__all__ += ["UrdfJoint", "UrdfTree", "urdf_tree"]

# Reachability maps (robokin.dask, the [dask] extra, is imported on demand).
from .reachability import ReachabilityMap, reachability  # noqa: E402

__all__ += ["ReachabilityMap", "reachability"]


def __getattr__(name):
    # rk.symbolic and rk.plots on first use: sympy (the [symbolic] extra) and matplotlib (the [plot]
    # extra) are imported only by who asks for them.
    if name in ("symbolic", "plots"):
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'robokin' has no attribute {name!r}")
