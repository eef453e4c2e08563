// Cycles' five sampling patterns drawn as samplab's pixel_throughput example draws its
// families: 256 x 256 pixels x 64 dimensions (path_rng_2D for dimension sets 0-31 of each
// pixel, the pixel's rng_pixel from path_rng_pixel_init) at one sample index per run, 16
// spp, counted in 4D draws (two 2D draws each) as samplab's example counts them, timed by
// ../peer_timing.h per pattern. Prints one JSON object per pattern. Built and run by
// throughput.sh, with the stub globals of patterns.sh.
#include "kernel/sample/pattern.h"
#include "scene/tabulated_sobol.h"

#include "../peer_timing.h"

#include <string>
#include <vector>

using namespace ccl;

static std::vector<float4> lut;

static double run(int sample, volatile int *keep_x) {
  double sum = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      *keep_x = x;  // the pixel's state is not hoisted out of the loop
      const uint rng_pixel = path_rng_pixel_init(nullptr, sample, *keep_x, y);
      for (int set = 0; set < 32; ++set) {
        const float2 v = path_rng_2D(nullptr, rng_pixel, sample, set);
        sum += double(v.x) + double(v.y);
      }
    }
  return sum;
}

int main() {
  const char *names[] = {"sobol_burley", "tabulated_sobol", "blue_noise_pure", "blue_noise_first"};
  const int spp = 16;
  for (int pattern = 0; pattern < 4; ++pattern) {
    // the settings of Integrator::device_update for 16 spp and seed 1 (blue noise round is
    // pure at a power of two)
    StubIntegrator &k = kernel_data.integrator;
    k.sampling_pattern = pattern;
    k.scrambling_distance = 1.0f;
    k.sobol_index_mask = reverse_integer_bits(next_power_of_two(spp - 1) - 1);
    k.blue_noise_sequence_length = pattern == SAMPLING_PATTERN_BLUE_NOISE_FIRST ? spp - 1 : spp;
    k.seed = pattern >= SAMPLING_PATTERN_BLUE_NOISE_PURE ? hash_uint(1) : 1;
    k.tabulated_sobol_sequence_size = MIN_TAB_SOBOL_SAMPLES;
    lut.assign(MIN_TAB_SOBOL_SAMPLES * NUM_TAB_SOBOL_PATTERNS, make_float4(0.0f, 0.0f, 0.0f, 0.0f));
    for (int j = 0; j < NUM_TAB_SOBOL_PATTERNS; ++j) {
      tabulated_sobol_generate_4D(lut.data() + j * MIN_TAB_SOBOL_SAMPLES, MIN_TAB_SOBOL_SAMPLES, j);
    }
    sample_pattern_lut = reinterpret_cast<float *>(lut.data());
    const std::string peer = std::string("Cycles ") + names[pattern];
    report_median(peer.c_str(), run);
  }
}
