#!/usr/bin/env bash
# Compares bench_cdi of two builds side by side: runs them alternately (so a change in machine
# load hits both alike), each run with --benchmark_repetitions=5, and prints per benchmark the
# median CPU and real time over all repetitions of all rounds, before and after.
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
real, cpu, rates, units = {}, {}, {}, {}  # (benchmark, side) -> every repetition's value
for side in ("before", "after"):
    for r in range(1, rounds + 1):
        with open(f"{out}/{side}.{r}.json") as f:
            data = json.load(f)
        for b in data["benchmarks"]:
            if b.get("run_type") != "iteration":
                continue
            key = (b["run_name"], side)
            real.setdefault(key, []).append(b["real_time"])
            cpu.setdefault(key, []).append(b["cpu_time"])
            units[b["run_name"]] = b["time_unit"]
            if "bytes_per_second" in b:  # Google Benchmark divides by CPU time
                rates.setdefault(key, []).append(b["bytes_per_second"] / 1e6)
med = statistics.median
print(f"{'benchmark':32} {'unit':>4} {'cpu before':>11} {'cpu after':>11} {'speed-up':>8}"
      f" {'real before':>12} {'real after':>11}  MB/s (cpu) before -> after")
for name in sorted({n for n, _ in real}):
    b, a = (name, "before"), (name, "after")
    line = (f"{name:32} {units[name]:>4} {med(cpu[b]):11.1f} {med(cpu[a]):11.1f}"
            f" {med(cpu[b]) / med(cpu[a]):7.2f}x {med(real[b]):12.1f} {med(real[a]):11.1f}")
    if b in rates and a in rates:
        line += f"  {med(rates[b]):7.1f} -> {med(rates[a]):7.1f}"
    print(line)
print(f"(medians over {rounds} alternating rounds x 5 repetitions; on a loaded machine trust the "
      "CPU-time columns, real time includes waiting for a core)")
EOF
