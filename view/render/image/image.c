/* Frame images: the pixels, PFM by hand, comparison figures and the layer
 * heat map; PNG (libpng) is image_png.c's, so that what links only this
 * (liboit) does not need libpng. Readers trust nothing in a header: sizes
 * are checked against the file before anything is allocated from them. */
#include "view/render/image/image.h"
#include "view/render/image/shade.h"
#include "base/args.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

oit_status oit_image_alloc(oit_image *img, int width, int height, oit_error *err)
{
    img->width = img->height = 0;
    img->rgba = NULL;
    if (width <= 0 || height <= 0 || width > OIT_IMAGE_MAX_SIDE || height > OIT_IMAGE_MAX_SIDE)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "image size %dx%d out of range (1..%d)",
                             width, height, OIT_IMAGE_MAX_SIDE);
    size_t n = (size_t)width * (size_t)height * 4;
    img->rgba = calloc(n, sizeof(float));
    if (!img->rgba)
        return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate a %dx%d image (%zu bytes)",
                             width, height, n * sizeof(float));
    img->width = width;
    img->height = height;
    return OIT_OK;
}

oit_status oit_image_reserve(oit_image *img, int width, int height, int *made, oit_error *err)
{
    *made = !(img->rgba && img->width == width && img->height == height);
    return *made ? oit_image_alloc(img, width, height, err) : OIT_OK;
}

void oit_image_free(oit_image *img)
{
    if (!img)
        return;
    free(img->rgba);
    img->rgba = NULL;
    img->width = img->height = 0;
}

static int file_size(FILE *f, long long *size)
{
    struct stat st;
    if (fstat(fileno(f), &st) != 0)
        return 0;
    *size = (long long)st.st_size;
    return 1;
}
/* ---- PFM -------------------------------------------------------------- */

/* PFM holds linear light (image.h): images are sRGB-encoded in memory, so
 * the writer decodes and the reader encodes, odd-symmetric so that any
 * finite value survives the round trip to float rounding. */
static float pfm_to_linear(float v)
{
    return v < 0.0f ? -(float)oit_srgb_decode(-(double)v) : (float)oit_srgb_decode(v);
}

static float pfm_to_encoded(float v)
{
    return v < 0.0f ? -(float)oit_srgb_encode(-(double)v) : (float)oit_srgb_encode(v);
}

oit_status oit_image_write_pfm(const oit_image *img, const char *path, oit_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open for writing", path);
    fprintf(f, "PF\n%d %d\n-1.0\n", img->width, img->height);
    float *row = malloc((size_t)img->width * 3 * sizeof(float));
    if (!row) {
        fclose(f);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate a row", path);
    }
    int ok = 1;
    /* PFM stores rows bottom first; floats are written little-endian, which
     * is the host order on every platform we build for. */
    for (int y = img->height - 1; ok && y >= 0; y--) {
        const float *src = img->rgba + (size_t)y * img->width * 4;
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++)
                row[(size_t)x * 3 + c] = pfm_to_linear(src[(size_t)x * 4 + c]);
        ok = fwrite(row, sizeof(float) * 3, (size_t)img->width, f) == (size_t)img->width;
    }
    free(row);
    if (fclose(f) != 0 || !ok)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed (disk full?)", path);
    return OIT_OK;
}

static uint32_t swap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

/* Reads one whitespace-delimited header token; PFM allows any whitespace
 * between the three header fields but exactly one after the scale. */
static int pfm_token(FILE *f, char *buf, size_t cap)
{
    int ch;
    do
        ch = fgetc(f);
    while (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r');
    size_t n = 0;
    while (ch != EOF && ch != ' ' && ch != '\t' && ch != '\n' && ch != '\r') {
        if (n + 1 >= cap)
            return 0;
        buf[n++] = (char)ch;
        ch = fgetc(f);
    }
    buf[n] = 0;
    return n > 0 && ch != EOF;
}

oit_status oit_image_read_pfm_stream(FILE *f, const char *path, oit_image *img, oit_error *err)
{
    img->width = img->height = 0;
    img->rgba = NULL;
    char magic[8], ws[24], hs[24], ss[48];
    int wi, hi;
    if (!pfm_token(f, magic, sizeof magic) || (strcmp(magic, "PF") && strcmp(magic, "Pf")))
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: not a PFM file (magic)", path);
    if (!pfm_token(f, ws, sizeof ws) || !pfm_token(f, hs, sizeof hs) ||
        oit_parse_int(ws, 1, OIT_IMAGE_MAX_SIDE, &wi) ||
        oit_parse_int(hs, 1, OIT_IMAGE_MAX_SIDE, &hi))
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: bad PFM size", path);
    long w = wi, h = hi;
    if (!pfm_token(f, ss, sizeof ss))
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: bad PFM scale", path);
    double scale;
    if (oit_parse_double(ss, -DBL_MAX, DBL_MAX, &scale) || scale == 0.0)
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: bad PFM scale '%s'", path, ss);
    int channels = magic[1] == 'F' ? 3 : 1;
    int big_endian = scale > 0.0;
    long long header = ftell(f), bytes = 0;
    size_t need = (size_t)w * (size_t)h * (size_t)channels * sizeof(float);
    if (header < 0 || !file_size(f, &bytes))
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot stat", path);
    if ((unsigned long long)(bytes - header) < need)
        return oit_error_set(err, OIT_ERR_FORMAT,
                             "%s: truncated PFM: %ldx%ld needs %zu data bytes, file has %lld",
                             path, w, h, need, bytes - header);
    oit_status s = oit_image_alloc(img, (int)w, (int)h, err);
    if (s != OIT_OK) {
        oit_error_prefix(err, path);
        return s;
    }
    uint32_t px[3];
    for (long y = h - 1; y >= 0; y--)
        for (long x = 0; x < w; x++) {
            if (fread(px, sizeof(uint32_t), (size_t)channels, f) != (size_t)channels) {
                oit_image_free(img);
                return oit_error_set(err, OIT_ERR_IO, "%s: read failed at row %ld", path,
                                     h - 1 - y);
            }
            float *dst = img->rgba + ((size_t)y * (size_t)w + (size_t)x) * 4;
            for (int c = 0; c < 3; c++) {
                uint32_t bits = px[channels == 3 ? c : 0];
                if (big_endian)
                    bits = swap32(bits);
                memcpy(&dst[c], &bits, sizeof bits);
                dst[c] = pfm_to_encoded(dst[c]);
            }
            dst[3] = 1.0f;
        }
    return OIT_OK;
}
/* ---- comparison ------------------------------------------------------- */

/* 8-bit round trips differ by up to half a level; this margin keeps a value
 * that is exactly one level off (1/255 up to float rounding) from counting. */
#define OIT_OVER_EPS 1e-6

oit_status oit_image_compare(const oit_image *a, const oit_image *b,
                             oit_image_diff *d, oit_image *diff_img, float gain,
                             oit_error *err)
{
    memset(d, 0, sizeof *d);
    if (a->width != b->width || a->height != b->height)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "image sizes differ: %dx%d vs %dx%d",
                             a->width, a->height, b->width, b->height);
    if (a->width <= 0 || a->height <= 0 || !a->rgba || !b->rgba)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "cannot compare empty images");
    if (diff_img) {
        oit_status s = oit_image_alloc(diff_img, a->width, a->height, err);
        if (s != OIT_OK)
            return s;
    }
    size_t n = (size_t)a->width * (size_t)a->height;
    double sum2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        int over = 0;
        for (int c = 0; c < 3; c++) {
            double e = fabs((double)a->rgba[i * 4 + c] - (double)b->rgba[i * 4 + c]);
            if (!(e <= 1e30)) /* NaN or inf in either image: maximal error */
                e = 1e30;
            sum2 += e * e;
            if (e > d->max_abs)
                d->max_abs = e;
            over |= e > 1.0 / 255.0 + OIT_OVER_EPS;
            if (diff_img)
                diff_img->rgba[i * 4 + c] = (float)fmin(1.0, e * gain);
        }
        if (diff_img)
            diff_img->rgba[i * 4 + 3] = 1.0f;
        d->pixels_over += (uint64_t)over;
    }
    double mse = sum2 / (3.0 * (double)n);
    d->rmse = sqrt(mse);
    d->psnr = mse > 0.0 ? 10.0 * log10(1.0 / mse) : INFINITY;
    d->pct_over_1_255 = 100.0 * (double)d->pixels_over / (double)n;
    return OIT_OK;
}

/* ---- heat map --------------------------------------------------------- */

/* Turbo (Mikhailov 2019), polynomial fit by the same author: perceptually
 * ordered, and its dark-blue low end stays distinct from the black used for
 * pixels without any fragment. */
static void turbo(double t, float rgb[3])
{
    t = fmin(1.0, fmax(0.0, t));
    static const double k[3][6] = {
        {0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943},
        {0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604},
        {0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973},
    };
    for (int c = 0; c < 3; c++) {
        double v = k[c][5];
        for (int i = 4; i >= 0; i--)
            v = v * t + k[c][i];
        rgb[c] = (float)fmin(1.0, fmax(0.0, v));
    }
}

/* Turbo's darkest tenth is kept out of the ramp so that one layer never
 * reads as the black of an empty pixel. */
static void layer_colour(double t, float rgb[3])
{
    turbo(0.1 + 0.9 * t, rgb);
}

/* 3x5 digits, one row per 3-bit group, most significant bit on the left. */
static const unsigned char digit_font[10][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7},
};

/* Legend geometry in font pixels; the whole legend scales with the image
 * so that labels stay readable on large frames. */
#define LEGEND_ROWS 16
#define LEGEND_MARGIN 2
#define LEGEND_BAR_ROWS 6
#define DIGIT_ADVANCE 4

static int legend_scale(int width, int height)
{
    int s = (width < height ? width : height) / 200;
    return s < 1 ? 1 : s;
}

static void fill_rect(oit_image *img, int x, int y, int w, int h, const float rgb[3])
{
    for (int j = y < 0 ? 0 : y; j < y + h && j < img->height; j++)
        for (int i = x < 0 ? 0 : x; i < x + w && i < img->width; i++) {
            float *p = img->rgba + ((size_t)j * img->width + i) * 4;
            memcpy(p, rgb, 3 * sizeof(float));
            p[3] = 1.0f;
        }
}

static void draw_number(oit_image *img, unsigned value, int cx, int top, int scale)
{
    char text[16];
    int len = snprintf(text, sizeof text, "%u", value);
    int w = (len * DIGIT_ADVANCE - 1) * scale;
    int x0 = cx - w / 2;
    if (x0 + w > img->width - scale) x0 = img->width - scale - w;
    if (x0 < scale) x0 = scale;
    static const float white[3] = {1, 1, 1};
    for (int i = 0; i < len; i++)
        for (int r = 0; r < 5; r++)
            for (int b = 0; b < 3; b++)
                if (digit_font[text[i] - '0'][r] & (4 >> b))
                    fill_rect(img, x0 + (i * DIGIT_ADVANCE + b) * scale, top + r * scale, scale,
                              scale, white);
}

/* The legend occupies the bottom LEGEND_ROWS * scale rows: a ramp bar from 1
 * to max layers and labels under its ends and middle. */
static void draw_legend(oit_image *img, uint32_t max_count, int scale)
{
    int top = img->height - LEGEND_ROWS * scale, margin = LEGEND_MARGIN * scale;
    static const float panel[3] = {0.12f, 0.12f, 0.12f};
    fill_rect(img, 0, top, img->width, LEGEND_ROWS * scale, panel);
    int x0 = margin, x1 = img->width - margin; /* bar [x0, x1) */
    for (int x = x0; x < x1; x++) {
        float rgb[3];
        layer_colour((double)(x - x0) / (double)(x1 - x0 - 1 > 0 ? x1 - x0 - 1 : 1), rgb);
        fill_rect(img, x, top + margin, 1, LEGEND_BAR_ROWS * scale, rgb);
    }
    int label_top = top + margin + (LEGEND_BAR_ROWS + 2) * scale;
    draw_number(img, max_count > 0 ? 1 : 0, x0, label_top, scale);
    if (max_count > 2) {
        /* The middle label sits where its own value falls on the bar. */
        uint32_t mid = (1 + max_count) / 2;
        int x = x0 + (int)lround((double)(mid - 1) / (double)(max_count - 1) * (x1 - x0 - 1));
        draw_number(img, mid, x, label_top, scale);
    }
    draw_number(img, max_count, x1 - 1, label_top, scale);
}

oit_status oit_image_heatmap(const uint32_t *counts, int width, int height,
                             oit_image *out, oit_error *err)
{
    oit_status s = oit_image_alloc(out, width, height, err);
    if (s != OIT_OK)
        return s;
    size_t n = (size_t)width * (size_t)height;
    uint32_t max_count = 0;
    for (size_t i = 0; i < n; i++)
        if (counts[i] > max_count)
            max_count = counts[i];
    for (size_t i = 0; i < n; i++) {
        float rgb[3] = {0, 0, 0};
        /* 1 layer maps to the low end, max to the high end. */
        if (counts[i] > 0)
            layer_colour(max_count > 1 ? (double)(counts[i] - 1) / (double)(max_count - 1) : 1.0, rgb);
        memcpy(out->rgba + i * 4, rgb, sizeof rgb);
        out->rgba[i * 4 + 3] = 1.0f;
    }
    /* Too small an image keeps its pixels: a legend would cover all of it. */
    int scale = legend_scale(width, height);
    if (height >= 2 * LEGEND_ROWS * scale && width >= 24 * scale)
        draw_legend(out, max_count, scale);
    return OIT_OK;
}

void oit_image_put_rgb(oit_image *img, int x, int y, const float rgb[3])
{
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return;
    float *p = img->rgba + 4 * ((size_t)y * (size_t)img->width + (size_t)x);
    p[0] = rgb[0];
    p[1] = rgb[1];
    p[2] = rgb[2];
    p[3] = 1.0f;
}
