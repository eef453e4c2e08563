// Prints the values of the OneTwo paper's pbrt-v4 sampler (OneTwoSampler of its
// sampler/pbrt/src-pbrt-ours/samplers.h) for the fixture crates/samplab/tests/fixtures/
// onetwo_pixels.txt (see pixels.sh): sample12(index, dim), the OneTwo point's dimension dim
// Owen-scrambled per pixel and dimension, before the sampler's Get1D/Get2D bookkeeping
// deals the dimensions out to the camera and the integrator. One line per value:
// spp seed px py index dim bits, bits the IEEE-754 single in hex.
// the standard headers first, untouched by the define below
#include <algorithm>
#include <array>
#include <atomic>
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

int main() {
    const Point2i pixels[] = {{0, 0}, {3, 5}, {63, 1}, {17, 40}};
    const unsigned dims[] = {0, 1, 2, 3, 4, 5, 6, 7, 100, 691};
    for (unsigned seed : {0u, 7u})
        for (Point2i p : pixels)
            for (int i = 0; i < 64; ++i) {
                OneTwoSampler s(64, seed);
                s.StartPixelSample(p, i, 0);
                for (unsigned d : dims) {
                    float v = s.sample12(i, d);
                    uint32_t bits;
                    std::memcpy(&bits, &v, 4);
                    std::printf("64 %u %d %d %d %u %08x\n", seed, p.x, p.y, i, d, bits);
                }
            }
    return 0;
}
