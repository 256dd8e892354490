/* Every GL program render/baselines can build, for the offline check
 * (render/gl/glsl_program.h, tests/render/test_glsl_offline.sh). */
#ifndef OIT_RENDER_BASELINES_BASELINE_GLSL_H
#define OIT_RENDER_BASELINES_BASELINE_GLSL_H

#include "render/gl/glsl_program.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Visits each program of every baseline, each variant once, from the
 * tables and functions the baselines build from. */
void oit_baseline_glsl_variants(oit_glsl_visit *visit, void *user);

#ifdef __cplusplus
}
#endif

#endif
