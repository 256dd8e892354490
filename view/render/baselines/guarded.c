/* Guarded OIT (guarded.h) on the list store (list_store.h): a unit is one
 * node; pixel p's head words are [2p] the list (newest node) and [2p + 1]
 * the nearest stored node. */
#include "view/render/baselines/guarded.h"
#include "view/render/baselines/methods.h"

#include "view/render/gl/gl_util.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/baselines/list_store.h"

/* glsl/guarded_append.glsl: the append with its guards. */
extern const char oit_guarded_append_fs[];

#define HEAD_WORDS 2 /* a pixel's head words: the list, the nearest node */

/* 0xffffffff means no node, so it is no node index. A pass that overflows
 * counts as if guards past the pool never culled, so the pool doubles at
 * most per pass rather than growing to PLL's size at once. */
static const oit_list_desc desc = {"guarded OIT", oit_guarded_append_fs,
                                   {OIT_LIST_HEAD_WORDS_GLSL(HEAD_WORDS), oit_glsl_node_walk}, 1,
                                   HEAD_WORDS, 0xfffffffeull, 2};

void oit_guarded_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_list_store_glsl_variants(&desc, visit, user);
}

static oit_status oit_guarded_init(oit_guarded *g, oit_error *err)
{
    oit_status s = oit_list_store_init(g, &desc, err);
    if (s == OIT_OK)
        s = oit_guarded_set_threshold(g, OIT_GUARDED_DEFAULT_THRESHOLD, err);
    return s;
}

oit_status oit_guarded_set_threshold(oit_guarded *g, float threshold, oit_error *err)
{
    if (!(threshold >= 0.0f && threshold < 1.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "guarded OIT: threshold %g is outside "
                             "[0, 1)", (double)threshold);
    GLuint prog = oit_list_store_append_program(g);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_threshold"), threshold);
    return oit_gl_check("guarded OIT: threshold", err);
}

OIT_BASELINE_METHOD_FRAMED(guarded, oit_guarded, desc.method, oit_guarded_init,
                           oit_list_store_release, oit_list_store_render, OIT_LIST_FRAME,
                           OIT_RENDER_METHOD_EPSILON, OIT_THRESHOLD);
