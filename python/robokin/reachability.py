"""Reachability (capability) maps of serial arms: for each voxel of a grid, K tool orientations
are sampled and solved with the core's batch IK (``robokin.ik_batch``: the GIL released, every
core); a voxel's reachability index is the fraction solved, and its best manipulability the
largest ``chain.manipulability`` over the solutions found.

A 6R arm with a closed form (:func:`robokin.closed.family`) is solved by it instead, for the
``"pose"`` task (``ClosedSolver.solve_batch``, also on every core): a target counts as solved when
one of its solutions is within the joint limits, and the manipulability is the best over all of
those. The meaning is the numerical IK's, without its misses (a target the restarts fail to
solve) or its tolerance; the IK options and ``q0`` are then unused.

Determinism: target ``g = voxel * K + j`` (voxel in C order of the grid, j the orientation) draws
its orientation from a counter-based generator of ``(seed, g)`` and its IK restarts from
``seed + g``. Any split of the grid into blocks (threads, chunks, Dask workers) therefore gives
the same bits. The IK runs with an explicit number of restarts and no time budget, so nothing
depends on the machine's speed (unless a ``timeout`` is asked for).

Tasks: ``"pose"`` (3-D grid, K random rotations, uniform on SO(3)), ``"position"`` (3-D grid,
orientation free: K must be 1), ``"xyphi"`` (planar arms: 2-D grid, K angles phi uniform in
[-pi, pi)), ``"xy"`` (2-D grid, K = 1); by default the chain's natural task
(``chain.natural_task``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from . import _core
from ._checks import chain as check_chain
from ._checks import choice, finite, joints, number, real_array, whole
from ._checks import seed as check_seed
from ._core import IKOptions
from ._options import keywords, with_options
from .ik import ik_batch
from .pose import from_quaternion

__all__ = ["BLOCK", "IK_OPTIONS", "MAX_ORIENTATIONS", "MAX_VOXELS", "ORIENTATIONS", "ReachabilityMap",
           "ReachabilityPlan", "grid", "plan", "reachability"]

#: The IK options of a map unless told otherwise: explicit restarts, hence no time budget (a map
#: does not depend on the machine's speed), and tolerances of a micrometre / microradian; every other
#: field the IK's own. Read when the module is imported (the keywords of :func:`reachability` change
#: them per call).
IK_OPTIONS = IKOptions(tol_p=1e-6, tol_r=1e-6, restarts=10)
#: Orientations sampled per voxel by default, for the tasks with an orientation ("pose", "xyphi").
ORIENTATIONS = 50
#: Voxels per batch IK call of :func:`reachability` (bounds the memory, not the result).
BLOCK = 2048
#: The largest grid accepted (voxels) and the most orientations per voxel.
MAX_VOXELS = 10**8
MAX_ORIENTATIONS = 10**5

_PLANAR = ("xy", "xyphi")
_TASKS = ("pose", "position", "xy", "xyphi")
_MASK = np.uint64(0xFFFFFFFFFFFFFFFF)


@dataclass(frozen=True)
class ReachabilityMap:
    """A reachability map on a regular grid (2-D for the planar tasks, 3-D otherwise).

    Attributes:
        index: Per voxel, the fraction of the K orientations solved, in [0, 1]; shape
            ``(nx, ny)`` or ``(nx, ny, nz)``, element ``[i, j, k]`` at ``(x[i], y[j], z[k])``.
        manipulability: Per voxel, the best ``chain.manipulability`` (Yoshikawa, the task's rows)
            among the solutions found; 0 where none was found.
        axes: The voxel centres along each axis, ``(x, y)`` or ``(x, y, z)``.
        resolution: The voxel edge (m).
        orientations: K, orientations sampled per voxel.
        seed: The seed of the orientations and of the IK restarts.
        task: The IK task (``"pose"``, ``"position"``, ``"xy"`` or ``"xyphi"``).
    """

    index: np.ndarray
    manipulability: np.ndarray
    axes: Tuple[np.ndarray, ...]
    resolution: float
    orientations: int
    seed: int
    task: str

    @property
    def extent(self) -> Tuple[Tuple[float, float], ...]:
        """``((x_lo, x_hi), ...)``: the outer faces of the grid (m), for ``imshow``."""
        h = self.resolution / 2
        return tuple((float(a[0] - h), float(a[-1] + h)) for a in self.axes)

    @property
    def reachable_volume(self) -> float:
        """Volume (area for a planar map) of the voxels with a non-zero index (m^3 or m^2)."""
        return float(np.count_nonzero(self.index)) * self.resolution ** len(self.axes)


def grid(bounds, resolution) -> Tuple[np.ndarray, ...]:
    """Voxel centres along each axis for ``bounds`` ((2, 2) or (3, 2): ``(lo, hi)`` per axis, m)
    at ``resolution`` (m): ``ceil((hi - lo) / resolution)`` voxels per axis (one for ``lo == hi``),
    centred on the interval."""
    b = _bounds(bounds)
    h = number(resolution, "resolution", positive=True)
    counts = [max(1.0, math.ceil((hi - lo) / h - 1e-9)) for lo, hi in b]
    if math.prod(counts) > MAX_VOXELS:
        raise ValueError(f"resolution: the grid would have {math.prod(counts):.3g} voxels (at most {MAX_VOXELS})")
    return tuple((lo + hi) / 2 + (np.arange(int(n)) - (n - 1) / 2) * h for (lo, hi), n in zip(b, counts))


@with_options(IKOptions, defaults=IK_OPTIONS, exclude=("task",))
def reachability(chain: _core.Chain, bounds, resolution, orientations: Optional[int] = None, seed: int = 0,
                 task: Optional[str] = None, q0=None, **ik_options) -> ReachabilityMap:
    """The reachability map of ``chain`` over a grid.

    Args:
        chain: The serial chain; its joint limits are respected.
        bounds: ``((x_lo, x_hi), (y_lo, y_hi), (z_lo, z_hi))`` (m); ``((x_lo, x_hi), (y_lo, y_hi))``
            for the planar tasks.
        resolution: Voxel edge (m).
        orientations: K, the tool orientations sampled per voxel (must be 1 for ``"position"``,
            ``"xy"``); None: :data:`ORIENTATIONS` (50) for ``"pose"`` and ``"xyphi"``, 1 for the
            others.
        seed: Seed of the orientations and of the IK restarts (an int in ``[0, 2**64)``).
        task: ``"pose"``, ``"position"``, ``"xyphi"`` or ``"xy"`` (see the module docstring);
            None: ``chain.natural_task``.
        q0: IK start for every target, (dof,); None: the middle of each joint's finite limits, 0
            for unlimited joints.
        The options are the batch IK's (:func:`robokin.ik_batch`), with the map's defaults
        (:data:`IK_OPTIONS`); a ``timeout`` makes the map depend on the machine's speed.

    Returns:
        ReachabilityMap.

    Raises:
        ValueError: For bounds, resolution, orientations, seed, task, q0 or IK option values out of
            range (the message names the argument).
        TypeError: For a value of the wrong kind (a string for a number, a float for a count),
            or a keyword that is no IKOptions field (the message lists them).
    """
    p = plan(chain, bounds, resolution, orientations, seed, task, q0, **ik_options)
    count = p.voxels
    index = np.empty(count)
    manip = np.empty(count)
    for v0 in range(0, count, BLOCK):
        n = min(BLOCK, count - v0)
        index[v0:v0 + n], manip[v0:v0 + n] = p.block(v0, n)
    return p.result(index, manip)


@dataclass(frozen=True)
class ReachabilityPlan:
    """A reachability map's checked arguments, computable block by block in any order and on any
    worker (:func:`robokin.dask.reachability` does so): ``result`` of the blocks covering
    ``0 .. voxels - 1`` is :func:`reachability`'s map, bit for bit. Made by :func:`plan`."""

    chain: _core.Chain
    axes: Tuple[np.ndarray, ...]
    resolution: float
    orientations: int
    seed: int
    task: str
    q0: np.ndarray
    options: IKOptions  # the batch IK's, its task the map's
    closed: Optional[_core.ClosedSolver] = None  # the arm's closed form, which then replaces the IK

    @property
    def shape(self) -> Tuple[int, ...]:
        return tuple(len(a) for a in self.axes)

    @property
    def voxels(self) -> int:
        return math.prod(self.shape)

    def block(self, first: int, count: int) -> Tuple[np.ndarray, np.ndarray]:
        """(index, best manipulability) of the voxels ``first .. first + count - 1`` (C order)."""
        K = self.orientations
        cells = np.unravel_index(np.arange(first, first + count), self.shape)
        centres = np.column_stack([a[c] for a, c in zip(self.axes, cells)])
        g0 = first * K
        targets = _targets(self.task, np.repeat(centres, K, axis=0), _uniforms(self.seed, g0, count * K, 3))
        if self.closed is not None:
            q, _, within = self.closed.solve_batch(targets)  # (count K, 8, 6): every solution
            m = np.zeros(within.shape)
            if within.any():
                m[within] = self.chain.manipulability(q[within], task=self.task)
            return within.any(axis=1).reshape(count, K).sum(axis=1) / K, m.reshape(count, -1).max(axis=1)
        r = ik_batch(self.chain, targets, self.q0, seed=(self.seed + g0) % 2**64, **keywords(self.options))
        ok = r.success.reshape(count, K)
        m = np.zeros(count * K)
        if ok.any():
            m[r.success] = self.chain.manipulability(r.q[r.success], task=self.task)
        return ok.sum(axis=1) / K, m.reshape(count, K).max(axis=1)

    def result(self, index: np.ndarray, manip: np.ndarray) -> ReachabilityMap:
        """The map of every block's ``index`` and best manipulability ``manip``, joined in C order."""
        return ReachabilityMap(index.reshape(self.shape), manip.reshape(self.shape), self.axes, self.resolution,
                               self.orientations, self.seed, self.task)


@with_options(IKOptions, defaults=IK_OPTIONS, exclude=("task",))
def plan(chain: _core.Chain, bounds, resolution, orientations: Optional[int] = None, seed: int = 0,
         task: Optional[str] = None, q0=None, **ik_options) -> ReachabilityPlan:
    """The plan of :func:`reachability`'s map (``chain``, ``bounds``, ``resolution``,
    ``orientations``, ``seed``, ``task``, ``q0`` and the options as it takes them, the same
    checks), to compute its blocks with a scheduler of your own: ``p.block(first, count)`` gives
    the voxels ``first .. first + count - 1`` (C order) as (index, best manipulability),
    ``p.result(index, manip)`` the map."""
    check_chain(chain)
    task = chain.natural_task if task is None else choice(task, "task", _TASKS)
    axes = grid(bounds, resolution)
    if len(axes) != (2 if task in _PLANAR else 3):
        raise ValueError(f"bounds: task {task!r} takes {2 if task in _PLANAR else 3} (lo, hi) pairs, got {len(axes)}")
    free = task in ("position", "xy")  # the orientation is left free: one target per voxel
    K = (1 if free else ORIENTATIONS) if orientations is None else whole(orientations, "orientations", 1,
                                                                        MAX_ORIENTATIONS)
    if free and K != 1:
        raise ValueError(f"orientations: task {task!r} leaves the orientation free: expected 1, got {K}")
    s = check_seed(seed)
    options = IKOptions(**{**keywords(IK_OPTIONS), **ik_options, "task": task})  # names and kinds checked
    options.validate()  # ranges
    if q0 is not None:  # checked here: the closed form, when the arm has one, does not read it
        q0 = joints(chain, q0, "q0")
    if q0 is None:  # the middle of finite limits, else the finite one, else 0
        lo, hi = chain.limits
        q0 = np.zeros(chain.dof)
        q0 = np.where(np.isfinite(lo), lo, np.where(np.isfinite(hi), hi, q0))
        with np.errstate(invalid="ignore"):  # inf - inf where unlimited: not used
            q0 = np.where(np.isfinite(lo) & np.isfinite(hi), (lo + hi) / 2, q0)
    h = number(resolution, "resolution", positive=True)
    closed = _core.ClosedSolver.find(chain) if task == "pose" else None
    return ReachabilityPlan(chain, axes, h, K, s, task, q0, options, closed)


def _targets(task: str, centres: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The IK targets at ``centres`` (N, 2|3) with orientations drawn from uniforms ``u`` (N, 3)."""
    if task == "xy":
        return centres
    if task == "xyphi":
        return np.column_stack((centres, (2 * u[:, 0] - 1) * np.pi))
    if task == "position":
        return centres
    # Shoemake's uniform unit quaternion (w, x, y, z) from three uniforms.
    a, b = np.sqrt(1 - u[:, 0]), np.sqrt(u[:, 0])
    t1, t2 = 2 * np.pi * u[:, 1], 2 * np.pi * u[:, 2]
    quat = np.column_stack((b * np.cos(t2), a * np.sin(t1), a * np.cos(t1), b * np.sin(t2)))
    return from_quaternion(quat, centres)


def _splitmix64(x: np.ndarray) -> np.ndarray:
    """splitmix64's output function of uint64 counters (wrapping arithmetic)."""
    z = (x + np.uint64(0x9E3779B97F4A7C15)) & _MASK
    z = ((z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)) & _MASK
    z = ((z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)) & _MASK
    return z ^ (z >> np.uint64(31))


def _uniforms(seed: int, first: int, count: int, per: int) -> np.ndarray:
    """(count, per) uniforms in [0, 1) for targets first .. first + count - 1: a function of
    (seed, target, column) only (a counter-based generator)."""
    key = _splitmix64(np.array([seed], dtype=np.uint64))[0]
    g = np.arange(first, first + count, dtype=np.uint64)
    with np.errstate(over="ignore"):
        counters = (g[:, None] * np.uint64(per) + np.arange(per, dtype=np.uint64)[None, :]) ^ key
        return (_splitmix64(counters) >> np.uint64(11)).astype(np.float64) * 2.0**-53


def _bounds(bounds) -> np.ndarray:
    b = real_array(bounds, "bounds")
    if b.ndim != 2 or b.shape[1] != 2 or b.shape[0] not in (2, 3):
        raise ValueError(f"bounds: expected shape (2, 2) or (3, 2) ((lo, hi) per axis), got {b.shape}")
    finite(b, "bounds")
    if np.any(b[:, 0] > b[:, 1]):
        raise ValueError("bounds: a lower bound is above its upper bound")
    if np.any(np.abs(b) > 1e6):
        raise ValueError("bounds: coordinates beyond 1e6 m")
    return b

