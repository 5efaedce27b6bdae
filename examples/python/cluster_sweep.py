#!/usr/bin/python3
"""A 1 M-pose collision sweep on a Dask cluster, checked against the serial run.

Mesh B (a small box) is placed at --poses random poses around mesh A; every pose is one exact
collide query (--query distance: one exact distance query, about ten times costlier). antcd.cluster.collide_batch sends the two Models to each worker once (pickled as
their model-file bytes, nothing is rebuilt there), maps chunks of --chunk poses as
client.submit(antcd.collide_batch, ...) tasks and joins the answers in order. With --check the
serial antcd.collide_batch runs too and the two must agree entry for entry. Prints both times.

Where the cluster is:
  * default: a LocalCluster on this machine with --workers worker processes (one thread each);
  * --scheduler tcp://HOST:8786: an existing cluster. Start one with `dask-scheduler` on HOST and
    `dask-worker tcp://HOST:8786 --nthreads 1` on each machine (Debian python3-distributed; every
    worker needs the same antcd importable). Pass --threads N to let each task use N C++ threads
    when workers have more cores than Dask threads.
Mesh arguments may be model files (*.antcd, antcd info MESH --save M.antcd), which load without a
build; they are read here, on the client, only.

Usage: examples/python/cluster_sweep.py [MESH_A] [--poses 1000000] [--chunk 50000]
       [--query collide|distance] [--workers 2] [--scheduler tcp://HOST:8786] [--check]

The poses travel from this process to the workers (128 bytes each): on one machine a collide
sweep (about a microsecond per query) is faster in process (antcd.collide_batch with threads=0);
the cluster pays off with more machines and costlier queries.
"""
import argparse
import time

import numpy as np

import antcd
import antcd.cluster

MODELS = "/usr/share/assimp/models"


def random_poses(rng, count, extent):
    """count uniformly random rotations (unit quaternions) with translations in [-extent, extent]^3."""
    q = rng.normal(size=(count, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    poses = np.zeros((count, 4, 4))
    poses[:, 0, 0] = 1 - 2 * (y * y + z * z)
    poses[:, 0, 1] = 2 * (x * y - w * z)
    poses[:, 0, 2] = 2 * (x * z + w * y)
    poses[:, 1, 0] = 2 * (x * y + w * z)
    poses[:, 1, 1] = 1 - 2 * (x * x + z * z)
    poses[:, 1, 2] = 2 * (y * z - w * x)
    poses[:, 2, 0] = 2 * (x * z - w * y)
    poses[:, 2, 1] = 2 * (y * z + w * x)
    poses[:, 2, 2] = 1 - 2 * (x * x + y * y)
    poses[:, :3, 3] = rng.uniform(-extent, extent, size=(count, 3))
    poses[:, 3, 3] = 1
    return poses


def main():
    from distributed import Client, LocalCluster  # Debian python3-distributed

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh_a", nargs="?", default=f"{MODELS}/PLY/Wuson.ply")
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--chunk", type=int, default=50_000)
    parser.add_argument("--query", choices=("collide", "distance"), default="collide")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    parser.add_argument("--threads", type=int, default=1, help="C++ threads per task")
    parser.add_argument("--scheduler", help="address of a running scheduler (tcp://HOST:8786)")
    parser.add_argument("--check", action="store_true", help="also run serially and compare")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    a = antcd.Model.load(args.mesh_a)
    size = float(np.max(a.bounds[1] - a.bounds[0]))
    half = np.full(3, 0.1 * size)
    box = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
    faces = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    b = antcd.Model(box, faces, name="probe box")
    centre = 0.5 * (a.bounds[0] + a.bounds[1])
    poses_b = random_poses(np.random.default_rng(args.seed), args.poses, 0.6 * size)
    poses_b[:, :3, 3] += centre

    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        workers = len(client.scheduler_info()["workers"])
        start = time.perf_counter()
        on_cluster = getattr(antcd.cluster, f"{args.query}_batch")
        answers = on_cluster(client, a, b, None, poses_b, chunk=args.chunk, threads=args.threads)
        cluster_s = time.perf_counter() - start
        summary = (f"{int(answers.sum())} colliding" if args.query == "collide"
                   else f"{int((answers == 0).sum())} touching")
        print(f"{args.poses} {args.query} poses on {workers} workers: {summary}, "
              f"{cluster_s:.2f} s ({args.poses / cluster_s:,.0f} poses/s)")
        if args.check:
            start = time.perf_counter()
            serial = getattr(antcd, f"{args.query}_batch")(a, b, None, poses_b, threads=1)
            serial_s = time.perf_counter() - start
            same = bool(np.array_equal(serial, answers))
            print(f"serial, one thread: {serial_s:.2f} s ({args.poses / serial_s:,.0f} poses/s); "
                  f"cluster/serial throughput {serial_s / cluster_s:.2f}x; identical: {same}")
            if not same:
                raise SystemExit("the cluster's answers differ from the serial run")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    main()
