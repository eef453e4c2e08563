// Prints Blender Cycles' five sampling patterns' values for the fixture
// crates/samplab/tests/fixtures/cycles_patterns.txt (see patterns.sh): Cycles' own kernel
// functions (path_rng_pixel_init, path_rng_4D and what they call) and its table generator
// (tabulated_sobol_generate_4D), under the integrator settings that Integrator::device_update
// (src/scene/integrator.cpp) derives from the seed, the sample count and the pattern, which
// setup() below follows line by line (that file needs the whole scene to compile).
// One line per sample: pattern spp seed scrambling x y sample, then dimensions 0-7 as the
// IEEE-754 singles Cycles returns, in hex; dimension d is component d % 2 of path_rng_2D's
// draw for dimension set d / 2 (Cycles' kernel draws in 1D, 2D and 3D, never 4D).
#include "kernel/sample/pattern.h"
#include "scene/tabulated_sobol.h"

#include <cstdio>
#include <cstring>
#include <vector>

using namespace ccl;

static std::vector<float4> lut;

static void setup(int pattern, int aa_samples, uint seed, float scrambling) {
  StubIntegrator &k = kernel_data.integrator;
  k.sampling_pattern = pattern;
  k.scrambling_distance = scrambling;
  k.sobol_index_mask = reverse_integer_bits(next_power_of_two(aa_samples - 1) - 1);
  k.blue_noise_sequence_length = aa_samples;
  if (k.sampling_pattern == SAMPLING_PATTERN_BLUE_NOISE_ROUND) {
    if (!is_power_of_two(aa_samples)) {
      k.blue_noise_sequence_length = next_power_of_two(aa_samples);
    }
    k.sampling_pattern = SAMPLING_PATTERN_BLUE_NOISE_PURE;
  }
  if (k.sampling_pattern == SAMPLING_PATTERN_BLUE_NOISE_FIRST) {
    k.blue_noise_sequence_length -= 1;
  }
  if (k.sampling_pattern == SAMPLING_PATTERN_BLUE_NOISE_FIRST ||
      k.sampling_pattern == SAMPLING_PATTERN_BLUE_NOISE_PURE) {
    k.seed = hash_uint(seed);
  } else {
    k.seed = seed;
  }
  const int size = clamp((int)next_power_of_two(aa_samples - 1), MIN_TAB_SOBOL_SAMPLES, MAX_TAB_SOBOL_SAMPLES);
  k.tabulated_sobol_sequence_size = size;
  lut.assign(size * NUM_TAB_SOBOL_PATTERNS, make_float4(0.0f, 0.0f, 0.0f, 0.0f));
  for (int j = 0; j < NUM_TAB_SOBOL_PATTERNS; ++j) {
    tabulated_sobol_generate_4D(lut.data() + j * size, size, j);
  }
  sample_pattern_lut = reinterpret_cast<float *>(lut.data());
}

int main() {
  const char *names[] = {"sobol_burley", "tabulated_sobol", "blue_noise_pure", "blue_noise_first",
                         "blue_noise_round"};
  struct Case { int pattern, spp; uint seed; float scrambling; };
  const Case cases[] = {
      {0, 16, 0, 1.0f}, {0, 12, 7, 1.0f}, {0, 1, 3, 1.0f}, {1, 16, 0, 1.0f}, {1, 300, 7, 1.0f}, {1, 16, 3, 0.25f},
      {2, 16, 0, 1.0f}, {2, 12, 7, 1.0f}, {3, 16, 0, 1.0f}, {3, 12, 7, 1.0f}, {4, 12, 7, 1.0f},
      {4, 16, 5, 1.0f},
  };
  const int pixels[][2] = {{0, 0}, {3, 5}, {63, 1}, {17, 40}};
  for (const Case &c : cases) {
    setup(c.pattern, c.spp, c.seed, c.scrambling);
    for (const auto &p : pixels) {
      const uint rng_pixel = path_rng_pixel_init(nullptr, 0, p[0], p[1]);
      for (int sample = 0; sample < 64; ++sample) {
        std::printf("%s %d %u %g %d %d %d", names[c.pattern], c.spp, c.seed, c.scrambling, p[0], p[1], sample);
        for (int set = 0; set < 4; ++set) {
          const float2 v = path_rng_2D(nullptr, rng_pixel, sample, set);
          const float f[2] = {v.x, v.y};
          for (int k = 0; k < 2; ++k) {
            uint bits;
            std::memcpy(&bits, &f[k], 4);
            std::printf(" %08x", bits);
          }
        }
        std::printf("\n");
      }
    }
  }
  // the seed of frame f of the pixel jitter, hash_uint2(seed, f): samplab's frames
  for (uint seed : {0u, 7u, 0xdeadbeefu}) {
    for (uint frame = 1; frame < 4; ++frame) {
      std::printf("frame_seed %u %u %08x\n", seed, frame, hash_uint2(seed, frame));
    }
  }
  // the A/B classes of adaptive sampling: one line per sample, 0 or 1
  for (int sample = 0; sample < 64; ++sample) {
    std::printf("class_a %d %d\n", sample, sample_is_class_A(0, sample) ? 1 : 0);
  }
}
