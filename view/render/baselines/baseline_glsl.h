/* Every GL program view/render/baselines can build, for the offline check
 * (view/render/gl/glsl_program.h, tests/view/render/test_glsl_offline.sh). */
#ifndef OIT_RENDER_BASELINES_BASELINE_GLSL_H
#define OIT_RENDER_BASELINES_BASELINE_GLSL_H

#include "view/render/gl/glsl_program.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Visits each program of every baseline, each variant once, from the
 * tables and functions the baselines build from. */
void oit_baseline_glsl_variants(oit_glsl_visit *visit, void *user);

/* One baseline's programs, from the table or function its init builds
 * from (each in the baseline's .c). */
void oit_unsorted_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_wboit_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_pll_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_ppll4_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_guarded_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_b3d_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_depth_peel_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_dual_peel_glsl_variants(oit_glsl_visit *visit, void *user);
void oit_f2b_glsl_variants(oit_glsl_visit *visit, void *user);

/* visit(user, &table[i]) for i in [0, n). */
void oit_baseline_visit_table(const oit_glsl_program *table, int n, oit_glsl_visit *visit,
                              void *user);

#ifdef __cplusplus
}
#endif

#endif
