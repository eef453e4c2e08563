// The few names Cycles' sampling headers read from its kernel globals, for the fixture
// program beside this folder (not Cycles' kernel: one set of integrator settings at a time).
#pragma once

#include "util/types.h"

#include <cassert>

#define MIN_TAB_SOBOL_SAMPLES 256
#define MAX_TAB_SOBOL_SAMPLES 8192
#define NUM_TAB_SOBOL_DIMENSIONS 4
#define NUM_TAB_SOBOL_PATTERNS 256

CCL_NAMESPACE_BEGIN

enum SamplingPattern {
  SAMPLING_PATTERN_SOBOL_BURLEY = 0,
  SAMPLING_PATTERN_TABULATED_SOBOL = 1,
  SAMPLING_PATTERN_BLUE_NOISE_PURE = 2,
  SAMPLING_PATTERN_BLUE_NOISE_FIRST = 3,
  SAMPLING_PATTERN_BLUE_NOISE_ROUND = 4,
};

struct StubIntegrator {
  int sampling_pattern;
  float scrambling_distance;
  uint seed;
  int sobol_index_mask;
  int blue_noise_sequence_length;
  int tabulated_sobol_sequence_size;
};

struct StubKernelData {
  StubIntegrator integrator;
};

inline StubKernelData kernel_data;
inline float *sample_pattern_lut = nullptr;
using KernelGlobals = const void *;

#define kernel_data_fetch(name, index) (name[(index)])
#define kernel_assert(x) assert(x)

CCL_NAMESPACE_END
