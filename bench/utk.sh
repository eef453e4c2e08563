#!/usr/bin/env bash
# Builds the UTK executables bench/blue.py compares against (DartThrowing, Bridson, Step,
# SinglePeak, and SOT when its source is given), from UTK's public source, with
# Debian's packages instead of the downloads UTK's CMake makes (CPM from GitHub):
#
#   bench/utk.sh UTK_SOURCE BUILD_DIR [SOT_SOURCE]
#
# UTK_SOURCE: a checkout of github.com/utk-team/utk (measured: commit 2940c4c, 2024-08-23);
# SOT_SOURCE: a checkout of github.com/loispaulin/Sliced-Optimal-Transport-Sampling at
# commit e1a9aad (UTK's pin), for UTK's SOT; without it SOT is not built. UTK_SOURCE's
# cmake/spdlog.cmake, cli11.cmake and stb.cmake are replaced by find_package calls (the
# only change to UTK). Then: bench/compare blue --utk BUILD_DIR/src/samplers
set -euo pipefail
src=$(realpath "$1"); build=$2; sot=${3:-}
if ! dpkg -s cmake libspdlog-dev libcli11-dev libstb-dev libgsl-dev >/dev/null 2>&1; then
  apt-get install -y -q cmake libspdlog-dev libcli11-dev libstb-dev libgsl-dev >/dev/null ||
    sudo apt-get install -y -q cmake libspdlog-dev libcli11-dev libstb-dev libgsl-dev >/dev/null
fi
printf 'include(CPM)\nfind_package(spdlog REQUIRED)\n' > "$src/cmake/spdlog.cmake"
printf 'find_package(CLI11 REQUIRED)\n' > "$src/cmake/cli11.cmake"
printf 'include_directories(/usr/include/stb)\n' > "$src/cmake/stb.cmake"
targets=(DartThrowing Bridson Step SinglePeak)
extra=()
if [ -n "$sot" ]; then
  sot=$(realpath "$sot")
  (cd "$sot" && git apply "$src/cmake/externals/sot.patch" 2>/dev/null || true)
  extra=(-DCPM_SOT_SOURCE="$sot")
  targets+=(SOT)
fi
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCPM_USE_LOCAL_PACKAGES=ON -DUTK_USE_FFTW=OFF \
  -DFETCHCONTENT_FULLY_DISCONNECTED=ON "${extra[@]}" >/dev/null
make -C "$build" -j"$(nproc)" "${targets[@]}" >/dev/null
echo "UTK executables in $build/src/samplers"
