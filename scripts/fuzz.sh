#!/usr/bin/env bash
# Fuzzing: builds the libFuzzer targets (fuzz/) with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs each one for a while on a copy of its seed corpus.
#
#   bash scripts/fuzz.sh
#
# Environment:
#   ANTCD_FUZZ_SECONDS     seconds per fuzzer (default 60)
#   ANTCD_FUZZ_SEED        libFuzzer's -seed (default 1: repeatable; 0: random)
#   ANTCD_FUZZ_BUILD_DIR   build folder (default <repo>/build-fuzz)
#   ANTCD_FUZZ_JOBS        parallel build jobs (default: the number of cores)
#
# The committed corpus (fuzz/corpus/<name>) is never modified: each run works on a copy in
# <build>/fuzz-run/<fuzzer>/corpus, and crashing inputs are written to
# <build>/fuzz-run/<fuzzer>/crash-* (also listed at the end). Exits non-zero when a fuzzer finds
# a crash, a sanitizer report, a leak, a timeout (-timeout=10 s per input) or an out-of-memory
# (-rss_limit_mb=4096). Installs clang with apt-get if it is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"

seconds="${ANTCD_FUZZ_SECONDS:-60}"
# A fixed seed makes a run repeatable (the same inputs in the same order; a faster machine just
# gets further along them). ANTCD_FUZZ_SEED=0 lets libFuzzer pick one.
seed="${ANTCD_FUZZ_SEED:-1}"
build_dir="${ANTCD_FUZZ_BUILD_DIR:-$repo/build-fuzz}"
jobs="${ANTCD_FUZZ_JOBS:-$(nproc)}"

# ---- clang and its libFuzzer runtime (Debian 12: clang, libclang-rt-dev) ----
./scripts/install-deps.sh clang libclang-rt-dev
. scripts/compiler-cache.sh

# ---- build ----
cmake -S "$repo" -B "$build_dir" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DANTCD_BUILD_FUZZERS=ON \
  -DANTCD_BUILD_TESTS=OFF -DANTCD_BUILD_APPS=OFF -DANTCD_BUILD_BENCHMARKS=OFF
fuzzers=(fuzz_mesh_load fuzz_scene_parse)
# Hostile-input readers (issue 28): points CSV (fuzz/corpus/points), run results (fuzz/corpus/run).
fuzzers+=(fuzz_points_csv fuzz_run_result)
# The model-file reader (issue 27), corpus fuzz/corpus/model.
fuzzers+=(fuzz_model_file)
# Self-collision and the vertex update (issue 41), corpus fuzz/corpus/self.
fuzzers+=(fuzz_self)
# The deforming sweeps and World::set_vertices (issue 41), corpus fuzz/corpus/deform.
fuzzers+=(fuzz_deform_ccd)
cmake --build "$build_dir" -j "$jobs" --target "${fuzzers[@]}"

# ---- run ----
# Leaks are findings too (except inside assimp, see fuzz/lsan.supp); undefined behaviour stops
# the run.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$repo/fuzz/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
summary=()
for fuzzer in "${fuzzers[@]}"; do
  corpus_name="${fuzzer#fuzz_}"
  corpus_name="${corpus_name%%_*}"  # fuzz_mesh_load -> mesh, fuzz_deform_ccd -> deform
  run_dir="$build_dir/fuzz-run/$fuzzer"
  rm -rf "$run_dir"
  mkdir -p "$run_dir/corpus"
  cp -r "$repo/fuzz/corpus/$corpus_name/." "$run_dir/corpus/"
  seeds=$(find "$run_dir/corpus" -type f | wc -l)
  echo "== $fuzzer: ${seconds}s on $seeds seed inputs (fuzz/corpus/$corpus_name)" >&2
  set +e
  (cd "$run_dir" && TMPDIR="$run_dir" "$build_dir/fuzz/$fuzzer" \
     -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
     -artifact_prefix="$run_dir/" corpus) 2>&1 | tee "$run_dir/log.txt" | grep -E \
     "^(#[0-9]+[[:space:]]+(INITED|DONE)|stat::|==[0-9]+==|SUMMARY|Test unit written|artifact_prefix|.*ERROR)" >&2
  rc=${PIPESTATUS[0]}
  set -e
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$run_dir/log.txt" | tail -1)
  corpus_size=$(find "$run_dir/corpus" -type f | wc -l)
  crashes=$(find "$run_dir" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' \
              -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  summary+=("$fuzzer: exit $rc, ${execs:-?} executions in ${seconds}s, corpus $seeds -> $corpus_size, findings $crashes")
  if [ "$rc" -ne 0 ] || [ "$crashes" -ne 0 ]; then
    status=1
    find "$run_dir" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' \
      -o -name 'oom-*' \) -printf '  finding: %p\n' >&2
  fi
done

echo "== summary" >&2
printf '%s\n' "${summary[@]}" >&2
if [ "$status" -ne 0 ]; then
  echo "error: fuzzing found a problem (logs in $build_dir/fuzz-run/*/log.txt)" >&2
fi
exit "$status"
