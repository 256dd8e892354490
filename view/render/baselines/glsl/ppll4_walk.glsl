/* The paged lists' walk for the sorted resolve (ppll4.h,
 * sorted_resolve.glsl): newest first, down the slots of a page, then to
 * slot 3 of the page it links to; NO_PAGE * 4 + 3 is OIT_LIST_END. */
layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = OIT_BIND_FRAGS) buffer Slots { uvec4 slots[]; };
layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Links { uint links[]; };
uint oit_list_first(uint p) { return heads[p]; }
uint oit_list_next(uint i) {
    return (i & 3u) != 0u ? i - 1u : links[i >> 2] * 4u + 3u;
}
uvec4 oit_list_load(uint i) { return slots[i]; }
/* Fragments share a page: no link of their own to sort by. A table of
 * the pixel's pages (up to 256, 1024 fragments) reaches the k-th one
 * directly for a heap sort; longer lists take the quadratic walk. */
bool oit_list_can_relink() { return false; }
void oit_list_relink(uint i, uint n) {}
uint oit_pages[256];
uint oit_head, oit_in_head;
bool oit_list_index(uint first, uint n) {
    oit_head = first;
    oit_in_head = (first & 3u) + 1u;
    if (n > oit_in_head + 4u * 256u) return false;
    uint page = first >> 2;
    for (uint j = 0u; j * 4u < n - min(n, oit_in_head); j++) {
        page = links[page];
        oit_pages[j] = page;
    }
    return true;
}
uint oit_list_at(uint k) {
    if (k < oit_in_head) return oit_head - k;
    uint r = k - oit_in_head;
    return oit_pages[r >> 2] * 4u + 3u - (r & 3u);
}
void oit_list_store(uint i, uvec4 f) { slots[i] = f; }
