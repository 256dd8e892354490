/* Frame images: PNG through libpng, PFM by hand, comparison figures and the
 * layer heat map. Readers trust nothing in a header: sizes are checked
 * against the file before anything is allocated from them. */
#include "render/image.h"
#include "render/shade.h"
#include "base/args.h"

#include <float.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* Large enough for any frame we render, small enough that width*height*4
 * floats cannot overflow size_t arithmetic on a 64-bit host. */
#define OIT_IMAGE_MAX_SIDE 65536

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

void oit_image_free(oit_image *img)
{
    if (!img)
        return;
    free(img->rgba);
    img->rgba = NULL;
    img->width = img->height = 0;
}

static int has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n >= e && strcasecmp(path + n - e, ext) == 0;
}

static int file_size(FILE *f, long long *size)
{
    struct stat st;
    if (fstat(fileno(f), &st) != 0)
        return 0;
    *size = (long long)st.st_size;
    return 1;
}

/* ---- PNG -------------------------------------------------------------- */

/* libpng reports errors through a callback that must not return; we keep
 * its message and longjmp back to the call that owns the png struct. */
typedef struct png_ctx {
    jmp_buf jmp;
    char message[256];
} png_ctx;

static void png_on_error(png_structp png, png_const_charp msg)
{
    png_ctx *ctx = png_get_error_ptr(png);
    snprintf(ctx->message, sizeof ctx->message, "%s", msg);
    longjmp(ctx->jmp, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings (e.g. a bad iCCP profile) do not affect pixels */
}

static unsigned char to_byte(float v)
{
    if (!(v > 0.0f)) return 0; /* also NaN */
    if (v >= 1.0f) return 255;
    return (unsigned char)lrintf(v * 255.0f);
}

oit_status oit_image_write_png(const oit_image *img, const char *path, oit_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open for writing", path);
    png_ctx ctx = {0};
    unsigned char *volatile row = malloc((size_t)img->width * 3);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, png_on_error,
                                              png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!row || !png || !info) {
        png_destroy_write_struct(&png, &info);
        free(row);
        fclose(f);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate PNG writer", path);
    }
    if (setjmp(ctx.jmp)) {
        png_destroy_write_struct(&png, &info);
        free(row);
        fclose(f);
        return oit_error_set(err, OIT_ERR_IO, "%s: PNG write failed: %s", path, ctx.message);
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < img->height; y++) {
        const float *src = img->rgba + (size_t)y * img->width * 4;
        for (int x = 0; x < img->width; x++)
            for (int c = 0; c < 3; c++)
                row[(size_t)x * 3 + c] = to_byte(src[(size_t)x * 4 + c]);
        png_write_row(png, row);
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    free(row);
    if (fclose(f) != 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed (disk full?)", path);
    return OIT_OK;
}

/* Deflate cannot expand data by more than about 1032:1, so a header that
 * promises more pixel bytes than that is lying (or a bomb); refusing it
 * keeps a tiny bogus file from triggering a huge allocation. */
/* zlib inflates at most 1032:1, so a file that holds its rows (the file's own
 * row bytes, as its IHDR declares them, and a filter byte each) is at least
 * that much smaller: a mostly black 8-bit mask compresses far beyond what a
 * 16-bit RGBA row count would allow. */
static int png_size_plausible(png_uint_32 w, png_uint_32 h, size_t row_bytes, long long file_bytes)
{
    double raw = ((double)row_bytes + 1.0) * (double)h;
    return w <= OIT_IMAGE_MAX_SIDE && h <= OIT_IMAGE_MAX_SIDE &&
           raw <= 1032.0 * (double)file_bytes + 65536.0;
}

static void png_row_to_float(const unsigned char *row, int width, int bit16, float *dst)
{
    for (int x = 0; x < width * 4; x++)
        dst[x] = bit16 ? (float)((row[2 * x] << 8 | row[2 * x + 1]) / 65535.0)
                       : (float)(row[x] / 255.0);
}

static oit_status read_png(const char *path, FILE *f, oit_image *img, oit_error *err)
{
    long long bytes = 0;
    if (!file_size(f, &bytes))
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot stat", path);
    png_ctx ctx = {0};
    png_bytep *volatile rows = NULL;
    unsigned char *volatile pixels = NULL;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, png_on_error,
                                             png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_read_struct(&png, &info, NULL);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate PNG reader", path);
    }
    if (setjmp(ctx.jmp)) {
        png_destroy_read_struct(&png, &info, NULL);
        free(rows);
        free(pixels);
        oit_image_free(img);
        return oit_error_set(err, OIT_ERR_FORMAT, "%s: bad PNG: %s", path, ctx.message);
    }
    png_init_io(png, f);
    png_read_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if (!png_size_plausible(w, h, png_get_rowbytes(png, info), bytes))
        png_error(png, "image size does not fit the file");
    int bit16 = png_get_bit_depth(png, info) == 16;
    /* Everything becomes RGBA of the file's depth (8 or 16). */
    png_set_expand(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, bit16 ? 0xffff : 0xff, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    size_t stride = png_get_rowbytes(png, info);
    if (stride != (size_t)w * (bit16 ? 8 : 4))
        png_error(png, "unexpected row layout after expansion");
    pixels = malloc(stride * h);
    rows = malloc(sizeof(png_bytep) * h);
    if (!pixels || !rows)
        png_error(png, "out of memory");
    for (png_uint_32 y = 0; y < h; y++)
        rows[y] = pixels + stride * y;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    oit_status s = oit_image_alloc(img, (int)w, (int)h, err);
    for (png_uint_32 y = 0; s == OIT_OK && y < h; y++)
        png_row_to_float(rows[y], (int)w, bit16, img->rgba + (size_t)y * w * 4);
    png_destroy_read_struct(&png, &info, NULL);
    free(rows);
    free(pixels);
    if (s != OIT_OK)
        oit_error_prefix(err, path);
    return s;
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

static oit_status read_pfm(const char *path, FILE *f, oit_image *img, oit_error *err)
{
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

oit_status oit_image_read(const char *path, oit_image *img, oit_error *err)
{
    img->width = img->height = 0;
    img->rgba = NULL;
    int png = has_ext(path, ".png");
    if (!png && !has_ext(path, ".pfm"))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: unknown image type (want .png or .pfm)",
                             path);
    FILE *f = fopen(path, "rb");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open", path);
    oit_status s = oit_image_read_stream(f, path, png, img, err);
    fclose(f);
    return s;
}

oit_status oit_image_read_stream(FILE *f, const char *name, int png, oit_image *img,
                                 oit_error *err)
{
    img->width = img->height = 0;
    img->rgba = NULL;
    return png ? read_png(name, f, img, err) : read_pfm(name, f, img, err);
}

oit_status oit_image_write(const oit_image *img, const char *path, oit_error *err)
{
    if (has_ext(path, ".png"))
        return oit_image_write_png(img, path, err);
    if (has_ext(path, ".pfm"))
        return oit_image_write_pfm(img, path, err);
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: unknown image type (want .png or .pfm)",
                         path);
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
