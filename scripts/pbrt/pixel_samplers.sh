#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/pbrt_pixel_samplers.txt from a pbrt-v4 checkout:
#   scripts/pbrt/pixel_samplers.sh PATH/TO/pbrt-v4
# Only headers and two tables of pbrt's sources are compiled (no CMake, no submodules).
# The fixture's first line names the pbrt-v4 commit it was built from (PBRT_COMMIT=... when
# PATH is an exported tree, not a git checkout).
set -euo pipefail
pbrt=${1:?usage: pixel_samplers.sh PATH/TO/pbrt-v4}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/../../crates/samplab/tests/fixtures/pbrt_pixel_samplers.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
g++ -std=c++17 -O1 -I "$pbrt/src" "$here/pixel_samplers.cpp" "$here/stubs.cpp" \
    "$pbrt/src/pbrt/util/sobolmatrices.cpp" "$pbrt/src/pbrt/util/primes.cpp" -o "$tmp/dump"
commit=${PBRT_COMMIT:-$(git -C "$pbrt" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# pbrt-v4 $commit: sampler randomize spp resx resy seed px py index dim f32-bits"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
