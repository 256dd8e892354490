/* Parts wholly behind the caller's opaque depth (frag_glsl.h,
 * oit_opaque_depth), for the stream to skip as it skips saturated ones
 * (saturation.h): the capture would drop every fragment of such a part
 * (oit_behind_opaque), so it need be neither uploaded nor drawn.
 *
 * At a frame's begin, the largest depth of each 16x16-pixel tile of the
 * view is computed on the GPU from the depth texture bound at unit
 * OIT_TEX_OPAQUE_DEPTH and read back (the frame's one wait: on the
 * caller's opaque pass). A part is behind when the nearest window depth of
 * its bounding box, under the camera's view and the caller's projection,
 * exceeds the largest depth of every tile its screen rectangle touches by
 * a margin (OIT_OPAQUE_MARGIN) that covers the rounding of the GPU's own
 * depth. Conservative: a part with any fragment in front is never
 * skipped. Requires a current GL context for its whole life. */
#ifndef OIT_RENDER_OPAQUE_TILES_H
#define OIT_RENDER_OPAQUE_TILES_H

#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/host_wait.h"
#include "view/render/image/view.h"

#define OIT_OPAQUE_TILE 16
#define OIT_OPAQUE_MARGIN 1e-5

typedef struct oit_opaque_tiles oit_opaque_tiles;

oit_status oit_opaque_tiles_create(oit_opaque_tiles **out, oit_error *err);
void oit_opaque_tiles_destroy(oit_opaque_tiles *t);
/* Its program, for the offline check (glsl_program.h). */
void oit_opaque_tiles_glsl_variants(oit_glsl_visit *visit, void *user);
/* Starts a frame of view's size: with o enabled, reads the tiles of the
 * texture bound at unit OIT_TEX_OPAQUE_DEPTH (texel of pixel (0, 0) at
 * o->origin); else nothing is behind. Needs no buffer bindings of the
 * caller (it uses OIT_BIND_OPAQUE_TILES and leaves it bound). The
 * read-back is a wait counted on waits (host_wait.h). */
oit_status oit_opaque_tiles_begin(oit_opaque_tiles *t, const oit_view *view,
                                  const oit_opaque_depth *o, oit_host_waits *waits,
                                  oit_error *err);
/* 1 when the box [bmin, bmax] on screen rectangle rect ({x0, y0, x1, y1},
 * row 0 at the top, exclusive ends, as the packer's part rectangles) lies
 * behind the opaque depth everywhere; 0 otherwise and without one. */
int oit_opaque_tiles_behind(const oit_opaque_tiles *t, const float bmin[3], const float bmax[3],
                            const int rect[4]);
uint64_t oit_opaque_tiles_gpu_bytes(const oit_opaque_tiles *t);

#endif
