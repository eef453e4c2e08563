// OpenQMC's SobolSampler (the SZ matrices since its pull request #108) drawn as samplab's
// pixel_throughput example draws its families: 4D draws over 256 x 256 pixels x 64
// dimensions (16 draws per pixel) at one sample index per run, every draw from its keys
// (SobolSampler(x, y, 0, index).newDomain(block).drawSample<4>); the median of at least 7
// rounds and 2 s. Prints one JSON object. Built and run by sz_throughput.sh.
#include <oqmc/sobol.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <vector>

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

int main() {
    using clock = std::chrono::steady_clock;
    volatile int keep_x = 0;
    std::vector<double> times;
    double sink = 0;
    const auto start = clock::now();
    while (times.size() < 7 || (std::chrono::duration<double>(clock::now() - start).count() < 2.0 && times.size() < 60)) {
        const auto t = clock::now();
        sink += run(static_cast<int>(times.size() % 16), &keep_x);
        times.push_back(std::chrono::duration<double>(clock::now() - t).count());
    }
    std::sort(times.begin(), times.end());
    const double draws = 256.0 * 256.0 * 16.0;
    std::printf("{\"peer\": \"OpenQMC SobolSampler (SZ)\", \"draws_per_second\": %.4e, \"checksum\": %.6f}\n",
                draws / times[times.size() / 2], sink);
}
