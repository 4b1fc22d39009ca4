#!/usr/bin/env bash
# Start-up time and memory of the simnode program running scenarios/network-1000.ini (1,000 nodes
# on one segment): the program's own "initialized in" line (alias allocation to the last
# Initialization Complete, from the first CID) and the peak RSS measured by /usr/bin/time.
# Usage: bench/simnode_network.sh [BUILD_DIR] [IMAGE_DIR]
#   BUILD_DIR defaults to build-i2-bench; IMAGE_DIR to a fresh directory on /dev/shm when there
#   is one (fresh images cost an fsync per file; run twice with the same IMAGE_DIR to time a
#   warm start from existing images).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-i2-bench}
base=/tmp
[ -d /dev/shm ] && base=/dev/shm
images=${2:-$(mktemp -d "$base/simnode-network-XXXXXX")}
start=$(date +%s.%N)
/usr/bin/time -f "peak RSS %M KiB, %e s wall, %U s user, %S s system" \
    "$build/simnode/simnode" scenarios/network-1000.ini --listen 127.0.0.1:0 \
    --image-dir "$images" --run-for 12 2>&1 | while IFS= read -r line; do
    printf '%8.3f s  %s\n' "$(echo "$(date +%s.%N) - $start" | bc)" "$line"
done
[ -z "${2:-}" ] && rm -rf "$images"
