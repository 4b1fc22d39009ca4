#!/bin/sh
# A full lcc-conform run at real CAN speed against its frame-time bound (issue 32): simnode paces
# its segment at 125 kbit/s and logs every frame (candump -L); the bound is the bus time of the
# run's own frames, each at its worst-case stuffed length (openlcb/can_timing.hpp). Prints the
# run's wall time, the bound, their ratio and the gaps between frames longer than GAP_MS.
# usage: bench/can_speed_bound.sh BUILD SCENARIO NODE_ID [lcc-conform options...]
# e.g.   bench/can_speed_bound.sh build io-board 05.01.01.01.22.10
set -eu
build=$1 scenario=$2 node=$3
shift 3
dir=$(mktemp -d)
"$build/simnode/simnode" --scenario "$scenario" --listen 127.0.0.1:0 --bitrate 125000 \
    --image-dir "$dir/img" --candump "$dir/can.log" --trace "$dir/trace.txt" --run-for 600 \
    >"$dir/sim.out" 2>&1 &
sim=$!
trap 'kill $sim 2>/dev/null; rm -rf "$dir"' EXIT
for _ in $(seq 50); do grep -q listening "$dir/sim.out" && break; sleep 0.1; done
port=$(sed -n 's/.*listening on [0-9.]*:\([0-9]*\).*/\1/p' "$dir/sim.out" | head -1)
sleep 1  # the nodes' own start-up frames are not the run's
before=$(wc -l <"$dir/can.log")
start=$(date +%s.%N)
"$build/conformance/lcc-conform" --connect "127.0.0.1:$port" --node "$node" --backup "$dir/b.txt" \
    --json "$dir/r.json" "$@" >"$dir/out.txt" 2>&1 || true
end=$(date +%s.%N)
sleep 0.2
python3 - "$dir/can.log" "$before" "$start" "$end" "$dir/r.json" "${GAP_MS:-40}" <<'PY'
import json, re, sys
log, before, start, end, report, gap_ms = sys.argv[1:7]
lines = open(log).read().splitlines()[int(before):]
def bits(n):  # worst-case stuffed 29-bit frame, as openlcb/can_timing.hpp
    stuffed = 54 + 8 * min(n, 8)
    return stuffed + 13 + (stuffed - 1) // 4
frames = []
for l in lines:
    m = re.match(r"\((\d+\.\d+)\) \S+ ([0-9A-Fa-f]+)#([0-9A-Fa-f]*)", l)
    if m: frames.append((float(m.group(1)), len(m.group(3)) // 2, m.group(2), m.group(3)))
bound = sum(bits(n) for _, n, _, _ in frames) / 125000
nominal = sum(67 + 8 * n for _, n, _, _ in frames) / 125000
wall = float(end) - float(start)
r = json.load(open(report))["nodes"][0]["summary"]
print(f"frames {len(frames)}  bound {bound:.3f} s (worst-case stuffing; {nominal:.3f} s nominal)")
print(f"run {wall:.3f} s wall  ratio {wall / bound:.3f}  checks {r}")
gaps = [(b[0] - a[0], a, b) for a, b in zip(frames, frames[1:]) if b[0] - a[0] > float(gap_ms) / 1000]
print(f"gaps > {gap_ms} ms: {len(gaps)}, {sum(g for g, _, _ in gaps):.3f} s; first frame at +{frames[0][0] - float(start):.3f} s, last at +{frames[-1][0] - float(start):.3f} s")
for g, a, b in gaps:
    print(f"  +{a[0] - float(start):7.3f} s  {g * 1000:6.0f} ms  after {a[2]}#{a[3]}  before {b[2]}#{b[3]}")
PY
[ -z "${KEEP:-}" ] || cp -r "$dir" "$KEEP"
