"""Reachability map of the UR5: 5 cm voxels, 50 orientations each, on one thread, on
every core (the batch IK's threads), and on a distributed.LocalCluster of one single-threaded
worker process per core (ROBOKIN_NUM_THREADS=1 in the workers). Prints the times, the parallel
efficiency (one-thread time / (cores x time)) and the throughput per core, and checks that the three
maps are the same bits. The UR5 has a closed form (robokin.closed.family), which the map uses: the
same map made with the numerical batch IK instead (the plan without its closed form), on every
core, gives the ratio of the two and checks that they mean the same (every target the IK solves the
closed form solves, with a manipulability at least as good). Then the cost of shipping a chain to a
worker: pickling it, and unpickling it on the worker, against building it from its DH table in the
same process.

The whole map (x, y in [-0.9, 0.9], z in [-0.8, 1.0]: 36 x 36 x 36 voxels, 2.3 million IK solves)
takes minutes on a 2-core machine; by default a slab of it runs (``--z``), ``--full`` runs it all.

    python benchmarks/bench_reachability.py [--full] [--z LO HI] [--resolution M] [--orientations K]
"""

from __future__ import annotations

import argparse
import os
import pickle
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _timing import fmt, once, per_call, ratio_line  # noqa: E402

import robokin as rk  # noqa: E402
from robokin.reachability import grid  # noqa: E402

FULL_Z = (-0.8, 1.0)
SLAB_Z = (0.0, 0.2)
XY = (-0.9, 0.9)


def timed(fn):
    start = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - start


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help=f"the whole map (z in {FULL_Z})")
    parser.add_argument("--z", type=float, nargs=2, default=None, help=f"z range (m), default {SLAB_Z}")
    parser.add_argument("--resolution", type=float, default=0.05)
    parser.add_argument("--orientations", type=int, default=50)
    parser.add_argument("--no-cluster", action="store_true", help="skip the LocalCluster run")
    args = parser.parse_args([] if argv is None else argv)
    z = FULL_Z if args.full else tuple(args.z or SLAB_Z)
    bounds = (XY, XY, z)
    chain = rk.robots.ur5()
    cores = os.cpu_count() or 1
    shape = tuple(len(a) for a in grid(bounds, args.resolution))
    solves = int(np.prod(shape)) * args.orientations
    print(f"UR5 reachability map: bounds {bounds} m, {args.resolution} m voxels {shape}, {args.orientations} "
          f"orientations: {solves} IK solves ({'the whole map' if args.full else 'a slab; --full for all'}), "
          f"{cores} cores", flush=True)
    kw = dict(orientations=args.orientations, seed=0)

    saved = os.environ.get("ROBOKIN_NUM_THREADS")
    os.environ["ROBOKIN_NUM_THREADS"] = "1"
    try:
        one, t1 = timed(lambda: rk.reachability(chain, bounds, args.resolution, **kw))
    finally:
        if saved is None:
            del os.environ["ROBOKIN_NUM_THREADS"]
        else:
            os.environ["ROBOKIN_NUM_THREADS"] = saved
    print(f"  one thread        {t1:8.2f} s   {solves / t1:9.0f} solves/s per core   "
          f"(reachable share of the voxels: {np.count_nonzero(one.index) / one.index.size:.2f}, "
          f"mean index {one.index.mean():.3f})", flush=True)
    every, tn = timed(lambda: rk.reachability(chain, bounds, args.resolution, **kw))
    assert every.index.tobytes() == one.index.tobytes() and every.manipulability.tobytes() == one.manipulability.tobytes()
    print(f"  all {cores} cores       {tn:8.2f} s   speed-up {t1 / tn:5.2f}x   parallel efficiency "
          f"{t1 / (cores * tn):5.1%}   (same bits)", flush=True)

    closed_against_ik(chain, bounds, args.resolution, kw, tn)

    if not args.no_cluster:
        import distributed

        import robokin.dask as rkd

        with distributed.LocalCluster(n_workers=cores, threads_per_worker=1, processes=True, dashboard_address=None,
                                      env={"ROBOKIN_NUM_THREADS": "1"}) as cluster, distributed.Client(cluster) as client:
            client.run(lambda: __import__("robokin"))  # workers warm (imports) before the clock starts
            spread, tc = timed(lambda: rkd.reachability(chain, bounds, args.resolution, chunks=512, **kw))
            assert spread.index.tobytes() == one.index.tobytes()
            assert spread.manipulability.tobytes() == one.manipulability.tobytes()
            print(f"  LocalCluster {cores}x1   {tc:8.2f} s   speed-up {t1 / tc:5.2f}x   parallel efficiency "
                  f"{t1 / (cores * tc):5.1%}   (same bits; 512-voxel chunks)", flush=True)
            shipping(chain, client)
    else:
        shipping(chain, None)
    return []


def closed_against_ik(chain, bounds, resolution, kw, t_closed):
    """The map with the numerical batch IK (the plan's closed form removed) against the closed form's."""
    import dataclasses

    from robokin.reachability import plan

    p = plan(chain, bounds, resolution, **kw)
    assert p.closed is not None, "the UR5 has a closed form"
    closed = p.result(*p.block(0, p.voxels))
    numeric = dataclasses.replace(p, closed=None)
    ik_map, t_ik = timed(lambda: numeric.result(*numeric.block(0, numeric.voxels)))
    assert np.all(ik_map.index <= closed.index)
    both = (ik_map.index > 0) & (closed.index > 0)
    assert np.all(ik_map.manipulability[both] <= closed.manipulability[both] + 1e-5)
    print(f"  batch IK instead  {t_ik:8.2f} s   closed form / IK: {t_closed / t_ik:6.3f}x   (mean index "
          f"{ik_map.index.mean():.4f} against {closed.index.mean():.4f}; "
          f"{np.count_nonzero(ik_map.index < closed.index)} voxels where the IK's restarts missed some)", flush=True)


def shipping(chain, client):
    """Pickling a chain, and unpickling it (here and on a worker), against building it from DH."""
    rows = [(0.0, np.pi / 2, 0.089159, 0.0, "R"), (-0.425, 0.0, 0.0, 0.0, "R"), (-0.39225, 0.0, 0.0, 0.0, "R"),
            (0.0, np.pi / 2, 0.10915, 0.0, "R"), (0.0, -np.pi / 2, 0.09465, 0.0, "R"), (0.0, 0.0, 0.0823, 0.0, "R")]
    ns = {"rk": rk, "pickle": pickle, "rows": rows, "limits": chain.limits, "chain": chain,
          "blob": pickle.dumps(chain)}
    build = per_call("rk.Chain.from_dh(rows, limits=limits)", ns)
    goals: list = []
    print(f"  a pickled UR5 is {len(ns['blob'])} bytes", flush=True)
    ratio_line(goals, "pickle.dumps(chain)", per_call("pickle.dumps(chain)", ns), "from_dh", build)
    ratio_line(goals, "pickle.loads(blob)", per_call("pickle.loads(blob)", ns), "from_dh", build)
    if client is not None:
        def on_worker(blob, rows, limits):
            import pickle as p
            import timeit

            import robokin as r
            n = 2000
            loads = min(timeit.repeat(lambda: p.loads(blob), number=n, repeat=5)) / n
            made = min(timeit.repeat(lambda: r.Chain.from_dh(rows, limits=limits), number=n, repeat=5)) / n
            return loads, made

        loads, made = client.submit(on_worker, ns["blob"], rows, chain.limits).result()
        print(f"  on a worker: pickle.loads(blob) {fmt(loads)}  |  from_dh {fmt(made)}  ->  {loads / made:6.3f}x",
              flush=True)
        roundtrip = once(lambda: client.submit(len, ns["blob"], pure=False).result(), repeat=20)
        print(f"  (a task's round trip through the scheduler, for scale: {fmt(roundtrip[0])}, median "
              f"{fmt(roundtrip[1]).strip()})", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
