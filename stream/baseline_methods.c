/* One handle over the baselines (baseline_methods.h). */
#include "stream/baseline_methods.h"

#include <stdlib.h>

#include "render/b3d.h"
#include "render/depth_peel.h"
#include "render/dual_peel.h"
#include "render/f2b.h"
#include "render/guarded.h"
#include "render/ppll.h"
#include "render/ppll4.h"
#include "render/unsorted.h"
#include "render/wboit.h"

struct oit_baseline {
    oit_baseline_kind kind;
    union {
        oit_unsorted *unsorted;
        oit_wboit *wboit;
        oit_pll *pll;
        oit_depth_peel *dp;
        oit_ppll4 *ppll4;
        oit_b3d *b3d;
        oit_dual_peel *ddp;
        oit_guarded *guarded;
        oit_f2b *f2b;
    } m;
};

static oit_status create_kind(oit_baseline *b, oit_error *err)
{
    switch (b->kind) {
    case OIT_BASELINE_UNSORTED: return oit_unsorted_create(&b->m.unsorted, err);
    case OIT_BASELINE_WBOIT: return oit_wboit_create(&b->m.wboit, err);
    case OIT_BASELINE_PLL: return oit_pll_create(&b->m.pll, err);
    case OIT_BASELINE_DEPTH_PEEL: return oit_depth_peel_create(&b->m.dp, err);
    case OIT_BASELINE_PPLL4: return oit_ppll4_create(&b->m.ppll4, err);
    case OIT_BASELINE_B3D: return oit_b3d_create(&b->m.b3d, err);
    case OIT_BASELINE_DUAL_PEEL: return oit_dual_peel_create(&b->m.ddp, err);
    case OIT_BASELINE_GUARDED: return oit_guarded_create(&b->m.guarded, err);
    case OIT_BASELINE_F2B: return oit_f2b_create(&b->m.f2b, err);
    }
    return oit_error_set(err, OIT_ERR_ARGUMENT, "baseline method: unknown kind %d",
                         (int)b->kind);
}

oit_status oit_baseline_create(oit_baseline_kind kind, oit_baseline **out, oit_error *err)
{
    *out = NULL;
    oit_baseline *b = calloc(1, sizeof *b);
    if (!b)
        return oit_error_set(err, OIT_ERR_NOMEM, "baseline method: out of memory");
    b->kind = kind;
    oit_status s = create_kind(b, err);
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
    case OIT_BASELINE_PPLL4: oit_ppll4_destroy(b->m.ppll4); break;
    case OIT_BASELINE_B3D: oit_b3d_destroy(b->m.b3d); break;
    case OIT_BASELINE_DUAL_PEEL: oit_dual_peel_destroy(b->m.ddp); break;
    case OIT_BASELINE_GUARDED: oit_guarded_destroy(b->m.guarded); break;
    case OIT_BASELINE_F2B: oit_f2b_destroy(b->m.f2b); break;
    }
    free(b);
}

oit_status oit_baseline_set_threshold(oit_baseline *b, float threshold, oit_error *err)
{
    if (b->kind == OIT_BASELINE_GUARDED)
        return oit_guarded_set_threshold(b->m.guarded, threshold, err);
    if (b->kind == OIT_BASELINE_F2B)
        return oit_f2b_set_threshold(b->m.f2b, threshold, err);
    return oit_error_set(err, OIT_ERR_ARGUMENT, "baseline method: kind %d has no threshold",
                         (int)b->kind);
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
    case OIT_BASELINE_PPLL4:
        return oit_ppll4_render(b->m.ppll4, meshes, n, view, out, stats, err);
    case OIT_BASELINE_B3D:
        return oit_b3d_render(b->m.b3d, meshes, n, view, out, stats, err);
    case OIT_BASELINE_DUAL_PEEL:
        return oit_dual_peel_render(b->m.ddp, meshes, n, view, out, stats, err);
    case OIT_BASELINE_GUARDED:
        return oit_guarded_render(b->m.guarded, meshes, n, view, out, stats, err);
    case OIT_BASELINE_F2B:
        return oit_f2b_render(b->m.f2b, meshes, n, view, out, stats, err);
    }
    return oit_error_set(err, OIT_ERR_ARGUMENT, "baseline method: unknown kind %d",
                         (int)b->kind);
}
