#!/usr/bin/python3
"""Throughput of antcd.collide_batch / distance_batch against a Python loop of single queries.

Small meshes (a 16x8 UV sphere and a box, the issue's "small meshes" case), the same random pose
pairs for every side; best of --rounds runs of each. Prints microseconds per query and the
speed-up of the batch (1 thread, and all hardware threads) over the loop. Target: >= 5x.
A benchmark, not a test: on a shared machine absolute times are noise.

Usage: /usr/bin/python3 python/bench/batch.py [--pairs 20000] [--rounds 5]
(with the build tree's package: PYTHONPATH=build/python).
"""
import argparse
import os
import sys
import time

import numpy as np

import antcd

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
from conftest import box_mesh, random_pose, sphere_mesh  # noqa: E402


def best(rounds, f):
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=20000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--extent", type=float, default=2.0, help="poses spread over [-extent, extent]^3")
    args = parser.parse_args()
    a, b = antcd.Model(*sphere_mesh(1.0, 16, 8)), antcd.Model(*box_mesh((0.4, 0.3, 0.2)))
    rng = np.random.default_rng(1)
    poses_a = np.stack([random_pose(rng, args.extent) for _ in range(args.pairs)])
    poses_b = np.stack([random_pose(rng, args.extent) for _ in range(args.pairs)])
    n = args.pairs
    for name, single, batch in (
            ("collide", lambda pa, pb: antcd.collide(a, pa, b, pb).colliding, antcd.collide_batch),
            ("distance", lambda pa, pb: antcd.distance(a, pa, b, pb).distance, antcd.distance_batch)):
        t_loop = best(args.rounds, lambda: [single(pa, pb) for pa, pb in zip(poses_a, poses_b)])
        t_one = best(args.rounds, lambda: batch(a, b, poses_a, poses_b, threads=1))
        t_all = best(args.rounds, lambda: batch(a, b, poses_a, poses_b))
        print(f"{name}: python loop {t_loop / n * 1e6:.2f} us/query; batch 1 thread "
              f"{t_one / n * 1e6:.2f} us/query ({t_loop / t_one:.1f}x); batch {os.cpu_count()} "
              f"threads {t_all / n * 1e6:.2f} us/query ({t_loop / t_all:.1f}x)")


if __name__ == "__main__":
    main()
