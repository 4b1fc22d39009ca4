#!/usr/bin/env bash
# Start-up time and memory of the simnode program running a network on one segment: the
# program's own "initialized in" line (alias allocation to the last Initialization Complete, from
# the first CID), the time since launch of every line (node creation included), the peak RSS
# measured by /usr/bin/time, and how long `lcc-conform --list` takes to find every node.
# Usage: bench/simnode_network.sh [BUILD_DIR] [IMAGE_DIR] [NODES]
#   BUILD_DIR defaults to build-i2-bench; IMAGE_DIR to a fresh directory on /dev/shm when there
#   is one (fresh images cost an fsync per file; run twice with the same IMAGE_DIR to time a
#   warm start from existing images; "" for a fresh one). NODES: scenarios/network-1000.ini's
#   mix (60 % I/O boards, 40 % small nodes) with that many nodes, at most 4,095 (one segment's
#   aliases); without it scenarios/network-1000.ini itself.
# Environment: LCC_CONFORM, the lcc-conform for --list (default BUILD_DIR's; none: no --list, as
#   for a build of simnode alone); STARTUP_LIMIT, seconds to wait for the nodes (default 600).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${1:-build-i2-bench}
base=/tmp
[ -d /dev/shm ] && base=/dev/shm
images=${2:-}
nodes=${3:-}
fresh_images=0
if [ -z "$images" ]; then
    images=$(mktemp -d "$base/simnode-network-XXXXXX")
    fresh_images=1
fi
conform=${LCC_CONFORM-$build/conformance/lcc-conform}
limit=${STARTUP_LIMIT:-600}
work=$(mktemp -d)
cleanup() {
    rm -rf "$work"
    if [ "$fresh_images" = 1 ]; then rm -rf "$images"; fi
}
trap cleanup EXIT

scenario=scenarios/network-1000.ini
if [ -n "$nodes" ]; then
    if ! [ "$nodes" -ge 2 ] 2>/dev/null; then
        echo "NODES must be a number >= 2, not '$nodes'" >&2
        exit 2
    fi
    io=$((nodes * 6 / 10))
    scenario=$work/network.ini
    cat >"$scenario" <<EOF
# scenarios/network-1000.ini's mix with $nodes nodes (bench/simnode_network.sh).
user-description = Node {n} of its group, {id}

[node.io]
node-id = 05.01.01.02.00.00
count = $io
cdi = $root/scenarios/io-board.xml
user-name = I/O board {n}

[node.small]
node-id = 05.01.01.03.00.00
count = $((nodes - io))
cdi = $root/scenarios/default.xml
user-name = Small node {n}
EOF
fi

# Every line of simnode's with the time since launch; the one line per node is counted instead.
start=$(date +%s.%N)
stamp() {
    local line described=0
    while IFS= read -r line; do
        case $line in
            "simnode: node "*) described=$((described + 1)) ;;
            *) printf '%8.3f s  %s\n' "$(echo "$(date +%s.%N) - $start" | bc)" "$line" ;;
        esac
    done
    echo "          ($described node lines)"
}
mkfifo "$work/out"
stamp <"$work/out" | tee "$work/log" &
reader=$!
/usr/bin/time -o "$work/time" -f "peak RSS %M KiB, %e s wall, %U s user, %S s system" \
    "$build/simnode/simnode" "$scenario" --listen 127.0.0.1:0 --image-dir "$images" \
    --run-for "$((limit + 600))" >"$work/out" 2>&1 &
timer=$!

# SIGINT, and SIGKILL when it is not heeded within 10 s (a build from before issue 32 never
# returns to its io loop while more nodes than aliases contend for one).
stop_simnode() {
    local pid
    pid=$(pgrep -P "$timer") || return 0
    kill -INT "$pid" 2>/dev/null || return 0
    for _ in $(seq 1 100); do
        kill -0 "$pid" 2>/dev/null || return 0
        sleep 0.1
    done
    kill -KILL "$pid" 2>/dev/null || true
}

for _ in $(seq 1 $((limit * 10))); do
    grep -q "initialized in" "$work/log" && break
    kill -0 "$timer" 2>/dev/null || break
    sleep 0.1
done
if ! grep -q "initialized in" "$work/log"; then
    stop_simnode
    wait "$timer" || true
    wait "$reader" || true
    echo "simnode did not initialize its nodes" >&2
    exit 1
fi

if [ -x "$conform" ]; then
    port=$(grep -o "listening on 127.0.0.1:[0-9]*" "$work/log" | sed 's/.*://')
    wanted=$(grep -o "[0-9]* node(s) initialized" "$work/log" | cut -d' ' -f1)
    listed=$(date +%s.%N)
    "$conform" --connect "127.0.0.1:$port" --list >"$work/list" 2>&1 || true
    took=$(echo "$(date +%s.%N) - $listed" | bc)
    found=$(grep -c '^05\.01\.01\.0' "$work/list" || true)
    printf '          --list: %s of %s nodes in %.3f s\n' "$found" "$wanted" "$took"
    if [ "$found" != "$wanted" ]; then tail -n 3 "$work/list" | sed 's/^/          /'; fi
fi

stop_simnode
wait "$timer" || true
wait "$reader" || true
cat "$work/time"
