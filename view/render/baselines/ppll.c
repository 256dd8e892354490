/* Per-pixel linked lists (ppll.h) on the list store (list_store.h): a unit
 * is one node, a pixel's one head word indexes its newest node. */
#include "view/render/baselines/ppll.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_glsl.h"
#include "view/render/baselines/list_store.h"

/* glsl/pll_append.glsl */
extern const char oit_pll_append_fs[];

#define HEAD_WORDS 1 /* a pixel's head words */

/* 0xffffffff ends a list, so it is no node index. */
static const oit_list_desc desc = {"PLL", oit_pll_append_fs,
                                   {OIT_LIST_HEAD_WORDS_GLSL(HEAD_WORDS), oit_glsl_node_walk}, 1,
                                   HEAD_WORDS, 0xfffffffeull, 0};

void oit_pll_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_list_store_glsl_variants(&desc, visit, user);
}

uint64_t oit_pll_capacity(const oit_pll *p)
{
    return oit_list_store_capacity(p);
}

OIT_LIST_METHOD(pll, oit_pll, desc, 0, OIT_NO_THRESHOLD);
