/* image.h: PNG/PFM round trips, a 16-bit grey PNG, comparison figures on
 * images with known differences, the heat map and its legend, and truncated
 * or lying files that must fail with the file's name. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/image.h"
#include "view/render/image/shade.h"
#include "tests/lib/test_check.h"


static char tmpdir[512];

static const char *tmp_path(const char *name)
{
    static char buf[8][640];
    static int slot;
    char *p = buf[slot++ % 8];
    snprintf(p, 640, "%s/test_image_%s", tmpdir, name);
    return p;
}

static float *px(const oit_image *img, int x, int y)
{
    return img->rgba + ((size_t)y * img->width + x) * 4;
}

static void fill_pattern(oit_image *img)
{
    uint32_t s = 12345;
    for (size_t i = 0; i < (size_t)img->width * img->height * 4; i++) {
        s = s * 1664525u + 1013904223u;
        img->rgba[i] = (float)((s >> 8) & 0xffff) / 65535.0f * 1.2f - 0.1f; /* some out of [0,1] */
    }
}

/* A w x h image of fill_pattern in a, written to name in the scratch
 * folder and read back into b (free both); returns the file's path. */
static const char *round_trip(int w, int h, const char *name, oit_image *a, oit_image *b)
{
    oit_error err;
    CHECK(oit_image_alloc(a, w, h, &err) == OIT_OK, "%s", err.message);
    fill_pattern(a);
    const char *path = tmp_path(name);
    CHECK(oit_image_write(a, path, &err) == OIT_OK, "%s", err.message);
    *b = (oit_image){0};
    CHECK(oit_image_read(path, b, &err) == OIT_OK, "%s", err.message);
    CHECK(b->width == w && b->height == h, "%s: size %dx%d", name, b->width, b->height);
    return path;
}

static void test_png_round_trip(void)
{
    oit_image a, b;
    round_trip(37, 21, "rt.png", &a, &b);
    double worst = 0;
    for (int y = 0; y < a.height; y++)
        for (int x = 0; x < a.width; x++)
            for (int c = 0; c < 3; c++) {
                double want = fmin(1.0, fmax(0.0, px(&a, x, y)[c]));
                worst = fmax(worst, fabs(px(&b, x, y)[c] - want));
            }
    printf("png round trip: max error %.6f (limit %.6f)\n", worst, 0.5 / 255.0);
    CHECK(worst <= 0.5 / 255.0 + 1e-6, "png error %g", worst);
    oit_image_free(&a);
    oit_image_free(&b);
}

static void test_pfm_round_trip(void)
{
    oit_image a, b;
    oit_error err;
    const char *path = round_trip(13, 7, "rt.pfm", &a, &b);
    /* The file holds linear light (image.h): the reader encodes it back to
     * within float rounding, and to the same 8-bit value exactly. */
    int mismatches = 0, byte_mismatches = 0;
    double worst = 0.0;
    for (int y = 0; y < a.height && b.rgba; y++)
        for (int x = 0; x < a.width; x++)
            for (int c = 0; c < 3; c++) {
                float va = px(&a, x, y)[c], vb = px(&b, x, y)[c];
                double e = fabs((double)va - vb);
                worst = e > worst ? e : worst;
                mismatches += !(e <= 1e-6);
                byte_mismatches += lrintf(fminf(fmaxf(va, 0.f), 1.f) * 255.f) !=
                                   lrintf(fminf(fmaxf(vb, 0.f), 1.f) * 255.f);
            }
    printf("pfm round trip: %d values off by > 1e-6 (max %.3g), %d 8-bit values changed\n",
           mismatches, worst, byte_mismatches);
    CHECK(b.rgba && mismatches == 0 && byte_mismatches == 0, "pfm round trip not exact");
    /* Bottom row first on disk: the first float stored is pixel (0, h-1). */
    FILE *f = fopen(path, "rb");
    char hdr[32];
    float first = 0;
    CHECK(f && fgets(hdr, sizeof hdr, f) && fgets(hdr, sizeof hdr, f) && fgets(hdr, sizeof hdr, f) &&
              fread(&first, sizeof first, 1, f) == 1,
          "cannot read back %s", path);
    if (f) fclose(f);
    /* Encoded 0.5 is 0.2140 in linear light (the exact EOTF, not 0.5^2.2). */
    oit_image g;
    CHECK(oit_image_alloc(&g, 1, 1, &err) == OIT_OK, "%s", err.message);
    g.rgba[0] = g.rgba[1] = g.rgba[2] = 0.5f, g.rgba[3] = 1.0f;
    const char *gp = tmp_path("grey.pfm");
    float lin[3] = {0};
    CHECK(oit_image_write(&g, gp, &err) == OIT_OK, "%s", err.message);
    FILE *gf = fopen(gp, "rb");
    CHECK(gf && fgets(hdr, sizeof hdr, gf) && fgets(hdr, sizeof hdr, gf) &&
              fgets(hdr, sizeof hdr, gf) && fread(lin, sizeof lin, 1, gf) == 1,
          "cannot read back %s", gp);
    if (gf) fclose(gf);
    printf("pfm of sRGB 0.5 grey: %.6f %.6f %.6f linear\n", lin[0], lin[1], lin[2]);
    CHECK(fabsf(lin[0] - 0.2140411f) < 1e-6f && lin[1] == lin[0] && lin[2] == lin[0],
          "pfm of 0.5 grey holds %.7f, want linear 0.2140411", lin[0]);
    oit_image_free(&g);
    float v0 = px(&a, 0, a.height - 1)[0];
    float want = v0 < 0.0f ? -(float)oit_srgb_decode(-(double)v0) : (float)oit_srgb_decode(v0);
    CHECK(first == want, "pfm row order and linear light: first float %.9g, want %.9g "
          "(decoded from %.9g)", first, want, px(&a, 0, a.height - 1)[0]);
    oit_image_free(&a);
    oit_image_free(&b);
}

static void test_png16_gray(void)
{
    const char *path = tmp_path("gray16.png");
    FILE *f = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, 3, 1, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    unsigned char row[6] = {0x00, 0x00, 0x80, 0x01, 0xff, 0xff}; /* big-endian samples */
    png_write_row(png, row);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    fclose(f);
    oit_image img;
    oit_error err;
    CHECK(oit_image_read(path, &img, &err) == OIT_OK, "%s", err.message);
    if (!img.rgba)
        return;
    printf("16-bit grey: %.6f %.6f %.6f\n", px(&img, 0, 0)[0], px(&img, 1, 0)[1], px(&img, 2, 0)[2]);
    CHECK(px(&img, 0, 0)[0] == 0.0f && px(&img, 2, 0)[2] == 1.0f, "grey ends");
    CHECK(fabs(px(&img, 1, 0)[1] - 0x8001 / 65535.0) < 1e-7, "16-bit precision kept");
    CHECK(px(&img, 1, 0)[3] == 1.0f, "opaque alpha added");
    oit_image_free(&img);
}

static void test_compare(void)
{
    oit_image a, b, diff;
    oit_error err;
    oit_image_alloc(&a, 10, 10, &err);
    oit_image_alloc(&b, 10, 10, &err);
    oit_image_diff d;
    CHECK(oit_image_compare(&a, &b, &d, NULL, 1, &err) == OIT_OK, "%s", err.message);
    CHECK(d.rmse == 0 && isinf(d.psnr) && d.pixels_over == 0, "identical images");

    px(&b, 3, 4)[0] = 0.5f;        /* one clearly wrong pixel   */
    px(&b, 7, 1)[1] = 1.0f / 255;  /* exactly one level: not over */
    px(&b, 8, 8)[2] = 1.5f / 255;  /* 1.5 levels: over          */
    CHECK(oit_image_compare(&a, &b, &d, &diff, 2.0f, &err) == OIT_OK, "%s", err.message);
    double mse = (0.25 + pow(1.0 / 255, 2) + pow(1.5 / 255, 2)) / 300.0;
    printf("compare: rmse %.6g max_abs %.6g pct_over %.3f psnr %.3f (want %.6g 0.5 2.000 %.3f)\n",
           d.rmse, d.max_abs, d.pct_over_1_255, d.psnr, sqrt(mse), 10 * log10(1 / mse));
    CHECK(fabs(d.rmse - sqrt(mse)) < 1e-7, "rmse");
    CHECK(fabs(d.max_abs - 0.5) < 1e-7, "max_abs");
    CHECK(d.pixels_over == 2 && fabs(d.pct_over_1_255 - 2.0) < 1e-9, "over %llu",
          (unsigned long long)d.pixels_over);
    CHECK(fabs(d.psnr - 10 * log10(1 / mse)) < 1e-6, "psnr");
    CHECK(px(&diff, 3, 4)[0] == 1.0f && fabs(px(&diff, 7, 1)[1] - 2.0 / 255) < 1e-7 &&
              px(&diff, 0, 0)[0] == 0.0f,
          "diff image scaled by gain and clamped");
    oit_image_free(&diff);

    oit_image c;
    oit_image_alloc(&c, 10, 11, &err);
    CHECK(oit_image_compare(&a, &c, &d, NULL, 1, &err) == OIT_ERR_ARGUMENT, "size mismatch accepted");
    oit_image_free(&a);
    oit_image_free(&b);
    oit_image_free(&c);
}

static int same_rgb(const float *a, const float *b)
{
    return fabsf(a[0] - b[0]) < 1e-6f && fabsf(a[1] - b[1]) < 1e-6f && fabsf(a[2] - b[2]) < 1e-6f;
}

static void test_heatmap(void)
{
    enum { W = 64, H = 64 };
    static uint32_t counts[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            counts[y * W + x] = (uint32_t)(x / 8); /* 0..7 layers in columns */
    counts[5 * W + 60] = 12;                      /* the maximum */
    oit_image img;
    oit_error err;
    CHECK(oit_image_heatmap(counts, W, H, &img, &err) == OIT_OK, "%s", err.message);
    if (!img.rgba)
        return;
    const float *zero = px(&img, 2, 2), *one = px(&img, 10, 2), *two = px(&img, 18, 2),
                *max = px(&img, 60, 5);
    printf("heatmap: 0 -> %.2f %.2f %.2f, 1 -> %.2f %.2f %.2f, 12 -> %.2f %.2f %.2f\n", zero[0],
           zero[1], zero[2], one[0], one[1], one[2], max[0], max[1], max[2]);
    CHECK(zero[0] == 0 && zero[1] == 0 && zero[2] == 0, "0 layers must be black");
    CHECK(!same_rgb(one, zero) && !same_rgb(one, two) && !same_rgb(one, max), "distinct levels");
    /* The legend bar (bottom rows) runs from the 1-layer to the max colour. */
    int bar_found = 0, white = 0;
    for (int y = H - 20; y < H; y++) {
        bar_found |= same_rgb(px(&img, 2, y), one) && same_rgb(px(&img, W - 3, y), max);
        for (int x = 0; x < W; x++)
            white += same_rgb(px(&img, x, y), (const float[3]){1, 1, 1});
    }
    printf("legend: bar %s, %d white label pixels\n", bar_found ? "found" : "MISSING", white);
    CHECK(bar_found, "legend bar missing");
    CHECK(white >= 20, "legend labels missing (%d white pixels)", white);
    oit_image_free(&img);
}

static void truncate_copy(const char *src, const char *dst, long keep)
{
    FILE *in = fopen(src, "rb"), *out = fopen(dst, "wb");
    for (long i = 0; i < keep; i++) {
        int ch = fgetc(in);
        if (ch == EOF) break;
        fputc(ch, out);
    }
    fclose(in);
    fclose(out);
}

static void expect_fail(const char *path, const char *what)
{
    oit_image img;
    oit_error err = {0};
    oit_status s = oit_image_read(path, &img, &err);
    printf("%s: status %s, \"%s\"\n", what, oit_status_name(s), err.message);
    CHECK(s != OIT_OK, "%s accepted", what);
    CHECK(strstr(err.message, path) != NULL, "%s: message does not name the file", what);
    CHECK(img.rgba == NULL, "%s: image left allocated", what);
}

static void test_bad_files(void)
{
    oit_image a;
    oit_error err;
    oit_image_alloc(&a, 64, 64, &err);
    fill_pattern(&a);
    const char *png = tmp_path("full.png"), *pfm = tmp_path("full.pfm");
    oit_image_write(&a, png, &err);
    oit_image_write(&a, pfm, &err);
    oit_image_free(&a);
    const char *tpng = tmp_path("trunc.png"), *tpfm = tmp_path("trunc.pfm");
    truncate_copy(png, tpng, 200);
    truncate_copy(pfm, tpfm, 1000);
    expect_fail(tpng, "truncated png");
    expect_fail(tpfm, "truncated pfm");

    const char *lie = tmp_path("lie.pfm");
    FILE *f = fopen(lie, "wb");
    fputs("PF\n60000 60000\n-1.0\n0123456789abcdef", f);
    fclose(f);
    expect_fail(lie, "pfm header larger than the file");
    expect_fail(tmp_path("missing.pfm"), "missing file");
}

int main(void)
{
    const char *t = getenv("OIT_TEST_TMP");
    snprintf(tmpdir, sizeof tmpdir, "%s", t && *t ? t : "/tmp");
    test_png_round_trip();
    test_pfm_round_trip();
    test_png16_gray();
    test_compare();
    test_heatmap();
    test_bad_files();
    return test_verdict();
}
