/* A small path tracer that draws every random number from samplab's C library (issue 97:
 * the C library as renderers link it). A room of five diffuse walls, open towards the
 * camera, with a diffuse and a mirror sphere, lit by a spherical light under the ceiling;
 * paths end by Russian roulette
 * only (no depth limit), so a path may reach past the film's dimensions, where samplab pads
 * with independent values. Dimensions of sample i of a pixel: 0-1 the position in the pixel,
 * then 3 per bounce (2 for the direction, 1 for the roulette).
 *
 * usage: pathtracer SPEC SIZE SPP DIMS SEED OUT.f32
 * writes SIZE x SIZE floats (the luminance of each pixel, row 0 at the top) to OUT.f32 and
 * prints the mean path length and the share of values drawn past DIMS.
 *
 * The same file compiled as C++ (`c++ -x c++ -std=c++17 -DSAMPLAB_HEADER`) draws from the
 * header-only samplers instead (samplab/samplers.hpp: inlined, no library to link), for the
 * families that need no tables (SPEC a bare name); past DIMS it draws samplab::Unbounded's
 * padding, as the library does. Both builds write the same image bytes (the test
 * crates/samplab-c/tests/header.rs). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* SAMPLE(name, x, y, i) declares sample i of pixel (x, y), VALUE(name, dim) draws from it */
#ifdef SAMPLAB_HEADER
#include <samplab/samplers.hpp>

#include <vector>
/* a family of the header, drawn past the film's dimensions as the library pads: its draw
 * made once per sample */
#define SAMPLER template <class Sampler>
#define SAMPLE(name, x, y, i) const auto name = s.at(x, y, 0, i)
#define VALUE(name, dim) name.sample(dim)
#else
#include "samplab.h"
typedef const SamplabPixels *Sampler;
#define SAMPLER
#define SAMPLE(name, x, y, i) const uint32_t name = i
#define VALUE(name, dim) samplab_pixel_sample(s, x, y, 0, name, dim)
#endif

typedef struct { double x, y, z; } V;
static V v(double x, double y, double z) { V r = {x, y, z}; return r; }
static V add(V a, V b) { return v(a.x + b.x, a.y + b.y, a.z + b.z); }
static V sub(V a, V b) { return v(a.x - b.x, a.y - b.y, a.z - b.z); }
static V mul(V a, double s) { return v(a.x * s, a.y * s, a.z * s); }
static double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static V unit(V a) { return mul(a, 1.0 / sqrt(dot(a, a))); }
static V cross(V a, V b) { return v(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }

/* the room [0,1]^3: walls as planes n.p = d, albedo; spheres: centre, radius, albedo, kind */
typedef struct { V n; double d, albedo; } Plane;
typedef struct { V c; double r, albedo, emit; int mirror; } Ball;
static const Plane walls[5] = {
    {{1, 0, 0}, 0.0, 0.75}, {{-1, 0, 0}, -1.0, 0.25}, {{0, 1, 0}, 0.0, 0.75},
    {{0, -1, 0}, -1.0, 0.75}, {{0, 0, -1}, -1.0, 0.75},
};
static const Ball balls[3] = {
    {{0.3, 0.2, 0.6}, 0.2, 0.8, 0.0, 0}, {{0.72, 0.18, 0.35}, 0.18, 0.95, 0.0, 1},
    {{0.5, 0.9, 0.5}, 0.06, 0.0, 40.0, 0},
};

/* nearest hit along o + t d: its distance, normal, albedo, emission and whether it mirrors */
static int hit(V o, V d, double *t, V *n, double *albedo, double *emit, int *mirror) {
    *t = 1e30;
    for (int k = 0; k < 5; ++k) {
        double den = dot(walls[k].n, d);
        if (fabs(den) < 1e-12) continue;
        double s = (walls[k].d - dot(walls[k].n, o)) / den;
        if (s > 1e-9 && s < *t) { *t = s; *n = walls[k].n; *albedo = walls[k].albedo; *emit = 0; *mirror = 0; }
    }
    for (int k = 0; k < 3; ++k) {
        V oc = sub(o, balls[k].c);
        double b = dot(oc, d), c = dot(oc, oc) - balls[k].r * balls[k].r, disc = b * b - c;
        if (disc < 0) continue;
        double s = -b - sqrt(disc);
        if (s <= 1e-9) s = -b + sqrt(disc);
        if (s > 1e-9 && s < *t) {
            *t = s;
            *n = unit(sub(add(o, mul(d, s)), balls[k].c));
            *albedo = balls[k].albedo; *emit = balls[k].emit; *mirror = balls[k].mirror;
        }
    }
    return *t < 1e29;
}

/* Render SIZE x SIZE pixels at spp samples into `image`; the mean bounces a path and the
 * share of values drawn past dims into stats[0], stats[1]. */
SAMPLER static void render(Sampler s, uint32_t size, uint32_t spp, uint32_t dims, float *image, double *stats) {
    const V eye = v(0.5, 0.5, -1.2);
    double bounces = 0, past = 0, drawn = 0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            double sum = 0;
            for (uint32_t i = 0; i < spp; ++i) {
                uint32_t dim = 0;
                SAMPLE(sample, x, y, i);
#define DRAW() (drawn += 1, past += dim >= dims, VALUE(sample, dim++))
                double px = (x + DRAW()) / size, py = 1.0 - (y + DRAW()) / size;
                V o = eye, d = unit(sub(v(px, py, 0.0), eye));
                double weight = 1.0;
                for (;;) {
                    double t = 0, albedo = 0, emit = 0; V n = {0, 0, 0}; int mirror = 0;
                    if (!hit(o, d, &t, &n, &albedo, &emit, &mirror)) break;
                    if (emit > 0) { sum += weight * emit; break; }
                    if (dot(n, d) > 0) n = mul(n, -1.0);
                    o = add(o, mul(d, t));
                    double u1 = DRAW(), u2 = DRAW(), u3 = DRAW();
                    bounces += 1;
                    if (mirror) {
                        d = sub(d, mul(n, 2.0 * dot(n, d)));
                    } else {
                        /* cosine-weighted direction about n (the albedo is the whole weight) */
                        double r = sqrt(u1), phi = 6.283185307179586 * u2;
                        V a = fabs(n.x) > 0.5 ? v(0, 1, 0) : v(1, 0, 0);
                        V tx = unit(cross(a, n)), ty = cross(n, tx);
                        d = unit(add(add(mul(tx, r * cos(phi)), mul(ty, r * sin(phi))), mul(n, sqrt(1.0 - u1))));
                    }
                    /* Russian roulette with the albedo as survival probability: unbiased */
                    if (u3 >= albedo) break;
                }
#undef DRAW
            }
            image[y * size + x] = (float)(sum / spp);
        }
    stats[0] = bounces / ((double)size * size * spp);
    stats[1] = past / drawn;
}

int main(int argc, char **argv) {
    if (argc != 7) {
        fprintf(stderr, "usage: pathtracer SPEC SIZE SPP DIMS SEED OUT.f32\n");
        return 2;
    }
    uint32_t size = (uint32_t)atoi(argv[2]), spp = (uint32_t)atoi(argv[3]), dims = (uint32_t)atoi(argv[4]);
    uint64_t seed = strtoull(argv[5], NULL, 10);
    float *image = (float *)malloc(sizeof(float) * size * size);
    if (!image) return 2;
    double stats[2];
#ifdef SAMPLAB_HEADER
    const char *spec = argv[1];
    /* sobol's and halton's tables for the film's dimensions, as the library keeps them */
    std::vector<uint32_t> tables(samplab::sobol_tables_size(dims)), permutations(samplab::halton_permutations_size(dims));
    samplab::sobol_tables(seed, dims, tables.data());
    samplab::halton_permutations(seed, dims, permutations.data());
    using samplab::Unbounded;
    if (!strcmp(spec, "independent")) render(Unbounded<samplab::Independent>(seed, samplab::Independent(seed), dims), size, spp, dims, image, stats);
    else if (!strcmp(spec, "sobol")) render(Unbounded<samplab::Sobol>(seed, samplab::Sobol(seed, tables.data(), dims), dims), size, spp, dims, image, stats);
    else if (!strcmp(spec, "sobol.padded")) render(Unbounded<samplab::PaddedSobol>(seed, samplab::PaddedSobol(seed, spp), dims), size, spp, dims, image, stats);
    else if (!strcmp(spec, "zsobol")) render(Unbounded<samplab::ZSobol>(seed, samplab::ZSobol(seed, size, size, spp), dims), size, spp, dims, image, stats);
    else if (!strcmp(spec, "stratified")) render(Unbounded<samplab::Stratified>(seed, samplab::Stratified(seed, spp), dims), size, spp, dims, image, stats);
    else if (!strcmp(spec, "lattice")) render(Unbounded<samplab::Lattice>(seed, samplab::Lattice(seed), dims), size, spp, dims, image, stats);
    else if (!strcmp(spec, "halton")) render(Unbounded<samplab::Halton>(seed, samplab::Halton(seed, size, size, samplab::HaltonRandomize::PermuteDigits, permutations.data(), dims), dims), size, spp, dims, image, stats);
    else { fprintf(stderr, "pathtracer: %s is not a header family without tables\n", spec); return 2; }
#else
    char error[256];
    SamplabPixels *s = samplab_pixels_new(argv[1], size, size, spp, dims, seed, error, sizeof error);
    if (!s) { fprintf(stderr, "pathtracer: %s\n", error); return 2; }
    render(s, size, spp, dims, image, stats);
    const char *spec = samplab_pixels_spec(s);
#endif
    FILE *out = fopen(argv[6], "wb");
    if (!out || fwrite(image, sizeof(float), size * size, out) != size * size || fclose(out) != 0) {
        fprintf(stderr, "pathtracer: cannot write %s\n", argv[6]);
        return 2;
    }
    printf("%s: %.2f bounces a path, %.3f%% of values past %u dimensions\n", spec, stats[0], 100.0 * stats[1], dims);
#ifndef SAMPLAB_HEADER
    samplab_pixels_free(s);
#endif
    free(image);
    return 0;
}
