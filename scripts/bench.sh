#!/usr/bin/env bash
# Builds in Release and runs every benchmark with 5 repetitions; prints medians.
#   scripts/bench.sh [FILTER]   (a Google Benchmark --benchmark_filter regex)
# bench_projection prints its own report (100,000 points per set, about a minute).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" release
for b in "$root"/build/release/bench/bench_*; do
  [[ -x "$b" ]] || continue
  echo "== $(basename "$b")"
  if [[ "$(basename "$b")" == bench_projection ]]; then
    "$b"  # a report of its own: sets A/B/C against brute force, medians of 5 runs
    continue
  fi
  "$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
       --benchmark_filter="${1:-.}" 2>&1 | grep -E "median|^Run on|CPU|^-|Benchmark"
done
