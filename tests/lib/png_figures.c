/* png_figures FILE.png: prints "WIDTH HEIGHT NON_WHITE COLOURS" (pixels that
 * are not white, distinct 8-bit colours up to 4096), so shell tests can
 * tell a drawn chart from a blank or truncated one.
 * png_figures --red-blue IMAGE [MASK]: prints "RED BLUE": pixels where red
 * exceeds blue by more than 0.1, and the other way round, leaving out the
 * mask's non-black pixels (the decal test: which colour is in front).
 * png_figures --pfm-linear FILE.pfm FILE.png (one frame written both ways):
 * the PFM's raw floats are linear light (image.h): each, encoded with the
 * exact sRGB OETF and rounded as the PNG writer rounds, must give the PNG's
 * byte, and so must the PFM read back through oit_image_read; and where the
 * PNG holds mid-tones the raw floats must differ from them (a PFM that held
 * the encoded values would pass the first checks). Prints "VALUES
 * RAW_MISMATCH READ_MISMATCH MIDTONES APART"; exit 1 on a mismatch.
 * Exit 3 when a file does not read as an image. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/image.h"
#include "view/render/image/shade.h"

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

static long to_byte(double v)
{
    return v <= 0.0 ? 0 : v >= 1.0 ? 255 : lrintf((float)v * 255.0f);
}

static int pfm_linear(const char *pfm, const char *png)
{
    oit_image img = {0}, back = {0};
    oit_error err;
    if (oit_image_read(png, &img, &err) != OIT_OK || oit_image_read(pfm, &back, &err) != OIT_OK) {
        fprintf(stderr, "png_figures: %s\n", err.message);
        return 3;
    }
    FILE *f = fopen(pfm, "rb");
    int w = 0, h = 0;
    char scale[32];
    if (!f || fscanf(f, "PF %d %d %31s", &w, &h, scale) != 3 || fgetc(f) != '\n' ||
        w != img.width || h != img.height || back.width != w || back.height != h ||
        strtod(scale, NULL) >= 0.0) {
        fprintf(stderr, "png_figures: %s: not a little-endian PFM of %s's size\n", pfm, png);
        if (f) fclose(f);
        return 3;
    }
    size_t n = (size_t)w * h * 3, raw_bad = 0, read_bad = 0, mid = 0, apart = 0;
    float *raw = malloc(n * sizeof *raw);
    if (!raw || fread(raw, sizeof *raw, n, f) != n) {
        fprintf(stderr, "png_figures: %s: short read\n", pfm);
        fclose(f);
        free(raw);
        return 3;
    }
    fclose(f);
    for (int y = 0; y < h; y++) /* PFM rows bottom first */
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                float lin = raw[((size_t)(h - 1 - y) * w + x) * 3 + c];
                size_t i = ((size_t)y * w + x) * 4 + c;
                long want = to_byte(img.rgba[i]);
                raw_bad += to_byte(oit_srgb_encode(lin)) != want;
                read_bad += to_byte(back.rgba[i]) != want;
                if (img.rgba[i] > 0.05f && img.rgba[i] < 0.95f) {
                    mid++;
                    apart += fabsf(lin - img.rgba[i]) > 0.01f;
                }
            }
    printf("%zu %zu %zu %zu %zu\n", n, raw_bad, read_bad, mid, apart);
    free(raw);
    oit_image_free(&img);
    oit_image_free(&back);
    return raw_bad == 0 && read_bad == 0 && (mid == 0 || apart * 2 > mid) ? 0 : 1;
}

int main(int argc, char **argv)
{
    if (argc >= 3 && argc <= 4 && !strcmp(argv[1], "--red-blue"))
        return red_blue(argv[2], argc == 4 ? argv[3] : NULL);
    if (argc == 4 && !strcmp(argv[1], "--pfm-linear"))
        return pfm_linear(argv[2], argv[3]);
    if (argc != 2) {
        fprintf(stderr, "usage: png_figures FILE.png | --red-blue IMAGE [MASK] | "
                        "--pfm-linear FILE.pfm FILE.png\n");
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
