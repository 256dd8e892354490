/* Saturated screen tiles, for early termination that skips whole parts
 * (Wang & Xie's per-pixel rule raised to parts, issue 6).
 *
 * Per 16x16-pixel tile the grid holds the largest transmittance, over the
 * tile's pixels and the three channels, that the frame's state buffer
 * carries. A part whose screen rectangle touches only tiles below epsilon
 * would have every fragment dropped by the capture's per-pixel epsilon test
 * (capture.h), so it can be neither uploaded nor drawn: the image is the
 * same bit for bit, the work and the upload are saved.
 *
 * The grid is recomputed on the GPU under each batch's rectangle and read
 * back asynchronously (a copy into a persistently mapped buffer behind a
 * fence; one in flight at a time). Transmittance only falls within a frame,
 * so the newest read-back that has landed is a safe upper bound: a late one
 * skips fewer parts, never a visible one. Nothing ever waits on the GPU.
 * Requires a current GL context for its whole life. */
#ifndef OIT_RENDER_SATURATION_H
#define OIT_RENDER_SATURATION_H

#include "view/render/gl/gl_util.h"
#include "view/render/gl/glsl_program.h"
#include "view/render/gl/host_wait.h"

#define OIT_SATURATION_TILE 16

typedef struct oit_saturation oit_saturation;

oit_status oit_saturation_create(oit_saturation **out, oit_error *err);
void oit_saturation_destroy(oit_saturation *s);
/* Its program, for the offline check (glsl_program.h). */
void oit_saturation_glsl_variants(oit_glsl_visit *visit, void *user);

/* Starts a frame of w x h pixels, in the shading whose state layout the
 * capture's buffer has (translucent or not: frag_glsl.h): no tile saturated. */
oit_status oit_saturation_begin(oit_saturation *s, int w, int h, int translucent,
                                oit_error *err);
/* After a batch was composited into state (the capture's state buffer of
 * w*h pixels, GL rows bottom first): recomputes the tiles under rect ({x0, y0, x1, y1}, row 0 at
 * the top, exclusive ends) and starts a read-back when none is in flight. */
oit_status oit_saturation_update(oit_saturation *s, unsigned state, const int rect[4],
                                 oit_error *err);
/* Blocks until the read-back in flight, if any, has landed, so that the
 * next oit_saturation_covered sees every batch updated so far. For a few
 * large batches a frame, where a late read-back would let a whole batch of
 * hidden parts through; with many small ones, the wait for the GPU to
 * drain would cost more than it saves. */
oit_status oit_saturation_wait(oit_saturation *s, oit_host_waits *waits, oit_error *err);
/* 1 when, in the newest read-back, every tile rect touches has a largest
 * transmittance below epsilon; 0 otherwise (and always for epsilon <= 0). */
int oit_saturation_covered(oit_saturation *s, const int rect[4], float epsilon);
/* GPU bytes held. */
uint64_t oit_saturation_gpu_bytes(const oit_saturation *s);

#endif
