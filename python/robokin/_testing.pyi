"""robokin._testing: hooks for robokin's tests and references for its benchmarks (not part of the API)."""

from typing import Tuple

from numpy.typing import ArrayLike, NDArray

from ._core import Chain

def parallel_for_throwing(count: int, on_caller: bool) -> int:
    """Runs count items of 1 ms on every core; those on the calling thread (or the others) throw."""
def throw(kind: str) -> None:
    """Throws a C++ exception: "kdl", "bad_alloc", "logic", "interrupted", anything else an int."""
def vmath_sincos(x: ArrayLike) -> Tuple[NDArray, NDArray]:
    """(sin x, cos x) from the batch paths' vectorised routines (SLEEF)."""
def vmath_atan2(y: ArrayLike, x: ArrayLike) -> NDArray:
    """atan2(y, x) from the batch paths' vectorised routine (SLEEF)."""
def hessian_times(chain: Chain, q: ArrayLike, a: ArrayLike) -> NDArray:
    """sum_j a_j dJ/dq_j (6, dof): Halley's kinematic Hessian term."""

class KdlIk:
    """Benchmark reference: KDL's ChainIkSolverPos_LMA ("lma", "lma_unit") or ChainIkSolverPos_NR_JL ("nr_jl")."""
    def __init__(self, chain: Chain, solver: str = "lma", max_iter: int = 500, eps: float = 1e-5) -> None: ...
    def solve(self, target: ArrayLike, q0: ArrayLike) -> Tuple[NDArray, int]: ...
