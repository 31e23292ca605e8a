"""robokin over Dask (the ``[dask]`` extra: ``dask``, ``distributed``): batch FK, batch IK,
reachability maps and the 3-RRR design sweeps cut into ``dask.array`` chunks, each chunk one call
of the core's GIL-free batch routine on a worker.

The results are bit-identical to the one-machine calls for any chunking and any number of workers:
every random draw is derived from the seed and the item's global index (row of the batch, voxel
and orientation of the map), never from the chunk (``ik_batch``'s target ``k`` uses ``seed + k``).
For the batch IK that needs an explicit ``restarts`` (no time budget: with one, how many restarts
fit depends on the machine, on one machine too). Models (``Chain``, ``RRR3``) pickle, so they
travel to the workers with the tasks.

Threads: the core's batch calls use every core of a machine (``ROBOKIN_NUM_THREADS`` caps them).
Run **either** one worker process per machine with its threads (``dask worker --nworkers 1
--nthreads 1`` and the core spreads each chunk over the cores), **or** one single-threaded worker
per core with ``ROBOKIN_NUM_THREADS=1`` in the workers' environment (``--nworkers N --nthreads 1``)
-- never both (N workers each starting N threads oversubscribe the machine N times).

Interrupting (Ctrl-C) a computation started here cancels its tasks on the cluster.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass
from typing import Optional

import numpy as np

try:
    import dask
    import dask.array as da
except ImportError as exc:  # pragma: no cover - depends on the environment
    raise ImportError("robokin.dask needs dask: pip install 'robokin[dask]'") from exc

from . import _core, rrr3_design
from ._checks import chain as check_chain
from ._checks import real_array, whole
from ._checks import seed as check_seed
from ._options import with_options
from .ik import ik_batch as _ik_batch
from .reachability import BLOCK as _BLOCK
from .reachability import IK_OPTIONS as _IK_OPTIONS
from .reachability import ReachabilityMap, plan

__all__ = ["IKBatchArrays", "area_vs_platform_radius", "best_l2", "fk", "ik_batch", "reachability",
           "region_areas"]


@dataclass(frozen=True)
class IKBatchArrays:
    """What :func:`ik_batch` gives: the fields of an ``IKBatchResult`` as arrays (lazy dask
    arrays, or numpy arrays after :meth:`compute`)."""

    q: object           # (N, dof) joints
    success: object     # (N,) verified successes
    iterations: object  # (N,) iterations
    attempts: object    # (N,) 1 + restarts used
    error_p: object     # (N,) position errors (m)
    error_r: object     # (N,) orientation errors (rad)

    def compute(self) -> "IKBatchArrays":
        """The numpy arrays (one computation for all the fields; Ctrl-C cancels it)."""
        return IKBatchArrays(*_compute(self.q, self.success, self.iterations, self.attempts, self.error_p,
                                       self.error_r))


def fk(chain: _core.Chain, q, chunks="auto"):
    """Tool poses (N, 4, 4) of configurations ``q`` (N, dof) as a dask array, chunk by chunk with
    ``chain.fk`` (GIL released). ``q``: a numpy or dask array; ``chunks``: rows per chunk when
    ``q`` is not already a dask array."""
    check_chain(chain)
    qd = _rows(q, "q", chunks)
    chain.fk(np.empty((0,) + qd.shape[1:]))  # the one-machine call's checks (shape), before any work
    return qd.map_blocks(_fk_block, chain, chunks=(qd.chunks[0], (4,), (4,)), new_axis=2, dtype=np.float64,
                         meta=np.empty((0, 4, 4)))


@with_options(_core.IKOptions)
def ik_batch(chain: _core.Chain, targets, q0, seed: int = 0, chunks="auto", **options) -> IKBatchArrays:
    """:func:`robokin.ik_batch` over chunks of ``targets`` ((N, 4, 4) frames for ``task="pose"``,
    (N, rows) otherwise; numpy or dask), one start ``q0`` (dof,) for all. Target ``k`` uses
    ``seed + k`` whatever chunk it is in: with ``restarts`` given the arrays are the one-machine
    call's, bit for bit. The options are robokin.ik_batch's (``path`` is sequential: not here).

    Returns:
        IKBatchArrays of dask arrays (``.compute()`` for numpy).
    """
    check_chain(chain)
    if "path" in options:
        raise ValueError("options: path=True is sequential (each target starts from the previous): use robokin.ik_batch")
    check_seed(seed)  # an int, not None: a random seed would differ per chunk
    td = _rows(targets, "targets", chunks)
    _ik_batch(chain, np.empty((0,) + td.shape[1:]), q0, seed=int(seed), **options)  # the one-machine checks
    n = chain.dof
    packed = td.map_blocks(_ik_block, chain, q0, int(seed), options, chunks=(td.chunks[0], (n + 5,)),
                           drop_axis=list(range(2, td.ndim)), dtype=np.float64, meta=np.empty((0, n + 5)))
    return IKBatchArrays(packed[:, :n], packed[:, n] > 0.5, packed[:, n + 1].astype(np.int32),
                         packed[:, n + 2].astype(np.int32), packed[:, n + 3], packed[:, n + 4])


@with_options(_core.IKOptions, defaults=_IK_OPTIONS, exclude=("task",))
def reachability(chain: _core.Chain, bounds, resolution, orientations: Optional[int] = None, seed: int = 0,
                 task: Optional[str] = None, q0=None, chunks: int = _BLOCK, **ik_options) -> ReachabilityMap:
    """:func:`robokin.reachability.reachability` with the voxels cut into chunks of ``chunks``
    voxels, computed with Dask (the active ``distributed.Client`` when there is one). The same
    arguments (``chain``, ``bounds``, ``resolution``, ``orientations``, ``seed``, ``task``, ``q0``)
    and options, and the same map, bit for bit, whatever the chunking and the workers."""
    p = plan(chain, bounds, resolution, orientations, seed, task, q0, **ik_options)
    whole(chunks, "chunks", 1, 2**63 - 1, "voxels per chunk")
    voxels = da.arange(p.voxels, chunks=int(chunks), dtype=np.int64)
    out = voxels.map_blocks(_reach_block, p, new_axis=1, chunks=(voxels.chunks[0], (2,)), dtype=np.float64,
                            meta=np.empty((0, 2)))
    (table,) = _compute(out)
    return p.result(table[:, 0].copy(), table[:, 1].copy())


@with_options(_core.RRR3WorkspaceOptions)
def region_areas(robots, *, chunks="auto", **options):
    """The 3-RRR sweep's areas (``RRR3Workspace.area``) of each row ``(base_radius,
    platform_radius, l1, l2)`` of ``robots`` (N, 4) as a dask array (N,), chunk by chunk (``chunks``
    rows each, dask's chunk sizes) with the core's batch call on the maps of the options."""
    rd = _rows(robots, "robots", chunks)
    _core.rrr3_region_areas(np.empty((0,) + rd.shape[1:]), **options)  # the one-machine checks
    return rd.map_blocks(_areas_block, options, drop_axis=1, dtype=np.float64, meta=np.empty((0,)))


def _on_dask(study):
    """The design study ``study`` of robokin.rrr3_design with its workspace maps on Dask: the same
    signature, ``areas`` replaced by ``chunks`` (robots per chunk)."""
    def on_dask(*args, chunks="auto", **kwargs):
        return study(*args, areas=_distributed_areas(chunks), **kwargs)

    sig = inspect.signature(study)
    params = [p.replace(name="chunks", default="auto") if p.name == "areas" else p for p in sig.parameters.values()]
    on_dask.__signature__ = sig.replace(parameters=params)
    on_dask.__name__ = on_dask.__qualname__ = study.__name__
    on_dask.__doc__ = (f":func:`robokin.rrr3_design.{study.__name__}` with its workspace maps on Dask, ``chunks``"
                       f" robots per chunk.\n\n{study.__doc__}")
    on_dask.options_class, on_dask.option_names = study.options_class, study.option_names
    return on_dask


area_vs_platform_radius = _on_dask(rrr3_design.area_vs_platform_radius)
best_l2 = _on_dask(rrr3_design.best_l2)


# --- the work of one chunk (runs on the workers) ----------------------------------------------------

def _fk_block(q: np.ndarray, chain: _core.Chain) -> np.ndarray:
    return chain.fk(q) if len(q) else np.empty((0, 4, 4))


def _ik_block(targets: np.ndarray, chain: _core.Chain, q0, seed: int, options: dict, block_info=None) -> np.ndarray:
    first = block_info[0]["array-location"][0][0] if block_info else 0
    if not len(targets):
        return np.empty((0, chain.dof + 5))
    r = _ik_batch(chain, targets, q0, seed=(seed + first) % 2**64, **options)
    return np.column_stack((r.q, r.success, r.iterations, r.attempts, r.error_p, r.error_r))


def _reach_block(voxels: np.ndarray, p) -> np.ndarray:
    if not len(voxels):
        return np.empty((0, 2))
    first = int(voxels[0])
    index, manip = p.block(first, len(voxels))
    return np.column_stack((index, manip))


def _areas_block(robots: np.ndarray, options: dict) -> np.ndarray:
    return _core.rrr3_region_areas(robots, **options) if len(robots) else np.empty((0,))


def _distributed_areas(chunks):
    def areas(robots, **options):
        (out,) = _compute(region_areas(robots, chunks=chunks, **options))
        return out
    return areas


# --- helpers ------------------------------------------------------------------------------------------

def _rows(a, name: str, chunks):
    """``a`` as a float64 dask array chunked along its first axis only (whole rows per chunk)."""
    if not isinstance(a, da.Array):
        a = real_array(a, name)
        if a.ndim < 1:
            raise ValueError(f"{name}: expected a batch (N, ...), got a scalar")
        if not (isinstance(chunks, str) and chunks == "auto"):
            chunks = whole(chunks, "chunks", 1, 2**63 - 1, "rows per chunk, or 'auto'")
        a = da.from_array(a, chunks=(chunks,) + (-1,) * (a.ndim - 1))
    elif a.dtype.kind not in "biuf":
        raise TypeError(f"{name}: expected real numbers, got a {a.dtype} dask array")
    elif a.ndim < 1:
        raise ValueError(f"{name}: expected a batch (N, ...), got a scalar")
    return a.astype(np.float64).rechunk({i: -1 for i in range(1, a.ndim)})


def _client():
    try:
        from distributed import get_client
        return get_client()
    except (ImportError, ValueError):
        return None


def _compute(*arrays):
    """Computes on the active distributed client (cancelling the tasks on Ctrl-C), else with
    dask's default scheduler."""
    client = _client()
    if client is None:
        return dask.compute(*arrays)
    futures = client.compute(list(arrays))
    try:
        return tuple(client.gather(futures))
    except KeyboardInterrupt:
        client.cancel(futures)
        raise
