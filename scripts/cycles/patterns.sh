#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/cycles_patterns.txt from a Blender Cycles
# checkout (github.com/blender/cycles, or intern/cycles of Blender's tree as PATH/..):
#   scripts/cycles/patterns.sh PATH/TO/cycles
# Compiles Cycles' sampling headers (kernel/sample/*.h, util/*.h) and its table generator
# (scene/tabulated_sobol.cpp) with the stub kernel globals of scripts/cycles/stub (no CMake,
# no scene). The fixture's first line names the commit (CYCLES_COMMIT=... when PATH is an
# exported tree, not a git checkout).
set -euo pipefail
cycles=${1:?usage: patterns.sh PATH/TO/cycles}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/../../crates/samplab/tests/fixtures/cycles_patterns.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Cycles' kernel is compiled without contracting a * b + c (its CPU kernels are built per
# instruction set; the baseline x86-64 one has no FMA): -ffp-contract=off keeps the table
# generator's float arithmetic as written
g++ -std=c++20 -O1 -ffp-contract=off -DCCL_NAMESPACE_BEGIN='namespace ccl {' -DCCL_NAMESPACE_END='}' \
    -I "$here/stub" -I "$cycles/src" "$here/patterns.cpp" "$cycles/src/scene/tabulated_sobol.cpp" -o "$tmp/dump"
commit=${CYCLES_COMMIT:-$(git -C "$cycles" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# cycles $commit: pattern spp seed scrambling_distance x y sample, f32 bits of dimensions 0-7; frame_seed seed frame hash_uint2; class_a sample 0|1"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
