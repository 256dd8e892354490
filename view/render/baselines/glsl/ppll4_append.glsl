/* The paged lists' append (ppll4.h, list_store.h), after
 * oit_glsl_fragment_gen and premultiplied.glsl. A page taken but not
 * swapped in (another fragment filled the pixel first) is kept for the
 * next full page this fragment meets, so one fragment wastes at most one
 * page. Pages at or past u_capacity exist only in the count: nothing is
 * written to them, and the frame is drawn again. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Heads { uint heads[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Slots { uvec4 slots[]; };
layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Links { uint links[]; };
layout(std430, binding = OIT_BIND_STATE) buffer Stats { uint counter; uint max_len; uint total; };
layout(location = OIT_LOC_CAPACITY) uniform uint u_capacity;
#define NO_PAGE 0x3fffffffu
void main() {
    if (oit_clipped()) discard;
    uint p = oit_pixel_index();
    uint spare = NO_PAGE, w = heads[p], want;
    for (;;) {
        if ((w & 3u) == 3u) {
            if (spare == NO_PAGE) spare = min(atomicAdd(counter, 1u), NO_PAGE - 1u);
            want = spare << 2;
        } else {
            want = w + 1u;
        }
        uint seen = atomicCompSwap(heads[p], w, want);
        if (seen == w) break;
        w = seen;
    }
    uint page = want >> 2;
    if (page >= u_capacity) return;
    if ((want & 3u) == 0u) links[page] = w >> 2;
    slots[want] = oit_fragment();
}
