#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/onetwo_pixels.txt from a checkout of the OneTwo
# paper's supplement (Bonneel et al. 2025, github.com/liris-origami/OneTwoSobolSequences),
# whose sampler/pbrt/src-pbrt-ours is the pbrt-v4 source tree with the authors' OneTwoSampler:
#   scripts/onetwo/pixels.sh PATH/TO/OneTwoSobolSequences
# Only headers, pbrt's memory resource and its two tables are compiled, with the stubs of
# scripts/pbrt (no CMake, no submodules). The fixture's first line names the commit
# (ONETWO_COMMIT=... when PATH is an exported tree, not a git checkout).
set -euo pipefail
src=${1:?usage: pixels.sh PATH/TO/OneTwoSobolSequences}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/../../crates/samplab/tests/fixtures/onetwo_pixels.txt
pbrt=$src/sampler/pbrt/src-pbrt-ours
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the tree is pbrt's src/pbrt under another name
mkdir "$tmp/include" && ln -s "$(cd "$pbrt" && pwd)" "$tmp/include/pbrt"
g++ -std=c++17 -O1 -I "$tmp/include" "$here/pixels.cpp" "$here/../pbrt/stubs.cpp" \
    "$pbrt/util/sobolmatrices.cpp" "$pbrt/util/primes.cpp" \
    -DPBRT_HAVE_POSIX_MEMALIGN "$pbrt/util/pstd.cpp" -o "$tmp/dump"
commit=${ONETWO_COMMIT:-$(git -C "$src" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# OneTwoSobolSequences $commit (its pbrt-v4 OneTwoSampler): spp seed px py index dim f32-bits"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
