/* What the baseline methods (unsorted.h, wboit.h, ppll.h, depth_peel.h)
 * share beyond frag_glsl.h: the premultiplied colour of a packed fragment,
 * frame-size validation, and readback of a GL-ordered (bottom row first)
 * RGBA float result into a top-first oit_image. None keeps state. */
#ifndef OIT_RENDER_BASELINE_COMMON_H
#define OIT_RENDER_BASELINE_COMMON_H

#include "render/frag_glsl.h"
#include "render/view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fragment-stage GLSL, placed after oit_glsl_fragment_gen (it uses u_mode):
 * vec4 oit_premultiplied(uvec4 f) returns (a * colour, a) of a packed
 * fragment, the terms oit_composite adds for one fragment on a clear state.
 * Translucent absorption needs the order and is not part of it. */
extern const char oit_glsl_premultiplied[];

/* OIT_ERR_ARGUMENT naming 'method' when the frame cannot be rendered here
 * (non-positive or larger than GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT, n < 0). */
oit_status oit_baseline_check_frame(const char *method, const oit_view *v, int n,
                                    oit_error *err);

/* Allocates out and fills it from an RGBA32F texture or from a buffer of
 * w*h vec4, both bottom row first; alpha is set to 1 (a composited frame). */
oit_status oit_baseline_read_texture(const char *method, GLuint tex, int w, int h,
                                     oit_image *out, oit_error *err);
oit_status oit_baseline_read_buffer(const char *method, GLuint buf, int w, int h,
                                    oit_image *out, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
