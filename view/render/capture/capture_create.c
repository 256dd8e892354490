/* A capture's making and unmaking (capture.h): the backend's table looked
 * up from the fill and the cut (capture.h's table), the stencil routing
 * chosen (capture_choice.h) or asked for exactly, the shared part made
 * before the backend's and the settings applied after its self-test.
 * This file and capture_choice.c are the only ones that tell the backends
 * apart (tests/view/render/test_render_layout.sh). */
#include "view/render/capture/capture.h"

#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_glsl.h"
#include "view/render/gl/frag_glsl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The table of a kind: the one place that tells the backends apart. */
static const oit_capture_ops *ops_of(oit_capture_kind kind)
{
    switch (kind) {
    case OIT_CAPTURE_ARRAY: return &oit_capture_array_ops;
    case OIT_CAPTURE_STENCIL: return &oit_capture_stencil_ops;
    case OIT_CAPTURE_COUNTED: return &oit_capture_counted_ops;
    case OIT_CAPTURE_FIRSTK: return &oit_capture_firstk_ops;
    case OIT_CAPTURE_COMPUTE: return &oit_capture_compute_ops;
    default: return NULL;
    }
}

const char *oit_capture_kind_name(oit_capture_kind kind)
{
    const oit_capture_ops *ops = ops_of(kind);
    return ops ? ops->name : NULL;
}

static void release(oit_capture *c)
{
    if (c->be)
        c->ops->destroy(c->be);
    free(c->be);
    oit_glsl_programs_delete(&c->end_prog, 1);
    glDeleteFramebuffers(1, &c->fbo);
    glDeleteBuffers(OIT_CAPTURE_BUFS, c->buf);
    oit_gpu_draws_destroy(c->draws);
    oit_opaque_keys_destroy(c->keys);
    free(c);
}

void oit_capture_destroy(oit_capture *c)
{
    if (c)
        release(c);
}

oit_capture_kind oit_capture_backend(const oit_capture *c)
{
    return c->ops->kind;
}

const oit_glsl_program oit_capture_end_program = {
    "capture end", .cs = {oit_glsl_composite, oit_glsl_state_io, oit_capture_end_cs}};

/* The shared part, then the backend's (stencil_k: the samples of its
 * routed fills, 0 for none; a routed backend runs the self-test), then
 * the settings. */
static oit_status make(const oit_capture_desc *d, const oit_capture_ops *ops, int stencil_k,
                       oit_capture **out, oit_error *err)
{
    oit_program_cache *pc = d->programs;
    oit_capture *c = calloc(1, sizeof *c);
    if (!c)
        return oit_error_set(err, OIT_ERR_NOMEM, "capture: out of memory");
    c->ops = ops;
    c->programs = pc;
    c->K = d->K;
    c->faults = d->faults;
    c->be = calloc(1, ops->size);
    if (!c->be) {
        free(c);
        return oit_error_set(err, OIT_ERR_NOMEM, "capture: out of memory");
    }
    /* the end program before the backend, whose self-test ends a frame */
    oit_status s = oit_glsl_programs_build(pc, &oit_capture_end_program, 1, &c->end_prog, err);
    if (s == OIT_OK)
        s = oit_gpu_draws_create(&c->draws, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &c->fbo);
        c->max_groups = oit_gl_max_groups_x();
        s = ops->create(c, stencil_k, err);
    }
    if (s == OIT_OK)
        s = oit_gl_check("capture: set-up", err);
    if (s != OIT_OK) {
        release(c);
        return s;
    }
    /* after the backend's self-test, which runs with no settings */
    oit_capture_apply(c, &d->settings);
    *out = c;
    return OIT_OK;
}

/* A capture of kind (STENCIL or FIRSTK) routed into stencil_k samples a
 * pixel, after its self-test passed there. */
static oit_status create_routed(const oit_capture_desc *d, oit_capture_kind kind, int stencil_k,
                                oit_capture **out, oit_error *err)
{
    oit_status s = make(d, ops_of(kind), stencil_k, out, err);
    if (s == OIT_OK)
        return OIT_OK;
    /* A driver error while setting stencil routing up means it is not
     * offered here, which the caller reads as UNSUPPORTED. */
    if (s == OIT_ERR_GL && err) {
        char why[sizeof err->message];
        memcpy(why, err->message, sizeof why);
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s", why);
    }
    return s == OIT_ERR_GL ? OIT_ERR_UNSUPPORTED : s;
}

/* The routed capture capture_choice.c tries at stencil_k samples, kept
 * once its self-test passes. */
typedef struct routed_try {
    const oit_capture_desc *desc;
    oit_capture_kind kind;
    oit_capture *made;
} routed_try;

static oit_status try_routed(void *ctx, int stencil_k, oit_error *err)
{
    routed_try *t = ctx;
    return create_routed(t->desc, t->kind, stencil_k, &t->made, err);
}

static const char *fill_name(const oit_capture_desc *d)
{
    return d->fill_name ? d->fill_name : "capture fill";
}

/* A cut whose batches the first-K capture takes (AUTO: as the streamer
 * resolves it). */
static int cut_firstk(oit_render_pack cut)
{
    return cut == OIT_RENDER_PACK_FIRSTK || cut == OIT_RENDER_PACK_AUTO;
}

/* fill and cut as the table in capture.h has them, before any GL. */
static oit_status check_axes(const oit_capture_desc *d, oit_error *err)
{
    const char *fill = oit_capture_asked_name(d->fill);
    const char *cut = d->cut_name ? d->cut_name : "capture cut";
    if (!fill)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not auto, array, stencil or compute",
                             fill_name(d), (int)d->fill);
    if ((unsigned)d->cut > (unsigned)OIT_RENDER_PACK_FIRSTK)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %d: not an oit_render_pack", cut,
                             (int)d->cut);
    if (d->fill == OIT_RENDER_CAPTURE_STENCIL && d->cut == OIT_RENDER_PACK_COUNTED)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = stencil: counted packs have no K-slot "
                             "fill to route (%s = first-k, budget or disjoint)", fill_name(d),
                             cut);
    int firstk = cut_firstk(d->cut);
    int sk = d->stencil_k;
    if (sk && (d->fill != OIT_RENDER_CAPTURE_STENCIL || sk < 2 || sk > d->K ||
               (!firstk && sk != d->K)))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "capture: %d routed samples for %s at K=%d "
                             "(2..K for first-K, K for K-slot batches; a stencil fill only)", sk,
                             fill, d->K);
    return OIT_OK;
}

/* The K-slot fill of a K-slot or first-K capture: the choice, or the
 * routing asked for exactly (stencil_k). */
static oit_status create_slots(const oit_capture_desc *d, int firstk, oit_capture **out,
                               oit_error *err)
{
    oit_capture_kind routed = firstk ? OIT_CAPTURE_FIRSTK : OIT_CAPTURE_STENCIL;
    oit_capture_choice choice = {.asked = d->fill, .slots = OIT_RENDER_CAPTURE_STENCIL,
                                 .stencil_k = d->stencil_k};
    oit_status s;
    if (d->stencil_k) {
        s = create_routed(d, routed, d->stencil_k, out, err);
    } else {
        routed_try t = {d, routed, NULL};
        s = oit_capture_choose(d->fill, fill_name(d), d->K, firstk, try_routed, &t, &choice,
                               err);
        *out = t.made;
        if (s == OIT_OK && !t.made)
            s = make(d, ops_of(firstk ? OIT_CAPTURE_FIRSTK : OIT_CAPTURE_ARRAY), 0, out, err);
    }
    if (s == OIT_OK)
        (*out)->choice = choice;
    return s;
}

oit_status oit_capture_create(const oit_capture_desc *desc, oit_capture **out, oit_error *err)
{
    *out = NULL;
    oit_status s = oit_capture_k_check(desc->K, NULL, err);
    if (s == OIT_OK)
        s = check_axes(desc, err);
    if (s != OIT_OK)
        return s;
    if (desc->fill != OIT_RENDER_CAPTURE_COMPUTE && desc->cut != OIT_RENDER_PACK_COUNTED)
        return create_slots(desc, cut_firstk(desc->cut), out, err);
    s = make(desc, ops_of(desc->fill == OIT_RENDER_CAPTURE_COMPUTE ? OIT_CAPTURE_COMPUTE
                                                                   : OIT_CAPTURE_COUNTED),
             0, out, err);
    if (s == OIT_OK)
        (*out)->choice = (oit_capture_choice){.asked = desc->fill};
    return s;
}

const oit_capture_choice *oit_capture_get_choice(const oit_capture *c)
{
    return &c->choice;
}

int oit_capture_routed_k(const oit_capture *c)
{
    return c->routed_k;
}
