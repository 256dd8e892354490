/* Every program of render/capture, for the offline check
 * (capture_glsl_variants.h): one call a module. */
#include "render/capture/capture_glsl_variants.h"

void oit_capture_glsl_variants(oit_glsl_visit *visit, void *user)
{
    (void)visit;
    (void)user;
}
