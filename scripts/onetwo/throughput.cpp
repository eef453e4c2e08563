// The OneTwo paper's pbrt-v4 sampler drawn as samplab's pixel_throughput example draws its
// families: 256 x 256 pixels x 64 dimensions (sample12 of each dimension after the pixel's
// StartPixelSample) at one sample index per run, 16 spp, counted in 4D draws as samplab's
// example counts them, timed by ../peer_timing.h. Prints one JSON object.
// Built and run by throughput.sh, against the authors' pbrt tree as pixels.sh builds it.
#include "../peer_timing.h"

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

int main() { report_median("OneTwo pbrt OneTwoSampler", run); }
