/* The generic half of every method (method.h): the GL context, the mesh on
 * the GPU, and the order in which they are released. */
#include "render/method.h"

#include <stdlib.h>

#include "render/gl_context.h"

struct oit_method_state {
    const oit_method *method;
    const oit_mesh *mesh;
    oit_gl *gl;
    int gl_borrowed; /* gl is the caller's (oit_method_options.gl): not ours to destroy */
    oit_gpu_mesh *gpu;
    void *impl;
};

void oit_method_close(oit_method_state *st)
{
    if (!st)
        return;
    /* GL objects go before the context that owns them. */
    if (st->impl)
        st->method->destroy(st->impl);
    if (st->gpu)
        oit_gpu_mesh_destroy(st->gpu);
    if (st->gl && !st->gl_borrowed)
        oit_gl_destroy(st->gl);
    free(st);
}

/* The caller's context when it gives one (the viewer's window), else a
 * headless one of our own; an in-core method's mesh goes up once. */
static oit_status prepare_gl(oit_method_state *st, const oit_method_options *opt, oit_error *err)
{
    oit_status s = OIT_OK;
    if (opt && opt->gl) {
        st->gl = opt->gl;
        st->gl_borrowed = 1;
    } else {
        s = oit_gl_create(&(oit_gl_desc){0}, &st->gl, err);
    }
    if (s == OIT_OK && !(st->method->flags & OIT_METHOD_PARTFILE))
        s = oit_gpu_mesh_create(st->mesh->tris, st->mesh->count, 0, &st->gpu, err);
    return s;
}

oit_status oit_method_open(const oit_method *m, const oit_mesh *mesh,
                           const oit_method_options *opt, oit_method_state **out,
                           oit_error *err)
{
    *out = NULL;
    oit_method_state *st = calloc(1, sizeof *st);
    if (!st)
        return oit_error_set(err, OIT_ERR_NOMEM, "method %s: cannot allocate its state", m->name);
    st->method = m;
    st->mesh = mesh;
    oit_status s = m->flags & OIT_METHOD_GL ? prepare_gl(st, opt, err) : OIT_OK;
    if (s == OIT_OK)
        s = m->create(mesh, opt, &st->impl, err);
    if (s != OIT_OK) {
        oit_method_close(st);
        return s;
    }
    *out = st;
    return OIT_OK;
}

oit_status oit_method_render(oit_method_state *st, const oit_view *view, oit_image *out,
                             uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                             oit_error *err)
{
    unsigned f = st->method->flags;
    oit_method_frame frame = {.mesh = st->mesh, .gpu = st->gpu, .view = view, .out = out,
                              .counts = f & OIT_METHOD_COUNTS ? counts : NULL,
                              .ambiguous = f & OIT_METHOD_AMBIGUITY ? ambiguous : NULL,
                              .stats = stats};
    oit_status s = st->method->render(st->impl, &frame, err);
    /* A borrowed context is checked too: the viewer's window is ours. */
    if (s == OIT_OK)
        s = oit_gl_debug_check(st->gl, st->method->name, err);
    return s;
}

const char *oit_method_renderer(const oit_method_state *st)
{
    if (st->method->renderer)
        return st->method->renderer(st->impl);
    return st->gl ? oit_gl_renderer(st->gl) : "none";
}

const struct oit_stream_frame_stats *oit_method_stream_stats(const oit_method_state *st)
{
    return st->method->stream_stats ? st->method->stream_stats(st->impl) : NULL;
}
