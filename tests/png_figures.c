/* png_figures FILE.png: prints "WIDTH HEIGHT NON_WHITE COLOURS" (pixels that
 * are not white, distinct 8-bit colours up to 4096), so shell tests can
 * tell a drawn chart from a blank or truncated one.
 * png_figures --red-blue IMAGE [MASK]: prints "RED BLUE": pixels where red
 * exceeds blue by more than 0.1, and the other way round, leaving out the
 * mask's non-black pixels (the decal test: which colour is in front).
 * Exit 3 when a file does not read as an image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

static int red_blue(const char *path, const char *mask_path)
{
    oit_image img, mask = {0};
    oit_error err;
    if (oit_image_read(path, &img, &err) != OIT_OK ||
        (mask_path && oit_image_read(mask_path, &mask, &err) != OIT_OK)) {
        fprintf(stderr, "png_figures: %s\n", err.message);
        return 3;
    }
    if (mask_path && (mask.width != img.width || mask.height != img.height)) {
        fprintf(stderr, "png_figures: %s is %dx%d, %s %dx%d\n", mask_path, mask.width,
                mask.height, path, img.width, img.height);
        return 3;
    }
    size_t red = 0, blue = 0;
    for (size_t i = 0; i < (size_t)img.width * (size_t)img.height; i++) {
        const float *p = img.rgba + 4 * i;
        if (mask_path && mask.rgba[4 * i] + mask.rgba[4 * i + 1] + mask.rgba[4 * i + 2] > 0.0f)
            continue;
        red += p[0] > p[2] + 0.1f;
        blue += p[2] > p[0] + 0.1f;
    }
    printf("%zu %zu\n", red, blue);
    oit_image_free(&img);
    oit_image_free(&mask);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 3 && argc <= 4 && !strcmp(argv[1], "--red-blue"))
        return red_blue(argv[2], argc == 4 ? argv[3] : NULL);
    if (argc != 2) {
        fprintf(stderr, "usage: png_figures FILE.png | --red-blue IMAGE [MASK]\n");
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
