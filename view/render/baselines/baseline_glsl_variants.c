/* Every program of view/render/baselines, for the offline check
 * (baseline_glsl.h): one call a baseline. */
#include "view/render/baselines/baseline_glsl.h"

void oit_baseline_visit_table(const oit_glsl_program *table, int n, oit_glsl_visit *visit,
                              void *user)
{
    for (int i = 0; i < n; i++)
        visit(user, &table[i]);
}

void oit_baseline_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_unsorted_glsl_variants(visit, user);
    oit_wboit_glsl_variants(visit, user);
    oit_pll_glsl_variants(visit, user);
    oit_ppll4_glsl_variants(visit, user);
    oit_guarded_glsl_variants(visit, user);
    oit_b3d_glsl_variants(visit, user);
    oit_depth_peel_glsl_variants(visit, user);
    oit_dual_peel_glsl_variants(visit, user);
    oit_f2b_glsl_variants(visit, user);
}
