/* png_figures FILE.png: prints "WIDTH HEIGHT NON_WHITE COLOURS" (pixels that
 * are not white, distinct 8-bit colours up to 4096), so shell tests can
 * tell a drawn chart from a blank or truncated one. Exit 3 when the file
 * does not read as an image. */
#include <stdio.h>
#include <stdlib.h>

#include "render/image.h"

enum { MAX_COLOURS = 4096 };

static unsigned pack(const float *p)
{
    unsigned v = 0;
    for (int c = 0; c < 3; c++) {
        float x = p[c] < 0.0f ? 0.0f : p[c] > 1.0f ? 1.0f : p[c];
        v = v << 8 | (unsigned)(x * 255.0f + 0.5f);
    }
    return v;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: png_figures FILE.png\n");
        return 2;
    }
    oit_image img;
    oit_error err;
    if (oit_image_read(argv[1], &img, &err) != OIT_OK) {
        fprintf(stderr, "png_figures: %s\n", err.message);
        return 3;
    }
    static unsigned seen[MAX_COLOURS];
    size_t non_white = 0, colours = 0;
    for (size_t i = 0; i < (size_t)img.width * (size_t)img.height; i++) {
        unsigned v = pack(img.rgba + 4 * i);
        non_white += v != 0xffffffu;
        size_t k = 0;
        while (k < colours && seen[k] != v)
            k++;
        if (k == colours && colours < MAX_COLOURS)
            seen[colours++] = v;
    }
    printf("%d %d %zu %zu\n", img.width, img.height, non_white, colours);
    oit_image_free(&img);
    return 0;
}
