/* One handle over the four baselines (baseline_methods.h). */
#include "stream/baseline_methods.h"

#include <stdlib.h>

#include "render/depth_peel.h"
#include "render/ppll.h"
#include "render/unsorted.h"
#include "render/wboit.h"

struct oit_baseline {
    oit_baseline_kind kind;
    union {
        oit_unsorted *unsorted;
        oit_wboit *wboit;
        oit_pll *pll;
        oit_depth_peel *dp;
    } m;
};

oit_status oit_baseline_create(oit_baseline_kind kind, oit_baseline **out, oit_error *err)
{
    *out = NULL;
    oit_baseline *b = calloc(1, sizeof *b);
    if (!b)
        return oit_error_set(err, OIT_ERR_NOMEM, "baseline method: out of memory");
    b->kind = kind;
    oit_status s;
    switch (kind) {
    case OIT_BASELINE_UNSORTED: s = oit_unsorted_create(&b->m.unsorted, err); break;
    case OIT_BASELINE_WBOIT: s = oit_wboit_create(&b->m.wboit, err); break;
    case OIT_BASELINE_PLL: s = oit_pll_create(&b->m.pll, err); break;
    case OIT_BASELINE_DEPTH_PEEL: s = oit_depth_peel_create(&b->m.dp, err); break;
    default: s = oit_error_set(err, OIT_ERR_ARGUMENT, "baseline method: unknown kind %d",
                               (int)kind);
    }
    if (s != OIT_OK) {
        free(b);
        return s;
    }
    *out = b;
    return OIT_OK;
}

void oit_baseline_destroy(oit_baseline *b)
{
    if (!b)
        return;
    switch (b->kind) {
    case OIT_BASELINE_UNSORTED: oit_unsorted_destroy(b->m.unsorted); break;
    case OIT_BASELINE_WBOIT: oit_wboit_destroy(b->m.wboit); break;
    case OIT_BASELINE_PLL: oit_pll_destroy(b->m.pll); break;
    case OIT_BASELINE_DEPTH_PEEL: oit_depth_peel_destroy(b->m.dp); break;
    }
    free(b);
}

oit_status oit_baseline_render(oit_baseline *b, const oit_gpu_mesh *const *meshes, int n,
                               const oit_view *view, oit_image *out, oit_frame_stats *stats,
                               oit_error *err)
{
    switch (b->kind) {
    case OIT_BASELINE_UNSORTED:
        return oit_unsorted_render(b->m.unsorted, meshes, n, view, out, stats, err);
    case OIT_BASELINE_WBOIT:
        return oit_wboit_render(b->m.wboit, meshes, n, view, out, stats, err);
    case OIT_BASELINE_PLL:
        return oit_pll_render(b->m.pll, meshes, n, view, out, stats, err);
    case OIT_BASELINE_DEPTH_PEEL:
        return oit_depth_peel_render(b->m.dp, meshes, n, view, out, stats, err);
    }
    return oit_error_set(err, OIT_ERR_ARGUMENT, "baseline method: unknown kind %d",
                         (int)b->kind);
}
