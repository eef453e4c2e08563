// Prints OpenQMC's SobolSampler values (on the SZ matrices since its pull request #108) for
// the fixture crates/samplab/tests/fixtures/openqmc_sz.txt (see sz_fixture.sh).
// One line per value: key x y frame index dim bits, bits the 32-bit integer drawSample
// returns, in hex; dimension d is domain d / 4 of the key's domain, component d % 4, as
// samplab's pixel layer draws OpenQMC's samplers.
#include <oqmc/sobol.h>

#include <cstdint>
#include <cstdio>

int main() {
    const int keys[] = {0x23456789, 7};
    const int pixels[][3] = {{0, 0, 0}, {8, 6, 3}, {4, 1, 1}, {511, 300, 17}};
    for (int key : keys)
        for (const auto &p : pixels)
            for (int index = 0; index < 64; ++index) {
                const oqmc::SobolSampler root(p[0], p[1], p[2], index, nullptr);
                for (int block = 0; block < 2; ++block) {
                    std::uint32_t v[4];
                    root.newDomain(key).newDomain(block).drawSample<4>(v);
                    for (int k = 0; k < 4; ++k)
                        std::printf("%d %d %d %d %d %d %08x\n", key, p[0], p[1], p[2], index,
                                    4 * block + k, v[k]);
                }
            }
}
