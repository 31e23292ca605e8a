"""Type stubs for robokin._core, the C++ extension (Eigen + Orocos KDL).

Arrays are float64; bad input raises ValueError naming the argument.
"""

import os
from typing import ClassVar, Dict, Iterator, Optional, Sequence, Tuple, Union
from typing import Literal, Mapping

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
NDArray = npt.NDArray[np.float64]

# --- chains (cpp/bindings/chain.cpp) ---------------------------------------------------------
# Every class below (models and results) pickles and deep-copies (py::pickle, versioned state).

class Chain:
    """A serial kinematic chain (an Orocos KDL chain with joint limits)."""

    # Pickling and copies (cpp/bindings/pickle_chain.cpp): a versioned state tuple, the DH table of
    # a chain built from one, else a record of every KDL segment's constructor arguments; the copy
    # computes the same bits. == compares the kinematics (joint types, limits, constant frames).
    def __getstate__(self) -> tuple: ...
    def __setstate__(self, state: tuple) -> None: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

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
    @staticmethod
    def from_urdf(path_or_string: Union[str, os.PathLike], base: str, tip: str) -> "Chain":
        """Builds the chain from link ``base`` to link ``tip`` of a URDF (a file path or the XML
        itself; urdfdom parses it, robokin builds the KDL tree); joint limits come from the file
        (continuous joints unlimited). A bad file is a ValueError saying why (urdfdom's reason, two
        parents, lower > upper, mimic / floating / planar joints in the chain, origins beyond 1e9 m,
        ...); equal lower and upper limits load unlimited with a robokin.URDFWarning."""
    @property
    def dof(self) -> int: ...
    @property
    def joint_types(self) -> str:
        """One letter per joint, ``"R"`` or ``"P"``."""
    @property
    def limits(self) -> Tuple[NDArray, NDArray]:
        """``(lower, upper)``; ``+-inf`` where a joint is unlimited."""
    def fk(self, q: ArrayLike, out: Literal["frame", "position"] = "frame") -> NDArray:
        """Tool pose (4, 4) for q of shape (dof,); (N, 4, 4) for a batch (N, dof).
        ``out="position"``: the tool point only, (3,) or (N, 3)."""
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
    # Manipulability (cpp/bindings/manipulability.cpp).
    def manipulability(self, q: ArrayLike, measure: str = "yoshikawa", task: str = "pose") -> Union[float, NDArray]:
        """Manipulability from the singular values of the task's Jacobian rows (Eigen's JacobiSVD):
        ``"yoshikawa"`` their product (``sqrt(det(J J^T))`` when rows <= dof), ``"condition"``
        ``sigma_min / sigma_max`` (the inverse condition number: 1 isotropic, 0 singular),
        ``"min_singular"`` ``sigma_min``. A float for q (dof,); (N,) for a batch (N, dof), computed
        with the GIL released on every core."""
    def ellipsoid(self, q: ArrayLike, part: str = "translation") -> Tuple[NDArray, NDArray]:
        """Velocity ellipsoid ``{J_part qd : |qd| <= 1}`` of the rows v (``"translation"``) or w
        (``"rotation"``) at q (dof,): ``(axes, lengths)``, axes (3, 3) unit columns in the base frame
        (right-handed), lengths (3,) the singular values, decreasing (0 for missing directions)."""

# --- Reach and tracking (cpp/bindings/reach.cpp) ---------------------------------------------

class ReachOptions:
    """The options of one Reach (seed 000, Algorithm 1); the seed's values by default."""
    fields: ClassVar[Tuple[str, ...]]
    kinds: ClassVar[Tuple[str, ...]]
    max_iter: int
    tol: float
    gain: float
    dt: float
    saturate: bool
    damping: float
    def __init__(self, *, max_iter: int = 25, tol: float = 1e-5, gain: float = 0.75, dt: float = 0.025,
                 saturate: bool = True, damping: float = 0.0) -> None: ...

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
    chain: Chain, target: ArrayLike, q: ArrayLike, task: str = "xy", *,
    nullspace: Union[None, str, ArrayLike] = None, max_iter: int = 25, tol: float = 1e-5,
    gain: float = 0.75, dt: float = 0.025, saturate: bool = True, damping: float = 0.0,
) -> ReachResult: ...
def track(
    chain: Chain, points: ArrayLike, q0: ArrayLike, task: str = "xy", *,
    nullspace: Union[None, str, ArrayLike] = None, max_iter: int = 25, tol: float = 1e-5,
    gain: float = 0.75, dt: float = 0.025, saturate: bool = True, damping: float = 0.0,
) -> TrackResult: ...

def joint_limit_cost(chain: Chain, q: ArrayLike) -> Union[float, NDArray]:
    """Seed 000's joint-limit cost ``z = 1/2 |W (qbar - q)|^2``, ``W = diag(1 / (q_max - q_min))``
    (0 for an unlimited or fixed joint), ``qbar`` the middle of the range: a float for q (dof,),
    an array (N,) for a batch (N, dof)."""

# --- the seed-000 RPR arm (cpp/bindings/rpr.cpp) ---------------------------------------------

def rpr_self_motion(
    point: ArrayLike, t1: ArrayLike, l1: float, l3: float, lower: ArrayLike, upper: ArrayLike
) -> NDArray:
    """(2, K, 3) joints putting the RPR tip at ``point`` for each t1 sample and branch; NaN where none."""

# --- the planar 3-RRR parallel robot of seed 002 (cpp/bindings/rrr3.cpp) ---------------------

Mode = Tuple[int, int, int]

class RRR3Newton:
    """Answer of RRR3.ik_newton; unpacks as ``alpha, beta = result``."""

    @property
    def alpha(self) -> NDArray: ...
    @property
    def beta(self) -> NDArray: ...
    @property
    def converged(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def error(self) -> float:
        """Largest loop-closure residual (m)."""
    def __iter__(self) -> Iterator[NDArray]: ...

class RRR3Fk:
    """Answer of RRR3.fk."""

    @property
    def pose(self) -> NDArray: ...
    @property
    def converged(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def error(self) -> float:
        """Largest ``| |A_i B_i| - l2 |`` (m)."""

class RRR3Singularity:
    """Answer of RRR3.singularity. ``det_a_norm = det A / platform_radius`` and
    ``det_b_norm = det B / l1**3`` make one tolerance fit any robot size; ``distance`` is the
    inverse condition number of A with its third column divided by platform_radius (0 at a
    parallel singularity, at most 1)."""

    @property
    def kind(self) -> str:
        """``"none"``, ``"parallel"`` or ``"serial"``."""
    @property
    def det_a(self) -> float: ...
    @property
    def det_b(self) -> float: ...
    @property
    def det_a_norm(self) -> float: ...
    @property
    def det_b_norm(self) -> float: ...
    @property
    def distance(self) -> float: ...
    @property
    def leg(self) -> Optional[int]:
        """The stretched or folded leg of a serial singularity."""
    @property
    def lines(self) -> Optional[str]:
        """For a parallel singularity, ``"parallel"`` or ``"concurrent"`` lines A_iB_i."""

class RRR3Plan:
    """Answer of RRR3.plan: the poses to follow and what they give along the path."""

    @property
    def poses(self) -> NDArray:
        """(K, 3) poses (x, y, phi)."""
    @property
    def alpha(self) -> NDArray:
        """(K, 3) actuated angles, NaN rows where unreachable."""
    @property
    def det_a_norm(self) -> NDArray: ...
    @property
    def det_b_norm(self) -> NDArray: ...
    @property
    def distance(self) -> NDArray:
        """Inverse condition number of A along the path (RRR3Singularity.distance)."""
    @property
    def sign(self) -> int:
        """The sign of det A kept along the path."""
    @property
    def feasible(self) -> bool:
        """Every pose reachable, clear of serial singularities, at distance >= margin, one sign of det A."""

class RRR3Workspace:
    """Answer of RRR3.workspace: a constant-orientation map on an n x n grid."""

    @property
    def cells(self) -> npt.NDArray[np.uint8]:
        """(n, n) codes, row j at ``y[j]``, column i at ``x[i]``: 0 unreachable, 1 regular,
        2 parallel singular (``|det_a_norm| < tol`` or det A changes sign to a neighbour), 3 serial."""
    @property
    def x(self) -> NDArray: ...
    @property
    def y(self) -> NDArray: ...
    @property
    def extent(self) -> Tuple[float, float, float, float]:
        """``(x_min, x_max, y_min, y_max)`` for matplotlib's imshow."""
    @property
    def cell_size(self) -> float: ...
    @property
    def reachable_area(self) -> float:
        """Area of the reachable cells (m^2)."""
    @property
    def regular_area(self) -> float:
        """Area of the reachable, non-singular cells (m^2)."""
    @property
    def area(self) -> float:
        """Area of the largest 4-connected singularity-free region (m^2)."""

def rrr3_region_areas(robots: ArrayLike, phi: float = 0.0, mode: Sequence[int] = (1, 1, 1), n: int = 150,
                      tol: float = 1e-3) -> NDArray:
    """RRR3Workspace.area for each row (base_radius, platform_radius, l1, l2). Use robokin.rrr3_design."""

#: The seed's robot and thresholds (read-only): base_radius 0.13, platform_radius 0.07, l1 0.12, l2 0.12
#: (m); singular_tol 1e-3 (normalised determinants); near_distance 0.05 (RRR3Singularity.distance kept by
#: plan and connect); serial_margin 0.02 (|det B| / l1^3).
RRR3_DEFAULTS: Mapping[str, float]

class RRR3PlanOptions:
    """The options of RRR3.plan (keywords); defaults as in the seed's simulator."""
    fields: ClassVar[Tuple[str, ...]]
    kinds: ClassVar[Tuple[str, ...]]
    phi: float
    mode: Tuple[int, int, int]
    avoid: bool
    max_step: float
    margin: float
    serial_margin: float
    span: float
    resolution: float
    smoothing: float
    def __init__(self, *, phi: float = 0.0, mode: Sequence[int] = (1, 1, 1), avoid: bool = True,
                 max_step: float = 0.01, margin: float = 0.05, serial_margin: float = 0.02, span: float = 1.0,
                 resolution: float = 0.005, smoothing: float = 10.0) -> None: ...

class RRR3WorkspaceOptions:
    """The options of RRR3.workspace (its arguments, one map's)."""
    fields: ClassVar[Tuple[str, ...]]
    kinds: ClassVar[Tuple[str, ...]]
    phi: float
    mode: Tuple[int, int, int]
    n: int
    tol: float
    def __init__(self, *, phi: float = 0.0, mode: Sequence[int] = (1, 1, 1), n: int = 200,
                 tol: float = 1e-3) -> None: ...
    def validate(self) -> None: ...

class RRR3ConnectOptions:
    """The options of RRR3.connect (keywords)."""
    fields: ClassVar[Tuple[str, ...]]
    kinds: ClassVar[Tuple[str, ...]]
    mode: Tuple[int, int, int]
    clearance: float
    serial_margin: float
    max_step: float
    max_turn: float
    resolution: float
    span: float
    def __init__(self, *, mode: Sequence[int] = (1, 1, 1), clearance: float = 0.05, serial_margin: float = 0.02,
                 max_step: float = 0.001, max_turn: float = 0.01, resolution: float = 0.005,
                 span: float = 1.5) -> None: ...

class RRR3:
    """The planar 3-RRR parallel robot (seed 002, geometry and conventions of DESIGN.md).

    Base joints ``O_i = R_b u(t_i)``, platform joints ``B_i = E + R_e R(phi) u(t_i)``,
    ``t_i = -90 deg + 120 deg i``. A pose is ``(x, y, phi)``; a working mode ``(m_0, m_1, m_2)``
    with ``m_i = sign(beta_i)``. Every length must lie in [1e-6, 1e6] m; single poses (and fk's
    guess) must be finite with ``|x|, |y| <= 1e100`` m.
    """

    modes: Tuple[Mode, ...]
    """The 8 modes in ik_all's row order, ``itertools.product((1, -1), repeat=3)``."""

    def __init__(self, base_radius: float = 0.13, platform_radius: float = 0.07, l1: float = 0.12,
                 l2: float = 0.12) -> None: ...
    # Pickles as its four lengths; == compares them.
    def __getstate__(self) -> tuple: ...
    def __setstate__(self, state: tuple) -> None: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    @property
    def base_radius(self) -> float: ...
    @property
    def platform_radius(self) -> float: ...
    @property
    def l1(self) -> float: ...
    @property
    def l2(self) -> float: ...
    @property
    def base_joints(self) -> NDArray:
        """(3, 2) base joints O_i = R_b (cos t_i, sin t_i), t_i = -90 deg + 120 deg i (read-only)."""
    def ik(self, pose: ArrayLike, mode: Sequence[int] = (1, 1, 1)) -> NDArray:
        """Actuated angles (3,); ``UnreachableError`` (with ``.leg``) when a leg cannot reach."""
    def ik_all(self, pose: ArrayLike) -> NDArray:
        """(8, 3): row k for ``modes[k]``, NaN rows where unreachable."""
    def ik_batch(self, poses: ArrayLike, mode: Sequence[int] = (1, 1, 1)) -> NDArray:
        """(N, 3) for (N, 3) poses, NaN rows where a leg cannot reach; both cores, GIL released."""
    def ik_newton(self, pose: ArrayLike, guess: ArrayLike, max_iter: int = 50, tol: float = 1e-12) -> RRR3Newton:
        """Newton-Raphson on the 6 loop equations from ``guess`` = (alpha, beta), shape (2, 3) or (6,).
        ``max_iter`` in [0, 100000]; ``converged`` and ``error`` are those of the returned (wrapped) angles."""
    def fk(self, alpha: ArrayLike, guess: ArrayLike, max_iter: int = 50, tol: float = 1e-12) -> RRR3Fk:
        """One assembly mode by Newton from a guess pose. ``max_iter`` in [0, 100000]; ``converged``
        and ``error`` are those of the returned pose (phi wrapped to [-pi, pi])."""
    def fk_all(self, alpha: ArrayLike) -> NDArray:
        """(k, 3) every assembly mode, k <= 6, sorted by phi in [-pi, pi); each closes the loops to 1e-10 m
        (1e-10 of ``base_radius + platform_radius + l1 + l2`` when that exceeds 1 m) and is given once, a
        double root at a parallel singularity too; modes closer than the loops can tell apart in floating
        point (some 1e-7 of the size) are given as one. Where the elbows form a triangle congruent to the
        platform's (e.g. equal ``alpha_i`` when ``base_radius == platform_radius``), the platform also moves
        on a continuum (phi fixed, E on a circle of radius l2, the legs parallel): those poses are not
        returned, only the isolated modes."""
    def points(self, pose: ArrayLike, mode: Sequence[int] = (1, 1, 1)) -> Dict[str, NDArray]:
        """(3, 2) arrays ``"O"``, ``"A"``, ``"B"`` for drawing."""
    def jacobians(self, pose: ArrayLike, mode: Sequence[int] = (1, 1, 1)) -> Tuple[NDArray, NDArray]:
        """The seed's ``(A, B)``: ``A v = B alpha_dot``, v = (v_x, v_y, w) in the effector frame."""
    def singularity(self, pose: ArrayLike, mode: Sequence[int] = (1, 1, 1), tol: float = 1e-3) -> RRR3Singularity:
        """Serial when ``|det_b_norm| < tol``, else parallel when ``|det_a_norm| < tol``, else none."""
    def workspace(self, phi: float = 0.0, mode: Sequence[int] = (1, 1, 1), n: int = 200,
                  tol: float = 1e-3) -> RRR3Workspace:
        """Constant-orientation workspace on an n x n grid around the reachable set, with its
        singular cells and areas; computed on every core."""
    def plan(
        self, points: ArrayLike, *, phi: float = 0.0, mode: Sequence[int] = (1, 1, 1), avoid: bool = True,
        max_step: float = 0.01, margin: float = 0.05, serial_margin: float = 0.02, span: float = 1.0,
        resolution: float = 0.005, smoothing: float = 10.0,
    ) -> RRR3Plan:
        """Poses to follow the (K, 2) points at the nominal orientation ``phi`` in one mode.

        With ``avoid`` the orientations minimise ``sum (phi_k - phi)^2 + smoothing (phi_k -
        phi_{k-1})^2`` over a grid (step ``resolution``, within ``phi +- span``) by dynamic
        programming, with ``|phi_k - phi_{k-1}| <= max_step``, every pose reachable in ``mode``,
        ``|det_b_norm| >= serial_margin``, det A of the sign it has at the first point, and a
        distance to parallel singularities below ``margin`` penalised heavily. Excursions from
        the nominal orientation go out and back once (dips are filled), so nothing chatters.
        """
    def connect(
        self, start: ArrayLike, goal: ArrayLike, *, mode: Sequence[int] = (1, 1, 1), clearance: float = 0.05,
        serial_margin: float = 0.02, max_step: float = 0.001, max_turn: float = 0.01, resolution: float = 0.005,
        span: float = 1.5,
    ) -> RRR3Plan:
        """A motion from pose ``start`` to pose ``goal`` (x, y, phi) that never crosses a parallel
        singularity: poses (K, 3), start first and goal last, consecutive ones at most ``max_step``
        metres and ``max_turn`` radians apart, each reachable in ``mode`` with det A of the start's
        sign, a distance to parallel singularities (RRR3Singularity.distance) of at least
        ``clearance`` and ``|det_b_norm| >= serial_margin`` (less only where start or goal is
        itself nearer: then at least as much as there). Answered as an RRR3Plan (``feasible`` True,
        ``sign`` the sign kept).

        A* search in (x, y, phi) on a grid of step ``resolution`` in x and y and ``resolution *
        max_turn / max_step`` in phi (anchored at the start, phi within ``span`` of the two
        orientations), cost the number of steps, then straight shortcuts; every returned pose is
        checked. Raises ``rk.NoRouteError`` (an ``UnreachableError``) when there is none, its
        ``reason`` "start" or "goal" (that pose unreachable or singular) or "regions" (the two
        poses are in different singularity-free regions of ``mode``: det A has opposite signs, or
        every path of one sign comes nearer than ``clearance``).
        """

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
    """What ik_batch found, one row per target (read-only arrays)."""
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

class IKOptions:
    """The options of a numerical IK solve (robokin.ik's keywords); None: the default rule.

    restarts and timeout None: restart until success within IK_DEFAULTS["timeout"] seconds (of the
    solving thread's CPU time); an explicit restarts count without a timeout has no time budget.
    damping None: the C++ default_damping, lm 1e-1 (initial mu relative to max diag(J^T J)), nr
    1e-6, halley 1e-9 (lambda of the damped pseudoinverse), unused by gn. restarts <= 1_000_000.
    """
    fields: ClassVar[Tuple[str, ...]]
    kinds: ClassVar[Tuple[str, ...]]
    method: str
    task: str
    tol_p: float
    tol_r: float
    max_iter: int
    restarts: Optional[int]
    timeout: Optional[float]
    damping: Optional[float]
    def __init__(self, *, method: str = "lm", task: str = "pose", tol_p: float = 1e-9, tol_r: float = 1e-9,
                 max_iter: int = 100, restarts: Optional[int] = None, timeout: Optional[float] = None,
                 damping: Optional[float] = None) -> None: ...
    def validate(self) -> None: ...

# The defaults as a solve resolves them: restarts 1_000_000 and timeout 0.005 when neither is given.
IK_DEFAULTS: Mapping[str, Union[str, float, int]]
def ik(
    chain: Chain, target: ArrayLike, q0: ArrayLike, *, seed: Optional[int] = None, method: str = "lm",
    task: str = "pose", tol_p: float = 1e-9, tol_r: float = 1e-9, max_iter: int = 100,
    restarts: Optional[int] = None, timeout: Optional[float] = None, damping: Optional[float] = None,
) -> IKResult: ...
def ik_batch(
    chain: Chain, targets: ArrayLike, q0: ArrayLike, *, seed: Optional[int] = None, path: bool = False,
    method: str = "lm", task: str = "pose", tol_p: float = 1e-9, tol_r: float = 1e-9, max_iter: int = 100,
    restarts: Optional[int] = None, timeout: Optional[float] = None, damping: Optional[float] = None,
) -> IKBatchResult: ...
class IKSolver:
    """A numerical IK solver bound to a chain and options; solve(target, q0) costs only the solve.

    Options as ik (keyword-only, IKOptions). Like ik, solve releases the GIL when it may be long (a
    timeout, or more than ~1700 iterations in all); concurrent calls on one solver are serialised.
    """
    def __init__(
        self, chain: Chain, *, seed: Optional[int] = None, method: str = "lm", task: str = "pose",
        tol_p: float = 1e-9, tol_r: float = 1e-9, max_iter: int = 100, restarts: Optional[int] = None,
        timeout: Optional[float] = None, damping: Optional[float] = None,
    ) -> None: ...
    def solve(self, target: ArrayLike, q0: ArrayLike) -> IKResult: ...
    # Pickles with its chain, its options and its seed's call count (a copy continues the sequence).
    def __getstate__(self) -> tuple: ...
    def __setstate__(self, state: tuple) -> None: ...
    @property
    def method(self) -> str: ...
    @property
    def task(self) -> str: ...
    @property
    def options(self) -> IKOptions: ...

# --- trajectories (cpp/bindings/traj.cpp); use robokin.traj -----------------

def traj_quintic(q0: ArrayLike, q1: ArrayLike, t: ArrayLike, qd0: Optional[ArrayLike] = None,
                 qd1: Optional[ArrayLike] = None) -> Tuple[NDArray, NDArray, NDArray, NDArray]:
    """(t, q, qd, qdd) of the quintic from (q0, qd0) at t[0] to (q1, qd1) at t[-1]."""
def traj_trapezoidal(q0: ArrayLike, q1: ArrayLike, vmax: ArrayLike, amax: ArrayLike,
                     dt: float) -> Tuple[NDArray, NDArray, NDArray, NDArray]:
    """(t, q, qd, qdd) of the synchronised trapezoidal profile, sampled every dt."""
def traj_via_points(points: ArrayLike, vmax: ArrayLike, amax: ArrayLike,
                    dt: float) -> Tuple[NDArray, NDArray, NDArray, NDArray, NDArray]:
    """(t, q, qd, qdd, via_times) of linear segments with parabolic blends through the points."""
def traj_cartesian(T0: ArrayLike, T1: ArrayLike, law: str, t: Optional[ArrayLike], vmax: Optional[ArrayLike],
                   amax: Optional[ArrayLike], dt: float) -> Tuple[NDArray, NDArray, NDArray, NDArray]:
    """(t, poses (K, 4, 4), velocity (K, 6), acceleration (K, 6)) of the straight line T0 -> T1."""

# --- velocity-level IK (cpp/bindings/resolved_rate.cpp); use robokin ---------

def resolved_rate(chain: Chain, q: ArrayLike, twist: ArrayLike, damping: float = 0.0,
                  nullspace: Union[None, str, ArrayLike] = None, task: str = "pose") -> NDArray:
    """(dof,) joint velocities: damped least squares of the twist plus the null-space term."""
def servo(chain: Chain, poses: ArrayLike, q0: ArrayLike, dt: float, gain: float = 0.75, damping: float = 0.0,
          nullspace: Union[None, str, ArrayLike] = None, task: str = "pose",
          saturate: bool = True) -> Tuple[NDArray, NDArray, NDArray, NDArray]:
    """(q, qdot, error_p, error_r) of the resolved-rate servo along the targets."""

# --- pose helpers (cpp/bindings/pose.cpp); use robokin.pose ------------------

def pose_from_rpy(rpy: ArrayLike) -> NDArray:
    """Frames (4, 4) / (N, 4, 4) of R = Rz(yaw) Ry(pitch) Rx(roll)."""
def pose_rpy(T: ArrayLike) -> NDArray:
    """(roll, pitch, yaw) of rotations (3, 3) / frames (4, 4), or batches."""
def pose_from_quaternion(quaternion: ArrayLike) -> NDArray:
    """Frames of quaternions (w, x, y, z) (normalised first)."""
def pose_quaternion(T: ArrayLike) -> NDArray:
    """Unit quaternions (w, x, y, z), w >= 0."""
def pose_from_rotation_vector(rotation_vector: ArrayLike) -> NDArray:
    """Frames of rotation vectors (angle * unit axis)."""
def pose_rotation_vector(T: ArrayLike) -> NDArray:
    """Rotation vectors, angle in [0, pi]."""
def pose_exp(xi: ArrayLike) -> NDArray:
    """SE(3) exponential of twists (v, w)."""
def pose_log(T: ArrayLike) -> NDArray:
    """SE(3) logarithm (v, w), |w| in [0, pi]."""
def pose_error(target: ArrayLike, current: ArrayLike) -> NDArray:
    """The IK's pose error (p_t - p, rotation vector of R_t R^T)."""
# ---- UR-family closed form (robokin.closed.ur) ----
UR_POSTURES: Tuple[str, ...]
def ik_ur(target: ArrayLike, chain: Chain, limits: Union[str, None, Tuple[ArrayLike, ArrayLike]] = "default") -> IKSolutions: ...
def ik_ur_batch(
    targets: ArrayLike, chain: Chain, limits: Union[str, None, Tuple[ArrayLike, ArrayLike]] = "default"
) -> Tuple[NDArray, NDArray]: ...
def ur_geometry(chain: Chain) -> Tuple[Dict[str, float], NDArray]: ...
class _URSolver:
    def __init__(self, chain: Chain, limits: Union[str, None, Tuple[ArrayLike, ArrayLike]] = "default") -> None: ...
    def solve(self, target: ArrayLike) -> IKSolutions: ...
    def solve_batch(self, targets: ArrayLike) -> Tuple[NDArray, NDArray]: ...
def ik_3r(target: ArrayLike, chain: Chain, limits: Union[str, None, Tuple[ArrayLike, ArrayLike]] = "default") -> IKSolutions: ...
def det_3r(chain: Chain, q2: float, q3: float) -> float: ...
def cuspidal_3r(chain: Chain, resolution: int = 256) -> Dict[str, object]: ...
