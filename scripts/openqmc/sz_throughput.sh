#!/usr/bin/env bash
# OpenQMC's SobolSampler on the SZ matrices (its pull request #108, commit 909333c or later)
# beside samplab's openqmc.sz, drawn the same way, side by side in one run:
#   scripts/openqmc/sz_throughput.sh PATH/TO/openqmc
# Compiled as a CMake Release build of OpenQMC compiles it (-O3 -DNDEBUG), for the same
# baseline x86-64 as samplab's release build.
set -euo pipefail
oqmc=${1:?usage: sz_throughput.sh PATH/TO/openqmc}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
g++ -std=c++17 -O3 -DNDEBUG -I "$oqmc/include" "$here/sz_throughput.cpp" -o "$tmp/throughput"
cd "$here/../.."
cargo build --release --quiet -p samplab --example pixel_throughput
for round in 1 2 3; do
  "$tmp/throughput"
  target/release/examples/pixel_throughput openqmc.sz
done
