/* Per-pixel linked lists (ppll.h) on the list store (list_store.h): a unit
 * is one node, a pixel's one head word indexes its newest node. */
#include "render/baselines/ppll.h"
#include "render/baselines/methods.h"

#include "render/baselines/list_store.h"

static const char append_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Heads { uint heads[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Nodes { uvec4 nodes[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Next { uint next[]; };\n"
    "layout(std430, binding = OIT_BIND_STATE) "
    "buffer Stats { uint counter; uint max_len; uint total; };\n"
    "layout(location = 13) uniform uint u_capacity;\n"
    "void main() {\n"
    "    if (oit_clipped()) discard;\n"
    "    uint n = atomicAdd(counter, 1u);\n"
    "    if (n >= u_capacity) return;\n"
    "    nodes[n] = oit_fragment();\n"
    "    next[n] = atomicExchange(heads[oit_pixel_index()], n);\n"
    "}\n";

/* 0xffffffff ends a list, so it is no node index. */
static const oit_list_desc desc = {"PLL", append_fs, OIT_LIST_NODE_WALK(1u), 1, 1, 0xfffffffeull,
                                   0};

uint64_t oit_pll_capacity(const oit_pll *p)
{
    return oit_list_store_capacity(p);
}

OIT_LIST_METHOD(pll, oit_pll, desc, 0, OIT_NO_THRESHOLD);
