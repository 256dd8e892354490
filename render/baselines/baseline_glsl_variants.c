/* Every program of render/baselines, for the offline check
 * (baseline_glsl.h): one call a baseline. */
#include "render/baselines/baseline_glsl.h"

void oit_baseline_glsl_variants(oit_glsl_visit *visit, void *user)
{
    (void)visit;
    (void)user;
}
