/* Frame images on disk and their comparison: 8-bit sRGB PNG for looking,
 * PFM (float) for measuring error, a layer heat map, and the error figures
 * every test and benchmark prints. Two libraries: oit_image (image.c: the
 * pixels, PFM, comparison, heat map; no dependency) and oit_image_png
 * (image_png.c: PNG through libpng and the by-extension read and write). */
#ifndef OIT_RENDER_IMAGE_H
#define OIT_RENDER_IMAGE_H

#include <stdint.h>
#include <stdio.h>

#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Large enough for any frame we render, small enough that width*height*4
 * floats cannot overflow size_t arithmetic on a 64-bit host. */
#define OIT_IMAGE_MAX_SIDE 65536

oit_status oit_image_alloc(oit_image *img, int width, int height, oit_error *err);
void oit_image_free(oit_image *img);
/* img as a width x height image for a renderer to write every pixel of:
 * kept where it is one already (a caller's own buffer, written in place:
 * no second image and copy a frame), else allocated (img empty, {0});
 * *made: 1 when allocated here, so the renderer frees it on a failure and
 * never frees a kept one. */
oit_status oit_image_reserve(oit_image *img, int width, int height, int *made, oit_error *err);

/* Sets pixel (x, y), row 0 at the top, to opaque rgb; outside: nothing. */
void oit_image_put_rgb(oit_image *img, int x, int y, const float rgb[3]);
/* PFM: little-endian RGB float ("PF", negative scale), bottom row first as
 * the format requires, holding LINEAR light: an oit_image is sRGB-encoded
 * (view.h) in both colour spaces, so the writer decodes each colour with the
 * exact sRGB EOTF (oit_srgb_decode, view/render/image/shade.h; odd-symmetric for
 * negative values) and the reader encodes it back. So every image in
 * memory, and every comparison (oit_image_compare, the tools' comparisons,
 * PNG against PFM alike), is in the sRGB-encoded space, where the 1/255
 * figures are 8-bit steps; a round trip returns each value to float
 * rounding (a few 1e-8), and its 8-bit encoding exactly. */
oit_status oit_image_write_pfm(const oit_image *img, const char *path, oit_error *err);
/* Reads a PFM ("PF" or grey "Pf", either byte order) from an open, seekable
 * stream; name is used in messages. */
oit_status oit_image_read_pfm_stream(FILE *f, const char *name, oit_image *img, oit_error *err);

/* ---- PNG and by extension: library oit_image_png (view/render/image/image_png.c) ----
 * Only what links oit_image_png may call these: it is the one that needs
 * libpng, and liboit does not link it. */

/* PNG: 8-bit RGB, values clamped to [0,1] and rounded, tagged sRGB. */
oit_status oit_image_write_png(const oit_image *img, const char *path, oit_error *err);
/* Reads .png (8- or 16-bit, gray/RGB/RGBA) or .pfm (linear light, encoded
 * on reading: above), chosen by extension. */
oit_status oit_image_read(const char *path, oit_image *img, oit_error *err);
/* The same from an open, seekable stream (fmemopen for bytes in memory);
 * png selects the format, name is used in messages. */
oit_status oit_image_read_stream(FILE *f, const char *name, int png, oit_image *img,
                                 oit_error *err);
/* Writes .png or .pfm by extension. */
oit_status oit_image_write(const oit_image *img, const char *path, oit_error *err);

/* ---- comparison and heat map (oit_image) ---- */

typedef struct oit_image_diff {
    double rmse;            /* over rgb channels, values in [0,1]          */
    double max_abs;         /* largest per-channel difference              */
    double pct_over_1_255;  /* % of pixels with any channel off by > 1/255 */
    double psnr;            /* dB; INFINITY for identical images           */
    uint64_t pixels_over;   /* count behind pct_over_1_255                 */
} oit_image_diff;

/* Compares rgb of two images of equal size. When diff_img is non-NULL it is
 * allocated and filled with |a - b| scaled by 'gain' (clamped). */
oit_status oit_image_compare(const oit_image *a, const oit_image *b,
                             oit_image_diff *d, oit_image *diff_img, float gain,
                             oit_error *err);

/* Heat map of fragments per pixel (counts: width*height, row 0 at the top),
 * with a legend bar and its scale drawn into the image's bottom rows. */
oit_status oit_image_heatmap(const uint32_t *counts, int width, int height,
                             oit_image *out, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
