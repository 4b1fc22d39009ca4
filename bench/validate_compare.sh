#!/usr/bin/env bash
# Compares bench_cdi of two builds side by side: runs them alternately (so a change in machine
# load hits both alike), each run with --benchmark_repetitions=5, and prints per benchmark the
# median CPU and real time over all repetitions of all rounds, before and after.
#
#   bench/validate_compare.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [ROUNDS] [FILTER]
#
# ROUNDS defaults to 5; FILTER to the validate and parse+layout benchmarks. Each build dir must
# hold bench/bench_cdi (cmake --build DIR --target bench_cdi).
#
#   bench/validate_compare.sh --e2e BEFORE_BUILD_DIR AFTER_BUILD_DIR [PAIRS]
#
# End to end instead: whole `lcc-cdi validate` processes over every corpus and scenario CDI, one
# process for all files and one per file, before and after alternating; prints the median wall
# time of each and the median of the per-pair ratios. PAIRS defaults to 100 (a tenth of that
# for the per-file loop). Each build dir must hold cdi/lcc-cdi.
set -euo pipefail

usage() {
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
}

if [ "${1:-}" = --e2e ]; then
    [ $# -ge 3 ] || usage
    root=$(cd "$(dirname "$0")/.." && pwd)
    for program in "$2/cdi/lcc-cdi" "$3/cdi/lcc-cdi"; do
        [ -x "$program" ] || { echo "not found: $program" >&2; exit 2; }
    done
    exec python3 - "$2/cdi/lcc-cdi" "$3/cdi/lcc-cdi" "${4:-100}" "$root" <<'PY'
import glob, statistics, subprocess, sys, time
before, after, pairs, root = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
files = sorted(glob.glob(f"{root}/../shared/corpus/cdi/*.xml"))
files += sorted(glob.glob(f"{root}/scenarios/*.xml"))

def run(program, per_file):
    # Output goes to /dev/null: what is timed is the program, not a terminal or a pipe.
    start = time.perf_counter()
    for args in ([[f] for f in files] if per_file else [files]):
        subprocess.run([program, "validate", *args], stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    return time.perf_counter() - start

print(f"{len(files)} CDIs; before {before}, after {after}")
med = statistics.median
for per_file, n in ((False, pairs), (True, max(pairs // 10, 3))):
    for program in (before, after):  # warm-up: page cache, dynamic loader
        run(program, per_file)
    b, a = [], []
    for _ in range(n):  # alternating, so a drift in machine speed hits both alike
        b.append(run(before, per_file))
        a.append(run(after, per_file))
    what = "one process per file" if per_file else "one process, all files"
    print(f"{what:23} before {med(b) * 1e3:8.2f} ms  after {med(a) * 1e3:8.2f} ms"
          f"  after/before {med([y / x for x, y in zip(b, a)]):.3f} (median of {n} pairs)")
PY
fi

[ $# -ge 2 ] || usage
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
