/* The counted backend (OIT_CAPTURE_COUNTED, capture.h): each batch the
 * counted capture's (capture_counted.h), its store the frame's output at
 * the end. */
#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_counted.h"

oit_status oit_capture_counted_batch(oit_capture *c, oit_counted *k,
                                     const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                     oit_error *err)
{
    oit_counted_frame f = oit_capture_counted_frame(c);
    /* the store budget bounds its fragment store; deep pixels are those
     * first-K's K slots would not hold */
    uint64_t budget = oit_capture_store_budget(c);
    k->budget = budget ? budget : UINT64_MAX;
    k->deep_over = (uint32_t)c->K;
    oit_status s = oit_counted_batch(k, &f, meshes, n, r, err);
    oit_capture_note_peak(c);
    oit_capture_bind_buffers(c);
    return s;
}

/* The whole frame in one band where the budget allows: each band is a pass
 * and a read-back of its own. */
oit_status oit_capture_store_out(oit_capture *c, GLuint *buf, uint64_t *cap, const char *name,
                                 uint64_t want, uint64_t row, oit_capture_out *out, oit_error *err)
{
    uint64_t budget = oit_capture_store_budget(c);
    if (budget && want > budget)
        want = budget > row ? budget : row;
    want = oit_capture_within_binding(c, want, row);
    oit_status s = oit_capture_reserve(c, buf, cap, want, name, err);
    *out = (oit_capture_out){*buf, *cap};
    return s;
}

static oit_status counted_create(oit_capture *c, int stencil_k, oit_error *err)
{
    return oit_counted_init(c->be, c->programs, err);
}

static void counted_destroy(void *be)
{
    oit_counted_release(be);
}

/* Fragments one store holds: the store budget where set, one binding. */
uint64_t oit_capture_counted_fit(const oit_capture *c)
{
    uint64_t budget = oit_capture_store_budget(c);
    budget = budget ? budget : UINT64_MAX;
    return (budget < c->frame.bind ? budget : c->frame.bind) / 16;
}

static oit_status counted_begin(oit_capture *c, oit_error *err)
{
    oit_counted_begin(c->be, c->set.no_wait, oit_capture_counted_fit(c));
    return OIT_OK;
}

static int counted_ended(oit_capture *c)
{
    return oit_counted_ended(c->be);
}

static void counted_uniforms(oit_capture *c)
{
    oit_counted *k = c->be;
    oit_glsl_set_view_all(k->prog, OIT_COUNTED_PROGS, &c->view);
    /* the opaque depth's projection replaces the view's */
    oit_glsl_set_opaque_all(k->prog, OIT_COUNTED_PROGS, &c->opaque);
}

static void counted_epsilon(oit_capture *c, float e)
{
    oit_glsl_set_epsilon_all(((oit_counted *)c->be)->prog, OIT_COUNTED_GEOMETRY_PROGS, e);
}

/* Nothing at OIT_BIND_OUT within the frame: its output passes through the
 * fragment store at the end. */
static void counted_bind(const oit_capture *c)
{
    oit_capture_bind_within(c, OIT_BIND_OUT, 0, 0);
}

/* No per-pixel limit: a batch of any number of layers is an ordinary one. */
static oit_status counted_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                const int rect[4], int layers, oit_error *err)
{
    int r[4] = {0}, empty = 1;
    oit_status s = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    return oit_capture_counted_batch(c, c->be, meshes, n, r, err);
}

static oit_status counted_end(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                              oit_error *err)
{
    oit_counted *k = c->be;
    return oit_capture_store_out(c, &k->frags, &k->frags_cap, "counted capture fragments", want,
                                 row, out, err);
}

static uint64_t counted_bytes(const void *be)
{
    return oit_counted_bytes(be);
}

static void counted_stats(const oit_capture *c, oit_frame_stats *stats)
{
    const oit_counted *k = c->be;
    stats->capture = c->ops->name;
    stats->batches += k->splits;
    stats->deep_pixels = k->deep_pixels;
    stats->predicted_batches = k->predicted_batches;
}

OIT_CAPTURE_OPS(counted, OIT_CAPTURE_COUNTED, "counted", oit_counted, NULL, NULL, counted_ended);
