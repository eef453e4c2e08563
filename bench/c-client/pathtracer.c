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
 * prints the mean path length and the share of values drawn past DIMS. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "samplab.h"

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

int main(int argc, char **argv) {
    if (argc != 7) {
        fprintf(stderr, "usage: pathtracer SPEC SIZE SPP DIMS SEED OUT.f32\n");
        return 2;
    }
    uint32_t size = (uint32_t)atoi(argv[2]), spp = (uint32_t)atoi(argv[3]), dims = (uint32_t)atoi(argv[4]);
    char error[256];
    SamplabPixels *s = samplab_pixels_new(argv[1], size, size, spp, dims, strtoull(argv[5], NULL, 10), error, sizeof error);
    if (!s) { fprintf(stderr, "pathtracer: %s\n", error); return 2; }
    float *image = malloc(sizeof(float) * size * size);
    if (!image) return 2;
    const V eye = v(0.5, 0.5, -1.2);
    double bounces = 0, past = 0, drawn = 0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            double sum = 0;
            for (uint32_t i = 0; i < spp; ++i) {
                uint32_t dim = 0;
#define DRAW() (drawn += 1, past += dim >= dims, samplab_pixel_sample(s, x, y, 0, i, dim++))
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
    FILE *out = fopen(argv[6], "wb");
    if (!out || fwrite(image, sizeof(float), size * size, out) != size * size || fclose(out) != 0) {
        fprintf(stderr, "pathtracer: cannot write %s\n", argv[6]);
        return 2;
    }
    printf("%s: %.2f bounces a path, %.3f%% of values past %u dimensions\n", samplab_pixels_spec(s),
           bounces / ((double)size * size * spp), 100.0 * past / drawn, dims);
    samplab_pixels_free(s);
    free(image);
    return 0;
}
