// The header's values for keys read from standard input, for the test `header.rs`.
//
//   header_values FAMILY SEED WIDTH HEIGHT SPP RANDOMIZE [TABLES] < keys > values
//
// sobol+table and halton+table draw their first dimensions from samplab::sobol_tables and
// samplab::halton_permutations. A key is five little-endian u32 (x, y, frame, index, dimension; a point set reads index and
// dimension from the last two), a value one little-endian f64.
#include <samplab/samplers.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

samplab::Scramble scramble_of(const std::string& word) {
    if (word == "none") return samplab::Scramble::None;
    if (word == "xor") return samplab::Scramble::Xor;
    if (word == "owen") return samplab::Scramble::Owen;
    return samplab::Scramble::FastOwen;
}

samplab::HaltonRandomize halton_of(const std::string& word) {
    if (word == "none") return samplab::HaltonRandomize::None;
    if (word == "owen") return samplab::HaltonRandomize::Owen;
    return samplab::HaltonRandomize::PermuteDigits;
}

samplab::Randomization randomization_of(const std::string& word) {
    if (word == "xor") return samplab::Randomization::Xor;
    if (word == "owen") return samplab::Randomization::Owen;
    if (word == "shift") return samplab::Randomization::Shift;
    return samplab::Randomization::None;
}

template <class Draw>
int run(Draw draw) {
    uint32_t key[5];
    std::vector<double> out;
    while (std::fread(key, sizeof key, 1, stdin) == 1) {
        out.push_back(draw(key));
        if (out.size() == 4096) {
            std::fwrite(out.data(), sizeof(double), out.size(), stdout);
            out.clear();
        }
    }
    std::fwrite(out.data(), sizeof(double), out.size(), stdout);
    return 0;
}

// A family's value of each key; the same from its draw's pair and from its four
// dimensions (a difference exits 3).
template <class Family>
int pixels(const Family& f) {
    return run([&](const uint32_t* k) {
        const double value = f.sample(k[0], k[1], k[2], k[3], k[4]);
        const auto draw = f.at(k[0], k[1], k[2], k[3]);
        double uv[2], v[4];
        draw.pair(k[4] & ~1u, uv);
        // four dimensions ending at this one (from 0 below dimension 3): never past the film's
        const uint32_t back = k[4] < 3 ? k[4] : 3;
        draw.sample4(k[4] - back, v);
        if (std::memcmp(&uv[k[4] & 1u], &value, sizeof value) != 0 || std::memcmp(&v[back], &value, sizeof value) != 0) {
            std::fprintf(stderr, "header_values: pair, sample4 and sample differ at (%u, %u, %u, %u, %u)\n", k[0], k[1], k[2],
                         k[3], k[4]);
            std::exit(3);
        }
        return value;
    });
}

}  // namespace

// The words of a file of little-endian u32 (a family's header tables).
std::vector<uint32_t> words_of(const char* path) {
    std::vector<uint32_t> words;
    if (FILE* f = std::fopen(path, "rb")) {
        uint32_t w;
        while (std::fread(&w, sizeof w, 1, f) == 1) words.push_back(w);
        std::fclose(f);
    }
    return words;
}

int main(int argc, char** argv) {
    if (argc != 7 && argc != 8) {
        std::fprintf(stderr, "usage: header_values FAMILY SEED WIDTH HEIGHT SPP RANDOMIZE [TABLES] < keys\n");
        return 2;
    }
    const std::string family = argv[1], randomize = argv[6];
    const uint64_t seed = std::strtoull(argv[2], nullptr, 10);
    const uint32_t width = (uint32_t)std::atoi(argv[3]), height = (uint32_t)std::atoi(argv[4]);
    const uint32_t spp = (uint32_t)std::atoi(argv[5]);
    if (family == "independent") return pixels(samplab::Independent(seed));
    if (family == "sobol") return pixels(samplab::Sobol(seed));
    if (family == "lattice") return pixels(samplab::Lattice(seed));
    if (family == "sobol+table") {
        // the tables of the first 300 dimensions (the others computed)
        std::vector<uint32_t> tables(samplab::sobol_tables_size(300));
        samplab::sobol_tables(seed, 300, tables.data());
        return pixels(samplab::Sobol(seed, tables.data(), 300));
    }
    if (family == "sobol.padded") return pixels(samplab::PaddedSobol(seed, spp, scramble_of(randomize)));
    if (family == "zsobol") return pixels(samplab::ZSobol(seed, width, height, spp, scramble_of(randomize)));
    if (family == "zsobol-hilbert")
        return pixels(samplab::ZSobol(seed, width, height, spp, scramble_of(randomize), samplab::Curve::Hilbert));
    if (family == "stratified") return pixels(samplab::Stratified(seed, spp));
    if (family == "halton") return pixels(samplab::Halton(seed, width, height, halton_of(randomize)));
    if (family == "pmj02" || family == "pmj02.bn") {
        // the tables samplab_pixels_header_tables gives, from a file; pmj02.bn's mask side as
        // its RANDOMIZE
        const std::vector<uint32_t> tables = words_of(argc == 8 ? argv[7] : "");
        const uint32_t side = family == "pmj02.bn" ? (uint32_t)std::atoi(argv[6]) : 0;
        return pixels(samplab::Pmj02(seed, spp, tables.data(), side));
    }
    if (family == "halton+table") {
        // the frame-0 digit permutations of the first 200 dimensions from a table
        std::vector<uint32_t> table(samplab::halton_permutations_size(200));
        samplab::halton_permutations(seed, 200, table.data());
        return pixels(samplab::Halton(seed, width, height, halton_of(randomize), table.data(), 200));
    }
    if (family == "sobol-sequence") return pixels(samplab::SobolSequence(seed, randomization_of(randomize)));
    if (family == "points:sobol") {
        const samplab::Randomization r = randomization_of(randomize);
        return run([&](const uint32_t* k) { return samplab::sobol_point(r, seed, k[3], k[4]); });
    }
    std::fprintf(stderr, "header_values: unknown family '%s'\n", family.c_str());
    return 2;
}
