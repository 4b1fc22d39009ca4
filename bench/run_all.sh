#!/usr/bin/env bash
# Runs every Google Benchmark of every bench/bench_* program, each benchmark in its own process
# (bench/run_each.py says why), and writes one result: RESULT.json and RESULT.md beside it (the
# machine, the settings, a table per program). docs/benchmarks.md's generated tables come from
# such a result: bench/benchmarks_doc.py RESULT.json docs/benchmarks.md.
#
#   bench/run_all.sh [--quick] [--build-dir DIR] [--no-build] [--out RESULT.json]
#                    [--processes P] [--repetitions R] [--filter REGEX] [--shared]
#
# Without --build-dir it builds build-bench in Release (as CI would not: CI runs no benchmarks);
# with it, it builds the bench targets in DIR (nothing with --no-build) and measures that build.
# Defaults: 3 processes x 3 repetitions per benchmark, about 8 minutes on the 2-core machine;
# --quick is 1 x 1 with short minimum times, under a minute (a smoke run, not a result). RESULT
# defaults to DIR/bench-results.json. --filter REGEX keeps benchmarks whose "program/name"
# matches; --shared runs each program's benchmarks in one process, the old way, for comparison.
# OLCB_JOBS sets the build's parallelism (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
}

build_dir=""
build=1
out=""
runner_args=()
while [ $# -gt 0 ]; do
    case $1 in
        --quick | --shared) runner_args+=("$1") ;;
        --processes | --repetitions | --filter)
            [ $# -ge 2 ] || usage
            runner_args+=("$1" "$2")
            shift
            ;;
        --build-dir)
            [ $# -ge 2 ] || usage
            build_dir=$2
            shift
            ;;
        --no-build) build=0 ;;
        --out)
            [ $# -ge 2 ] || usage
            out=$2
            shift
            ;;
        -h | --help) usage ;;
        *) usage ;;
    esac
    shift
done

jobs=${OLCB_JOBS:-2}
if [ -z "$build_dir" ]; then
    build_dir="build-bench"
    if [ "$build" = 1 ]; then
        ci/setup >/dev/null
        cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DOLCB_TESTS=OFF >/dev/null
        cmake --build "$build_dir" -j"$jobs" >/dev/null
    fi
elif [ "$build" = 1 ]; then
    # The bench targets only: a shared build dir's other targets are someone else's business.
    targets=()
    for src in bench/bench_*.cpp; do
        name=${src##*/}
        targets+=("${name%.cpp}")
    done
    cmake --build "$build_dir" -j"$jobs" --target "${targets[@]}" >/dev/null
fi
[ -n "$out" ] || out="$build_dir/bench-results.json"

python3 bench/run_each.py --build-dir "$build_dir" --out "$out" "${runner_args[@]}"
python3 bench/benchmarks_doc.py "$out" >"${out%.json}.md"
echo "result: $out and ${out%.json}.md"
