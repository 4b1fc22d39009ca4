#!/usr/bin/env bash
# Compares ImageFile::write of two source trees side by side: builds bench/image_write.cpp
# against each tree's built olcb_memory and olcb_base, then times them alternately with
# bench/paired.py (after, before, after, ...; per-pair ratios after/before of the microseconds
# per write each run prints, and of its whole process), on DIR's file system.
#
#   bench/image_write_compare.sh BEFORE_SRC BEFORE_BUILD AFTER_SRC AFTER_BUILD DIR [WRITES]
#
# Each build dir must hold memory/libolcb_memory.a and base/libolcb_base.a
# (cmake --build BUILD --target olcb_memory). WRITES defaults to 2000.
set -euo pipefail
[ $# -ge 5 ] || { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build() {  # SRC BUILD NAME
    g++ -std=c++20 -O2 -I"$1" "$here/image_write.cpp" "$2/memory/libolcb_memory.a" \
        "$2/base/libolcb_base.a" -o "$out/$3"
}
build "$1" "$2" before
build "$3" "$4" after
writes=${6:-2000}
python3 "$here/paired.py" -n 10 --warmup 1 --timeout 600 --names after,before \
    --figure 'us per write=([0-9.]+) us per write' -- \
    "$out/after" "$5/after" "$writes" --vs "$out/before" "$5/before" "$writes"
