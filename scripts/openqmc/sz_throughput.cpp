// OpenQMC's SobolSampler (the SZ matrices since its pull request #108) drawn as samplab's
// pixel_throughput example draws its families: 4D draws over 256 x 256 pixels x 64
// dimensions (16 draws per pixel) at one sample index per run, every draw from its keys
// (SobolSampler(x, y, 0, index).newDomain(block).drawSample<4>), timed by ../peer_timing.h.
// Prints one JSON object. Built and run by sz_throughput.sh.
#include <oqmc/sobol.h>

#include "../peer_timing.h"

#include <cstdint>

static double run(int index, volatile int *keep_x) {
    double sum = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            for (int block = 0; block < 16; ++block) {
                *keep_x = x;  // the pixel's state is not hoisted out of the loop
                const oqmc::SobolSampler s(*keep_x, y, 0, index, nullptr);
                std::uint32_t v[4];
                s.newDomain(block).drawSample<4>(v);
                for (int k = 0; k < 4; ++k) sum += v[k] * (1.0 / 4294967296.0);
            }
    return sum;
}

int main() { report_median("OpenQMC SobolSampler (SZ)", run); }
