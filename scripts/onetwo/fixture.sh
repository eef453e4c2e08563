#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/onetwo.txt from a checkout of the OneTwo paper's
# supplement (Bonneel et al. 2025, github.com/liris-origami/OneTwoSobolSequences):
#   scripts/onetwo/fixture.sh PATH/TO/OneTwoSobolSequences
# The samples come from the authors' own exported matrices (sampler/onetwo_matrices.cpp),
# which samplab does not read: it bakes data/onetwo-692.txt, whose body this script first
# checks is the supplement's OneTwoSeq_data/sobolOneTwoSeq_init_tab.dat.
# The fixture's first line names the commit it was built from (ONETWO_COMMIT=... when PATH
# is an exported tree, not a git checkout).
set -euo pipefail
src=${1:?usage: fixture.sh PATH/TO/OneTwoSobolSequences}
here=$(cd "$(dirname "$0")" && pwd)
root=$here/../..
out=$root/crates/samplab/tests/fixtures/onetwo.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -v '^#' "$root/crates/samplab/data/onetwo-692.txt" > "$tmp/ours.dat"
cmp -s "$tmp/ours.dat" "$src/OneTwoSeq_data/sobolOneTwoSeq_init_tab.dat" \
    || { echo "fixture.sh: data/onetwo-692.txt is not $src/OneTwoSeq_data/sobolOneTwoSeq_init_tab.dat" >&2; exit 2; }
g++ -std=c++11 -O1 -I "$src/sampler" "$here/fixture.cpp" "$src/sampler/onetwo_matrices.cpp" -o "$tmp/dump"
commit=${ONETWO_COMMIT:-$(git -C "$src" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# OneTwoSobolSequences $commit: dim index u32-bits"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
