/* Every GL program render/capture can build, for the offline check
 * (render/gl/glsl_program.h, tests/render/test_glsl_offline.sh). */
#ifndef OIT_RENDER_CAPTURE_GLSL_VARIANTS_H
#define OIT_RENDER_CAPTURE_GLSL_VARIANTS_H

#include "render/gl/glsl_program.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Visits each program of every module of render/capture, each variant
 * once, from the tables and functions the modules build from. */
void oit_capture_glsl_variants(oit_glsl_visit *visit, void *user);

#ifdef __cplusplus
}
#endif

#endif
