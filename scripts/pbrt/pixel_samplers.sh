#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/pbrt_pixel_samplers.txt from a pbrt-v4 checkout:
#   scripts/pbrt/pixel_samplers.sh PATH/TO/pbrt-v4
# Only headers, two tables, pbrt's memory resource and two functions cut from its sources
# (HaltonSampler's constructor, ComputeRadicalInversePermutations: samplers.cpp and
# lowdiscrepancy.cpp as wholes pull in the scene and its submodules) are compiled (no
# CMake, no submodules).
# The fixture's first line names the pbrt-v4 commit it was built from (PBRT_COMMIT=... when
# PATH is an exported tree, not a git checkout).
set -euo pipefail
pbrt=${1:?usage: pixel_samplers.sh PATH/TO/pbrt-v4}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/../../crates/samplab/tests/fixtures/pbrt_pixel_samplers.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cut() { sed -n "/^$1/,/^}/p" "$pbrt/src/pbrt/$2"; }
{
    echo '#include <pbrt/samplers.h>'
    echo 'namespace pbrt {'
    cut 'HaltonSampler::HaltonSampler(' samplers.cpp
    cut 'pstd::vector<DigitPermutation> \*ComputeRadicalInversePermutations(' util/lowdiscrepancy.cpp
    echo '}'
} > "$tmp/cut.cpp"
g++ -std=c++17 -O1 -I "$pbrt/src" "$here/pixel_samplers.cpp" "$here/stubs.cpp" "$tmp/cut.cpp" \
    "$pbrt/src/pbrt/util/sobolmatrices.cpp" "$pbrt/src/pbrt/util/primes.cpp" \
    -DPBRT_HAVE_POSIX_MEMALIGN "$pbrt/src/pbrt/util/pstd.cpp" -o "$tmp/dump"
commit=${PBRT_COMMIT:-$(git -C "$pbrt" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# pbrt-v4 $commit: sampler randomize spp resx resy seed px py index dim f32-bits"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
