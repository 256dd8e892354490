/* Every GL program view/render/capture can build, for the offline check
 * (view/render/gl/glsl_program.h, tests/view/render/test_glsl_offline.sh). */
#ifndef OIT_RENDER_CAPTURE_GLSL_VARIANTS_H
#define OIT_RENDER_CAPTURE_GLSL_VARIANTS_H

#include "view/render/gl/glsl_program.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Visits each program of every module of view/render/capture, each variant
 * once, from the tables and functions the modules build from. */
void oit_capture_glsl_variants(oit_glsl_visit *visit, void *user);

#ifdef __cplusplus
}
#endif

#endif
