/* samplab's samplers as header-only C++: host C++17 and CUDA, by nvcc or by NVRTC (CuPy's
 * RawModule: `-std=c++17 -I<this folder's parent>`); HIP's macros and intrinsics are taken
 * too, untested.
 *
 * Every value is a pure function of its keys, the same bits as the Rust library (and so as
 * `samplab pixels` and `samplab generate`): a pixel sampler's value of (seed, pixel, frame,
 * index, dimension) given its film, a point set's coordinate of (seed, index, dimension).
 * No allocation, no state, no dependency: the families are small structs, copied by value
 * into a kernel's arguments, and each draw is inlined into the caller's loop.
 *
 *   #include <samplab/samplers.hpp>
 *   const samplab::ZSobol zsobol(7, 1920, 1080, 16, samplab::Scramble::FastOwen);
 *   double u = zsobol.sample(x, y, frame, i, dim);       // = `samplab pixels zsobol --seed 7`
 *   double v = samplab::sobol_point(samplab::Randomization::Owen, samplab::set_seed(7, 0), i, dim);
 *                                                      // = `samplab generate sobol.owen --seed 7`
 *
 * Keys outside a family's film (index >= spp, a dimension past its table) are the caller's
 * to avoid, as with `samplab_sample` in samplab.h; the constructors do not check their
 * arguments (the C interface does: prepare a family there first to validate a film).
 * The families, their papers and the values' definitions are in docs/guide/header.md.
 */
#ifndef SAMPLAB_SAMPLERS_HPP
#define SAMPLAB_SAMPLERS_HPP

/* NVRTC (CuPy's RawModule, PyTorch's CUDA extensions at run time) has no C library
 * headers: the fixed-width types are declared here for it. */
#if defined(__CUDACC_RTC__)
#ifndef SAMPLAB_NVRTC_TYPES
#define SAMPLAB_NVRTC_TYPES
typedef unsigned char uint8_t;
typedef unsigned int uint32_t;
typedef long long int64_t;
typedef unsigned long long uint64_t;
#endif
#else
#include <stdint.h>
#endif

#if defined(__CUDACC__) || defined(__HIPCC__)
#define SAMPLAB_HD __host__ __device__ __forceinline__
#define SAMPLAB_DEVICE_TABLE __device__
#else
#define SAMPLAB_HD inline
#endif

/* A table of tables.hpp: its __device__ copy in device code. */
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define SAMPLAB_ON_DEVICE 1
#define SAMPLAB_TABLE(name) tables::name##_device
#else
#define SAMPLAB_TABLE(name) tables::name
#endif

#include "tables.hpp"

namespace samplab {

/* ---------------------------------------------------------------------------------------
 * Integer functions: hashes, scrambles, permutations.
 * ------------------------------------------------------------------------------------- */
namespace detail {

SAMPLAB_HD uint32_t reverse_bits(uint32_t x) {
#ifdef SAMPLAB_ON_DEVICE
    return __brev(x);
#else
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_bswap32(x);
#else
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
#endif
#endif
}

/* The number of leading zero bits of x (32 for 0). */
SAMPLAB_HD uint32_t leading_zeros(uint32_t x) {
    uint32_t n = 0;
    for (uint32_t bit = 0x80000000u; bit != 0 && (x & bit) == 0; bit >>= 1) ++n;
    return n;
}

/* SplitMix64's finalizer (Steele, Lea & Flood 2014): samplab's seed hash. */
SAMPLAB_HD uint64_t mix64(uint64_t x) {
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/* A further hash of a key with a word. */
SAMPLAB_HD uint64_t rekey(uint64_t key, uint64_t word) { return mix64(key + word * 0x9E3779B97F4A7C15ull); }

/* Burley 2020's nested uniform scramble in the bit-reversed domain (bit 0 the most
 * significant digit), with Vegdahl 2021's constants. */
SAMPLAB_HD uint32_t owen_scramble_reversed(uint32_t x, uint32_t seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}


/* pbrt-v4's MixBits. */
SAMPLAB_HD uint64_t mix_bits(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ull;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dull;
    return v ^ (v >> 33);
}

/* MurmurHash64A (Appleby) with seed 0 over n little-endian 32-bit words: pbrt's Hash(...)
 * of its int arguments. */
SAMPLAB_HD uint64_t hash_words(const uint32_t* words, uint32_t n) {
    const uint64_t m = 0xc6a4a7935bd1e995ull;
    uint64_t h = (4ull * n) * m;
    uint32_t k = 0;
    for (; k + 1 < n; k += 2) {
        uint64_t w = (uint64_t)words[k] | ((uint64_t)words[k + 1] << 32);
        w *= m;
        w ^= w >> 47;
        h ^= w * m;
        h *= m;
    }
    if (k < n) {
        h ^= (uint64_t)words[k];
        h *= m;
    }
    h ^= h >> 47;
    h *= m;
    return h ^ (h >> 47);
}

SAMPLAB_HD uint64_t hash2(uint32_t a, uint32_t b) {
    const uint32_t w[2] = {a, b};
    return hash_words(w, 2);
}

SAMPLAB_HD uint64_t hash3(uint32_t a, uint32_t b, uint32_t c) {
    const uint32_t w[3] = {a, b, c};
    return hash_words(w, 3);
}

SAMPLAB_HD uint64_t hash4(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    const uint32_t w[4] = {a, b, c, d};
    return hash_words(w, 4);
}

/* pbrt-v4's PermutationElement(i, l, p): Kensler 2013's hashed permutation of 0..l with
 * cycle walking, then a rotation by p. */
SAMPLAB_HD uint32_t permutation_element(uint32_t i, uint32_t l, uint32_t p) {
    const uint32_t w = 0xFFFFFFFFu >> leading_zeros((l < 2 ? 2u : l) - 1);
    do {
        i ^= p;
        i *= 0xe170893du;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3fu;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1u | p >> 27;
        i *= 0x6935fa69u;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303u;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3u;
        i ^= (i & w) >> 2;
        i *= 0xc860a3dfu;
        i &= w;
        i ^= i >> 5;
    } while (i >= l);
    return (i + p) % l;
}

/* Element i of a permutation of 0..len keyed by `key` (Kensler 2013, section 3): a keyed
 * bijection of the least power-of-two range holding len, masked at every step, walked until
 * it lands below len. i < len. */
SAMPLAB_HD uint32_t permute(uint32_t i, uint32_t len, uint32_t key) {
    if (len <= 1) return 0;
    const uint32_t mask = 0xFFFFFFFFu >> leading_zeros(len - 1);
    do {
        i ^= key;
        i = (i * 0xe170893du) & mask;
        i ^= key >> 16;
        i ^= (i & mask) >> 4;
        i ^= key >> 8;
        i = (i * 0x0929eb3fu) & mask;
        i ^= key >> 23;
        i ^= (i & mask) >> 1;
        i = (i * (1u | key >> 27)) & mask;
        i = (i * 0x6935fa69u) & mask;
        i ^= (i & mask) >> 11;
        i = (i * 0x74dcb303u) & mask;
        i ^= (i & mask) >> 2;
        i = (i * 0x9e501cc3u) & mask;
        i ^= (i & mask) >> 2;
        i = (i * 0xc860a3dfu) & mask;
        i ^= (i & mask) >> 5;
    } while (i >= len);
    return i;
}

/* pbrt-v4's OwenScrambler: digit b flipped by bit b of MixBits of the digits above it XOR
 * the seed. */
SAMPLAB_HD uint32_t owen_bit_by_bit(uint32_t v, uint32_t seed) {
    v ^= (seed & 1u) << 31;
    for (uint32_t b = 1; b < 32; ++b) {
        const uint32_t above = v & (0xFFFFFFFFu << (32 - b));
        v ^= (((uint32_t)mix_bits((uint64_t)(above ^ seed)) >> b) & 1u) << (31 - b);
    }
    return v;
}

/* Morton code of (x, y): x in the even bits, y in the odd ones. */
SAMPLAB_HD uint64_t spread_bits(uint32_t x) {
    uint64_t v = x;
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    return (v | (v << 1)) & 0x5555555555555555ull;
}

SAMPLAB_HD uint64_t morton2(uint32_t x, uint32_t y) { return (spread_bits(y) << 1) | spread_bits(x); }

/* The index of pixel (x, y) along the Hilbert curve of a 2^order x 2^order screen (Hilbert
 * 1891): quadrants in the order lower left, upper left, upper right, lower right. */
SAMPLAB_HD uint64_t hilbert2(uint32_t order, uint32_t x, uint32_t y) {
    uint64_t index = 0;
    for (uint32_t level = order; level-- > 0;) {
        const uint32_t s = 1u << level, right = (x & s) ? 1u : 0u, up = (y & s) ? 1u : 0u;
        index = (index << 2) | ((3u * right) ^ up);
        if (up == 0) {
            if (right == 1) {
                x = ~x;
                y = ~y;
            }
            const uint32_t t = x;
            x = y;
            y = t;
        }
    }
    return index;
}

/* The seed pbrt's samplers get for a frame: frame 0 the low 32 bits of samplab's seed,
 * a later frame their hash with the frame. */
SAMPLAB_HD uint32_t frame_seed(uint64_t seed, uint32_t frame) {
    return frame == 0 ? (uint32_t)seed : (uint32_t)hash2((uint32_t)seed, frame);
}

/* 32 fixed-point digits as a number in [0, 1): the left end of their cell. */
SAMPLAB_HD double unit(uint32_t bits) { return (double)bits * (1.0 / 4294967296.0); }

/* The centre of the cell [v, v + 1) 2^-32, in (0, 1). */
SAMPLAB_HD double cell_centre(uint32_t bits) { return ((double)bits + 0.5) * (1.0 / 4294967296.0); }

/* Column k of Sobol' dimension dim (Joe & Kuo 2008), bit-reversed: bit 0 the most
 * significant digit. */
SAMPLAB_HD uint32_t sobol_column(uint32_t dim, uint32_t k) { return SAMPLAB_TABLE(sobol_reversed)[dim][k]; }

/* The index of the lowest set bit of x (not 0). */
SAMPLAB_HD uint32_t lowest_bit(uint32_t x) {
#ifdef SAMPLAB_ON_DEVICE
    return (uint32_t)(__ffs((int)x) - 1);
#elif defined(__GNUC__) || defined(__clang__)
    return (uint32_t)__builtin_ctz(x);
#else
    uint32_t k = 0;
    while (!(x & 1u)) {
        x >>= 1;
        ++k;
    }
    return k;
#endif
}

/* The unscrambled digits of Sobol' point `index` (natural order) in dimension dim,
 * bit-reversed (bit 0 the most significant digit): the XOR of the reversed columns of the
 * index's set bits (dimension 0, van der Corput's, is the index itself). Reversed digits are
 * what Burley's scramble works on, so that a value costs one reversal. */
SAMPLAB_HD uint32_t sobol_reversed(uint32_t index, uint32_t dim) {
    if (dim == 0) return index;
    uint32_t x = 0;
    for (; index != 0; index &= index - 1) x ^= sobol_column(dim, lowest_bit(index));
    return x;
}

/* sobol_reversed of dimensions dim .. dim + 3 at once (one walk over the index's bits). */
SAMPLAB_HD void sobol_reversed4(uint32_t index, uint32_t dim, uint32_t* x) {
    x[0] = x[1] = x[2] = x[3] = 0;
    for (; index != 0; index &= index - 1) {
        const uint32_t k = lowest_bit(index);
        for (uint32_t j = 0; j < 4; ++j) x[j] ^= sobol_column(dim + j, k);
    }
}

/* Owen's scramble of reversed digits, back in their natural order. */
SAMPLAB_HD uint32_t owen_digits(uint32_t reversed, uint32_t seed) {
    return reverse_bits(owen_scramble_reversed(reversed, seed));
}

SAMPLAB_HD uint32_t prime(uint32_t i) { return SAMPLAB_TABLE(primes)[i]; }

/* How many base-b digits pbrt's Halton sampler randomizes in dimension dim: [0] without
 * the top digit's bound (Owen), [1] with it (digit permutations). */
SAMPLAB_HD uint32_t halton_digits(uint32_t dim, uint32_t with_top) { return SAMPLAB_TABLE(halton_digits)[dim][with_top]; }

/* 64 x 64 -> the high 64 bits of the 128-bit product. */
SAMPLAB_HD uint64_t mul_high(uint64_t a, uint64_t b) {
#ifdef SAMPLAB_ON_DEVICE
    return __umul64hi(a, b);
#elif defined(__SIZEOF_INT128__)
    __extension__ typedef unsigned __int128 u128;  // GCC's and Clang's, not ISO C++'s
    return (uint64_t)(((u128)a * b) >> 64);
#else
    const uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
    const uint64_t low = a0 * b0, mid1 = a1 * b0, mid2 = a0 * b1;
    const uint64_t carry = ((low >> 32) + (mid1 & 0xFFFFFFFFu) + (mid2 & 0xFFFFFFFFu)) >> 32;
    return a1 * b1 + (mid1 >> 32) + (mid2 >> 32) + carry;
#endif
}

/* PCG64 (O'Neill 2014: a 128-bit LCG with the XSL RR output), as Rust's rand_pcg
 * Lcg128Xsl64 is seeded from a samplab seed: the stream samplab's random offsets come from. */
struct Pcg64 {
    uint64_t hi, lo;

    SAMPLAB_HD explicit Pcg64(uint64_t seed) {
        const uint64_t h = mix64(seed);
        hi = h;
        lo = mix64(h ^ seed);
        // the stream 0xA02B...F96D, shifted left one bit with the low bit set
        inc_add();
        step();
    }

    SAMPLAB_HD uint64_t next() {
        step();
        const uint32_t rot = (uint32_t)(hi >> 58);
        const uint64_t x = hi ^ lo;
        return rot == 0 ? x : (x >> rot) | (x << (64 - rot));
    }

  private:
    static constexpr uint64_t INC_HI = 0x4057B7EF767814F5ull;
    static constexpr uint64_t INC_LO = 0x851F42D4C957F2DBull;
    static constexpr uint64_t MUL_HI = 0x2360ED051FC65DA4ull;
    static constexpr uint64_t MUL_LO = 0x4385DF649FCCF645ull;

    SAMPLAB_HD void inc_add() {
        const uint64_t l = lo + INC_LO;
        hi += INC_HI + (l < lo ? 1u : 0u);
        lo = l;
    }

    SAMPLAB_HD void step() {
        const uint64_t h = mul_high(lo, MUL_LO) + lo * MUL_HI + hi * MUL_LO;
        lo *= MUL_LO;
        hi = h;
        inc_add();
    }
};

/* samplab's per-pixel keys (the families `independent` and `sobol`). */
struct Keys {
    uint64_t base;

    SAMPLAB_HD explicit Keys(uint64_t seed) : base(mix64(seed ^ 0x517CC1B727220Aull)) {}

    SAMPLAB_HD uint64_t pixel(uint32_t x, uint32_t y, uint32_t frame) const {
        const uint64_t p = ((uint64_t)y << 32) | x;
        return mix64(base ^ (p * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)frame * 0xC2B2AE3D27D4EB4Full));
    }

    /* The key of a whole frame (a pattern shared by every pixel). */
    SAMPLAB_HD uint64_t frame(uint32_t frame) const {
        return mix64(base ^ 0xA0761D6478BD642Full ^ ((uint64_t)frame * 0xC2B2AE3D27D4EB4Full));
    }

    /* Dimension dim's word: the same for every pixel. */
    SAMPLAB_HD uint32_t word(uint32_t dim) const { return (uint32_t)(rekey(base, (uint64_t)dim + 1) >> 32); }

};

}  // namespace detail

/* ---------------------------------------------------------------------------------------
 * Seeds.
 * ------------------------------------------------------------------------------------- */

/* A sub-seed for `key` (samplab's Seed::derive). */
SAMPLAB_HD uint64_t derive(uint64_t seed, uint64_t key) {
    return detail::mix64(detail::mix64(seed ^ 0x9E3779B97F4A7C15ull) + key);
}

/* A sub-seed for a named purpose (samplab's Seed::derive_str: the label's FNV-1a, mixed). */
SAMPLAB_HD uint64_t derive_str(uint64_t seed, const char* label) {
    uint64_t h = 0xCBF29CE484222325ull;
    for (; *label; ++label) h = (h ^ (uint64_t)(uint8_t)*label) * 0x100000001B3ull;
    return derive(seed, detail::mix64(h));
}

/* The seed of set k that `samplab generate --seed SEED` writes (set 0 unless --sets). */
SAMPLAB_HD uint64_t set_seed(uint64_t seed, uint64_t k) { return derive(seed, k); }

/* ---------------------------------------------------------------------------------------
 * Point sets: coordinate `dim` of point `index` of the set whose seed is `seed`.
 * ------------------------------------------------------------------------------------- */

/* How a point set is randomized: samplab's spec suffixes `.none`, `.xor`, `.owen`, `.shift`. */
enum class Randomization { None, Xor, Owen, Shift };

/* The Cranley-Patterson offset of axis dim of a set (Cranley & Patterson 1976): draw dim of
 * the set's offset stream. O(dim): keep it once per dimension where a loop draws many. */
SAMPLAB_HD uint64_t shift_offset(uint64_t seed, uint32_t dim) {
    detail::Pcg64 rng(derive_str(seed, "shift"));
    uint64_t u = rng.next();
    for (uint32_t k = 0; k < dim; ++k) u = rng.next();
    return u;
}

/* x in [0, 1) shifted by the 64-bit fraction u, mod 1, to 53 bits. */
SAMPLAB_HD double shifted(double x, uint64_t u) {
    const uint64_t fixed = (uint64_t)(x * 18446744073709551616.0);
    return (double)((fixed + u) >> 11) * (1.0 / 9007199254740992.0);
}

/* `sobol[.none|.xor|.owen|.shift]`: the Sobol' sequence (Sobol' 1967, Joe & Kuo 2008
 * directions, dimensions below SAMPLAB_SOBOL_DIMS) in Gray-code order, as scipy orders it;
 * .xor a random digital shift, .owen Owen's nested uniform scramble (Burley 2020), both at
 * the centres of their 2^-32 cells; .shift a Cranley-Patterson rotation. */
SAMPLAB_HD double sobol_point(Randomization r, uint64_t seed, uint32_t index, uint32_t dim) {
    const uint32_t reversed = detail::sobol_reversed(index ^ (index >> 1), dim);
    const uint32_t key = (uint32_t)(detail::mix64(derive(seed, dim)) >> 32);
    if (r == Randomization::Owen) return detail::cell_centre(detail::owen_digits(reversed, key));
    const uint32_t x = detail::reverse_bits(reversed);
    switch (r) {
        case Randomization::Xor: return detail::cell_centre(x ^ key);
        case Randomization::Shift: return shifted(detail::unit(x), shift_offset(seed, dim));
        default: return detail::unit(x);
    }
}

/* ---------------------------------------------------------------------------------------
 * Pixel samplers: dimension `dim` of sample `index` of pixel (x, y) in `frame`.
 * ------------------------------------------------------------------------------------- */

/* pbrt-v4's RandomizeStrategy for its Sobol' samplers (the `randomize` setting). */
enum class Scramble { None, Xor, FastOwen, Owen };

namespace detail {

/* The scrambled digits of reversed digits. */
SAMPLAB_HD uint32_t apply(Scramble s, uint32_t reversed, uint32_t seed) {
    if (s == Scramble::FastOwen) return owen_digits(reversed, seed);
    const uint32_t v = reverse_bits(reversed);
    switch (s) {
        case Scramble::Xor: return v ^ seed;
        case Scramble::Owen: return owen_bit_by_bit(v, seed);
        default: return v;
    }
}

/* Sobol' dimensions 0 and 1 of point `index` under the pbrt hash `hash` (its low word
 * scrambles dimension 0, its high word dimension 1), as pbrt's 2D Sobol' samplers draw them. */
SAMPLAB_HD void sobol2(Scramble s, uint32_t index, uint64_t hash, double* uv) {
    uv[0] = unit(apply(s, index, (uint32_t)hash));
    uv[1] = unit(apply(s, sobol_reversed(index, 1), (uint32_t)(hash >> 32)));
}

/* What a draw D that makes its values one at a time (`sample(dim)`) also answers. */
template <class D>
struct OneAtATime {
    SAMPLAB_HD void pair(uint32_t dim, double* uv) const {
        const D& d = static_cast<const D&>(*this);
        uv[0] = d.sample(dim);
        uv[1] = d.sample(dim + 1);
    }
    SAMPLAB_HD void sample4(uint32_t dim, double* v) const {
        const D& d = static_cast<const D&>(*this);
        for (uint32_t j = 0; j < 4; ++j) v[j] = d.sample(dim + j);
    }
};

/* What a draw D that makes its values by pairs (`pair(dim, uv)`, dim even) also answers:
 * dimensions dim .. dim + 3 as two pairs from an even dim, one at a time from an odd one. */
template <class D>
struct ByPairs {
    SAMPLAB_HD double sample(uint32_t dim) const {
        double uv[2];
        static_cast<const D&>(*this).pair(dim, uv);
        return uv[dim & 1u];
    }
    SAMPLAB_HD void sample4(uint32_t dim, double* v) const {
        const D& d = static_cast<const D&>(*this);
        if (dim & 1u) {
            for (uint32_t j = 0; j < 4; ++j) v[j] = sample(dim + j);
        } else {
            d.pair(dim, v);
            d.pair(dim + 2, v + 2);
        }
    }
};

/* A pixel family F's value from all five keys, through its draw (`F::at`). */
template <class F>
struct Family {
    SAMPLAB_HD double sample(uint32_t x, uint32_t y, uint32_t frame, uint32_t index, uint32_t dim) const {
        return static_cast<const F&>(*this).at(x, y, frame, index).sample(dim);
    }
};

}  // namespace detail

/* Every pixel family below answers in two ways:
 *   family.sample(x, y, frame, index, dim)       one value from all its keys;
 *   auto d = family.at(x, y, frame, index);      a sample's draw, its pixel's work done once:
 *   d.sample(dim), d.pair(dim, uv)               a value, or dimensions dim and dim + 1
 *                                                (dim even: the pair-based families make
 *                                                both at once, as pbrt's Get2D does),
 *   d.sample4(dim, v)                            or dimensions dim .. dim + 3 (`sobol`
 *                                                walks the index's bits once for all four).
 * All are pure functions of the keys; a Draw is a few words, kept on the stack. */

/* `independent`: 53 random bits hashed from every key. */
struct Independent : detail::Family<Independent> {
    detail::Keys keys;

    SAMPLAB_HD explicit Independent(uint64_t seed) : keys(seed) {}

    struct Draw : detail::OneAtATime<Draw> {
        uint64_t key;
        uint32_t index;

        SAMPLAB_HD double sample(uint32_t dim) const {
            const uint64_t h = detail::rekey(key, ((uint64_t)index << 32) | dim);
            return (double)(h >> 11) * (1.0 / 9007199254740992.0);
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, keys.pixel(x, y, frame), index};
    }

};

/* How many words sobol_tables writes for dimensions 0..dims. */
SAMPLAB_HD uint64_t sobol_tables_size(uint32_t dims) { return 257ull * dims; }

/* Tables that make `sobol` draws on the CPU faster (the family computes the same values
 * without them, as it should on a GPU): for each dimension d below dims, 257 words from
 * out + 257 d: d's key word under `seed`, then for each value v of a byte the XOR of d's
 * reversed columns that v selects as the index's low byte (in the word's low 16 bits) and
 * as its second byte (in the high 16 bits). The reversed columns 0..15 have no digit past
 * bit 15, so the two fit one word. */
SAMPLAB_HD void sobol_tables(uint64_t seed, uint32_t dims, uint32_t* out) {
    const detail::Keys keys(seed);
    for (uint32_t d = 0; d < dims; ++d, out += 257) {
        out[0] = keys.word(d);
        for (uint32_t v = 0; v < 256; ++v)
            out[1 + v] = detail::sobol_reversed(v, d) | (detail::sobol_reversed(v << 8, d) << 16);
    }
}

/* `sobol`: Owen-scrambled Sobol' per pixel (Burley 2020): dimension d is Sobol' dimension d,
 * the index's low 16 digits nested-uniform scrambled by the pixel's hash (samples 0..2^m map
 * to an aligned block of 2^m points, a net), each dimension Owen-scrambled by its own hash;
 * dimensions below SAMPLAB_SOBOL_DIMS. `tables` (from sobol_tables for the same seed, in the
 * memory the draws run in) and `tabled` (its dimensions) are optional. */
struct Sobol : detail::Family<Sobol> {
    detail::Keys keys;
    const uint32_t* tables;
    uint32_t tabled;

    SAMPLAB_HD explicit Sobol(uint64_t seed, const uint32_t* tables_ = nullptr, uint32_t tabled_ = 0)
        : keys(seed), tables(tables_), tabled(tables_ ? tabled_ : 0) {}

    struct Draw : detail::OneAtATime<Draw> {
        const Sobol* f;
        /* The pixel's key, the part of Keys::combine that depends on it alone, the point. */
        uint32_t key, salt, point;

        /* The value of reversed digits x under dimension word `word`. */
        SAMPLAB_HD double value(uint32_t x, uint32_t word) const {
            return detail::unit(detail::owen_digits(x, key ^ (word + salt)));
        }

        /* Dimension dim's reversed digits from its table. */
        SAMPLAB_HD uint32_t tabled(const uint32_t* t, uint32_t dim) const {
            const uint32_t low = (t[1 + (point & 0xFFu)] & 0xFFFFu) ^ (t[1 + ((point >> 8) & 0xFFu)] >> 16);
            return point >> 16 ? low ^ detail::sobol_reversed(point & 0xFFFF0000u, dim) : low;
        }

        SAMPLAB_HD double sample(uint32_t dim) const {
            if (dim < f->tabled) {
                const uint32_t* t = f->tables + 257ull * dim;
                return value(tabled(t, dim), t[0]);
            }
            return value(detail::sobol_reversed(point, dim), f->keys.word(dim));
        }
        SAMPLAB_HD void sample4(uint32_t dim, double* v) const {
            if (dim + 3 < f->tabled) {
                const uint32_t* t = f->tables + 257ull * dim;
                for (uint32_t j = 0; j < 4; ++j) v[j] = value(tabled(t + 257 * j, dim + j), t[257 * j]);
                return;
            }
            uint32_t x[4];
            detail::sobol_reversed4(point, dim, x);
            for (uint32_t j = 0; j < 4; ++j) v[j] = value(x[j], f->keys.word(dim + j));
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        const uint64_t k = keys.pixel(x, y, frame);
        const uint32_t key = (uint32_t)k;
        const uint32_t low = detail::owen_scramble_reversed(detail::reverse_bits(index) >> 16, (uint32_t)(k >> 32));
        return Draw{{}, this, key, 0x9E3779B9u + (key << 6) + (key >> 2),
                    (index & 0xFFFF0000u) | (detail::reverse_bits(low) >> 16)};
    }

};

/* `sobol.padded`: pbrt-v4's PaddedSobolSampler; dimensions 2k, 2k+1 are Sobol' dimensions
 * 0, 1 at a per-pixel permutation of the index, scrambled by Hash(pixel, 2k, seed). */
struct PaddedSobol : detail::Family<PaddedSobol> {
    uint64_t seed;
    uint32_t spp;
    Scramble scramble;

    SAMPLAB_HD PaddedSobol(uint64_t seed_, uint32_t spp_, Scramble s = Scramble::FastOwen)
        : seed(seed_), spp(spp_), scramble(s) {}

    struct Draw : detail::ByPairs<Draw> {
        const PaddedSobol* f;
        uint32_t x, y, index, seed;

        SAMPLAB_HD void pair(uint32_t dim, double* uv) const {
            const uint64_t hash = detail::hash4(x, y, dim & ~1u, seed);
            const uint32_t i = detail::permutation_element(index, f->spp, (uint32_t)hash);
            detail::sobol2(f->scramble, i, hash, uv);
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, this, x, y, index, detail::frame_seed(seed, frame)};
    }

};

/* The order `zsobol` visits the pixels in (its `curve` setting). */
enum class Curve { Morton, Hilbert };

/* `zsobol[:curve=hilbert]`: pbrt-v4's ZSobolSampler (Ahmed & Wonka 2020): one Sobol'
 * sequence over the screen, pixels in Morton order (or along a Hilbert curve), each base-4
 * digit of the index permuted by a hash of the digits above it. spp must be a power of two. */
struct ZSobol : detail::Family<ZSobol> {
    uint64_t seed;
    uint32_t log2_spp, base4_digits, order;
    Scramble scramble;
    Curve curve;

    SAMPLAB_HD ZSobol(uint64_t seed_, uint32_t width, uint32_t height, uint32_t spp, Scramble s = Scramble::FastOwen,
                      Curve c = Curve::Morton)
        : seed(seed_), order(0), scramble(s), curve(c) {
        log2_spp = 31 - detail::leading_zeros(spp);
        for (uint32_t side = 1, most = width > height ? width : height; side < most; side <<= 1) ++order;
        base4_digits = order + (log2_spp + 1) / 2;
    }

    /* The permuted sequence index of Morton index `morton` for the pair starting at `dim`
     * (pbrt's GetSampleIndex). */
    SAMPLAB_HD uint64_t sequence_index(uint64_t morton, uint32_t dim) const {
        // the 24 permutations of four digits in pbrt's order, a byte each (digit d in bits 2d,
        // 2d + 1), eight to a word
        const uint64_t perms[3] = {0xB1E19C6C78D8B4E4ull, 0x72D236C68D2D39C9ull, 0x93634B1B87271E4Eull};
        const uint32_t odd = log2_spp & 1u;
        const uint64_t salt = (uint64_t)(0x55555555u * dim);
        const uint32_t digits = base4_digits - odd;
        uint64_t rest = morton >> odd, acc = 0;
        for (uint32_t k = 0; k < digits; ++k) {
            const uint32_t digit = (uint32_t)(rest & 3u);
            rest >>= 2;
            const uint32_t p = (uint32_t)((detail::mix_bits(rest ^ salt) >> 24) % 24);
            acc = (acc >> 2) | (((perms[p >> 3] >> (8 * (p & 7) + 2 * digit)) & 3u) << 62);
        }
        uint64_t index = digits == 0 ? 0 : (acc >> (64 - 2 * digits)) << odd;
        if (odd) index |= (morton & 1u) ^ (detail::mix_bits((morton >> 1) ^ salt) & 1u);
        return index;
    }

    struct Draw : detail::ByPairs<Draw> {
        const ZSobol* f;
        uint64_t morton;
        uint32_t seed;

        SAMPLAB_HD void pair(uint32_t dim, double* uv) const {
            const uint32_t first = dim & ~1u;
            const uint64_t i = f->sequence_index(morton, first);
            detail::sobol2(f->scramble, (uint32_t)i, detail::hash2(first + 2, seed), uv);
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        const uint64_t place = curve == Curve::Hilbert ? detail::hilbert2(order, x, y) : detail::morton2(x, y);
        return Draw{{}, this, (place << log2_spp) | index, detail::frame_seed(seed, frame)};
    }

};

/* `stratified`: jittered a x b strata per pixel for each pair of dimensions (a the largest
 * divisor of spp not above its square root), sample i in stratum pi(i), pi a hashed
 * permutation of (seed, pixel, frame, pair) (Kensler 2013); pairs independent. */
struct Stratified : detail::Family<Stratified> {
    detail::Keys keys;
    uint32_t spp, columns, rows;

    SAMPLAB_HD Stratified(uint64_t seed, uint32_t spp_) : keys(seed), spp(spp_) {
        uint64_t root = 1;
        while ((root + 1) * (root + 1) <= spp) ++root;
        rows = (uint32_t)root;
        while (spp % rows != 0) --rows;
        columns = spp / rows;
    }

    struct Draw : detail::ByPairs<Draw> {
        const Stratified* f;
        uint64_t key;
        uint32_t index;

        SAMPLAB_HD void pair(uint32_t dim, double* uv) const {
            const uint64_t k = detail::rekey(key, dim / 2);
            const uint32_t stratum = detail::permute(index % f->spp, f->spp, (uint32_t)k);
            const uint64_t jitter = detail::rekey(k, (uint64_t)index + 1);
            const double below_one = 0x1.fffffffffffffp-1;
            const double u = ((double)(stratum % f->columns) + detail::unit((uint32_t)jitter)) / f->columns;
            const double v = ((double)(stratum / f->columns) + detail::unit((uint32_t)(jitter >> 32))) / f->rows;
            uv[0] = u < below_one ? u : below_one;
            uv[1] = v < below_one ? v : below_one;
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, this, keys.pixel(x, y, frame), index};
    }
};

/* `lattice`: a rank-1 lattice sequence per pixel (Cools, Kuo & Nuyens 2006; the embedded
 * fast-CBC vector for 2^16 points of Nuyens & Cools 2006) in radical-inverse order, the
 * index nested-uniform scrambled by the pixel's hash (Burley 2020), so that each pixel's
 * first 2^m samples are a shifted lattice, and a random shift per pixel and dimension
 * (Cranley & Patterson 1976): frac(phi_2(i) z_d + shift), exact in 32-bit fixed point;
 * dimensions below SAMPLAB_LATTICE_DIMS. */
struct Lattice : detail::Family<Lattice> {
    detail::Keys keys;

    SAMPLAB_HD explicit Lattice(uint64_t seed) : keys(seed) {}

    struct Draw : detail::OneAtATime<Draw> {
        const Lattice* f;
        /* The pixel's key, the part of its dimensions' keys that depends on it alone, and
         * phi_2 of the shuffled index in 32-bit fixed point. */
        uint32_t key, salt, radical;

        SAMPLAB_HD double sample(uint32_t dim) const {
            const uint32_t shift = key ^ (f->keys.word(dim) + salt);
            return detail::unit(radical * SAMPLAB_TABLE(lattice)[dim] + shift);
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        const uint64_t k = keys.pixel(x, y, frame);
        const uint32_t key = (uint32_t)k;
        return Draw{{}, this, key, 0x9E3779B9u + (key << 6) + (key >> 2),
                    detail::owen_scramble_reversed(detail::reverse_bits(index), (uint32_t)(k >> 32))};
    }
};

/* `pmj02` and `pmj02.bn`: progressive multi-jittered (0, 2) sequences per pixel
 * (Christensen, Kensler & Kilpatrick 2018; the stochastic construction of Helmer, Christensen &
 * Kensler 2021) from a pool of 16 entries made when the family is prepared: `tables` are
 * samplab_pixels_header_tables' words for a sampler prepared through the C interface with
 * the same spec, film and seed (the pool, and pmj02.bn's mask of side `mask`, 64 unless its
 * spec says otherwise), in the memory the draws run in.
 *   pmj02: dimensions 4k .. 4k + 3 are the pool entry named by the top 4 bits of a hash h of
 *   (pixel, frame, k), its sample a scramble of the index (a nested uniform one for a
 *   power-of-two spp, so each prefix of 2^j samples is a net), digitally shifted by h;
 *   pmj02.bn: pair k is the first sequence of entry k mod 16 at a per-pixel permutation of
 *   the index, shifted mod 1 by the blue-noise mask read at the pixel (Georgiev & Fajardo
 *   2016), the mask offset by a hash of (frame, k). */
struct Pmj02 : detail::Family<Pmj02> {
    detail::Keys keys, offsets;
    uint32_t spp;
    const uint32_t* pool;
    const uint32_t* mask;
    uint32_t side;

    /* `pmj02` (mask_side 0) or `pmj02.bn` (the mask's side). */
    SAMPLAB_HD Pmj02(uint64_t seed, uint32_t spp_, const uint32_t* tables, uint32_t mask_side = 0)
        : keys(seed), offsets(derive_str(seed, "dither offsets")), spp(spp_), pool(tables),
          mask(mask_side ? tables + 64ull * spp_ : nullptr), side(mask_side) {}

    /* The scrambled index of the sample whose index is `index` (`reversed`: its 16 low bits,
     * below spp, reversed) under the 32-bit key `key`. */
    SAMPLAB_HD uint32_t scrambled(uint32_t reversed, uint32_t index, uint32_t key) const {
        if ((spp & (spp - 1)) == 0) {
            const uint32_t bits = detail::lowest_bit(spp);
            return (detail::owen_scramble_reversed(reversed, key) >> (16 - bits)) & (spp - 1);
        }
        return detail::permute(index % spp, spp, key);
    }

    struct Draw : detail::ByPairs<Draw> {
        const Pmj02* f;
        uint64_t key;
        uint32_t x, y, frame, index, reversed;

        /* pmj02's block of dimensions 4b .. 4b + 3 as 32-bit fixed point. */
        SAMPLAB_HD void block(uint32_t b, uint32_t* v) const {
            const uint64_t h = detail::rekey(key, b);
            const uint32_t* p = f->pool + 4ull * ((h >> 60) * f->spp + f->scrambled(reversed, index, (uint32_t)h));
            const uint64_t shifts[4] = {0x9E3779B97F4A7C15ull, 0xC2B2AE3D27D4EB4Full, 0x165667B19E3779F9ull,
                                        0xD6E8FEB86659FD93ull};
            for (uint32_t d = 0; d < 4; ++d) v[d] = p[d] ^ (uint32_t)detail::mul_high(h, shifts[d]);
        }

        SAMPLAB_HD void pair(uint32_t dim, double* uv) const {
            const uint32_t k = dim / 2;
            if (!f->mask) {
                uint32_t v[4];
                block(k / 2, v);
                uv[0] = detail::unit(v[k % 2 * 2]);
                uv[1] = detail::unit(v[k % 2 * 2 + 1]);
                return;
            }
            const uint32_t i = f->scrambled(reversed, index, (uint32_t)detail::rekey(key, k));
            const uint32_t* p = f->pool + 4ull * ((k % 16) * f->spp + i);
            const uint64_t fk = f->offsets.frame(frame);
            const uint32_t word = f->offsets.word(k);
            const uint32_t ox = (uint32_t)fk, oy = (uint32_t)(fk >> 32);
            const uint32_t mx = (x + (ox ^ (word + 0x9E3779B9u + (ox << 6) + (ox >> 2)))) % f->side;
            const uint32_t my = (y + (oy ^ (word + 0x9E3779B9u + (oy << 6) + (oy >> 2)))) % f->side;
            const uint32_t* m = f->mask + 2ull * ((uint64_t)my * f->side + mx);
            uv[0] = detail::unit(p[0] + m[0]);
            uv[1] = detail::unit(p[1] + m[1]);
        }

        SAMPLAB_HD void sample4(uint32_t dim, double* v) const {
            if (f->mask || dim % 4 != 0) return detail::ByPairs<Draw>::sample4(dim, v);
            uint32_t b[4];
            block(dim / 4, b);
            for (uint32_t d = 0; d < 4; ++d) v[d] = detail::unit(b[d]);
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, this, keys.pixel(x, y, frame), x, y, frame, index, detail::reverse_bits(index & (spp - 1)) >> 16};
    }
};

/* `sobol[.xor|.owen|.shift]` as a pixel sampler: the point-set sequence per pixel, each
 * pixel's sequence set 0 of the seed its key names (as `samplab pixels sobol.owen` serves a
 * point-set sequence), so one randomization word names one scramble through both front
 * doors; dimensions below SAMPLAB_SOBOL_DIMS. */
struct SobolSequence : detail::Family<SobolSequence> {
    detail::Keys keys;
    Randomization randomization;

    SAMPLAB_HD SobolSequence(uint64_t seed, Randomization r) : keys(seed), randomization(r) {}

    struct Draw : detail::OneAtATime<Draw> {
        Randomization randomization;
        uint64_t seed;
        uint32_t index;

        SAMPLAB_HD double sample(uint32_t dim) const { return sobol_point(randomization, seed, index, dim); }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, randomization, set_seed(keys.pixel(x, y, frame), 0), index};
    }
};

/* A family F drawn past its film's `dims` dimensions as the C interface's samplab_pixel_sample
 * and the library's Pixels::sample_padded draw (a path with no depth limit): independent
 * values under a seed of their own, never F's (which stop at their tables). */
template <class F>
struct Unbounded : detail::Family<Unbounded<F>> {
    F family;
    Independent padding;
    uint32_t dims;

    SAMPLAB_HD Unbounded(uint64_t seed, const F& f, uint32_t dims_)
        : family(f), padding(derive_str(seed, "pixel padding")), dims(dims_) {}

    struct Draw : detail::OneAtATime<Draw> {
        typename F::Draw family;
        Independent::Draw padding;
        uint32_t dims;

        SAMPLAB_HD double sample(uint32_t dim) const { return dim < dims ? family.sample(dim) : padding.sample(dim); }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, family.at(x, y, frame, index), padding.at(x, y, frame, index), dims};
    }
};

/* pbrt-v4's RandomizeStrategy for its Halton sampler. */
enum class HaltonRandomize { None, PermuteDigits, Owen };

/* How many words halton_permutations writes for dimensions 0..dims. */
SAMPLAB_HD uint64_t halton_permutations_size(uint32_t dims) {
    uint64_t size = dims;
    for (uint32_t d = 0; d < dims; ++d) size += (uint64_t)detail::halton_digits(d, 1) * detail::prime(d);
    return size;
}

/* The digit permutations of `halton:randomize=permutedigits` in frame 0 for dimensions
 * 0..dims (pbrt's DigitPermutation tables), into `out` (halton_permutations_size(dims)
 * words): word d is where dimension d's table starts, entry j * base + v its digit v at
 * position j. Optional: without them each digit's permutation is hashed at each draw. */
SAMPLAB_HD void halton_permutations(uint64_t seed, uint32_t dims, uint32_t* out) {
    uint32_t at = dims;
    for (uint32_t d = 0; d < dims; ++d) {
        out[d] = at;
        const uint32_t base = detail::prime(d);
        for (uint32_t j = 0; j < detail::halton_digits(d, 1); ++j) {
            const uint32_t p = (uint32_t)detail::hash3(base, j, detail::frame_seed(seed, 0));
            for (uint32_t v = 0; v < base; ++v) out[at++] = detail::permutation_element(v, base, p);
        }
    }
}

/* `halton`: pbrt-v4's HaltonSampler, one Halton sequence over the screen (tiles of at most
 * 128 x 128 pixels), every value computed in single precision as pbrt computes it;
 * dimensions below SAMPLAB_HALTON_DIMS. `permutations` (from halton_permutations, in the
 * memory the draws run in) and `permuted` (its dimensions) are optional. */
struct Halton : detail::Family<Halton> {
    uint64_t seed;
    HaltonRandomize randomize;
    uint64_t scales[2], inverses[2];
    uint32_t exponents[2];
    const uint32_t* permutations;
    uint32_t permuted;

    SAMPLAB_HD Halton(uint64_t seed_, uint32_t width, uint32_t height, HaltonRandomize r = HaltonRandomize::PermuteDigits,
                      const uint32_t* permutations_ = nullptr, uint32_t permuted_ = 0)
        : seed(seed_), randomize(r), permutations(permutations_), permuted(permutations_ ? permuted_ : 0) {
        const uint32_t sides[2] = {width, height};
        for (uint32_t i = 0; i < 2; ++i) {
            const uint32_t side = sides[i] < 128 ? sides[i] : 128;
            scales[i] = 1;
            exponents[i] = 0;
            while (scales[i] < side) {
                scales[i] *= detail::prime(i);
                ++exponents[i];
            }
        }
        inverses[0] = inverse_mod(scales[1], scales[0]);
        inverses[1] = inverse_mod(scales[0], scales[1]);
    }

    SAMPLAB_HD static uint64_t inverse_mod(uint64_t x, uint64_t n) {
        int64_t r0 = (int64_t)n, r1 = (int64_t)(x % n), s0 = 0, s1 = 1;
        while (r1 != 0) {
            const int64_t q = r0 / r1, r = r0 - q * r1, s = s0 - q * s1;
            r0 = r1;
            r1 = r;
            s0 = s1;
            s1 = s;
        }
        const int64_t m = s0 % (int64_t)n;
        return (uint64_t)(m < 0 ? m + (int64_t)n : m);
    }

    /* The Halton index of sample `index` of pixel (x, y). */
    SAMPLAB_HD uint64_t halton_index(uint32_t x, uint32_t y, uint32_t index) const {
        const uint64_t stride = scales[0] * scales[1];
        uint64_t offset = 0;
        if (stride > 1) {
            const uint32_t pixel[2] = {x, y};
            for (uint32_t i = 0; i < 2; ++i) {
                const uint64_t b = detail::prime(i);
                uint64_t c = pixel[i] % 128, reversed = 0;
                for (uint32_t k = 0; k < exponents[i]; ++k) {
                    reversed = reversed * b + c % b;
                    c /= b;
                }
                offset += reversed * (stride / scales[i]) * inverses[i];
            }
            offset %= stride;
        }
        return offset + (uint64_t)index * stride;
    }

    /* The radical inverse of a in `base` over `positions` digits (0: until a is exhausted),
     * digit j of value v mapped by `digit(j, v, reversed)`. */
    template <class Digit>
    SAMPLAB_HD static float radical_inverse(uint32_t base, uint64_t a, uint32_t positions, Digit digit) {
        const uint64_t b = base;
        const uint64_t limit = 0xFFFFFFFFFFFFFFFFull / b - b;
        const float inv = 1.0f / (float)base;
        float inv_m = 1.0f;
        uint64_t reversed = 0;
        for (uint32_t j = 0; (positions ? j < positions : a != 0) && reversed < limit; ++j) {
            const uint64_t next = a / b;
            reversed = reversed * b + digit(j, (uint32_t)(a - next * b), reversed);
            inv_m *= inv;
            a = next;
        }
        const float value = (float)reversed * inv_m;
        const float below_one = 0x1.fffffep-1f;
        return value < below_one ? value : below_one;
    }

    struct Identity {
        SAMPLAB_HD uint32_t operator()(uint32_t, uint32_t v, uint64_t) const { return v; }
    };
    struct Table {
        const uint32_t* t;
        uint32_t base;
        SAMPLAB_HD uint32_t operator()(uint32_t j, uint32_t v, uint64_t) const { return t[j * base + v]; }
    };
    struct Hashed {
        uint32_t base, seed;
        SAMPLAB_HD uint32_t operator()(uint32_t j, uint32_t v, uint64_t) const {
            return detail::permutation_element(v, base, (uint32_t)detail::hash3(base, j, seed));
        }
    };
    struct Owen {
        uint32_t base, hash;
        SAMPLAB_HD uint32_t operator()(uint32_t, uint32_t v, uint64_t reversed) const {
            return detail::permutation_element(v, base, (uint32_t)detail::mix_bits((uint64_t)hash ^ reversed));
        }
    };

    struct Draw : detail::OneAtATime<Draw> {
        const Halton* f;
        uint64_t a;
        uint32_t frame;

        SAMPLAB_HD double sample(uint32_t dim) const {
            if (dim == 0) return radical_inverse(2, a >> f->exponents[0], 0, Identity());
            if (dim == 1) return radical_inverse(3, a / f->scales[1], 0, Identity());
            const uint32_t base = detail::prime(dim);
            switch (f->randomize) {
                case HaltonRandomize::PermuteDigits: {
                    const uint32_t positions = detail::halton_digits(dim, 1);
                    if (frame == 0 && dim < f->permuted)
                        return radical_inverse(base, a, positions, Table{f->permutations + f->permutations[dim], base});
                    return radical_inverse(base, a, positions, Hashed{base, detail::frame_seed(f->seed, frame)});
                }
                case HaltonRandomize::Owen: {
                    const uint32_t hash = (uint32_t)detail::mix_bits(1 + ((uint64_t)dim << 4)) ^ detail::frame_seed(f->seed, frame);
                    return radical_inverse(base, a, detail::halton_digits(dim, 0), Owen{base, hash});
                }
                default: return radical_inverse(base, a, 0, Identity());
            }
        }
    };

    SAMPLAB_HD Draw at(uint32_t x, uint32_t y, uint32_t frame, uint32_t index) const {
        return Draw{{}, this, halton_index(x, y, index), frame};
    }

};

}  // namespace samplab

#endif
