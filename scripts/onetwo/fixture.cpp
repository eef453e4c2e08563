// Prints OneTwo Sobol' samples as the authors' stand-alone sampler computes them
// (onetwo_sample(d, i) of their sampler/onetwo_matrices.h: the 32 bits of coordinate d of
// point i), for the dimensions and indices the samplab test reads.
#include <cstdio>
#include <vector>

#include "onetwo_matrices.h"

int main()
{
    std::vector<unsigned> dims;
    for (unsigned d = 0; d < 8; d++) dims.push_back(d);
    for (unsigned d = 50; d < onetwo_matrices_size; d += 50) dims.push_back(d);
    dims.push_back(onetwo_matrices_size - 1);
    std::vector<unsigned> indices;
    for (unsigned i = 0; i < 64; i++) indices.push_back(i);
    for (unsigned k = 6; k < 32; k++) indices.push_back(1u << k);
    for (unsigned i : {1000003u, 123456789u, 2654435769u, 4294967295u}) indices.push_back(i);
    for (unsigned d : dims)
        for (unsigned i : indices) std::printf("%u %u %08x\n", d, i, onetwo_sample(d, i));
    return 0;
}
