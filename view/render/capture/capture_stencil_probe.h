/* What the stencil-routed capture (capture_stencil.h) trusts a driver with,
 * decided without GL so that tests can feed it what a driver might answer:
 *  - the sample mode: K samples of the target must be K true multisamples
 *    (a driver may serve "16 samples" as 8 multisamples x 2 supersamples,
 *    GL_NV_internalformat_sample_query, and then shades each pixel twice);
 *  - the self-test's probe: a tiny scene of triangles that cover parts of
 *    pixels, whose every pixel centre's covering triangles are known, and
 *    the verdict over what the fill wrote there (each fragment counted once,
 *    each in its own sample, none from a triangle missing the centre). */
#ifndef OIT_RENDER_CAPTURE_STENCIL_PROBE_H
#define OIT_RENDER_CAPTURE_STENCIL_PROBE_H

#include <stdint.h>

#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the sample mode ------------------------------------------------------ */

/* What a driver says of one sample count of one format
 * (glGetInternalformatSampleivNV): samples = multisamples x scale_x x
 * scale_y, the rest supersampled. */
typedef struct oit_sample_mode {
    int samples, multisamples, scale_x, scale_y, conformant;
} oit_sample_mode;

enum { OIT_SAMPLE_MODES_MAX = 16 };

/* The sample counts one format supports for a multisample target, in any
 * order, each with its mode. */
typedef struct oit_sample_modes {
    const char *what; /* "GL_RGBA32UI texture", named in messages */
    int n;
    oit_sample_mode mode[OIT_SAMPLE_MODES_MAX];
} oit_sample_modes;

/* The sample count the target gets for K (the smallest supported count >=
 * K of both the colour and the depth-stencil format, as GL allocates) in
 * *samples, when that count is K true multisamples of both. Otherwise
 * OIT_ERR_UNSUPPORTED with the numbers: what K samples are here, and the
 * largest K that is a true multisample count of both (none: < 2). */
oit_status oit_stencil_pick_samples(int K, const oit_sample_modes *colour,
                                    const oit_sample_modes *depth_stencil, int *samples,
                                    oit_error *err);

/* ---- the self-test's probe ------------------------------------------------ */

/* A pixel's sample that no fragment wrote: the probe clears every sample's
 * primitive field (bits 0-30 of the fragment's .y) to it first. */
#define OIT_STENCIL_UNWRITTEN 0x7fffffffu

enum { OIT_PROBE_ROWS = 2, OIT_PROBE_MAX_COLS = 2 * 16 + 1 };

/* K triangles (prims 0..K-1, drawn in that order at distinct depths) over a
 * (2K + 1) x 2 frame, one window unit a pixel (orthographic): triangle q
 * covers the centres of columns K - q .. 2K - 1 - q in row 0 (one more
 * column in row 1), so the middle column gets K fragments, the others
 * fewer down to none, and the sets differ from column to column. Every
 * edge crosses pixels without reaching a centre (>= 0.14 pixel): each
 * covers part of the pixels it crosses, and the coverage of a centre does
 * not hang on the tie rule. */
typedef struct oit_stencil_probe {
    int K, width, height;
    oit_triangle tris[16];
    /* GL rows (bottom first), x + y * width: bit q set when triangle q
     * covers the pixel centre, as single-sample rasterization decides */
    uint32_t cover[OIT_PROBE_MAX_COLS * OIT_PROBE_ROWS];
    oit_view view;
} oit_stencil_probe;

/* K in [2, 16]. */
void oit_stencil_probe_build(oit_stencil_probe *p, int K);

/* The verdict on one fill of the probe: counts[pixel] is what the fill
 * shader counted there, prims[pixel * K + i] the primitive sample i holds
 * (OIT_STENCIL_UNWRITTEN where none). OIT_OK when every pixel counted each
 * covering triangle once and its first samples hold each of them once;
 * else OIT_ERR_UNSUPPORTED naming the first pixel (GL rows) and what is
 * wrong: a count off (the fill shader ran more or less than once a pixel a
 * triangle), a sample never written (a fragment lost), one holding a
 * triangle that does not cover the centre, or a triangle twice. */
oit_status oit_stencil_probe_verdict(const oit_stencil_probe *p, const uint32_t *prims,
                                     const uint32_t *counts, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
