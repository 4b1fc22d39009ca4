#!/bin/sh
# Wall time of a full lcc-conform run against simnode's default scenario over TCP (target < 5 s).
# usage: bench/lcc_conform_run.sh BUILD_DIR
set -eu
build=${1:-build}
dir=$(mktemp -d)
"$build/simnode/simnode" --scenario "$(dirname "$0")/../scenarios/default.ini" --listen 127.0.0.1:0 \
    --image-dir "$dir/img" >"$dir/sim.out" 2>&1 &
sim=$!
trap 'kill $sim 2>/dev/null; rm -rf "$dir"' EXIT
for _ in 1 2 3 4 5 6 7 8 9 10; do grep -q listening "$dir/sim.out" && break; sleep 0.2; done
port=$(sed -n 's/.*listening on [0-9.]*:\([0-9]*\).*/\1/p' "$dir/sim.out" | head -1)
run="$build/conformance/lcc-conform --connect 127.0.0.1:$port --node 05.01.01.01.22.00 --backup $dir/b.txt"
if command -v hyperfine >/dev/null; then
    hyperfine -i --warmup 1 --runs 5 "$run"
else
    for _ in 1 2 3; do /usr/bin/time -f "full run: %e s wall" $run >/dev/null || true; done
fi
