/* DFB and the capture backends as method tables (method.h). */
#include "view/render/method.h"

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"

static oit_status dfb_create(const oit_mesh *mesh, const oit_method_options *opt, void **impl,
                             oit_error *err)
{
    oit_dfb *d = NULL;
    oit_status s = oit_dfb_create(&d, err);
    *impl = d;
    return s;
}

static oit_status dfb_render(void *impl, const oit_method_frame *f, oit_error *err)
{
    oit_dfb_set_gpu_timer(impl, f->timer);
    return oit_dfb_render(impl, &f->gpu, 1, f->view, f->out, f->counts, f->stats, err);
}

static void dfb_destroy(void *impl)
{
    oit_dfb_destroy(impl);
}

static uint64_t dfb_pixel_bytes(const void *impl, const oit_view *view)
{
    (void)impl;
    return oit_dfb_pixel_bytes(view, 0);
}

const oit_method oit_method_dfb = {
    .name = "dfb",
    .flags = OIT_RENDER_METHOD_GL | OIT_RENDER_METHOD_COUNTS | OIT_RENDER_METHOD_CLIP,
    .create = dfb_create,
    .render = dfb_render,
    .destroy = dfb_destroy,
    .pixel_bytes = dfb_pixel_bytes,
};

/* The whole mesh is one batch of K slots a pixel (a budget cut). */
static oit_status capture_create(oit_render_capture fill, const oit_method_options *opt,
                                 void **impl, oit_error *err)
{
    oit_capture *c = NULL;
    oit_capture_desc d = {.fill = fill, .cut = OIT_RENDER_PACK_BUDGET,
                          .K = opt ? opt->max_layers : 0,
                          .settings.store_limit = opt ? opt->store_limit : 0};
    oit_status s = oit_capture_create(&d, &c, err);
    *impl = c;
    return s;
}

/* The whole mesh as one batch. */
static oit_status capture_render(void *impl, const oit_method_frame *f, oit_error *err)
{
    oit_capture_settings cs = oit_capture_get_settings(impl);
    cs.timer = f->timer;
    oit_capture_apply(impl, &cs);
    oit_status s = oit_capture_begin(impl, f->view, err);
    if (s == OIT_OK)
        s = oit_capture_batch(impl, &f->gpu, 1, NULL, err);
    if (s == OIT_OK)
        s = oit_capture_end(impl, f->out, f->stats, err);
    return s;
}

static void capture_destroy(void *impl)
{
    oit_capture_destroy(impl);
}

static uint64_t capture_pixel_bytes(const void *impl, const oit_view *view)
{
    (void)impl;
    return oit_capture_pixel_bytes(view);
}

/* The table of the capture with the fill FILL, drawing the mesh as one
 * batch. */
#define CAPTURE_METHOD(NAME, FILL)                                                         \
    static oit_status NAME##_create(const oit_mesh *mesh, const oit_method_options *opt,  \
                                    void **impl, oit_error *err)                           \
    {                                                                                      \
        return capture_create(FILL, opt, impl, err);                                       \
    }                                                                                      \
    const oit_method oit_method_##NAME = {.name = #NAME,                                   \
                                          .flags = OIT_RENDER_METHOD_GL | OIT_RENDER_METHOD_CLIP,        \
                                          .create = NAME##_create,                         \
                                          .render = capture_render,                        \
                                          .destroy = capture_destroy,                      \
                                          .pixel_bytes = capture_pixel_bytes}

CAPTURE_METHOD(array, OIT_RENDER_CAPTURE_ARRAY);
CAPTURE_METHOD(stencil, OIT_RENDER_CAPTURE_STENCIL);
/* The compute capture (capture_compute.h): no raster pipeline. */
CAPTURE_METHOD(compute, OIT_RENDER_CAPTURE_COMPUTE);
