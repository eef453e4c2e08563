#!/usr/bin/env bash
# The OneTwo paper's pbrt-v4 sampler beside samplab's pbrt.onetwo, drawn the same way, side
# by side in one run:
#   scripts/onetwo/throughput.sh PATH/TO/OneTwoSobolSequences
# Their pbrt tree compiled as pbrt's Release build compiles it (-O3 -DNDEBUG), for the same
# baseline x86-64 as samplab's release build (StartPixelSample draws the camera's five
# dimensions; the loop then draws 64 more, so theirs does 69 of samplab's 64 per pixel).
set -euo pipefail
src=${1:?usage: throughput.sh PATH/TO/OneTwoSobolSequences}
here=$(cd "$(dirname "$0")" && pwd)
pbrt=$src/sampler/pbrt/src-pbrt-ours
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/include" && ln -s "$(cd "$pbrt" && pwd)" "$tmp/include/pbrt"
g++ -std=c++17 -O3 -DNDEBUG -I "$tmp/include" "$here/throughput.cpp" "$here/../pbrt/stubs.cpp" \
    "$pbrt/util/sobolmatrices.cpp" "$pbrt/util/primes.cpp" \
    -DPBRT_HAVE_POSIX_MEMALIGN "$pbrt/util/pstd.cpp" -o "$tmp/throughput"
cd "$here/../.."
cargo build --release --quiet -p samplab --example pixel_throughput
for round in 1 2 3; do
  "$tmp/throughput"
  target/release/examples/pixel_throughput pbrt.onetwo
done
