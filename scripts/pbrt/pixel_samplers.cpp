// Prints pbrt-v4's ZSobolSampler, PaddedSobolSampler and HaltonSampler values for the fixture
// crates/samplab/tests/fixtures/pbrt_pixel_samplers.txt (see pixel_samplers.sh).
// One line per value: sampler randomize spp resx resy seed px py index dim bits,
// bits the IEEE-754 single of the value pbrt returns, in hex.
#include <pbrt/samplers.h>

#include <cstdio>
#include <cstdlib>

using namespace pbrt;

static const char *name(RandomizeStrategy r) {
    switch (r) {
    case RandomizeStrategy::None: return "none";
    case RandomizeStrategy::PermuteDigits: return "permutedigits";
    case RandomizeStrategy::FastOwen: return "fastowen";
    default: return "owen";
    }
}

template <typename S>
static void dump(const char *sampler, S s, RandomizeStrategy r, int spp, Point2i res, int seed) {
    const Point2i pixels[] = {{0, 0}, {3, 5}, {res.x - 1, 1}, {17, res.y - 1}, {40, 33}};
    for (Point2i p : pixels)
        for (int i = 0; i < spp; ++i) {
            s.StartPixelSample(p, i, 0);
            for (int d = 0; d < 8; d += 2) {
                // dimensions 0, 1 are the film position (the Sobol' samplers' GetPixel2D is
                // their Get2D; Halton's is its own)
                Point2f u = d == 0 ? s.GetPixel2D() : s.Get2D();
                float v[2] = {u.x, u.y};
                for (int k = 0; k < 2; ++k) {
                    uint32_t bits;
                    std::memcpy(&bits, &v[k], 4);
                    std::printf("%s %s %d %d %d %d %d %d %d %d %08x\n", sampler, name(r), spp,
                                res.x, res.y, seed, p.x, p.y, i, d + k, bits);
                }
            }
        }
}

int main() {
    const RandomizeStrategy all[] = {RandomizeStrategy::None, RandomizeStrategy::PermuteDigits,
                                     RandomizeStrategy::FastOwen, RandomizeStrategy::Owen};
    for (RandomizeStrategy r : all) {
        dump("zsobol", ZSobolSampler(16, {64, 64}, r, 0), r, 16, {64, 64}, 0);
        dump("zsobol", ZSobolSampler(8, {100, 60}, r, 7), r, 8, {100, 60}, 7);
        dump("paddedsobol", PaddedSobolSampler(16, r, 0), r, 16, {64, 64}, 0);
        dump("paddedsobol", PaddedSobolSampler(8, r, 7), r, 8, {100, 60}, 7);
        if (r != RandomizeStrategy::FastOwen) {  // pbrt's Halton refuses FastOwen
            dump("halton", HaltonSampler(16, {64, 64}, r, 0), r, 16, {64, 64}, 0);
            dump("halton", HaltonSampler(8, {100, 60}, r, 7), r, 8, {100, 60}, 7);
            dump("halton", HaltonSampler(4, {300, 200}, r, 3), r, 4, {300, 200}, 3);
        }
    }
}
