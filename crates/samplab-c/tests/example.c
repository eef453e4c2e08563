/* A renderer's use of samplab's pixel samplers, compiled and run by tests/c_interface.rs:
 * prints "x y frame index dim value" lines (value as %a, exact) for the test to compare. */
#include <math.h>
#include <stdio.h>

#include "samplab.h"

int main(int argc, char **argv) {
    const char *spec = argc > 1 ? argv[1] : "zsobol";
    char error[256];
    SamplabPixels *s = samplab_pixels_new(spec, 16, 9, 16, 8, 7, error, sizeof error);
    if (!s) {
        fprintf(stderr, "%s\n", error);
        return 2;
    }
    printf("# %s\n", samplab_pixels_spec(s));
    double four_out[4];
    for (uint32_t y = 0; y < 9; y += 4)
        for (uint32_t x = 0; x < 16; x += 5)
            for (uint32_t i = 0; i < 16; i += 3) {
                /* dimensions 4..7 inside the film, 6..9 reaching past it (padding) */
                double four[4], past[4];
                if (samplab_pixel_sample4(s, x, y, 1, i, 4, four) != 0) return 3;
                if (samplab_pixel_sample4(s, x, y, 1, i, 6, past) != 0) return 3;
                for (uint32_t d = 0; d < 10; ++d) {
                    double u = samplab_pixel_sample(s, x, y, 1, i, d);
                    if (d >= 4 && d < 8 && u != four[d - 4]) return 4;
                    if (d >= 6 && u != past[d - 6]) return 4;
                    if (!(u >= 0.0 && u < 1.0)) return 4;
                    printf("%u %u 1 %u %u %a\n", x, y, i, d, u);
                }
            }
    /* a pixel or an index outside the film: NaN (and -1), not a crash */
    if (!isnan(samplab_pixel_sample(s, 16, 0, 0, 0, 0)) || !isnan(samplab_pixel_sample(s, 0, 0, 0, 16, 8))) return 5;
    if (samplab_pixel_sample4(s, 0, 9, 0, 0, 0, four_out) != -1 || samplab_pixel_sample4(s, 0, 0, 0, 0, UINT32_MAX - 1, four_out) != -1) return 5;
    samplab_pixels_free(s);
    /* a bad spec: NULL and the library's one-line message */
    if (samplab_pixels_new("zsobol", 16, 9, 3, 8, 7, error, sizeof error) != NULL) return 6;
    printf("# error: %s\n", error);
    return 0;
}
