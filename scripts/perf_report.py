#!/usr/bin/python3
"""Writes the performance report of scripts/perf-report.sh from its raw outputs.

Usage: perf_report.py WORK_DIR REPORT.md [--doc docs/performance.md]

WORK_DIR holds machine.txt, the peers folders (CSV files of `antcd-lab bench peers --out`),
Google Benchmark JSON files, the callgrind summary of the scene runner and the icount output.
With --doc, the report's summary (machine line and targets) replaces the block between the
perf-report markers of that file. Every figure is read from those files; none is typed in.
"""

import csv
import json
import os
import re
import sys

BEGIN = "<!-- perf-report:begin (scripts/perf-report.sh writes this block) -->"
END = "<!-- perf-report:end -->"


def num(x):
    """Three significant digits, as the benchmarks' own reports print."""
    if x is None:
        return "—"
    x = float(x)
    if x == 0:
        return "0"
    if abs(x) >= 1000:
        return f"{x:.0f}"
    return f"{x:.3g}"


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "| " + " | ".join("---" for _ in header) + " |"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out) + "\n"


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_bench(path):
    """Google Benchmark JSON: the runs (medians when repeated), keyed by name."""
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return {}
    with open(path) as f:
        data = json.load(f)
    out = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = re.sub(r"(/iterations:\d+|/min_time:[0-9.]+|/real_time|/repeats:\d+)", "",
                      b.get("run_name", b["name"]))
        out[name] = b
    return out


def machine(work):
    info = {}
    with open(os.path.join(work, "machine.txt")) as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition("=")
            info[key] = value
    return info


def scene_rows(rows):
    """(table rows, {(engine, query): cpu median ms}) of one peers scene run."""
    cpu = {(r["engine"], r["query"]): float(r["median_cpu_ms"]) for r in rows
           if r["median_cpu_ms"] not in ("", "nan")}
    out = []
    for r in rows:
        mine = cpu.get(("antcd exact", r["query"]))
        theirs = cpu.get((r["engine"], r["query"]))
        ratio = num(mine / theirs) if mine is not None and theirs else "—"
        out.append([r["engine"], r["query"], num(r["candidates_per_frame"]),
                    num(r["median_cpu_ms"]), num(r["median_ms"]), num(r["p99_ms"]), ratio])
    return out, cpu


def runner_share(path):
    """Scene::run_frame's instructions and the narrow phase's (collide) within them."""
    frame = narrow = None
    if not os.path.exists(path):
        return None
    for line in open(path):
        m = re.match(r"\s*([\d,]+)\s+\([^)]*\)\s+\?\?\?:(.*)", line)
        if not m:
            continue
        count = int(m.group(1).replace(",", ""))
        name = m.group(2)
        if frame is None and name.startswith("antcd::Scene::run_frame(unsigned long"):
            frame = count
        if narrow is None and (name.startswith("antcd::detail::collide_coherent(") or
                               name.startswith("antcd::collide(antcd::Model const&")):
            narrow = count
    if frame is None or narrow is None:
        return None
    return frame, narrow


def main():
    args = sys.argv[1:]
    doc = None
    if "--doc" in args:
        i = args.index("--doc")
        doc = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit("usage: perf_report.py WORK_DIR REPORT.md [--doc docs/performance.md]")
    work, report = args
    m = machine(work)
    md = []
    md.append(f"# Performance report {m['date']}\n")
    md.append(f"Written by `scripts/perf-report.sh{' --quick' if m['mode'] == 'quick' else ''}` "
              f"in {int(m['seconds']) // 60} min {int(m['seconds']) % 60} s.\n")
    md.append(table(["what", "value"], [
        ["commit", m["commit"]], ["CPU", m["cpu"]], ["cores", m["cores"]],
        ["memory", m["memory"]], ["compiler", m["compiler"]], ["mode", m["mode"]],
        ["load average before (1, 5, 15 min)", m["load_before"]],
        ["load average after", m["load_after"]]]))
    busy = max(float(m["load_before"].split()[0]), float(m["load_after"].split()[0]))
    if busy > float(m["cores"]) / 2:
        md.append(f"**Contended run**: load average up to {busy} on {m['cores']} cores. Ratios "
                  "within one benchmark (antcd against a peer, frame by frame or pose by pose) "
                  "hold better than absolute times; instruction counts are unaffected.\n")
    targets = []

    # Scenes.
    md.append("## Scenes of real meshes (`antcd-lab bench peers SCENE --only scenes --threads 1`)\n")
    scene_cpu = {}
    for scene, what in (("s90", "90 objects (45 moving) of 5 assimp meshes"),
                        ("pair2", "2 spiders (1 368 triangles each)")):
        rows = read_csv(os.path.join(work, f"peers-{scene}", "scenes.csv"))
        if not rows:
            continue
        body, cpu = scene_rows(rows)
        scene_cpu[scene] = cpu
        md.append(f"### {scene}: {what}, {rows[0]['frames']} frames\n")
        md.append(table(["engine", "query", "broad-phase pairs / frame", "median CPU ms",
                         "median wall ms", "p99 wall ms", "antcd / engine (CPU)"], body))
        if float(rows[0]["candidates_per_frame"]) < 1:
            md.append("Fewer than one candidate pair per frame: the median frame has none, so the "
                      "medians are each engine's fixed cost of a frame (timer reads included).\n")
        for query in ("boolean", "all contacts"):
            mine = cpu.get(("antcd exact", query))
            fcl = cpu.get(("FCL-OBBRSS", query))
            if mine and fcl:
                targets.append([f"scene {scene}, {query}: antcd ≤ 0.25 of FCL-OBBRSS per frame",
                                f"{num(mine / fcl)} (CPU medians {num(mine)} / {num(fcl)} ms)",
                                "met" if mine / fcl <= 0.25 else "not met"])

    # Pairs, build, memory.
    pairs = read_csv(os.path.join(work, "peers-pairs", "pairs.csv"))
    if pairs:
        md.append("## Mesh pairs: tumbling tori at four clearances (`antcd-lab bench peers "
                  "--only pairs`)\n")
        body = []
        worst_bool = worst_all = 0.0
        for r in pairs:
            rb = float(r["bool_antcd_us"]) / float(r["bool_fcl_us"])
            ra = float(r["all_antcd_us"]) / float(r["all_fcl_us"])
            worst_bool, worst_all = max(worst_bool, rb), max(worst_all, ra)
            body.append([r["triangles"], r["clearance"], num(r["bool_antcd_us"]),
                         num(r["bool_fcl_us"]), num(rb), num(r["all_antcd_us"]),
                         num(r["all_fcl_us"]), num(ra), r["disagreements"]])
        md.append(table(["triangles", "clearance", "boolean antcd µs", "FCL µs", "ratio",
                         "all antcd µs", "FCL µs", "ratio", "disagreements"], body))
        targets.append(["pairs (tori): antcd ≤ 0.25 of FCL-OBBRSS, boolean, worst cell",
                        num(worst_bool), "met" if worst_bool <= 0.25 else "not met"])
        targets.append(["pairs (tori): antcd ≤ 0.25 of FCL-OBBRSS, all contacts, worst cell",
                        num(worst_all), "met" if worst_all <= 0.25 else "not met"])
    builds = read_csv(os.path.join(work, "peers-pairs", "build.csv"))
    if builds:
        md.append("## Hierarchy build and memory (same run)\n")
        md.append(table(["triangles", "antcd build ms", "FCL-OBBRSS ms", "FCL-OBB ms",
                         "antcd B/triangle", "FCL-OBBRSS B/triangle", "FCL-OBB B/triangle"],
                        [[b["triangles"], num(b["antcd_build_ms"]), num(b["fcl_obbrss_build_ms"]),
                          num(b["fcl_obb_build_ms"]), num(b["antcd_bytes_per_tri"]),
                          num(b["fcl_obbrss_bytes_per_tri"]), num(b["fcl_obb_bytes_per_tri"])]
                         for b in builds]))
        worst = max(float(b["antcd_bytes_per_tri"]) for b in builds)
        targets.append(["memory ≤ 100 B/triangle (hierarchy and mesh copy)", num(worst),
                        "met" if worst <= 100 else "not met"])

    # FCL's own protocol.
    proto = read_bench(os.path.join(work, "protocol.json"))
    if proto:
        md.append("## FCL's env/rob protocol (`build/bench/antcd_bench_protocol`)\n")
        body = []
        for name, b in sorted(proto.items()):
            pair = name.split("/")[1]
            body.append([pair, num(b["colliding_fraction"]), num(b["bool_antcd_med_us"]),
                         num(b["bool_fcl_med_us"]), num(b["bool_ratio_median"]),
                         num(b["all_antcd_med_us"]), num(b["all_fcl_med_us"]),
                         num(b["all_ratio_median"])])
            for query, key in (("boolean", "bool_ratio_median"), ("all contacts",
                                                                  "all_ratio_median")):
                targets.append([f"FCL protocol {pair}, {query}: ≤ 0.33 of FCL (median query)",
                                num(b[key]), "met" if b[key] <= 0.33 else "not met"])
        md.append(table(["pair (env_rob)", "colliding", "boolean antcd µs", "FCL µs", "ratio",
                         "all antcd µs", "FCL µs", "ratio"], body))

    # Scene runner share.
    share = runner_share(os.path.join(work, "runner.txt"))
    if share:
        frame, narrow = share
        md.append("## The scene runner's own share (callgrind, `antcd run s90 --method exact "
                  "--threads 1`)\n")
        md.append(table(["instructions over 300 frames", "count"], [
            ["`Scene::run_frame`", f"{frame:,}"], ["narrow phase (collide per pair)",
                                                   f"{narrow:,}"],
            ["runner (poses, World broad phase, bookkeeping)", f"{frame - narrow:,}"]]))
        targets.append(["runner overhead ≤ 10 % of the frame's query time (s90)",
                        f"{100 * (frame - narrow) / narrow:.0f} % of the narrow phase "
                        f"({100 * (frame - narrow) / frame:.0f} % of the frame)",
                        "met" if frame - narrow <= 0.1 * narrow else "not met"])

    # World.
    world = read_bench(os.path.join(work, "world.json"))
    if world:
        md.append("## Live world vs FCL's dynamic AABB tree (`build/bench/antcd_bench_world`)\n")
        body = [[name, num(b.get("antcd_cpu_ms")), num(b.get("fcl_cpu_ms")),
                 num(b.get("ratio_cpu")), num(b.get("ratio_wall"))]
                for name, b in sorted(world.items()) if name.startswith("world_interleaved")]
        if body:
            md.append(table(["benchmark (objects)", "antcd CPU ms / frame", "FCL CPU ms / frame",
                             "antcd/FCL CPU", "antcd/FCL wall"], body))
        threads = {name: b for name, b in world.items()
                   if name.startswith(("dense_threads", "parallel_control"))}
        if threads:
            md.append("Two threads against one (wall medians; `parallel_control` is independent "
                      "arithmetic: what the machine gave two threads during the run):\n")
            md.append(table(["benchmark / threads", "wall ms"],
                            [[name, num(b["real_time"])] for name, b in sorted(threads.items())]))

    # Distance.
    dist = read_bench(os.path.join(work, "distance.json"))
    if dist:
        md.append("## Mesh distance vs FCL (`build/bench/antcd_bench_distance`), µs per query\n")
        body = []
        for name, b in sorted(dist.items()):
            if not name.startswith("distance_antcd/"):
                continue
            _, shape, size = name.split("/")
            rss = dist.get(f"distance_fcl_rss/{shape}/{size}")
            obbrss = dist.get(f"distance_fcl_obbrss/{shape}/{size}")
            mine = b["per_query"] * 1e6
            body.append([shape, size, num(mine),
                         num(rss["per_query"] * 1e6) if rss else "—",
                         num(obbrss["per_query"] * 1e6) if obbrss else "—",
                         num(b["per_query"] / rss["per_query"]) if rss else "—"])
        md.append(table(["shape", "triangles", "antcd", "FCL RSS", "FCL OBBRSS",
                         "antcd / FCL RSS"], body))

    # Penetration.
    pen = read_bench(os.path.join(work, "penetration.json"))
    if pen:
        md.append("## Penetration depth (`build/bench/antcd_bench_penetration`)\n")
        body = []
        for name, b in sorted(pen.items(), key=lambda item: item[1].get("triangles", 0)):
            if name.startswith("convex_antcd/"):
                fcl = pen.get(name.replace("convex_antcd", "convex_fcl_epa"))
                body.append([name, num(b["triangles"]), num(b["per_query"] * 1e6),
                             num(fcl["per_query"] * 1e6) if fcl else "—",
                             num(b["per_query"] / fcl["per_query"]) if fcl else "—"])
        if body:
            md.append(table(["convex pair", "triangles", "antcd µs", "FCL EPA µs",
                             "antcd / FCL"], body))
        general = [[name, num(b["triangles"]), num(b["ratio_to_collide_all"]),
                    "yes" if b.get("converged") else "no"]
                   for name, b in sorted(pen.items()) if name.startswith("general_penetration")]
        if general:
            md.append(table(["general pair (shape/size)", "triangles",
                             "penetration / all-contacts collide", "converged"], general))

    # CCD.
    ccd = read_bench(os.path.join(work, "ccd.json"))
    if ccd:
        md.append("## Continuous collision (`build/bench/antcd_bench_ccd`)\n")
        body = []
        for name, b in sorted(ccd.items()):
            label = b.get("label", "")
            if "per_motion" in b:
                body.append([name, label, num(b["per_motion"] * 1e6), num(b.get("hits")),
                             num(b.get("misses")), num(b.get("late"))])
            elif "median_us" in b:
                body.append([name, label, num(b["median_us"]), num(b.get("hits")), "—", "—"])
        md.append(table(["benchmark", "set or pair", "µs per motion (primitives: median µs per "
                         "query)", "hits", "misses", "late"], body))

    # icount.
    icount_path = os.path.join(work, "icount.txt")
    if os.path.exists(icount_path):
        lines = [l.split() for l in open(icount_path) if re.match(r"^[a-z_]+\s+\d+\s+\d+", l)]
        if lines:
            md.append("## Instruction counts (`scripts/icount.sh`, against "
                      "bench/icount_baseline.txt)\n")
            md.append(table(["section", "baseline", "measured", "change"],
                            [[l[0], l[1], l[2], " ".join(l[3:])] for l in lines]))

    md.insert(3, "## Targets (issue 25)\n\n" + table(["target", "measured", "verdict"], targets))
    text = "\n".join(md)
    tmp = report + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, report)

    if doc:
        summary = [BEGIN, "",
                   f"Latest run: [{os.path.basename(report)}](performance/{os.path.basename(report)})"
                   f" — {m['date']}, commit {m['commit']}, {m['cpu']} ({m['cores']} cores), "
                   f"{m['mode']} mode, load average {m['load_before'].split()[0]} before and "
                   f"{m['load_after'].split()[0]} after.", "",
                   table(["target", "measured", "verdict"], targets), END]
        with open(doc) as f:
            old = f.read()
        if BEGIN not in old or END not in old:
            sys.exit(f"error: {doc} has no perf-report markers")
        new = old[:old.index(BEGIN)] + "\n".join(summary) + old[old.index(END) + len(END):]
        tmp = doc + ".tmp"
        with open(tmp, "w") as f:
            f.write(new)
        os.replace(tmp, doc)


if __name__ == "__main__":
    main()
