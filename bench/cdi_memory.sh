#!/usr/bin/env bash
# Peak memory and time of lcc-cdi on CDIs at the 16 MiB limit (issue 31): the peak resident set
# (GNU time's %M) and wall time of `validate`, `layout`, `render` and `render --html`, medians of
# RUNS runs, on two generated CDIs just under kMaxCdiBytes, and the refusal of a 100 MB one.
#
#   bench/cdi_memory.sh [BUILD_DIR [RUNS]]      BUILD_DIR defaults to build, RUNS to 5
#
# The CDIs (generated into a temporary directory, removed at the end):
#   realistic  3,200 segments of 4 replicated groups, each a string, two ints (one with a map)
#              and two eventids, all with names and descriptions: about 95 bytes per element
#   dense      1.1 million `<int size="1"/>`: 15 bytes per element, the worst case per byte
# Needs GNU time (/usr/bin/time; Debian package `time`) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
runs=${2:-5}
lcc_cdi="$build/cdi/lcc-cdi"
[ -x "$lcc_cdi" ] || { echo "not found: $lcc_cdi (cmake --build $build --target lcc-cdi)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "GNU time is not installed (apt-get install time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$work" <<'PY'
import sys
work = sys.argv[1]
limit = 16 * 1024 * 1024
head = ('<?xml version="1.0"?>\n<cdi xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
        'xsi:noNamespaceSchemaLocation="http://openlcb.org/schema/cdi/1/4/cdi.xsd">\n'
        '<identification><manufacturer>Bench</manufacturer><model>Big</model>'
        '<hardwareVersion>1</hardwareVersion><softwareVersion>1</softwareVersion>'
        '</identification>\n<acdi/>\n')

def realistic(seg):
    line = ('    <string size="32"><name>Description</name>'
            '<description>A name for this line.</description></string>\n'
            '    <int size="1"><name>Function</name><description>What the line does.</description>'
            '<min>0</min><max>2</max><default>0</default><map>'
            '<relation><property>0</property><value>Input</value></relation>'
            '<relation><property>1</property><value>Output</value></relation>'
            '<relation><property>2</property><value>Disabled</value></relation></map></int>\n'
            '    <int size="2"><name>Delay</name><description>Debounce delay in milliseconds.'
            '</description><min>0</min><max>60000</max><default>50</default></int>\n'
            '    <eventid><name>Event On</name><description>Sent when the line turns on.'
            '</description></eventid>\n'
            '    <eventid><name>Event Off</name><description>Sent when the line turns off.'
            '</description></eventid>\n')
    groups = ''.join(f'  <group replication="2"><name>Line {g}</name><description>One input or '
                     f'output line, with its events and timing.</description><repname>Line'
                     f'</repname>\n{line}  </group>\n' for g in range(4))
    return (f'<segment space="253" origin="{seg * 100000}"><name>Segment {seg}</name>'
            f'<description>Port block {seg} of the bench node.</description>\n{groups}</segment>\n')

def dense(seg):
    return (f'<segment space="253" origin="{seg * 1000}">' + '<int size="1"/>' * 1000 +
            '</segment>\n')

for name, make in (('realistic', realistic), ('dense', dense)):
    parts, size, seg = [head], len(head), 0
    while True:
        part = make(seg)
        if size + len(part) + len('</cdi>\n') > limit:
            break
        parts.append(part)
        size += len(part)
        seg += 1
    parts.append('</cdi>\n')
    with open(f'{work}/{name}.xml', 'w') as f:
        f.write(''.join(parts))
PY
truncate -s 100000000 "$work/huge.xml"

# One line per command and CDI: median wall seconds and peak RSS over the runs.
measure() {
    local label=$1 file=$2
    shift 2
    local samples=()
    for ((i = 0; i < runs; i++)); do
        /usr/bin/time -f '%e %M' -o "$work/time" "$lcc_cdi" "$@" "$file" >/dev/null 2>&1 || true
        samples+=("$(tail -1 "$work/time")")
    done
    printf '%s\n' "${samples[@]}" | python3 -c '
import statistics, sys
label, size = sys.argv[1], int(sys.argv[2])
rows = [line.split() for line in sys.stdin if line.strip()]
wall = statistics.median(float(r[0]) for r in rows)
rss = statistics.median(int(r[1]) for r in rows) * 1024
print(f"{label:34} {wall:8.2f} s {rss / 2**20:9.1f} MiB {rss / size:6.1f}x input")
' "$label" "$(stat -c %s "$file")"
}

echo "lcc-cdi: $lcc_cdi; medians of $runs runs; $(nproc) cores, $(uname -r)"
for cdi in realistic dense; do
    echo "$cdi.xml: $(stat -c %s "$work/$cdi.xml") bytes"
    measure "  validate" "$work/$cdi.xml" validate
    measure "  layout" "$work/$cdi.xml" layout
    measure "  render" "$work/$cdi.xml" render
    measure "  render --html" "$work/$cdi.xml" render --html
done
echo "huge.xml: 100000000 bytes (sparse), refused"
measure "  validate" "$work/huge.xml" validate
