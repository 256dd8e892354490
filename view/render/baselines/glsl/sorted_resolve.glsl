/* The resolve of the methods that store every fragment (baseline_common.h,
 * oit_glsl_sorted_resolve), after oit_glsl_composite: one sort and one
 * composite for all of them, so that the list methods and B3D differ only
 * in their store, which the method's walk (declared below, defined after
 * this file) reaches. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(std430, binding = OIT_BIND_STATE) buffer Stats { uint counter; uint max_len; uint total; };
layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };
#define LOCAL_MAX 32u
#define OIT_LIST_END 0xffffffffu
uint oit_list_first(uint p);
uint oit_list_next(uint it);
uvec4 oit_list_load(uint it);
bool oit_list_can_relink();
void oit_list_relink(uint it, uint next);
bool oit_list_index(uint first, uint n);
uint oit_list_at(uint k);
void oit_list_store(uint it, uvec4 f);
/* In-place heap sort over the walk's k-th positions, for stores that can
 * reach them directly (oit_list_index true): O(n log n) (baseline_common.h). */
void oit_list_sift(uint root, uint n) {
    for (;;) {
        uint child = 2u * root + 1u;
        if (child >= n) return;
        uint a = oit_list_at(child);
        if (child + 1u < n && oit_frag_less(oit_list_load(a), oit_list_load(oit_list_at(child + 1u)))) {
            child++;
            a = oit_list_at(child);
        }
        uint r = oit_list_at(root);
        uvec4 x = oit_list_load(r), y = oit_list_load(a);
        if (!oit_frag_less(x, y)) return;
        oit_list_store(r, y);
        oit_list_store(a, x);
        root = child;
    }
}
void oit_list_heap_sort(uint n) {
    for (uint i = n / 2u; i > 0u; i--) oit_list_sift(i - 1u, n);
    for (uint e = n - 1u; e > 0u; e--) {
        uint a = oit_list_at(0u), b = oit_list_at(e);
        uvec4 x = oit_list_load(a);
        oit_list_store(a, oit_list_load(b));
        oit_list_store(b, x);
        oit_list_sift(0u, e);
    }
}
/* Bottom-up merge sort of a list by relinking (stable, O(n log n)), for
 * stores whose every fragment has its own link. llvmpipe ends a
 * shader's loops after 65535 iterations in all, so the quadratic walk
 * below stops early, silently, beyond about 256 fragments a pixel. */
uint oit_list_sort(uint head) {
    for (uint k = 1u;; k *= 2u) {
        uint p = head, tail = OIT_LIST_END, merges = 0u;
        head = OIT_LIST_END;
        while (p != OIT_LIST_END) {
            merges++;
            uint q = p, psize = 0u, qsize = k;
            while (psize < k && q != OIT_LIST_END) { psize++; q = oit_list_next(q); }
            while (psize > 0u || (qsize > 0u && q != OIT_LIST_END)) {
                bool take_p = qsize == 0u || q == OIT_LIST_END;
                if (!take_p && psize > 0u) take_p = !oit_frag_less(oit_list_load(q), oit_list_load(p));
                uint e;
                if (take_p) { e = p; p = oit_list_next(p); psize--; }
                else { e = q; q = oit_list_next(q); qsize--; }
                if (tail == OIT_LIST_END) head = e; else oit_list_relink(tail, e);
                tail = e;
            }
            p = q;
        }
        oit_list_relink(tail, OIT_LIST_END);
        if (merges <= 1u) return head;
    }
    return head;
}
void composite_long(inout oit_state s, uint first, uint n) {
    uvec4 last = uvec4(0u);
    for (uint k = 0u; k < n; k++) {
        uvec4 best = uvec4(0xffffffffu);
        for (uint i = first; i != OIT_LIST_END; i = oit_list_next(i)) {
            uvec4 x = oit_list_load(i);
            if ((k == 0u || oit_frag_less(last, x)) && oit_frag_less(x, best)) best = x;
        }
        oit_composite(s, best);
        last = best;
    }
}
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    uint first = oit_list_first(p), n = 0u;
    for (uint i = first; i != OIT_LIST_END; i = oit_list_next(i)) n++;
    atomicMax(max_len, n);
    atomicAdd(total, n);
    oit_state s = oit_state_begin();
    if (n <= LOCAL_MAX) {
        uvec4 f[LOCAL_MAX];
        uint m = 0u;
        for (uint i = first; i != OIT_LIST_END; i = oit_list_next(i)) {
            uvec4 x = oit_list_load(i);
            OIT_SORTED_INSERT(f, m, x)
            m++;
        }
        for (uint i = 0u; i < m; i++) oit_composite(s, f[i]);
    } else if (oit_list_can_relink()) {
        for (uint i = oit_list_sort(first); i != OIT_LIST_END; i = oit_list_next(i))
            oit_composite(s, oit_list_load(i));
    } else if (oit_list_index(first, n)) {
        oit_list_heap_sort(n);
        for (uint k = 0u; k < n; k++) oit_composite(s, oit_list_load(oit_list_at(k)));
    } else {
        composite_long(s, first, n);
    }
    out_rgba[p] = oit_state_final(s);
}
