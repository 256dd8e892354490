/* The method table (render_methods.h): the in-core DFB, the Embree
 * reference, and the two capture backends drawing the whole mesh as one
 * batch (which is where their overflow count means something), and the
 * baselines of stream/baseline_methods.h (unsorted, wboit, pll, dp, ppll4,
 * b3d, ddp, guarded, f2b). */
#include "stream/render_methods.h"

#include <embree3/rtcore_config.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/capture.h"
#include "stream/baseline_methods.h"
#include "render/dfb.h"
#include "render/gl_context.h"
#include "render/reference.h"

struct oit_method_state {
    const oit_mesh *mesh;
    oit_gl *gl;
    int gl_borrowed; /* gl is the caller's (oit_method_options.gl): not ours to destroy */
    oit_gpu_mesh *gpu;
    oit_dfb *dfb;
    oit_capture *cap;
    oit_baseline *baseline;
    oit_reference_desc ref;
    oit_streamer *streamer;
    oit_stream_frame_stats stream_stats;
};

static void close_state(oit_method_state *st)
{
    if (!st)
        return;
    /* GL objects go before the context that owns them. */
    if (st->streamer) oit_streamer_destroy(st->streamer);
    if (st->cap) oit_capture_destroy(st->cap);
    if (st->baseline) oit_baseline_destroy(st->baseline);
    if (st->dfb) oit_dfb_destroy(st->dfb);
    if (st->gpu) oit_gpu_mesh_destroy(st->gpu);
    if (st->gl && !st->gl_borrowed) oit_gl_destroy(st->gl);
    free(st);
}

/* The caller's context when it gives one (the viewer's window), else a
 * headless one of our own. */
static oit_status attach_gl(oit_method_state *st, const oit_method_options *opt, oit_error *err)
{
    if (opt && opt->gl) {
        st->gl = opt->gl;
        st->gl_borrowed = 1;
        return OIT_OK;
    }
    oit_gl_desc desc;
    memset(&desc, 0, sizeof desc);
    return oit_gl_create(&desc, &st->gl, err);
}

static oit_status new_state(const oit_mesh *mesh, const oit_method_options *opt, int with_gl,
                            oit_method_state **out, oit_error *err)
{
    oit_method_state *st = calloc(1, sizeof *st);
    if (!st)
        return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate renderer state");
    st->mesh = mesh;
    *out = st;
    if (!with_gl)
        return OIT_OK;
    oit_status s = attach_gl(st, opt, err);
    if (s == OIT_OK)
        s = oit_gpu_mesh_create(mesh->tris, mesh->count, 0, &st->gpu, err);
    if (s != OIT_OK) {
        close_state(st);
        *out = NULL;
    }
    return s;
}

static const char *gl_renderer(const oit_method_state *st)
{
    return oit_gl_renderer(st->gl);
}

/* ---- dfb ---- */

static oit_status dfb_open(const oit_mesh *mesh, const oit_method_options *opt,
                           oit_method_state **out, oit_error *err)
{
    oit_status s = new_state(mesh, opt, 1, out, err);
    if (s == OIT_OK && (s = oit_dfb_create(&(*out)->dfb, err)) != OIT_OK) {
        close_state(*out);
        *out = NULL;
    }
    return s;
}

static oit_status dfb_render(oit_method_state *st, const oit_view *view, oit_image *out,
                             uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                             oit_error *err)
{
    const oit_gpu_mesh *meshes[1] = {st->gpu};
    return oit_dfb_render(st->dfb, meshes, 1, view, out, counts, stats, err);
}

/* ---- capture backends ---- */

static oit_status capture_open(oit_capture_kind kind, const oit_mesh *mesh,
                               const oit_method_options *opt, oit_method_state **out,
                               oit_error *err)
{
    oit_status s = new_state(mesh, opt, 1, out, err);
    if (s == OIT_OK && (s = oit_capture_create(kind, opt->max_layers, &(*out)->cap, err)) != OIT_OK) {
        close_state(*out);
        *out = NULL;
    }
    return s;
}

static oit_status array_open(const oit_mesh *mesh, const oit_method_options *opt,
                             oit_method_state **out, oit_error *err)
{
    return capture_open(OIT_CAPTURE_ARRAY, mesh, opt, out, err);
}

static oit_status stencil_open(const oit_mesh *mesh, const oit_method_options *opt,
                               oit_method_state **out, oit_error *err)
{
    return capture_open(OIT_CAPTURE_STENCIL, mesh, opt, out, err);
}

static oit_status capture_render(oit_method_state *st, const oit_view *view, oit_image *out,
                                 uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                             oit_error *err)
{
    const oit_gpu_mesh *meshes[1] = {st->gpu};
    oit_status s = oit_capture_begin(st->cap, view, err);
    if (s == OIT_OK)
        s = oit_capture_batch(st->cap, meshes, 1, NULL, err);
    if (s == OIT_OK)
        s = oit_capture_end(st->cap, out, stats, err);
    return s;
}

/* ---- baselines ---- */

/* The approximate baselines take opt->epsilon as their threshold. */
static oit_status baseline_open(oit_baseline_kind kind, const oit_mesh *mesh,
                                const oit_method_options *opt, oit_method_state **out,
                                oit_error *err)
{
    int thresholded = kind == OIT_BASELINE_GUARDED || kind == OIT_BASELINE_F2B;
    oit_status s = new_state(mesh, opt, 1, out, err);
    if (s == OIT_OK)
        s = oit_baseline_create(kind, &(*out)->baseline, err);
    if (s == OIT_OK && thresholded && opt && opt->epsilon >= 0.0f)
        s = oit_baseline_set_threshold((*out)->baseline, opt->epsilon, err);
    if (s != OIT_OK && *out) {
        close_state(*out);
        *out = NULL;
    }
    return s;
}

static oit_status unsorted_open(const oit_mesh *mesh, const oit_method_options *opt,
                                oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_UNSORTED, mesh, opt, out, err);
}

static oit_status wboit_open(const oit_mesh *mesh, const oit_method_options *opt,
                             oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_WBOIT, mesh, opt, out, err);
}

static oit_status pll_open(const oit_mesh *mesh, const oit_method_options *opt,
                           oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_PLL, mesh, opt, out, err);
}

static oit_status dp_open(const oit_mesh *mesh, const oit_method_options *opt,
                          oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_DEPTH_PEEL, mesh, opt, out, err);
}

static oit_status ppll4_open(const oit_mesh *mesh, const oit_method_options *opt,
                             oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_PPLL4, mesh, opt, out, err);
}

static oit_status b3d_open(const oit_mesh *mesh, const oit_method_options *opt,
                           oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_B3D, mesh, opt, out, err);
}

static oit_status ddp_open(const oit_mesh *mesh, const oit_method_options *opt,
                           oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_DUAL_PEEL, mesh, opt, out, err);
}

static oit_status guarded_open(const oit_mesh *mesh, const oit_method_options *opt,
                               oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_GUARDED, mesh, opt, out, err);
}

static oit_status f2b_open(const oit_mesh *mesh, const oit_method_options *opt,
                           oit_method_state **out, oit_error *err)
{
    return baseline_open(OIT_BASELINE_F2B, mesh, opt, out, err);
}

static oit_status baseline_render(oit_method_state *st, const oit_view *view, oit_image *out,
                                  uint32_t *counts, uint8_t *ambiguous,
                                  oit_frame_stats *stats, oit_error *err)
{
    const oit_gpu_mesh *meshes[1] = {st->gpu};
    return oit_baseline_render(st->baseline, meshes, 1, view, out, stats, err);
}

/* ---- reference ---- */

static oit_status reference_open(const oit_mesh *mesh, const oit_method_options *opt,
                                 oit_method_state **out, oit_error *err)
{
    oit_status s = new_state(mesh, opt, 0, out, err);
    if (s == OIT_OK && opt) {
        (*out)->ref.ambiguity_px = opt->ambiguity_px;
        (*out)->ref.saturation_epsilon = opt->epsilon > 0.0f ? opt->epsilon : 0.0f;
    }
    return s;
}

static oit_status reference_render(oit_method_state *st, const oit_view *view, oit_image *out,
                                   uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                             oit_error *err)
{
    oit_reference_desc desc = st->ref;
    desc.ambiguous = ambiguous;
    return oit_reference_render(st->mesh, view, &desc, out, counts, stats, err);
}

static const char *reference_renderer(const oit_method_state *st)
{
    return "Embree " RTC_VERSION_STRING " (CPU reference)";
}

/* ---- stream: the part file through order, packs and the upload ring ---- */

static oit_status stream_open(const oit_mesh *mesh, const oit_method_options *opt,
                              oit_method_state **out, oit_error *err)
{
    if (!opt->partfile)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--method stream renders a part file "
                             "(.oitp, made by oitprep); convert the model first");
    oit_status s = new_state(mesh, opt, 0, out, err);
    if (s == OIT_OK)
        s = attach_gl(*out, opt, err);
    oit_streamer_desc sd = {.K = opt->max_layers, .capture = OIT_CAPTURE_ARRAY, .pack = opt->pack,
                            .schedule = opt->schedule,
                            .upload_budget = opt->upload_budget,
                            .slot_budget = opt->slot_budget,
                            .cache_budget = opt->cache_budget,
                            .read_inline = opt->read_inline,
                            .epsilon = opt->epsilon > 0.0f ? opt->epsilon : 0.0f};
    if (s == OIT_OK)
        s = oit_streamer_create(opt->partfile, &sd, &(*out)->streamer, err);
    if (s != OIT_OK && *out) {
        close_state(*out);
        *out = NULL;
    }
    return s;
}

static oit_status stream_render(oit_method_state *st, const oit_view *view, oit_image *out,
                                uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                                oit_error *err)
{
    return oit_streamer_render(st->streamer, view, out, stats, &st->stream_stats, err);
}

static const oit_stream_frame_stats *stream_figures(const oit_method_state *st)
{
    return &st->stream_stats;
}

static const oit_render_method methods[] = {
    {"dfb", 1, 1, 0, dfb_open, dfb_render, gl_renderer, close_state, 0, NULL, 0},
    {"reference", 0, 1, 1, reference_open, reference_render, reference_renderer, close_state, 0, NULL, 0},
    {"array", 1, 0, 0, array_open, capture_render, gl_renderer, close_state, 0, NULL, 0},
    {"stencil", 1, 0, 0, stencil_open, capture_render, gl_renderer, close_state, 0, NULL, 0},
    {"stream", 1, 0, 0, stream_open, stream_render, gl_renderer, close_state, 1, stream_figures, 1},
    {"unsorted", 1, 0, 0, unsorted_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"wboit", 1, 0, 0, wboit_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"pll", 1, 0, 0, pll_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"dp", 1, 0, 0, dp_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"ppll4", 1, 0, 0, ppll4_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"b3d", 1, 0, 0, b3d_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"ddp", 1, 0, 0, ddp_open, baseline_render, gl_renderer, close_state, 0, NULL, 0},
    {"guarded", 1, 0, 0, guarded_open, baseline_render, gl_renderer, close_state, 0, NULL, 1},
    {"f2b", 1, 0, 0, f2b_open, baseline_render, gl_renderer, close_state, 0, NULL, 1},
};

const oit_render_method *oit_render_method_find(const char *name)
{
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
        if (!strcmp(methods[i].name, name))
            return &methods[i];
    return NULL;
}

void oit_render_method_names(char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = 0;
    for (size_t i = 0; i < sizeof methods / sizeof methods[0] && used < cap; i++)
        used += (size_t)snprintf(buf + used, cap - used, "%s%s", i ? "|" : "", methods[i].name);
}
