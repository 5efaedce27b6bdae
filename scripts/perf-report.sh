#!/usr/bin/env bash
# The performance report: runs the benchmark set and writes docs/performance/<stamp>.md (every
# table of the current figures, with the machine, commit and load average), then copies its
# summary into docs/performance.md between the perf-report markers.
#
#   scripts/perf-report.sh            full run (about 12 min on a 2-core machine)
#   scripts/perf-report.sh --quick    fewer frames, poses and sizes (about 2.5 min)
#   scripts/perf-report.sh --no-doc   leave docs/performance.md alone (write the report only)
#
# What runs (each is also a command of its own; docs/performance.md says what it measures):
#   antcd-lab bench peers SCENE --only scenes --threads 1   on two scenes of real meshes made by
#       `antcd scene generate --mesh` from Debian's assimp-testmodels (s90: 90 objects, pair2: 2)
#   antcd-lab bench peers --only pairs                     tumbling tori, build time, memory
#   antcd_bench_protocol                                   FCL's env/rob mesh test protocol
#   antcd_bench_world, antcd_bench_distance, antcd_bench_penetration, antcd_bench_ccd
#   valgrind callgrind on `antcd run s90 --method exact`   the scene runner's own share
#   scripts/icount.sh                                      the instruction-count guard
# Uses the Release build in $ANTCD_BUILD_DIR (default build/) and builds only these targets there.
# Benchmarks on a shared machine measure the machine too: the report records the load average
# before and after, and every comparison with a peer is a ratio of times taken in the same run.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${ANTCD_BUILD_DIR:-build}"
quick=0
update_doc=1
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    --no-doc) update_doc=0 ;;
    *)
      echo "error: unknown argument '$arg' (usage: scripts/perf-report.sh [--quick] [--no-doc])" >&2
      exit 2
      ;;
  esac
done
models=/usr/share/assimp/models
if [ ! -d "$models" ]; then
  echo "error: $models is missing (Debian package assimp-testmodels)" >&2
  exit 2
fi
for tool in valgrind callgrind_annotate /usr/bin/python3; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "error: $tool is not installed" >&2
    exit 2
  fi
done
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  echo "error: no build in $build_dir (configure a Release build first: docs/building.md)" >&2
  exit 2
fi
if ! grep -q '^CMAKE_BUILD_TYPE:STRING=Release$' "$build_dir/CMakeCache.txt"; then
  echo "error: $build_dir is not a Release build" >&2
  exit 2
fi

targets=(antcd_cli antcd_lab antcd_icount antcd_bench_protocol antcd_bench_world
  antcd_bench_distance antcd_bench_penetration antcd_bench_ccd)
cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]}" >/dev/null

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
start_seconds=$(date +%s)
stamp="$(date -u +%Y-%m-%dT%H%MZ)"
{
  echo "date=$(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "commit=$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- src include bench apps experiments 2>/dev/null || echo '+changes')"
  echo "cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "cores=$(nproc)"
  echo "memory=$(free -g | awk '/^Mem:/{print $2}') GiB"
  echo "compiler=$(c++ --version | head -1)"
  echo "mode=$([ $quick = 1 ] && echo quick || echo full)"
  echo "load_before=$(cut -d' ' -f1-3 /proc/loadavg)"
} >"$work/machine.txt"

bin="$build_dir/apps/antcd"
lab="$bin/antcd-lab"
step() { echo "perf-report: $*" >&2; }

step "scenes: generating s90 and pair2 from $models"
"$bin/antcd" scene generate --out "$work/s90" --objects 90 --frames 300 --seed 7 \
  --mesh "$models/OBJ/spider.obj" "$models/PLY/Wuson.ply" "$models/STL/sphereWithHole.stl" \
  "$models/STL/Spider_binary.stl" "$models/OBJ/box.obj" >/dev/null
"$bin/antcd" scene generate --out "$work/pair2" --objects 2 --frames 300 --seed 3 \
  --mesh "$models/OBJ/spider.obj" >/dev/null
frames=300
[ $quick = 1 ] && frames=60
for scene in s90 pair2; do
  step "peers scenes: $scene, $frames frames"
  "$lab" bench peers "$work/$scene/scene.json" --only scenes --threads 1 --frames "$frames" \
    --out "$work/peers-$scene" >/dev/null
done

step "peers pairs: tori at four clearances, build and memory"
if [ $quick = 1 ]; then
  "$lab" bench peers --only pairs --quick --out "$work/peers-pairs" >/dev/null
else
  "$lab" bench peers --only pairs --out "$work/peers-pairs" >/dev/null
fi

gbench() {  # gbench NAME BINARY [ARGS...]: Google Benchmark JSON into $work/NAME.json
  local name="$1" binary="$2"
  shift 2
  step "$name"
  "$build_dir/bench/$binary" --benchmark_out="$work/$name.json" --benchmark_out_format=json \
    "$@" >/dev/null
}
gbench protocol antcd_bench_protocol
if [ $quick = 1 ]; then
  gbench world antcd_bench_world --benchmark_filter='world_interleaved/10000/'
  gbench distance antcd_bench_distance --benchmark_filter='/(1000|10000)$'
  gbench penetration antcd_bench_penetration --benchmark_filter='convex|/(0|1)/1000$'
  gbench ccd antcd_bench_ccd --benchmark_filter='^(sweep|collide_end|fcl_ca)/'
else
  gbench world antcd_bench_world --benchmark_filter='world_interleaved|dense_threads|parallel_control'
  gbench distance antcd_bench_distance --benchmark_filter='/(1000|10000|100000)$' \
    --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
  gbench penetration antcd_bench_penetration --benchmark_filter='convex|/(0|1)/(1000|10000)$'
  gbench ccd antcd_bench_ccd
fi

step "callgrind: antcd run s90 --method exact --threads 1"
valgrind --tool=callgrind --callgrind-out-file="$work/runner.cg" \
  "$bin/antcd" run "$work/s90/scene.json" --method exact --threads 1 >/dev/null 2>"$work/runner.err"
callgrind_annotate --inclusive=yes "$work/runner.cg" >"$work/runner.txt" 2>/dev/null

step "icount guard"
bash scripts/icount.sh >"$work/icount.txt" 2>&1 || true

{
  echo "load_after=$(cut -d' ' -f1-3 /proc/loadavg)"
  echo "seconds=$(($(date +%s) - start_seconds))"
} >>"$work/machine.txt"

mkdir -p docs/performance
report="docs/performance/$stamp.md"
doc_arg=()
[ $update_doc = 1 ] && doc_arg=(--doc docs/performance.md)
/usr/bin/python3 scripts/perf_report.py "$work" "$report" "${doc_arg[@]}"
step "wrote $report$([ $update_doc = 1 ] && echo ' and the summary in docs/performance.md')"
