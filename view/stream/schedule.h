/* Packs formed front to back across the screen (view/stream/pack.h,
 * OIT_RENDER_SCHEDULE_WAVE).
 *
 * The part order of partfile/order.h walks the management tree depth first:
 * everything on the near side of a plane comes before anything on the far
 * side, even where the two never share a pixel. Only parts whose screen
 * rectangles overlap need their relative order kept, since no ray meets two
 * parts that share no pixel. The scheduler keeps exactly those constraints
 * (through 32x32-pixel bins: two parts that share a pixel share its bin, and
 * the parts of a bin form a chain in the input order) and otherwise takes
 * the available part nearest the eye first, offering it to the open pack.
 * The result is again a visibility order along every ray, packs included:
 * a part joins a pack only after every part it must follow has been placed
 * in that pack or an earlier one.
 *
 * Per call O((E + packs * OIT_SCHEDULE_MISSES) log n) for n parts touching E
 * bins in all; no O(n^2) work. */
#ifndef OIT_STREAM_SCHEDULE_H
#define OIT_STREAM_SCHEDULE_H

#include <stdint.h>

#include "oit/status.h"

typedef struct oit_scheduler oit_scheduler;

/* max_parts: the most parts one call schedules. */
oit_status oit_scheduler_create(uint32_t max_parts, oit_scheduler **out, oit_error *err);
void oit_scheduler_destroy(oit_scheduler *s);

/* Packs formed while scheduling. open starts a new, empty pack; join adds
 * input part i to the open pack and returns 1, or returns 0 when it does not
 * fit (per-pixel layers, bytes). join must accept any part into an empty
 * pack. A part joins only once every part that must precede it has been
 * emitted into this or an earlier pack: within a pack the capture sorts
 * fragments per pixel, so the order there does not matter. */
typedef struct oit_schedule_packer {
    void *ctx;
    void (*open)(void *ctx);
    int (*join)(void *ctx, uint32_t i);
} oit_schedule_packer;

/* Misses in a row after which an open pack is closed. */
#define OIT_SCHEDULE_MISSES 32u

/* rects[i] (x0, y0, x1, y1, exclusive, inside width x height) and near[i]
 * (the nearest depth of part i's box, the priority) describe input part i;
 * the input order 0..n-1 must be a visibility order. perm[k] receives the
 * input index of the k-th part to draw (perm may be NULL when the packer's
 * joins are all the caller needs); with a packer, each pack's parts are
 * consecutive in perm. Ties in near go to the earlier input, so the
 * result is deterministic. */
oit_status oit_schedule_run(oit_scheduler *s, uint32_t n, const int (*rects)[4],
                            const float *near, int width, int height,
                            const oit_schedule_packer *packer, uint32_t *perm, oit_error *err);

#endif
