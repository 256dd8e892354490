/* Paged per-pixel linked lists (ppll4.h) on the list store (list_store.h):
 * a unit is a page of four slots, a pixel's one head word packs the newest
 * page and its fill. */
#include "render/baselines/ppll4.h"
#include "render/baselines/methods.h"

#include "render/baselines/list_store.h"

/* A page taken but not swapped in (another fragment filled the pixel first)
 * is kept for the next full page this fragment meets, so one fragment
 * wastes at most one page. Pages at or past u_capacity exist only in the
 * count: nothing is written to them, and the frame is drawn again. */
static const char append_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) buffer Heads { uint heads[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Slots { uvec4 slots[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Links { uint links[]; };\n"
    "layout(std430, binding = OIT_BIND_STATE) "
    "buffer Stats { uint counter; uint max_len; uint total; };\n"
    "layout(location = 13) uniform uint u_capacity;\n"
    "#define NO_PAGE 0x3fffffffu\n"
    "void main() {\n"
    "    if (oit_clipped()) discard;\n"
    "    uint p = oit_pixel_index();\n"
    "    uint spare = NO_PAGE, w = heads[p], want;\n"
    "    for (;;) {\n"
    "        if ((w & 3u) == 3u) {\n"
    "            if (spare == NO_PAGE) spare = min(atomicAdd(counter, 1u), NO_PAGE - 1u);\n"
    "            want = spare << 2;\n"
    "        } else {\n"
    "            want = w + 1u;\n"
    "        }\n"
    "        uint seen = atomicCompSwap(heads[p], w, want);\n"
    "        if (seen == w) break;\n"
    "        w = seen;\n"
    "    }\n"
    "    uint page = want >> 2;\n"
    "    if (page >= u_capacity) return;\n"
    "    if ((want & 3u) == 0u) links[page] = w >> 2;\n"
    "    slots[want] = oit_fragment();\n"
    "}\n";

/* Newest first: down the slots of a page, then to slot 3 of the page it
 * links to; NO_PAGE * 4 + 3 is OIT_LIST_END. */
static const char walk_glsl[] =
    "layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Heads { uint heads[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) buffer Slots { uvec4 slots[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Links { uint links[]; };\n"
    "uint oit_list_first(uint p) { return heads[p]; }\n"
    "uint oit_list_next(uint i) {\n"
    "    return (i & 3u) != 0u ? i - 1u : links[i >> 2] * 4u + 3u;\n"
    "}\n"
    "uvec4 oit_list_load(uint i) { return slots[i]; }\n"
    /* Fragments share a page: no link of their own to sort by. A table of
     * the pixel's pages (up to 256, 1024 fragments) reaches the k-th one
     * directly for a heap sort; longer lists take the quadratic walk. */
    "bool oit_list_can_relink() { return false; }\n"
    "void oit_list_relink(uint i, uint n) {}\n"
    "uint oit_pages[256];\n"
    "uint oit_head, oit_in_head;\n"
    "bool oit_list_index(uint first, uint n) {\n"
    "    oit_head = first;\n"
    "    oit_in_head = (first & 3u) + 1u;\n"
    "    if (n > oit_in_head + 4u * 256u) return false;\n"
    "    uint page = first >> 2;\n"
    "    for (uint j = 0u; j * 4u < n - min(n, oit_in_head); j++) {\n"
    "        page = links[page];\n"
    "        oit_pages[j] = page;\n"
    "    }\n"
    "    return true;\n"
    "}\n"
    "uint oit_list_at(uint k) {\n"
    "    if (k < oit_in_head) return oit_head - k;\n"
    "    uint r = k - oit_in_head;\n"
    "    return oit_pages[r >> 2] * 4u + 3u - (r & 3u);\n"
    "}\n"
    "void oit_list_store(uint i, uvec4 f) { slots[i] = f; }\n";

/* Page indices take the head word's upper 30 bits; the top one is NO_PAGE. */
static const oit_list_desc desc = {"PPLL4", append_fs, walk_glsl, 4, 1, 0x3ffffffeull, 0};

uint64_t oit_ppll4_capacity(const oit_ppll4 *p)
{
    return oit_list_store_capacity(p);
}

OIT_LIST_METHOD(ppll4, oit_ppll4, desc, 0, OIT_NO_THRESHOLD);
