"""Type stubs for robokin._core, the C++ extension (Eigen + Orocos KDL).

Arrays are float64; bad input raises ValueError naming the argument.
"""

from typing import Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
NDArray = npt.NDArray[np.float64]

# --- chains (cpp/bindings/chain.cpp) ---------------------------------------------------------

class Chain:
    """A serial kinematic chain (an Orocos KDL chain with joint limits)."""

    @staticmethod
    def from_dh(
        rows: Sequence[Tuple[float, float, float, float, str]],
        modified: bool = False,
        tool: Optional[ArrayLike] = None,
        limits: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    ) -> "Chain":
        """Builds a chain from Denavit-Hartenberg rows ``(a, alpha, d, theta, "R"|"P")``.

        Standard DH: ``A = Rz(theta) Tz(d) Tx(a) Rx(alpha)``; ``modified=True`` (Craig):
        ``A = Rx(alpha) Tx(a) Rz(theta) Tz(d)``. A revolute joint adds q to theta, a prismatic one
        to d. ``tool`` is a constant (4, 4) frame after the last row; ``limits`` is
        ``(lower, upper)`` (``+-inf`` for an unlimited joint).
        """
    @staticmethod
    def from_segments(
        segments: Sequence[Tuple[str, ArrayLike, ArrayLike]],
        tool: Optional[ArrayLike] = None,
        limits: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    ) -> "Chain":
        """Builds a chain from KDL-style segments ``(joint, axis, tip)``: a joint ``"R"``,
        ``"P"`` or ``"F"`` (fixed) about / along ``axis`` (3,) through the segment's start, then the
        constant (4, 4) frame ``tip`` to the segment's end."""
    @property
    def dof(self) -> int: ...
    @property
    def joint_types(self) -> str:
        """One letter per joint, ``"R"`` or ``"P"``."""
    @property
    def limits(self) -> Tuple[NDArray, NDArray]:
        """``(lower, upper)``; ``+-inf`` where a joint is unlimited."""
    def fk(self, q: ArrayLike) -> NDArray:
        """Tool pose (4, 4) for q of shape (dof,); (N, 4, 4) for a batch (N, dof)."""
    def jacobian(self, q: ArrayLike, task: str = "pose") -> NDArray:
        """Geometric Jacobian at the tool point in the base frame, rows ``[v; w]`` selected by
        ``task`` ("pose" 6, "position" 3, "xy" rows 0-1, "xyphi" rows 0, 1, 5): (rows, dof), or
        (N, rows, dof) for a batch."""
    def frames(self, q: ArrayLike) -> NDArray:
        """(dof + 1, 4, 4): the base, then the frame after each joint (the last includes the tool)."""
    def point_in_frame(self, q: ArrayLike, point: ArrayLike, frame: int, in_frame: int = 0) -> NDArray:
        """The point (3,) given in frame ``frame`` expressed in frame ``in_frame`` (0 is the base)."""
    def _fk_kdl(self, q: ArrayLike) -> NDArray:
        """Reference: KDL's ChainFkSolverPos_recursive."""
    def _jacobian_kdl(self, q: ArrayLike) -> NDArray:
        """Reference: KDL's ChainJntToJacSolver, (6, dof)."""

# --- Reach and tracking (cpp/bindings/reach.cpp) ---------------------------------------------

class ReachResult:
    @property
    def q(self) -> NDArray: ...
    @property
    def converged(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def error(self) -> float: ...

class TrackResult:
    @property
    def q(self) -> NDArray: ...
    @property
    def error(self) -> NDArray: ...
    @property
    def converged(self) -> npt.NDArray[np.bool_]: ...
    @property
    def iterations(self) -> npt.NDArray[np.int32]: ...

def reach(
    chain: Chain, target: ArrayLike, q: ArrayLike, task: str = "xy", max_iter: int = 25, tol: float = 1e-5,
    gain: float = 0.75, dt: float = 0.025, saturate: bool = True,
    nullspace: Union[None, str, ArrayLike] = None, damping: float = 0.0,
) -> ReachResult: ...
def track(
    chain: Chain, points: ArrayLike, q0: ArrayLike, task: str = "xy", max_iter: int = 25, tol: float = 1e-5,
    gain: float = 0.75, dt: float = 0.025, saturate: bool = True,
    nullspace: Union[None, str, ArrayLike] = None, damping: float = 0.0,
) -> TrackResult: ...

# --- the seed-000 RPR arm (cpp/bindings/rpr.cpp) ---------------------------------------------

def rpr_self_motion(
    point: ArrayLike, t1: ArrayLike, l1: float, l3: float, lower: ArrayLike, upper: ArrayLike
) -> NDArray:
    """(2, K, 3) joints putting the RPR tip at ``point`` for each t1 sample and branch; NaN where none."""

# --- closed-form inverse kinematics (cpp/bindings/ik_closed.cpp) -------------------------------

class IKSolutions:
    """Every closed-form solution of a pose: ``q`` (k, dof), one posture label per row."""
    @property
    def q(self) -> NDArray: ...
    @property
    def postures(self) -> Sequence[str]: ...
    @property
    def singular(self) -> bool: ...
    @property
    def dof(self) -> int: ...
    def __len__(self) -> int: ...
    def nearest(self, q: ArrayLike) -> Optional[int]: ...

class _SphericalWrist6R:
    def __init__(
        self, a2: float, a3: float, d3: float, d4: float, d1: float = 0.0, d6: float = 0.0,
        limits: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    ) -> None: ...
    def solve(self, target: ArrayLike) -> IKSolutions: ...

def ik_planar_rp(target: ArrayLike, limits: Optional[Tuple[ArrayLike, ArrayLike]] = None) -> IKSolutions: ...
def ik_planar_2r(
    target: ArrayLike, a1: float, a2: float, limits: Optional[Tuple[ArrayLike, ArrayLike]] = None
) -> IKSolutions: ...
def ik_planar_3r(
    target: ArrayLike, a1: float, a2: float, a3: float, method: str = "algebraic",
    limits: Optional[Tuple[ArrayLike, ArrayLike]] = None,
) -> IKSolutions: ...
def ik_anthropomorphic(
    target: ArrayLike, a2: float, a3: float, d1: float = 0.0, limits: Optional[Tuple[ArrayLike, ArrayLike]] = None
) -> IKSolutions: ...
def ik_spherical_wrist(
    target: ArrayLike, a2: float, a3: float, d3: float, d4: float, d1: float = 0.0, d6: float = 0.0,
    limits: Optional[Tuple[ArrayLike, ArrayLike]] = None,
) -> IKSolutions: ...
def ik_spherical_wrist_path(
    targets: ArrayLike, a2: float, a3: float, d3: float, d4: float, d1: float, d6: float, q0: ArrayLike,
    limits: Optional[Tuple[ArrayLike, ArrayLike]] = None,
) -> Tuple[NDArray, npt.NDArray[np.bool_]]: ...

# --- numerical inverse kinematics (cpp/bindings/ik.cpp) ----------------------------------------

class IKResult:
    """What one numerical IK solve found."""
    @property
    def q(self) -> NDArray: ...
    @property
    def success(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def attempts(self) -> int: ...
    @property
    def error_p(self) -> float: ...
    @property
    def error_r(self) -> float: ...
    def __bool__(self) -> bool: ...

class IKBatchResult:
    """What ik_batch found, one row per target."""
    @property
    def q(self) -> NDArray: ...
    @property
    def success(self) -> npt.NDArray[np.bool_]: ...
    @property
    def iterations(self) -> npt.NDArray[np.int32]: ...
    @property
    def attempts(self) -> npt.NDArray[np.int32]: ...
    @property
    def error_p(self) -> NDArray: ...
    @property
    def error_r(self) -> NDArray: ...
    def __len__(self) -> int: ...

def ik(
    chain: Chain, target: ArrayLike, q0: ArrayLike, method: str = "lm", task: str = "pose", tol_p: float = 1e-9,
    tol_r: float = 1e-9, max_iter: int = 100, restarts: int = 0, seed: Optional[int] = None,
    timeout: Optional[float] = None, damping: Optional[float] = None,
) -> IKResult: ...
def ik_batch(
    chain: Chain, targets: ArrayLike, q0: ArrayLike, method: str = "lm", task: str = "pose", tol_p: float = 1e-9,
    tol_r: float = 1e-9, max_iter: int = 100, restarts: int = 0, seed: Optional[int] = None,
    timeout: Optional[float] = None, damping: Optional[float] = None, path: bool = False,
) -> IKBatchResult: ...
class IKSolver:
    """A numerical IK solver bound to a chain and options; solve(target, q0) costs only the solve."""
    def __init__(
        self, chain: Chain, method: str = "lm", task: str = "pose", tol_p: float = 1e-9, tol_r: float = 1e-9,
        max_iter: int = 100, restarts: int = 0, seed: Optional[int] = None, timeout: Optional[float] = None,
        damping: Optional[float] = None,
    ) -> None: ...
    def solve(self, target: ArrayLike, q0: ArrayLike) -> IKResult: ...
    @property
    def method(self) -> str: ...
    @property
    def task(self) -> str: ...

def _hessian_times(chain: Chain, q: ArrayLike, a: ArrayLike) -> NDArray: ...

class _KdlIk:
    """Benchmark reference: KDL's ChainIkSolverPos_LMA ("lma") or ChainIkSolverPos_NR_JL ("nr_jl")."""
    def __init__(self, chain: Chain, solver: str = "lma", max_iter: int = 500, eps: float = 1e-5) -> None: ...
    def solve(self, target: ArrayLike, q0: ArrayLike) -> Tuple[NDArray, int]: ...

# --- URDF (cpp/bindings/urdf.cpp) ----------------------------------------------------------------
# cpp/bindings/urdf.cpp adds a static method to Chain (kept out of the Chain section above to avoid
# merge conflicts; move it into the class when merging):
#     @staticmethod
#     def from_urdf(path_or_string: Union[str, os.PathLike], base: str, tip: str) -> Chain: ...
