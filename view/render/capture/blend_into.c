/* The blend into the caller's framebuffer (blend_into.h). */
#include "view/render/capture/blend_into.h"

#include "view/render/capture/capture_glsl.h"
#include "view/render/gl/frag_glsl.h"

extern const char oit_blend_into_fs[]; /* glsl/blend_into.glsl */

static const oit_glsl_program program = {
    "liboit blend",
    .vs = {oit_capture_fullscreen_vs},
    .fs = {oit_glsl_composite, oit_glsl_state_io, oit_blend_into_fs},
};

oit_status oit_blend_into_build(oit_program_cache *pc, GLuint *prog, oit_error *err)
{
    return oit_glsl_programs_build(pc, &program, 1, prog, err);
}

void oit_blend_into_glsl_variants(oit_glsl_visit *visit, void *user)
{
    visit(user, &program);
}
