#!/bin/sh
# Full lcc-conform runs of two builds against the same simnode, in one hyperfine run, for the
# default and io-board scenarios (docs/benchmarks.md "lcc-conform").
# usage: bench/lcc_conform_compare.sh OLD_LCC_CONFORM NEW_LCC_CONFORM [SIMNODE]
# e.g. a worktree of an older commit built into /tmp/old/build against this tree's build/.
set -eu
old=$1
new=$2
simnode=${3:-build/simnode/simnode}
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'kill $(cat "$dir"/*.pid 2>/dev/null) 2>/dev/null; rm -rf "$dir"' EXIT
for scenario in default io-board; do
    "$simnode" --scenario "$root/scenarios/$scenario.ini" --listen 127.0.0.1:0 \
        --image-dir "$dir/img-$scenario" --run-for 600 >"$dir/$scenario.out" 2>&1 &
    echo $! >"$dir/$scenario.pid"
    for _ in 1 2 3 4 5 6 7 8 9 10; do grep -q listening "$dir/$scenario.out" && break; sleep 0.2; done
    port=$(sed -n 's/.*listening on [0-9.]*:\([0-9]*\).*/\1/p' "$dir/$scenario.out" | head -1)
    node=$(sed -n 's/^node-id *= *//p' "$root/scenarios/$scenario.ini")
    args="--connect 127.0.0.1:$port --node $node --backup $dir/b.txt"
    echo "== $scenario ($node)"
    hyperfine -N -i --warmup 1 --runs 7 -n old "$old $args" -n new "$new $args" \
        --export-json "$dir/$scenario.json" >/dev/null
    python3 - "$dir/$scenario.json" <<'PY'
import json, statistics, sys
for r in json.load(open(sys.argv[1]))["results"]:
    print(f"{r['command']:>4}: median {statistics.median(r['times']):.3f} s "
          f"(min {min(r['times']):.3f}, max {max(r['times']):.3f}, {len(r['times'])} runs)")
PY
done
