// A minimal CUDA use of samplab's header: each thread writes one value of a pixel family, or
// one coordinate of a point set, straight into device memory. Every kernel takes plain
// words (launchable from CuPy as from C++). scripts/check-cuda-header compiles them to PTX
// for sm_80 and sm_90, warnings as errors; bench/gpu.py runs them on a device and compares
// their bytes with the CPU's.
//
//   nvcc -std=c++17 -I crates/samplab-c/include -arch=sm_90 --ptx fill.cu
#include <samplab/samplers.hpp>

// Dimension `dim` of every sample of every pixel of one frame: out[((y * width + x) * spp + i)].
template <class Family>
__device__ void fill_pixels(const Family& f, uint32_t width, uint32_t height, uint32_t spp, uint32_t frame,
                            uint32_t dim, double* out) {
    const uint64_t k = (uint64_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= (uint64_t)width * height * spp) return;
    const uint32_t i = (uint32_t)(k % spp), pixel = (uint32_t)(k / spp);
    out[k] = f.sample(pixel % width, pixel / width, frame, i, dim);
}

// One kernel per family: (seed, width, height, spp, frame, dim, out), the family made from
// them in each thread (a few integer operations).
#define SAMPLAB_FILL(name, family)                                                                             \
    extern "C" __global__ void name(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame,         \
                                    uint32_t dim, double* out) {                                                 \
        fill_pixels(family, w, h, spp, frame, dim, out);                                                         \
    }

SAMPLAB_FILL(independent, samplab::Independent(seed))
SAMPLAB_FILL(sobol, samplab::Sobol(seed))
SAMPLAB_FILL(sobol_padded, samplab::PaddedSobol(seed, spp))
SAMPLAB_FILL(zsobol, samplab::ZSobol(seed, w, h, spp))
SAMPLAB_FILL(zsobol_hilbert, samplab::ZSobol(seed, w, h, spp, samplab::Scramble::FastOwen, samplab::Curve::Hilbert))
SAMPLAB_FILL(stratified, samplab::Stratified(seed, spp))
SAMPLAB_FILL(lattice, samplab::Lattice(seed))
SAMPLAB_FILL(halton, samplab::Halton(seed, w, h))
// `samplab pixels sobol.owen`: the Owen-scrambled Sobol' sequence per pixel
SAMPLAB_FILL(sobol_owen_per_pixel, samplab::SobolSequence(seed, samplab::Randomization::Owen))

// pmj02 (mask 0) and pmj02.bn (the mask's side): `tables` in device memory, the words of
// samplab_pixels_header_tables (samplab.pixel_header_tables in Python) copied there.
extern "C" __global__ void pmj02(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                 const uint32_t* tables, uint32_t mask, double* out) {
    fill_pixels(samplab::Pmj02(seed, spp, tables, mask), w, h, spp, frame, dim, out);
}

// Points start .. start + n of a Sobol' set in `dims` dimensions, row-major (n x dims), under
// `randomization` (0 none, 1 xor, 2 owen, 3 shift) and the set's seed.
extern "C" __global__ void sobol_points(uint64_t seed, uint32_t start, uint32_t n, uint32_t dims,
                                        uint32_t randomization, double* out) {
    const uint64_t k = (uint64_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= (uint64_t)n * dims) return;
    const samplab::Randomization r = (samplab::Randomization)randomization;
    out[k] = samplab::sobol_point(r, seed, start + (uint32_t)(k / dims), (uint32_t)(k % dims));
}
