#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/xi.txt from the xi-sequence code of Ahmed et al.
# 2023 ("Analysis and synthesis of digital dyadic sequences"): the authors' supplemental
# xi.h, as Samplin' Safari carries it (github.com/wkjarosz/SamplinSafari,
# include/sampler/xi.h):
#   scripts/xi/fixture.sh PATH/TO/DIRECTORY/WITH/xi.h
# The fixture's first line names the source (XI_SOURCE=...).
set -euo pipefail
src=${1:?usage: fixture.sh PATH/TO/DIRECTORY/WITH/xi.h}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/../../crates/samplab/tests/fixtures/xi.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
g++ -std=c++11 -O1 -I "$src" "$here/fixture.cpp" -o "$tmp/dump"
{
    echo "# xi.h of ${XI_SOURCE:-$src}: index x-bits y-bits (default a and p0)"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
