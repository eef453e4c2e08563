// A minimal CUDA use of samplab's header: each thread writes one value of a pixel family, or
// one coordinate of a point set, straight into device memory. The kernels are the ones
// scripts/check-cuda-header compiles to PTX for sm_80 and sm_90, warnings as errors.
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

extern "C" __global__ void independent(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                       double* out) {
    fill_pixels(samplab::Independent(seed), w, h, spp, frame, dim, out);
}

extern "C" __global__ void sobol(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                 double* out) {
    fill_pixels(samplab::Sobol(seed), w, h, spp, frame, dim, out);
}

extern "C" __global__ void padded_sobol(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                        double* out) {
    fill_pixels(samplab::PaddedSobol(seed, spp, samplab::Scramble::FastOwen), w, h, spp, frame, dim, out);
}

extern "C" __global__ void lattice(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                   double* out) {
    fill_pixels(samplab::Lattice(seed), w, h, spp, frame, dim, out);
}

// The family's struct is made once on the host and passed by value.
extern "C" __global__ void zsobol(samplab::ZSobol f, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                  double* out) {
    fill_pixels(f, w, h, spp, frame, dim, out);
}

// Its pool (and pmj02.bn's mask) in device memory: samplab_pixels_header_tables' words,
// copied with cudaMemcpy, the pointer given to samplab::Pmj02's constructor on the host.
extern "C" __global__ void pmj02(samplab::Pmj02 f, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                 double* out) {
    fill_pixels(f, w, h, spp, frame, dim, out);
}

extern "C" __global__ void halton(samplab::Halton f, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame, uint32_t dim,
                                  double* out) {
    fill_pixels(f, w, h, spp, frame, dim, out);
}

// `samplab pixels sobol.owen`: the Owen-scrambled Sobol' sequence per pixel.
extern "C" __global__ void sobol_owen_per_pixel(uint64_t seed, uint32_t w, uint32_t h, uint32_t spp, uint32_t frame,
                                                uint32_t dim, double* out) {
    fill_pixels(samplab::SobolSequence(seed, samplab::Randomization::Owen), w, h, spp, frame, dim, out);
}

// Points 0..n of an Owen-scrambled Sobol' set in `dims` dimensions, row-major (n x dims).
extern "C" __global__ void sobol_owen_points(uint64_t seed, uint32_t n, uint32_t dims, double* out) {
    const uint64_t k = (uint64_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= (uint64_t)n * dims) return;
    out[k] = samplab::sobol_point(samplab::Randomization::Owen, seed, (uint32_t)(k / dims), (uint32_t)(k % dims));
}
