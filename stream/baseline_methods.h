/* The baseline renderers (render/unsorted.h, wboit.h, ppll.h, ppll4.h,
 * b3d.h, depth_peel.h, dual_peel.h, guarded.h, f2b.h) behind one handle, so
 * that the method table (render_methods.c) needs one field and one render
 * call for all of them. Requires a current GL context. */
#ifndef OIT_STREAM_BASELINE_METHODS_H
#define OIT_STREAM_BASELINE_METHODS_H

#include "render/gpu_mesh.h"

typedef enum oit_baseline_kind {
    OIT_BASELINE_UNSORTED,
    OIT_BASELINE_WBOIT,
    OIT_BASELINE_PLL,
    OIT_BASELINE_DEPTH_PEEL,
    OIT_BASELINE_PPLL4,
    OIT_BASELINE_B3D,
    OIT_BASELINE_DUAL_PEEL,
    OIT_BASELINE_GUARDED,
    OIT_BASELINE_F2B
} oit_baseline_kind;

typedef struct oit_baseline oit_baseline;

oit_status oit_baseline_create(oit_baseline_kind kind, oit_baseline **out, oit_error *err);
void oit_baseline_destroy(oit_baseline *b);

/* The threshold of the approximate methods: guarded's contribution
 * threshold, F2B's alpha threshold, in [0, 1). OIT_ERR_ARGUMENT for the
 * other kinds, which have none. */
oit_status oit_baseline_set_threshold(oit_baseline *b, float threshold, oit_error *err);

/* As oit_dfb_render without per-pixel counts. */
oit_status oit_baseline_render(oit_baseline *b, const oit_gpu_mesh *const *meshes, int n,
                               const oit_view *view, oit_image *out, oit_frame_stats *stats,
                               oit_error *err);

#endif
