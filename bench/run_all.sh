#!/usr/bin/env bash
# Builds the benchmarks in Release and runs each one with 5 repetitions, printing the medians.
# Usage: bench/run_all.sh [FILTER-REGEX]   (results are what docs/benchmarks.md quotes)
set -euo pipefail
cd "$(dirname "$0")/.."
ci/setup >/dev/null
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DOLCB_TESTS=OFF >/dev/null
cmake --build build-bench -j"${OLCB_JOBS:-2}" >/dev/null
filter=${1:-.}
for bench in build-bench/bench/bench_*; do
    [ -x "$bench" ] || continue
    echo "== $(basename "$bench")"
    "$bench" --benchmark_filter="$filter" --benchmark_repetitions=5 \
        --benchmark_report_aggregates_only=true --benchmark_display_aggregates_only=true 2>&1 |
        grep -E "_median|^Run on|CPU|^-" || true
done
