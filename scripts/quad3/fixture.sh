#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/quad_optimized.txt from a checkout of the code
# of "Quad-optimized low-discrepancy sequences" (Ostromoukhov et al. 2024,
# github.com/liris-origami/Quad-Optimized-LDS):
#   scripts/quad3/fixture.sh PATH/TO/Quad-Optimized-LDS
# Their tool `samplerGF3` prints the generating matrices it builds (9 x 9 digits, 46
# dimensions: the most it allows) before its randomly scrambled points; the fixture keeps
# the matrices. The script first checks that samplab's data/quad-optimized-gf3.txt is their
# initIrreducibleGF3.dat below its comment. The first line names the commit (QUAD_COMMIT=...
# when PATH is an exported tree, not a git checkout).
set -euo pipefail
src=${1:?usage: fixture.sh PATH/TO/Quad-Optimized-LDS}
here=$(cd "$(dirname "$0")" && pwd)
root=$here/../..
out=$root/crates/samplab/tests/fixtures/quad_optimized.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '^#' "$root/crates/samplab/data/quad-optimized-gf3.txt" > "$tmp/ours.dat"
cmp -s "$tmp/ours.dat" "$src/initIrreducibleGF3.dat" \
    || { echo "fixture.sh: data/quad-optimized-gf3.txt is not $src/initIrreducibleGF3.dat" >&2; exit 2; }
g++ -std=c++17 -O1 -I "$src" "$src/samplerGF3.cpp" -o "$tmp/samplerGF3"
commit=${QUAD_COMMIT:-$(git -C "$src" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# Quad-Optimized-LDS $commit: samplerGF3 -m 9 -d 46, the matrices (row r: the digits of weight 3^-(r+1))"
    "$tmp/samplerGF3" -i "$src/initIrreducibleGF3.dat" -m 9 -d 46 | sed '/dimensions\.$/,$d' | grep -v '^$'
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
