#!/usr/bin/env bash
# Compares bench_cdi of two builds side by side: runs them alternately (so a change in machine
# load hits both alike), each run with --benchmark_repetitions, and prints per benchmark the
# median over all repetitions of all runs, before and after.
#
#   bench/validate_compare.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [ROUNDS] [FILTER]
#
# ROUNDS defaults to 5; FILTER to the validate and parse+layout benchmarks. Each build dir must
# hold bench/bench_cdi (cmake --build DIR --target bench_cdi).
set -euo pipefail

if [ $# -lt 2 ]; then
    sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
before="$1/bench/bench_cdi"
after="$2/bench/bench_cdi"
rounds="${3:-5}"
filter="${4:-BM_ValidateLargestCorpusFile|BM_ParseLayoutLargestCorpusFile|BM_ParseLayoutGenerated1MB}"
for program in "$before" "$after"; do
    [ -x "$program" ] || { echo "not found: $program" >&2; exit 2; }
done

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for ((round = 1; round <= rounds; round++)); do
    for side in before after; do
        program=$before
        [ "$side" = after ] && program=$after
        "$program" --benchmark_filter="$filter" --benchmark_repetitions=5 \
            --benchmark_format=json >"$out/$side.$round.json" 2>/dev/null
        echo "round $round/$rounds: $side done" >&2
    done
done

python3 - "$out" "$rounds" <<'EOF'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
times = {}   # (benchmark, side) -> real times of every repetition, in the benchmark's unit
units = {}
rates = {}   # (benchmark, side) -> bytes/s of every repetition
for side in ("before", "after"):
    for r in range(1, rounds + 1):
        with open(f"{out}/{side}.{r}.json") as f:
            data = json.load(f)
        for b in data["benchmarks"]:
            if b.get("run_type") != "iteration":
                continue
            name = b["run_name"]
            times.setdefault((name, side), []).append(b["real_time"])
            units[name] = b["time_unit"]
            if "bytes_per_second" in b:
                rates.setdefault((name, side), []).append(b["bytes_per_second"])
names = sorted({name for name, _ in times})
print(f"{'benchmark':34} {'before':>12} {'after':>12} {'speed-up':>9}   MB/s before -> after")
for name in names:
    b = statistics.median(times[(name, "before")])
    a = statistics.median(times[(name, "after")])
    line = f"{name:34} {b:10.1f}{units[name]:>2} {a:10.1f}{units[name]:>2} {b / a:8.2f}x"
    if (name, "before") in rates and (name, "after") in rates:
        rb = statistics.median(rates[(name, "before")]) / 1e6
        ra = statistics.median(rates[(name, "after")]) / 1e6
        line += f"   {rb:7.1f} -> {ra:7.1f}"
    print(line)
print(f"(medians of {rounds} alternating rounds x 5 repetitions; real time)")
EOF
