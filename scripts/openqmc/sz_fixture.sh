#!/usr/bin/env bash
# Regenerates crates/samplab/tests/fixtures/openqmc_sz.txt from an OpenQMC checkout whose
# SobolSampler runs on the SZ matrices (its pull request #108, commit 909333c or later):
#   scripts/openqmc/sz_fixture.sh PATH/TO/openqmc
# OpenQMC is header-only: one translation unit, no CMake.
# The fixture's first line names the commit it was built from (OQMC_COMMIT=... when PATH is
# an exported tree, not a git checkout).
set -euo pipefail
oqmc=${1:?usage: sz_fixture.sh PATH/TO/openqmc}
here=$(cd "$(dirname "$0")" && pwd)
out=$here/../../crates/samplab/tests/fixtures/openqmc_sz.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
grep -q 'SZ' "$oqmc/include/oqmc/owen.h" || { echo "sz_fixture.sh: $oqmc/include/oqmc/owen.h has no SZ matrices (before pull request #108?)" >&2; exit 2; }
g++ -std=c++17 -O1 -I "$oqmc/include" "$here/sz_fixture.cpp" -o "$tmp/dump"
commit=${OQMC_COMMIT:-$(git -C "$oqmc" rev-parse HEAD 2>/dev/null || echo unknown)}
{
    echo "# openqmc $commit: key x y frame index dim u32-bits"
    "$tmp/dump"
} > "$out"
echo "wrote $(wc -l < "$out") lines to $out"
