/* The PNG half of the frame images (image.h): 8-bit sRGB PNG through libpng,
 * and the functions that pick PNG or PFM by a file's extension. Its own
 * library (oit_image_png), so that liboit, which writes no file, does not
 * link libpng: the tools and tests that read or write images link it. */
#include "view/render/image/image.h"

#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

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

/* ---- by extension ----------------------------------------------------- */

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
    return png ? read_png(name, f, img, err) : oit_image_read_pfm_stream(f, name, img, err);
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
