/* The first-K backend (OIT_CAPTURE_FIRSTK, capture.h): the first-K capture
 * (capture_firstk.h) of each pack, or the counted capture's
 * (capture_counted.h) where fewer than 2 slots a pixel fit the budget or
 * first-K is switched off; its pass 1 routed by the stencil where
 * oit_capture_desc.stencil_k asked for it. */
#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_firstk.h"

typedef struct firstk_backend {
    oit_firstk k;
    /* the packs too wide for 2 slots a pixel, and every pack while off;
     * built on first use (most one-image runs never need it) */
    oit_counted counted;
    int counted_ready;
    int off; /* capturing as the counted backend (oit_capture_set_first_k) */
    /* pass 1 routed by the stencil (c->routed_k > 0): the target and its
     * fill, the stencil fill built for pass 1 */
    oit_stencil_target target;
    GLuint fill;
    /* Pass 1's counts kept for the counted capture to predict the next
     * frame by (oit_counted_predict) in this frame, at its pack `packs`
     * (oit_capture_settings.no_counts); the last frame's view. */
    int predict;
    size_t packs;
    uint64_t last_view;
} firstk_backend;

/* Pass 1 through the stencil target (oit_capture_desc.stencil_k). */
static oit_status firstk_route(oit_capture *c, firstk_backend *b, int stencil_k, oit_error *err)
{
    oit_status s = oit_capture_route_init(c, &b->target, stencil_k, err);
    if (s == OIT_OK) {
        const oit_glsl_program fill = oit_capture_routed_fill(1, b->target.by_copy);
        s = oit_glsl_programs_build(c->programs, &fill, 1, &b->fill, err);
    }
    if (s != OIT_OK)
        return s;
    c->routed_k = stencil_k;
    return oit_capture_stencil_self_test(c, &b->target, b->fill, err);
}

static void firstk_uniforms(oit_capture *c);
static void firstk_epsilon(oit_capture *c, float e);

/* Programs built mid-frame get the frame's uniforms. */
static void reapply(void *ctx)
{
    oit_capture *c = ctx;
    firstk_uniforms(c);
    firstk_epsilon(c, c->frame.applied);
}

/* The route and its self-test first: a driver that refuses them costs
 * this try no more than theirs (oit_capture_choose tries fewer samples). */
static oit_status firstk_create(oit_capture *c, int stencil_k, oit_error *err)
{
    firstk_backend *b = c->be;
    oit_status s = stencil_k ? firstk_route(c, b, stencil_k, err) : OIT_OK;
    if (s == OIT_OK)
        s = oit_firstk_init(&b->k, c->K, c->programs, reapply, c, err);
    if (s == OIT_OK && stencil_k)
        oit_firstk_route(&b->k, &b->target, b->fill);
    return s;
}

/* The counted capture, built the first time a batch needs it, with this
 * frame's uniforms. */
static oit_status counted_ready(oit_capture *c, firstk_backend *b, oit_error *err)
{
    if (b->counted_ready)
        return OIT_OK;
    oit_status s = oit_counted_init(&b->counted, c->programs, err);
    if (s != OIT_OK)
        return s;
    b->counted_ready = 1;
    reapply(c);
    return OIT_OK;
}

static void firstk_destroy(void *be)
{
    firstk_backend *b = be;
    oit_counted_release(&b->counted);
    oit_firstk_release(&b->k);
    if (b->target.fbo)
        oit_stencil_target_release(&b->target);
    oit_glsl_programs_delete(&b->fill, 1);
}

static oit_status firstk_begin(oit_capture *c, oit_error *err)
{
    firstk_backend *b = c->be;
    /* built mid-frame where it is first needed: then on the host */
    if (b->counted_ready)
        oit_counted_begin(&b->counted, c->set.no_wait, oit_capture_counted_fit(c));
    b->k.second_pixels = 0;
    b->k.second_packs = b->k.second_draws = 0;
    /* pass 2 on the GPU while the store the host would split it by (the
     * store budget, or what the store holds; one binding) holds what a pack
     * needed; from the first frame on, in the store the slots take: a
     * first frame on the host and the next on the GPU paid pass 2's
     * programs, draws and buffers twice, the second time in the frame a
     * still view's user sees next (head.stl at 128x128: 94 ms against
     * 60 warm) */
    uint64_t room = oit_capture_store_budget(c) ? oit_capture_store_budget(c) : c->frame.bind;
    room = room > b->k.store_cap ? room : b->k.store_cap;
    room = room < c->frame.bind ? room : c->frame.bind;
    b->k.ahead = c->set.no_wait && (!b->k.measured || b->k.need * 16 <= room);
    /* the stencil self-test's frames run before oit_firstk_init (the route
     * is tried first): there is no first-K state to begin yet */
    if (b->k.totals)
        oit_firstk_begin(&b->k);
    /* A still view's next frame may go counted (auto's try), which then
     * draws once where it would count and store: the first frame of a view
     * keeps its counts where the caller asks (oit_capture_settings.no_counts),
     * the others pay nothing. */
    uint64_t view = c->frame.view_key;
    b->predict = c->set.no_wait && !c->set.no_counts && view != b->last_view;
    b->last_view = view;
    b->packs = 0;
    if (!b->fill)
        return OIT_OK;
    return oit_stencil_target_resize(&b->target, c->view.width, c->view.height, err);
}

static void firstk_uniforms(oit_capture *c)
{
    firstk_backend *b = c->be;
    oit_glsl_set_view_all(b->counted.prog, OIT_COUNTED_PROGS, &c->view);
    oit_glsl_set_view_all(b->k.prog, OIT_FIRSTK_PROGS, &c->view);
    /* the opaque depth's projection replaces the view's */
    oit_glsl_set_opaque_all(b->counted.prog, OIT_COUNTED_PROGS, &c->opaque);
    oit_glsl_set_opaque_all(b->k.prog, OIT_FIRSTK_PROGS, &c->opaque);
    if (!b->fill)
        return;
    oit_capture_set_frame_uniforms(c, &b->fill, 1);
    /* the routed pass 1 keeps as many fragments as the target has samples */
    glProgramUniform1i(b->fill, glGetUniformLocation(b->fill, "u_K"), b->target.K);
}

static void firstk_epsilon(oit_capture *c, float e)
{
    firstk_backend *b = c->be;
    if (b->fill)
        oit_glsl_set_epsilon_all(&b->fill, 1, e);
    /* the geometry passes */
    oit_glsl_set_epsilon_all(b->counted.prog, OIT_COUNTED_GEOMETRY_PROGS, e);
    oit_glsl_set_epsilon_all(b->k.prog, 2, e);
}

/* Nothing at OIT_BIND_OUT within the frame: its output passes through a
 * fragment store at the end. */
static void firstk_bind(const oit_capture *c)
{
    oit_capture_bind_within(c, OIT_BIND_OUT, 0, 0);
}

/* W slots a pixel within the slot budget, or, where fewer than 2 fit, the
 * counted capture's batch; any number of layers. */
static oit_status firstk_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                               const int rect[4], int layers, oit_error *err)
{
    firstk_backend *b = c->be;
    int r[4] = {0}, empty = 1;
    oit_status s = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    uint64_t budget = c->set.slot_budget, bind = c->frame.bind;
    uint64_t store = oit_capture_store_budget(c);
    b->k.budget = budget && budget < bind ? budget : bind;
    b->k.store_budget = store && store < bind ? store : bind;
    if (b->off || oit_firstk_slots(&b->k, r) == 0) {
        b->packs++;
        s = counted_ready(c, b, err);
        return s == OIT_OK ? oit_capture_counted_batch(c, &b->counted, meshes, n, r, err) : s;
    }
    oit_counted_frame f = oit_capture_counted_frame(c);
    /* the prediction within what the slots and store leave of the store
     * budget (the slots are the store's first bytes) */
    uint64_t slots = (uint64_t)(r[2] - r[0]) * (uint64_t)(r[3] - r[1]) * 16u *
                     (uint64_t)oit_firstk_slots(&b->k, r);
    slots = slots > b->k.store_cap ? slots : b->k.store_cap;
    if (b->predict && !b->k.routed && counted_ready(c, b, NULL) == OIT_OK)
        s = oit_counted_predict_target(&b->counted, &f, b->packs,
                                       store ? (store > slots ? store - slots : 0) : UINT64_MAX,
                                       &b->k.counts_copy, err);
    if (s == OIT_OK)
        s = oit_firstk_batch(&b->k, &f, meshes, n, r, err);
    if (s == OIT_OK && b->k.counts_copy)
        s = oit_counted_predict(&b->counted, &f, b->packs, err);
    b->k.counts_copy = 0;
    b->packs++;
    oit_capture_note_peak(c);
    oit_capture_bind_buffers(c);
    return s;
}

static oit_status firstk_end(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                             oit_error *err)
{
    firstk_backend *b = c->be;
    if (b->off)
        return oit_capture_store_out(c, &b->counted.frags, &b->counted.frags_cap,
                                     "counted capture fragments", want, row, out, err);
    return oit_capture_store_out(c, &b->k.store, &b->k.store_cap, "first-k capture fragments", want,
                                 row, out, err);
}

static uint64_t firstk_bytes(const void *be)
{
    const firstk_backend *b = be;
    return oit_counted_bytes(&b->counted) + oit_firstk_bytes(&b->k) +
           oit_stencil_target_bytes(&b->target);
}

/* Switched off, it captures as the counted backend does and says so. */
static void firstk_stats(const oit_capture *c, oit_frame_stats *stats)
{
    const firstk_backend *b = c->be;
    stats->capture = b->off ? oit_capture_counted_ops.name : c->ops->name;
    stats->batches += b->counted.splits;
    stats->second_pass_pixels = b->k.second_pixels;
    stats->second_pass_packs = b->k.second_packs;
    stats->deep_pixels = b->k.second_pixels + b->counted.deep_pixels;
    stats->predicted_batches = b->counted.predicted_batches;
    /* how its K-slot fills were made (the counted capture has none) */
    stats->capture_slots = b->off ? NULL : b->fill ? "stencil" : "array";
    stats->capture_slots_k = !b->off && b->fill ? (uint32_t)b->target.K : 0;
}

/* Both stores are kept across a switch, each within its own budget (the
 * slot and store budgets are shares of their own): the streamer's
 * automatic mode measures each path on a view by the frame it probes it
 * in, and a store made again there made the probe lose (head.stl at
 * 1024x1024: first-K back from counted in 325 ms, 169 of them outside the
 * passes, against 134 warm, so counted's 167 held). */
static void firstk_first_k(oit_capture *c, int on)
{
    firstk_backend *b = c->be;
    b->off = !on;
}

static int firstk_ended(oit_capture *c)
{
    firstk_backend *b = c->be;
    if (!b->k.totals)
        return 0; /* a self-test frame (firstk_begin) */
    oit_firstk_ended(&b->k);
    int counted_short = b->counted_ready && oit_counted_ended(&b->counted);
    return (b->k.ahead && b->k.ended_short) || counted_short;
}

/* The counted capture built and seeded with the last frame's fragments
 * (an upper bound of its largest pack's), its store reserved: the frame
 * after, drawn counted, then runs ahead on warm buffers. A failure here
 * leaves that frame to build and measure as it would have. */
static void firstk_ready_counted(oit_capture *c)
{
    firstk_backend *b = c->be;
    if (b->off || (b->counted_ready && b->counted.measured))
        return;
    if (counted_ready(c, b, NULL) == OIT_OK)
        oit_counted_seed(&b->counted, c->frame.fragments, oit_capture_counted_fit(c));
}

OIT_CAPTURE_OPS(firstk, OIT_CAPTURE_FIRSTK, "first-k", firstk_backend, firstk_first_k,
                firstk_ready_counted, firstk_ended);
