"""robokin.dask on a real cluster of two worker processes: FK, batch IK, reachability
maps and the 3-RRR sweeps give the one-machine call's bits for any chunking; a worker killed in
the middle of a map is replaced and the map is still the same; Ctrl-C on the client cancels the
tasks on the cluster. One cluster for the module."""

import os
import signal
import threading
import time

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")
import robokin as rk  # noqa: E402
import robokin.dask as rkd  # noqa: E402
from robokin import rrr3_design  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                       env={"ROBOKIN_NUM_THREADS": "1"})
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def worker_pids(client):
    return client.run(os.getpid)


def test_models_reach_the_workers_and_compute_the_same_bits(client):
    chain = rk.robots.panda()
    q = np.random.default_rng(0).uniform(-2, 2, (50, 7))
    remote = client.submit(lambda c, q: (c.fk(q), repr(c), c == rk.robots.panda()), chain, q).result()
    assert np.array_equal(remote[0], chain.fk(q)) and remote[1] == repr(chain) and remote[2]


@pytest.mark.parametrize("chunks", [1000, 97, 13])
def test_fk_is_the_one_machine_call(client, chunks):
    chain = rk.robots.ur5()
    q = np.random.default_rng(1).uniform(-3, 3, (1000, 6))
    out = rkd.fk(chain, q, chunks=chunks)
    assert out.shape == (1000, 4, 4) and out.numblocks[0] == -(-1000 // chunks)
    assert np.array_equal(out.compute(), chain.fk(q))


@pytest.mark.parametrize("chunks", [200, 37])
def test_ik_batch_is_the_one_machine_call(client, chunks):
    chain = rk.robots.ur5()
    q = np.random.default_rng(2).uniform(-3, 3, (200, 6))
    targets = chain.fk(q)
    targets[::7, 0, 3] += 5.0  # some unreachable: they use every restart
    got = rkd.ik_batch(chain, targets, np.zeros(6), seed=9, chunks=chunks, restarts=3).compute()
    ref = rk.ik_batch(chain, targets, np.zeros(6), seed=9, restarts=3)
    for name in ("q", "success", "iterations", "attempts", "error_p", "error_r"):
        a, b = getattr(got, name), getattr(ref, name)
        assert a.dtype == b.dtype and np.array_equal(a, b), name
    assert 0 < ref.success.mean() < 1
    # A planar task takes (N, rows) targets.
    p3 = rk.robots.planar_3r()
    xy = np.random.default_rng(3).uniform(-2, 2, (60, 2))
    got = rkd.ik_batch(p3, xy, np.zeros(3), task="xy", seed=1, chunks=chunks // 10, restarts=2).compute()
    assert np.array_equal(got.q, rk.ik_batch(p3, xy, np.zeros(3), task="xy", seed=1, restarts=2).q)


MAP = dict(bounds=((-0.8, 0.8), (-0.8, 0.8), (0.0, 0.6)), resolution=0.2, orientations=4, seed=3, restarts=2)


@pytest.fixture(scope="module")
def one_machine_map():
    return rk.reachability(rk.robots.ur5(), **MAP)


@pytest.mark.parametrize("chunks", [5, 29, 10_000])
def test_reachability_is_the_one_machine_map(client, one_machine_map, chunks):
    got = rkd.reachability(rk.robots.ur5(), chunks=chunks, **MAP)
    assert got.index.tobytes() == one_machine_map.index.tobytes()
    assert got.manipulability.tobytes() == one_machine_map.manipulability.tobytes()
    assert 0 < got.index.mean() < 1


def test_rrr3_sweeps_are_the_one_machine_sweeps(client):
    got = rkd.best_l2([0.08, 0.1, 0.12], [0.08, 0.1], n=30, chunks=2)
    ref = rrr3_design.best_l2([0.08, 0.1, 0.12], [0.08, 0.1], n=30)
    assert np.array_equal(got.area, ref.area) and np.array_equal(got.best_l2, ref.best_l2)
    curve = rkd.area_vs_platform_radius([0.03, 0.05, 0.07], n=30, chunks=1)
    assert np.array_equal(curve.area, rrr3_design.area_vs_platform_radius([0.03, 0.05, 0.07], n=30).area)
    assert curve.area.min() > 0


def test_a_worker_killed_mid_run_is_replaced_and_the_map_is_the_same(client):
    chain = rk.robots.ur5()
    args = dict(MAP, orientations=12)
    ref = rk.reachability(chain, **args)
    before = set(worker_pids(client).values())
    killed = []

    def kill_one_when_busy():
        deadline = time.time() + 30
        while time.time() < deadline and not killed:
            busy = [w for w, tasks in client.processing().items() if tasks]
            if busy:
                pid = worker_pids(client)[busy[0]]
                os.kill(pid, signal.SIGKILL)
                killed.append(pid)
            time.sleep(0.02)

    killer = threading.Thread(target=kill_one_when_busy)
    killer.start()
    got = rkd.reachability(chain, chunks=3, **args)
    killer.join()
    assert killed and killed[0] in before
    assert got.index.tobytes() == ref.index.tobytes()
    assert got.manipulability.tobytes() == ref.manipulability.tobytes()
    client.wait_for_workers(2, timeout=30)  # the nanny started a new one
    assert killed[0] not in set(worker_pids(client).values())


def test_ctrl_c_on_the_client_cancels_the_tasks(client):
    chain = rk.robots.ur5()
    # What Ctrl-C does: SIGINT to the client's process.
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    started = time.time()
    with pytest.raises(KeyboardInterrupt):
        # A map of some minutes on two single-threaded workers.
        rkd.reachability(chain, ((-1, 1), (-1, 1), (-1, 1)), 0.05, orientations=50, chunks=50, restarts=10)
    timer.cancel()
    assert time.time() - started < 5
    deadline = time.time() + 15
    while time.time() < deadline and any(client.processing().values()):
        time.sleep(0.1)
    assert not any(client.processing().values()), "tasks still running after Ctrl-C"
    assert not client.futures  # the client holds nothing of the cancelled map


def test_bad_arguments(client):
    chain = rk.robots.ur5()
    with pytest.raises(TypeError, match=r"seed: expected an int \(a random seed\), got None"):
        rkd.ik_batch(chain, chain.fk(np.zeros((2, 6))), np.zeros(6), seed=None)  # would differ per chunk
    with pytest.raises(ValueError, match="path"):
        rkd.ik_batch(chain, chain.fk(np.zeros((2, 6))), np.zeros(6), path=True)
    with pytest.raises(ValueError, match="q"):
        rkd.fk(chain, np.zeros((3, 5)))
    with pytest.raises(ValueError, match="chunks"):
        rkd.reachability(chain, chunks=0, **MAP)
    with pytest.raises(ValueError, match="resolution"):
        rkd.reachability(chain, **{**MAP, "resolution": -1})
    with pytest.raises(TypeError, match="chain"):
        rkd.fk("ur5", np.zeros((3, 6)))
