/* Every program of view/render/capture, for the offline check
 * (capture_glsl_variants.h): one call a module, each listing its programs
 * from the tables and functions it builds them from. */
#include "view/render/capture/capture_glsl_variants.h"

#include "view/render/capture/blend_into.h"
#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_compute.h"
#include "view/render/capture/capture_counted.h"
#include "view/render/capture/capture_firstk.h"
#include "view/render/capture/capture_stencil.h"
#include "view/render/capture/dfb.h"
#include "view/render/capture/opaque_keys.h"
#include "view/render/capture/opaque_tiles.h"
#include "view/render/capture/saturation.h"

void oit_capture_glsl_variants(oit_glsl_visit *visit, void *user)
{
    visit(user, &oit_capture_end_program); /* capture.c: every backend's end */
    oit_capture_array_glsl_variants(visit, user);
    oit_capture_stencil_glsl_variants(visit, user);
    oit_counted_glsl_variants(visit, user);
    oit_firstk_glsl_variants(visit, user);
    oit_compute_glsl_variants(visit, user);
    oit_dfb_glsl_variants(visit, user);
    oit_opaque_keys_glsl_variants(visit, user);
    oit_opaque_tiles_glsl_variants(visit, user);
    oit_saturation_glsl_variants(visit, user);
    oit_blend_into_glsl_variants(visit, user);
}
