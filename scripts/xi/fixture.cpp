// Prints the default xi-sequence's points as the authors' supplemental code computes them
// (class Xi of xi.h, default vector a and first point p0): index, then the 32 bits of x and y.
#include <cstdio>
#include <vector>

#include "xi.h"

int main()
{
    Xi xi;
    std::vector<uint32_t> indices;
    for (uint32_t i = 0; i < 256; i++) indices.push_back(i);
    for (uint32_t k = 8; k < 32; k++) indices.push_back(1u << k);
    for (uint32_t i : {1000003u, 123456789u, 2654435769u, 4294967295u}) indices.push_back(i);
    for (uint32_t i : indices) {
        Point p = xi[i];
        std::printf("%u %08x %08x\n", i, p.x, p.y);
    }
    return 0;
}
