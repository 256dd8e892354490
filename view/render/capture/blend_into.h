/* The blend of a frame's per-pixel state (C, T) into a framebuffer that
 * liboit's caller owns: a full-screen pass (oit_capture_fullscreen_vs)
 * whose fragment stage (glsl/blend_into.glsl) reads the state buffer at
 * OIT_BIND_STATE and writes dst = C + T * dst through dual-source blending
 * (glBlendFunc(GL_ONE, GL_SRC1_COLOR)). Its uniforms: OIT_LOC_SIZE, the
 * state's frame size; OIT_LOC_ORIGIN, the target pixel of the state's
 * pixel (0, 0); u_mode (by name), the state's layout (frag_glsl.h).
 *
 * The program lives here rather than in liboit, whose symbols the test
 * suite cannot see, so that the offline check lists it
 * (oit_blend_into_glsl_variants, view/render/gl/glsl_program.h). */
#ifndef OIT_RENDER_CAPTURE_BLEND_INTO_H
#define OIT_RENDER_CAPTURE_BLEND_INTO_H

#include "view/render/gl/glsl_program.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Builds the blend program into *prog through pc's entries (NULL:
 * compiled). */
oit_status oit_blend_into_build(oit_program_cache *pc, GLuint *prog, oit_error *err);

/* Visits the blend program, the one that oit_blend_into_build builds. */
void oit_blend_into_glsl_variants(oit_glsl_visit *visit, void *user);

#ifdef __cplusplus
}
#endif

#endif
