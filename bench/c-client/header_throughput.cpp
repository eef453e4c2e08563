// Values per second of the header-only samplers (include/samplab/samplers.hpp) inlined into a
// renderer's loop, against the same draws through the C interface (samplab.h), in one
// process, in alternation: 256 x 256 pixels x 64 dimensions at one sample index per run
// (the workload of crates/samplab/examples/pixel_throughput.rs), the median of at least 7
// rounds and 1 s per side. The two must agree bit for bit on every value drawn (checked
// here, so the comparison is of the same work). The header's draws: `at(pixel, frame, index)`
// once per sample, then the dimensions four at a time (as the C
// interface's samplab_pixel_sample4 and OpenQMC's draw_sample<4>); and, beside them, every value from its five keys. Prints one JSON object per family.
// Built and run by `bench/compare pixels`.
#include <samplab.h>
#include <samplab/samplers.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

const uint32_t SIDE = 256, DIMS = 64, SPP = 16;
const uint64_t SEED = 1;

double seconds_of(double (*run)(const void*, uint32_t), const void* what, uint32_t index, double* sum) {
    const auto t = std::chrono::steady_clock::now();
    *sum += run(what, index);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A renderer's loop: the sample's draw once, then its dimensions four at a time.
template <class Family>
double header_run(const void* f, uint32_t index) {
    const Family& s = *static_cast<const Family*>(f);
    double sum = 0, v[4];
    for (uint32_t y = 0; y < SIDE; ++y)
        for (uint32_t x = 0; x < SIDE; ++x) {
            const auto draw = s.at(x, y, 0, index);
            for (uint32_t d = 0; d < DIMS; d += 4) {
                draw.sample4(d, v);
                sum += v[0] + v[1] + v[2] + v[3];
            }
        }
    return sum;
}

// Every value from all five keys.
template <class Family>
double header_keys_run(const void* f, uint32_t index) {
    const Family& s = *static_cast<const Family*>(f);
    double sum = 0;
    for (uint32_t y = 0; y < SIDE; ++y)
        for (uint32_t x = 0; x < SIDE; ++x)
            for (uint32_t d = 0; d < DIMS; ++d) sum += s.sample(x, y, 0, index, d);
    return sum;
}

double abi_run(const void* p, uint32_t index) {
    const SamplabPixels* s = static_cast<const SamplabPixels*>(p);
    double sum = 0;
    for (uint32_t y = 0; y < SIDE; ++y)
        for (uint32_t x = 0; x < SIDE; ++x)
            for (uint32_t d = 0; d < DIMS; ++d) sum += samplab_pixel_sample(s, x, y, 0, index, d);
    return sum;
}

double abi4_run(const void* p, uint32_t index) {
    const SamplabPixels* s = static_cast<const SamplabPixels*>(p);
    double sum = 0, v[4];
    for (uint32_t y = 0; y < SIDE; ++y)
        for (uint32_t x = 0; x < SIDE; ++x)
            for (uint32_t d = 0; d < DIMS; d += 4) {
                samplab_pixel_sample4(s, x, y, 0, index, d, v);
                sum += v[0] + v[1] + v[2] + v[3];
            }
    return sum;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

template <class Family>
void compare(const char* spec, const Family& family, const char* variant = "keys only") {
    char error[256];
    SamplabPixels* abi = samplab_pixels_new(spec, SIDE, SIDE, SPP, DIMS, SEED, error, sizeof error);
    if (!abi) {
        std::fprintf(stderr, "%s: %s\n", spec, error);
        std::exit(1);
    }
    for (uint32_t y = 0; y < SIDE; y += 7)
        for (uint32_t i = 0; i < SPP; ++i)
            for (uint32_t d = 0; d < DIMS; ++d) {
                const double h = family.sample(y, SIDE - 1 - y, 0, i, d), c = samplab_pixel_sample(abi, y, SIDE - 1 - y, 0, i, d);
                if (std::memcmp(&h, &c, sizeof h) != 0) {
                    std::fprintf(stderr, "%s: the header and the C interface differ at (%u, %u, 0, %u, %u)\n", spec, y,
                                 SIDE - 1 - y, i, d);
                    std::exit(1);
                }
            }
    std::vector<double> th, tk, ta, t4;
    double sum = 0;
    const auto start = std::chrono::steady_clock::now();
    while (th.size() < 7 || (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 3.0 &&
                             th.size() < 40)) {
        const uint32_t index = (uint32_t)(th.size() % SPP);
        th.push_back(seconds_of(header_run<Family>, &family, index, &sum));
        tk.push_back(seconds_of(header_keys_run<Family>, &family, index, &sum));
        ta.push_back(seconds_of(abi_run, abi, index, &sum));
        t4.push_back(seconds_of(abi4_run, abi, index, &sum));
    }
    const double values = double(SIDE) * SIDE * DIMS;
    std::printf(
        "{\"spec\": \"%s\", \"header\": \"%s\", \"header_values_per_second\": %.4e, \"header_from_keys_values_per_second\": %.4e, "
        "\"c_abi_values_per_second\": %.4e, "
        "\"c_abi_sample4_values_per_second\": %.4e, \"header_over_c_abi\": %.3f, \"header_over_c_abi_sample4\": %.3f, "
        "\"checksum\": %.6e}\n",
        spec, variant, values / median(th), values / median(tk), values / median(ta), values / median(t4), median(ta) / median(th),
        median(t4) / median(th), sum);
    samplab_pixels_free(abi);
}

}  // namespace

int main() {
    using samplab::Scramble;
    compare("independent", samplab::Independent(SEED));
    compare("sobol", samplab::Sobol(SEED));
    std::vector<uint32_t> tables(samplab::sobol_tables_size(DIMS));
    samplab::sobol_tables(SEED, DIMS, tables.data());
    compare("sobol", samplab::Sobol(SEED, tables.data(), DIMS), "tables");
    compare("lattice", samplab::Lattice(SEED));
    for (const char* spec : {"pmj02", "pmj02.bn"}) {
        // the pool (and mask) through the C interface, as a renderer gets them
        char error[256];
        SamplabPixels* p = samplab_pixels_new(spec, SIDE, SIDE, SPP, DIMS, SEED, error, sizeof error);
        std::vector<uint32_t> words(samplab_pixels_header_tables(p, nullptr, 0));
        samplab_pixels_header_tables(p, words.data(), words.size());
        samplab_pixels_free(p);
        compare(spec, samplab::Pmj02(SEED, SPP, words.data(), std::strcmp(spec, "pmj02") == 0 ? 0 : 64), "tables");
    }
    compare("sobol.padded", samplab::PaddedSobol(SEED, SPP, Scramble::FastOwen));
    compare("zsobol", samplab::ZSobol(SEED, SIDE, SIDE, SPP, Scramble::FastOwen));
    // pbrt's digit permutations as a table, as pbrt's HaltonSampler keeps them
    std::vector<uint32_t> permutations(samplab::halton_permutations_size(DIMS));
    samplab::halton_permutations(SEED, DIMS, permutations.data());
    compare("halton", samplab::Halton(SEED, SIDE, SIDE, samplab::HaltonRandomize::PermuteDigits));
    compare("halton",
            samplab::Halton(SEED, SIDE, SIDE, samplab::HaltonRandomize::PermuteDigits, permutations.data(), DIMS),
            "tables");
    return 0;
}
