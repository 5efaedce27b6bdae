#!/usr/bin/python3
"""What a boolean collide() costs through Python on top of the same query in C++.

Both are timed in this one process and run, round after round, alternating: the C++ loop inside
the module (antcd._antcd._time_collide_cpp, result storage reused as a C++ caller would) and a
Python loop of antcd.collide() calls. The overhead is the median over rounds of (Python - C++)
per call. Target: <= 2 us. A benchmark, not a test: on a shared machine absolute times are noise;
say whether the run was contended when quoting it.

Usage: /usr/bin/python3 python/bench/overhead.py [--rounds 15] [--calls 20000] [--models DIR]
(with the build tree's package: PYTHONPATH=build/python).
"""
import argparse
import os
import statistics
import time

import numpy as np

import antcd
from antcd import _antcd


def python_loop(a, pose_a, b, pose_b, calls):
    collide = antcd.collide
    start = time.perf_counter()
    for _ in range(calls):
        collide(a, pose_a, b, pose_b)
    return (time.perf_counter() - start) / calls


def measure(label, a, pose_a, b, pose_b, rounds, calls):
    verdict = antcd.collide(a, pose_a, b, pose_b).colliding
    cpp, py = [], []
    for _ in range(rounds):
        cpp.append(_antcd._time_collide_cpp(a, pose_a, b, pose_b, calls))
        py.append(python_loop(a, pose_a, b, pose_b, calls))
    extra = [p - c for p, c in zip(py, cpp)]
    us = 1e6
    print(f"{label:<44} {'collide' if verdict else 'apart':>7} {statistics.median(cpp) * us:9.3f} "
          f"{statistics.median(py) * us:9.3f} {statistics.median(extra) * us:9.3f} "
          f"[{min(extra) * us:.3f}, {max(extra) * us:.3f}]")
    return statistics.median(extra)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--calls", type=int, default=20000)
    parser.add_argument("--models", default=os.environ.get("ANTCD_ASSIMP_MODELS", "/usr/share/assimp/models"))
    args = parser.parse_args()

    wuson = antcd.Model.load(os.path.join(args.models, "PLY", "Wuson.ply"))
    size = float(np.ptp(wuson.bounds[:, 0]))
    apart = np.eye(4)
    apart[0, 3] = 3 * size
    touching = np.eye(4)
    touching[0, 3] = 0.5 * size
    print(f"antcd {antcd.__version__}, Wuson.ply ({wuson.triangle_count} triangles) against itself; "
          f"{args.rounds} rounds x {args.calls} calls; load average {os.getloadavg()[0]:.1f} on "
          f"{os.cpu_count()} CPUs")
    print(f"{'query (boolean collide)':<44} {'verdict':>7} {'C++ us':>9} {'Py us':>9} {'extra us':>9} [min, max]")
    reference = []
    for _ in range(args.rounds):
        start = time.perf_counter()
        for _ in range(args.calls):
            wuson.triangle_count  # the cheapest call into the module: a C++ property read
        reference.append((time.perf_counter() - start) / args.calls)
    print(f"{'reference: Model.triangle_count (one trivial pybind11 call)':<60} "
          f"{statistics.median(reference) * 1e6:9.3f} us")
    worst = 0.0
    worst = max(worst, measure("4x4 float64 poses", wuson, np.eye(4), wuson, apart, args.rounds, args.calls))
    worst = max(worst, measure("4x4 float64 poses", wuson, np.eye(4), wuson, touching, args.rounds, args.calls))
    worst = max(worst, measure("(R, t) numpy pairs", wuson, (np.eye(3), np.zeros(3)), wuson,
                               (touching[:3, :3], touching[:3, 3]), args.rounds, args.calls))
    worst = max(worst, measure("4x4 nested lists (converted per call)", wuson, np.eye(4).tolist(), wuson,
                               touching.tolist(), args.rounds, args.calls))
    print(f"largest median extra cost per call: {worst * 1e6:.3f} us (target <= 2 us with numpy poses)")


if __name__ == "__main__":
    main()
