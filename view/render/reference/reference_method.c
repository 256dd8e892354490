/* The Embree reference as a method table (method.h): no GL; it fills
 * per-pixel counts and flags the pixels where rasterization and rays may
 * disagree. Its threshold (OIT_RENDER_METHOD_EPSILON) changes no pixel: it counts
 * the fragments an early termination at it would drop
 * (oit_reference_desc.saturation_epsilon). */
#include "view/render/method.h"

#include <embree3/rtcore_config.h>
#include <stdlib.h>

#include "view/render/reference/reference.h"

static oit_status reference_create(const oit_mesh *mesh, const oit_method_options *opt,
                                   void **impl, oit_error *err)
{
    oit_reference_desc *d = calloc(1, sizeof *d);
    if (!d)
        return oit_error_set(err, OIT_ERR_NOMEM, "method reference: out of memory");
    if (opt) {
        d->ambiguity_px = opt->ambiguity_px;
        d->saturation_epsilon = opt->threshold ? *opt->threshold : 0.0f;
    }
    *impl = d;
    return OIT_OK;
}

static oit_status reference_render(void *impl, const oit_method_frame *f, oit_error *err)
{
    oit_reference_desc desc = *(const oit_reference_desc *)impl;
    desc.ambiguous = f->ambiguous;
    return oit_reference_render(f->mesh, f->view, &desc, f->out, f->counts, f->stats, err);
}

static const char *reference_renderer(const void *impl)
{
    return "Embree " RTC_VERSION_STRING " (CPU reference)";
}

const oit_method oit_method_reference = {
    .name = "reference",
    .flags = OIT_RENDER_METHOD_COUNTS | OIT_RENDER_METHOD_AMBIGUITY | OIT_RENDER_METHOD_EPSILON | OIT_RENDER_METHOD_CLIP,
    .create = reference_create,
    .render = reference_render,
    .destroy = free,
    .renderer = reference_renderer,
    .pick = oit_reference_pick,
};
