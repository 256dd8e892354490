/* Guarded OIT's append (guarded.h, list_store.h), after
 * oit_glsl_fragment_gen and premultiplied.glsl; head words [2p] the list
 * (newest node) and [2p + 1] the nearest stored node. A node is written
 * before it is published (exchange or swap), and Nodes is coherent, so a
 * node a guard reads through either head word is whole. Nodes at or past
 * u_capacity were never written (an overflowing pass that is drawn again):
 * a guard that would need one does not cull. */
layout(std430, binding = OIT_BIND_COUNTS) coherent buffer Heads { uint heads[]; };
layout(std430, binding = OIT_BIND_FRAGS) coherent buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Next { uint next[]; };
layout(std430, binding = OIT_BIND_STATE) buffer Stats { uint counter; uint max_len; uint total; };
layout(location = OIT_LOC_CAPACITY) uniform uint u_capacity;
uniform float u_threshold;
bool nearer(uvec4 a, uvec4 b) {
    return a.x < b.x || (a.x == b.x && (a.y & 0x7fffffffu) < (b.y & 0x7fffffffu));
}
bool culled(uvec4 f, uint p) {
    uint h = heads[2u * p + 1u];
    if (h >= u_capacity) return false;
    uvec4 H = nodes[h];
    if (!nearer(H, f)) return false;
    float imp = oit_premultiplied(f).a * (1.0 - oit_premultiplied(H).a);
    if (imp < u_threshold) return true;
    uint k = heads[2u * p];
    if (k == h || k >= u_capacity) return false;
    uvec4 K = nodes[k];
    return nearer(K, f) && imp * (1.0 - oit_premultiplied(K).a) < u_threshold;
}
void main() {
    if (oit_clipped()) discard;
    uvec4 f = oit_fragment();
    uint p = oit_pixel_index();
    if (culled(f, p)) return;
    uint n = atomicAdd(counter, 1u);
    if (n >= u_capacity) return;
    nodes[n] = f;
    memoryBarrierBuffer();
    next[n] = atomicExchange(heads[2u * p], n);
    uint h = heads[2u * p + 1u];
    while (h == 0xffffffffu || (h < u_capacity && nearer(f, nodes[h]))) {
        uint seen = atomicCompSwap(heads[2u * p + 1u], h, n);
        if (seen == h) break;
        h = seen;
    }
}
