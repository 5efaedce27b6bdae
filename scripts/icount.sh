#!/usr/bin/env bash
# The performance guard: instruction counts of a fixed set of queries (bench/icount.cpp) under
# valgrind's callgrind, compared with the committed baseline bench/icount_baseline.txt.
#
#   scripts/icount.sh                 check: fails (exit 1) when a section's count grew by more than
#                                     3 % over the baseline, or when the baseline's counts were
#                                     edited without a why line
#   scripts/icount.sh --update WHY    rewrites the counts and appends the line "why DATE SUM: WHY"
#
# Counts are deterministic for a given build (same compiler, flags and Debian packages), so they
# do not depend on the machine's load the way wall-clock timings do. A change that makes some
# section more than 3 % costlier must update the baseline in the same commit and say why; the
# last why line carries a checksum of the counts, so counts edited by hand (without --update and
# its reason) fail the check. Uses the Release build in $ANTCD_BUILD_DIR (default build/), and
# builds only the antcd_icount target there when it is missing. About 5 s on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${ANTCD_BUILD_DIR:-build}"
baseline=bench/icount_baseline.txt
tolerance_percent=3

update_reason=""
if [ "${1:-}" = "--update" ]; then
  update_reason="${2:-}"
  if [ -z "$update_reason" ]; then
    echo "error: --update needs the reason for the new counts, e.g. --update 'nodes split hot/cold'" >&2
    exit 2
  fi
elif [ $# -gt 0 ]; then
  echo "error: unknown argument '$1' (usage: scripts/icount.sh [--update WHY])" >&2
  exit 2
fi

if ! command -v valgrind >/dev/null 2>&1; then
  echo "error: valgrind is not installed (Debian package valgrind)" >&2
  exit 2
fi
binary="$build_dir/bench/antcd_icount"
if [ ! -x "$binary" ]; then
  cmake --build "$build_dir" -j "$(nproc)" --target antcd_icount
fi

out_dir="$(mktemp -d)"
trap 'rm -rf "$out_dir"' EXIT
valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no \
  --callgrind-out-file="$out_dir/cg" "$binary" >"$out_dir/stdout" 2>"$out_dir/stderr" || {
  cat "$out_dir/stdout" "$out_dir/stderr" >&2
  echo "error: $binary failed under valgrind" >&2
  exit 2
}
# One dump per section: "desc: Trigger: Client Request: NAME" and "totals: COUNT".
measured="$out_dir/measured"
for f in "$out_dir"/cg.*; do
  awk '/^desc: Trigger: Client Request: /{name=$5} /^totals: /{count=$2}
       END{if (name != "") print name, count}' "$f"
done | sort >"$measured"
if [ ! -s "$measured" ]; then
  echo "error: no section counts in callgrind's output" >&2
  exit 2
fi

counts_sum() { grep -Ev '^(#|why |$)' "$1" | sort | cksum | cut -d' ' -f1; }

if [ -n "$update_reason" ]; then
  new="$out_dir/baseline"
  {
    grep -E '^(#|why )' "$baseline" 2>/dev/null || true
    echo "why $(date -u +%Y-%m-%d) $(counts_sum "$measured"): $update_reason"
    cat "$measured"
  } >"$new"
  cp "$new" "$baseline"
  echo "icount: baseline updated ($baseline):"
  cat "$measured"
  exit 0
fi

if [ ! -f "$baseline" ]; then
  echo "error: no baseline $baseline (create it with scripts/icount.sh --update WHY)" >&2
  exit 2
fi
last_why="$(grep '^why ' "$baseline" | tail -n 1 || true)"
if [ "$(echo "$last_why" | awk '{print $3}' | tr -d :)" != "$(counts_sum "$baseline")" ]; then
  echo "error: $baseline: its counts were changed without a why line; update it with" >&2
  echo "  scripts/icount.sh --update 'why the counts changed'" >&2
  exit 1
fi

status=0
fell=0
printf '%-20s %15s %15s %8s\n' section baseline measured change
while read -r name count; do
  base="$(awk -v n="$name" '$1 == n {print $2}' "$baseline")"
  if [ -z "$base" ]; then
    printf '%-20s %15s %15s %8s  NEW: not in the baseline\n' "$name" - "$count" -
    status=1
    continue
  fi
  verdict="$(awk -v b="$base" -v c="$count" -v t="$tolerance_percent" 'BEGIN{
    p = (c - b) * 100 / b; printf "%+.2f%% ", p
    if (p > t) print "GREW"; else if (p < -t) print "fell"; else print "ok"}')"
  printf '%-20s %15s %15s %8s\n' "$name" "$base" "$count" "$verdict"
  case "$verdict" in *GREW) status=1 ;; *fell) fell=1 ;; esac
done <"$measured"
while read -r name _; do
  if ! grep -q "^$name " "$measured"; then
    printf '%-20s  MISSING: in the baseline, not measured\n' "$name"
    status=1
  fi
done < <(grep -Ev '^(#|why |$)' "$baseline")

if [ "$status" -ne 0 ]; then
  echo "icount: FAILED: a section grew by more than ${tolerance_percent} % (or the sections changed)." >&2
  echo "If the cost is intended, run scripts/icount.sh --update 'why' and commit the baseline" >&2
  echo "with the change." >&2
  exit 1
fi
if [ "$fell" -ne 0 ]; then
  echo "icount: some section fell by more than ${tolerance_percent} %: lock the gain in with" \
    "scripts/icount.sh --update 'why'"
fi
echo "icount: ok (no section more than ${tolerance_percent} % above $baseline)"
