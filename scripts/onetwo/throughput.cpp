// The OneTwo paper's pbrt-v4 sampler drawn as samplab's pixel_throughput example draws its
// families: 256 x 256 pixels x 64 dimensions (sample12 of each dimension after the pixel's
// StartPixelSample) at one sample index per run, 16 spp, counted in 4D draws as samplab's
// example counts them; the median of at least 7 rounds and 2 s. Prints one JSON object.
// Built and run by throughput.sh, against the authors' pbrt tree as pixels.sh builds it.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#define private public  // sample12 is private: read it directly
#include <pbrt/samplers.h>
#undef private

using namespace pbrt;

static double run(int sample, volatile int *keep_x) {
  double sum = 0;
  OneTwoSampler s(16, 1);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      *keep_x = x;  // the pixel is not hoisted out of the loop
      s.StartPixelSample({*keep_x, y}, sample, 0);
      for (int d = 0; d < 64; ++d) sum += s.sample12(sample, d);
    }
  return sum;
}

int main() {
  using clock = std::chrono::steady_clock;
  volatile int keep_x = 0;
  std::vector<double> times;
  double sink = 0;
  const auto start = clock::now();
  while (times.size() < 7 || (std::chrono::duration<double>(clock::now() - start).count() < 2.0 && times.size() < 60)) {
    const auto t = clock::now();
    sink += run(static_cast<int>(times.size() % 16), &keep_x);
    times.push_back(std::chrono::duration<double>(clock::now() - t).count());
  }
  std::sort(times.begin(), times.end());
  std::printf("{\"peer\": \"OneTwo pbrt OneTwoSampler\", \"draws_per_second\": %.4e, \"checksum\": %.3f}\n",
              256.0 * 256.0 * 16.0 / times[times.size() / 2], sink);
}
