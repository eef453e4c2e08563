#!/usr/bin/env bash
# Cycles' sampling patterns beside samplab's cycles.* families, drawn the same way, side by
# side in one run:
#   scripts/cycles/throughput.sh PATH/TO/cycles
# Cycles' headers compiled as its Release build compiles them (-O3 -DNDEBUG), for the same
# baseline x86-64 as samplab's release build.
set -euo pipefail
cycles=${1:?usage: throughput.sh PATH/TO/cycles}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
g++ -std=c++20 -O3 -DNDEBUG -DCCL_NAMESPACE_BEGIN='namespace ccl {' -DCCL_NAMESPACE_END='}' \
    -I "$here/stub" -I "$cycles/src" "$here/throughput.cpp" "$cycles/src/scene/tabulated_sobol.cpp" -o "$tmp/throughput"
cd "$here/../.."
cargo build --release --quiet -p samplab --example pixel_throughput
for round in 1 2 3; do
  "$tmp/throughput"
  target/release/examples/pixel_throughput cycles.sobol-burley cycles.tabulated-sobol cycles.blue-noise-pure cycles.blue-noise-first
done
