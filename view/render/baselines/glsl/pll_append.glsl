/* The per-pixel linked lists' append (ppll.h, list_store.h), after
 * oit_glsl_fragment_gen and premultiplied.glsl: a node a fragment, pushed
 * onto its pixel's list. The counter runs past u_capacity so that the
 * frame's need is known when the pool overflowed (list_store.h, Sizing). */
layout(std430, binding = OIT_BIND_COUNTS) buffer Heads { uint heads[]; };
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Next { uint next[]; };
layout(std430, binding = OIT_BIND_STATE) buffer Stats { uint counter; uint max_len; uint total; };
layout(location = OIT_LOC_CAPACITY) uniform uint u_capacity;
void main() {
    if (oit_clipped()) discard;
    uint n = atomicAdd(counter, 1u);
    if (n >= u_capacity) return;
    nodes[n] = oit_fragment();
    next[n] = atomicExchange(heads[oit_pixel_index()], n);
}
