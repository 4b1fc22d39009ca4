#!/usr/bin/env bash
# Compares bench_cdi of two builds side by side: for each benchmark, pairs of processes (before,
# then after; each --benchmark_repetitions=5, that benchmark alone in its process, so no other
# benchmark's heap state is measured along), and prints per benchmark the median of both sides
# and the median of the per-pair ratios before/after (the speed-up), with their range.
#
#   bench/validate_compare.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [PAIRS] [FILTER]
#
# PAIRS defaults to 5 (after one warm-up pair); FILTER (a Google Benchmark regex) to the validate
# and parse+layout benchmarks. Each build dir must hold bench/bench_cdi (cmake --build DIR
# --target bench_cdi).
#
#   bench/validate_compare.sh --e2e BEFORE_BUILD_DIR AFTER_BUILD_DIR [PAIRS]
#
# End to end instead: whole `lcc-cdi validate` processes over every corpus and scenario CDI, one
# process for all files and one per file, before and after alternating; prints the median wall
# and CPU time of each and the median of the per-pair ratios before/after. PAIRS defaults to 100
# (a tenth of that for the per-file loop). Each build dir must hold cdi/lcc-cdi.
set -euo pipefail

usage() {
    sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
}

if [ "${1:-}" = --e2e ]; then
    [ $# -ge 3 ] || usage
    root=$(cd "$(dirname "$0")/.." && pwd)
    for program in "$2/cdi/lcc-cdi" "$3/cdi/lcc-cdi"; do
        [ -x "$program" ] || { echo "not found: $program" >&2; exit 2; }
    done
    exec python3 - "$2/cdi/lcc-cdi" "$3/cdi/lcc-cdi" "${4:-100}" "$root" <<'PY'
import glob, resource, subprocess, sys, time
before, after, pairs, root = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
sys.path.insert(0, f"{root}/bench")
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import paired  # noqa: E402  (bench/paired.py: A B A B, per-pair ratios)
files = sorted(glob.glob(f"{root}/../shared/corpus/cdi/*.xml"))
files += sorted(glob.glob(f"{root}/scenarios/*.xml"))

def timed(program, per_file):
    def run():
        # Output goes to /dev/null: what is timed is the program, not a terminal or a pipe.
        t0, c0 = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
        for args in ([[f] for f in files] if per_file else [files]):
            subprocess.run([program, "validate", *args], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
        return {"wall ms": (time.perf_counter() - t0) * 1e3, "cpu ms": cpu * 1e3}
    return run

print(f"{len(files)} CDIs; before {before}, after {after}")
for per_file, n in ((False, pairs), (True, max(pairs // 10, 3))):
    done = paired.run_pairs(timed(before, per_file), timed(after, per_file), n, warmup=1)
    print("== " + ("one process per file" if per_file else "one process, all files"))
    paired.print_summary(paired.summarize(done), ("before", "after"), len(done))
PY
fi

[ $# -ge 2 ] || usage
before="$1/bench/bench_cdi"
after="$2/bench/bench_cdi"
pairs="${3:-5}"
filter="${4:-BM_ValidateLargestCorpusFile|BM_ParseLayoutLargestCorpusFile|BM_ParseLayoutGenerated1MB}"
for program in "$before" "$after"; do
    [ -x "$program" ] || { echo "not found: $program" >&2; exit 2; }
done

here=$(cd "$(dirname "$0")" && pwd)
mapfile -t names < <("$after" --benchmark_list_tests --benchmark_filter="$filter")
[ ${#names[@]} -gt 0 ] || { echo "no benchmark of $after matches $filter" >&2; exit 2; }
for name in "${names[@]}"; do
    # The name as a regex matching only itself: Google Benchmark's filter is a regex.
    only="^$(printf '%s' "$name" | sed 's/[][\\^$.|?*+(){}]/\\&/g')\$"
    args=(--benchmark_filter="$only" --benchmark_repetitions=5
        --benchmark_report_aggregates_only=true --benchmark_format=json)
    echo "== $name"
    python3 "$here/paired.py" --gbench -n "$pairs" --warmup 1 --names before,after -- \
        "$before" "${args[@]}" --vs "$after" "${args[@]}"
done
echo "(before/after above 1: after is faster. Each side's figure is one process's median of 5"
echo " repetitions; on a loaded machine trust the cpu rows, real time includes waiting for a core)"
