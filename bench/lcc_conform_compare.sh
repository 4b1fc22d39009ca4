#!/usr/bin/env bash
# Full lcc-conform runs of two builds against the same simnode, side by side (new, old, new,
# old, ...: bench/paired.py), for the default and io-board scenarios; prints the medians and the
# median of the per-pair ratios new/old (docs/benchmarks.md "lcc-conform").
#
#   bench/lcc_conform_compare.sh OLD_LCC_CONFORM NEW_LCC_CONFORM [SIMNODE] [PAIRS]
#
# e.g. a worktree of an older commit built into /tmp/old/build against this tree's build/.
# SIMNODE defaults to build/simnode/simnode, PAIRS to 7 (after one warm-up pair).
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
old=$1
new=$2
simnode=${3:-build/simnode/simnode}
pairs=${4:-7}
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
cleanup() {
    for pidfile in "$dir"/*.pid; do
        [ -e "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null
    done
    rm -rf "$dir"
}
trap cleanup EXIT
for scenario in default io-board; do
    "$simnode" --scenario "$root/scenarios/$scenario.ini" --listen 127.0.0.1:0 \
        --image-dir "$dir/img-$scenario" --run-for 600 >"$dir/$scenario.out" 2>&1 &
    echo $! >"$dir/$scenario.pid"
    for _ in 1 2 3 4 5 6 7 8 9 10; do grep -q listening "$dir/$scenario.out" && break; sleep 0.2; done
    port=$(sed -n 's/.*listening on [0-9.]*:\([0-9]*\).*/\1/p' "$dir/$scenario.out" | head -1)
    node=$(sed -n 's/^node-id *= *//p' "$root/scenarios/$scenario.ini")
    args=(--connect "127.0.0.1:$port" --node "$node" --backup "$dir/b.txt")
    echo "== $scenario ($node)"
    python3 "$root/bench/paired.py" -n "$pairs" --warmup 1 --timeout 300 --names new,old -- \
        "$new" "${args[@]}" --vs "$old" "${args[@]}"
done
