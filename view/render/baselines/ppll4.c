/* Paged per-pixel linked lists (ppll4.h) on the list store (list_store.h):
 * a unit is a page of four slots, a pixel's one head word packs the newest
 * page and its fill. */
#include "view/render/baselines/ppll4.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_glsl.h"
#include "view/render/baselines/list_store.h"

/* glsl/ppll4_*.glsl: the append (a page of four slots per allocation)
 * and the walk of a pixel's pages for the sorted resolve. */
extern const char oit_ppll4_append_fs[], oit_ppll4_walk[];

/* Page indices take the head word's upper 30 bits; the top one is NO_PAGE. */
static const oit_list_desc desc = {"PPLL4", oit_ppll4_append_fs, {oit_ppll4_walk}, 4, 1,
                                   0x3ffffffeull, 0};

void oit_ppll4_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_list_store_glsl_variants(&desc, visit, user);
}

uint64_t oit_ppll4_capacity(const oit_ppll4 *p)
{
    return oit_list_store_capacity(p);
}

OIT_LIST_METHOD(ppll4, oit_ppll4, desc, 0, OIT_NO_THRESHOLD);
