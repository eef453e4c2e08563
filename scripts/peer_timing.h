// The timing that the peers' throughput drivers (scripts/cycles, scripts/onetwo,
// scripts/openqmc) share with samplab's pixel_throughput example: `run(index, keep_x)` draws
// 256 x 256 pixels at one sample index per round (the round's number mod 16, keep_x a
// volatile the driver writes each pixel's x to, so that the pixel's state is not hoisted out
// of its loop); the median of at least 7 rounds and 2 s (at most 60 rounds), counted as
// 256 x 256 x 16 4D draws; one JSON object printed.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

template <typename Run>
void report_median(const char *peer, Run run) {
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
    std::printf("{\"peer\": \"%s\", \"draws_per_second\": %.4e, \"checksum\": %.6f}\n", peer,
                256.0 * 256.0 * 16.0 / times[times.size() / 2], sink);
}
