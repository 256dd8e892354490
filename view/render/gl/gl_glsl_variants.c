/* Every GLSL variant of the GL floor (glsl_program.h), for the offline
 * compile and the build log: one file of its own, so that frag_glsl.c,
 * which the prefix sum and the meshes build their programs with, depends
 * on neither. */
#include "view/render/gl/glsl_program.h"
#include "view/render/gl/scan_glsl.h"

void oit_gl_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_scan_glsl_variants(visit, user);
    oit_gpu_draws_glsl_variants(visit, user);
}
