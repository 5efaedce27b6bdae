#!/usr/bin/python3
"""Runs the paper's production-line scene with every method and plots recall and time per method.

The scene comes from `antcd scene generate` (the CLI, installed with the library: see the README),
or pass --scene for an existing antcd-scene/1 file. The exact method is the ground truth; for each
other method, recall = colliding object pairs it reports that the truth has / pairs the truth has,
and precision = those / pairs it reports, summed over frames; time = mean wall time per frame
(broad + narrow phase). Prints a table and writes a bar chart (matplotlib, Debian
python3-matplotlib) to --plot.

Usage: examples/python/paper_scene.py [--objects 90 --vertices 750 --frames 300] [--scene FILE]
       [--methods sphere-obb,aco,maco,pso,ga] [--seed 1] [--plot paper_scene.png] [--antcd PATH]
"""
import argparse
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

import antcd


def generate(cli, out, objects, vertices, frames, seed):
    subprocess.run([cli, "scene", "generate", "--out", str(out), "--objects", str(objects), "--vertices",
                    str(vertices), "--frames", str(frames), "--seed", str(seed)], check=True,
                   stdout=subprocess.DEVNULL)
    return out / "scene.json"


def pair_sets(run):
    return [{(int(i), int(j)) for i, j in frame} for frame in run.pairs]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", help="an existing scene file (default: generate the paper scene)")
    parser.add_argument("--objects", type=int, default=90)
    parser.add_argument("--vertices", type=int, default=750)
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--methods", default="sphere-obb,aco,maco,pso,ga")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--plot", default="paper_scene.png")
    parser.add_argument("--antcd", default=shutil.which("antcd"), help="the antcd CLI (default: on PATH)")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        if args.scene:
            path = Path(args.scene)
        else:
            if not args.antcd:
                parser.error("the antcd CLI is not on PATH: pass --antcd PATH or --scene FILE")
            path = generate(args.antcd, Path(tmp), args.objects, args.vertices, args.frames, args.seed)
        scene = antcd.Scene(path)
        print(f"scene: {scene.object_count} objects, {scene.model_count} models, {scene.frames} frames "
              f"(built in {scene.build_ms:.0f} ms)")
        truth_run = scene.run(method="exact", threads=args.threads)
        truth = pair_sets(truth_run)
        true_pairs = sum(len(t) for t in truth)
        rows = [("exact", 1.0, 1.0, float(np.mean(truth_run.times_ms)))]
        for method in args.methods.split(","):
            run = scene.run(method=method, seed=args.seed, threads=args.threads)
            found = pair_sets(run)
            hits = sum(len(f & t) for f, t in zip(found, truth))
            reported = sum(len(f) for f in found)
            recall = hits / true_pairs if true_pairs else float("nan")
            precision = hits / reported if reported else float("nan")
            rows.append((method, recall, precision, float(np.mean(run.times_ms))))

    print(f"colliding pairs in the truth (summed over frames): {true_pairs}")
    print(f"{'method':<12} {'recall':>8} {'precision':>10} {'ms/frame':>10}")
    for method, recall, precision, ms in rows:
        print(f"{method:<12} {recall:8.3f} {precision:10.3f} {ms:10.3f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [r[0] for r in rows]
    x = np.arange(len(rows))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    left.bar(x - 0.2, [r[1] for r in rows], width=0.4, label="recall", color="tab:blue")
    left.bar(x + 0.2, [r[2] for r in rows], width=0.4, label="precision", color="tab:green")
    left.set_xticks(x, names)
    left.set_ylabel("share of colliding object pairs")
    left.set_ylim(0, 1.05)
    left.legend(loc="lower left")
    right.bar(x, [r[3] for r in rows], color="tab:orange")
    right.set_xticks(x, names)
    right.set_yscale("log")
    right.set_ylabel("time per frame (ms, log scale)")
    for ax in (left, right):
        ax.tick_params(axis="x", rotation=30)
    fig.suptitle(f"{scene.object_count} objects, {scene.frames} frames (shared machine: times are indicative)")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=120)
    print(f"plot written to {args.plot}")


if __name__ == "__main__":
    main()
