/* The capture's state buffer (frag_glsl.h, oit_glsl_state_io), after
 * state_struct.glsl. The XOR-ed T is only ever held as bits: as a float it
 * may be denormal, which a driver is free to flush. */
layout(std430, binding = OIT_BIND_STATE) buffer State { uint state_words[]; };
const uint OIT_ONE_BITS = 0x3f800000u;
uint oit_state_base(uint p) { return p * (u_mode == 1 ? 12u : 5u); }
uvec3 oit_state_bits3(uint w) {
    return uvec3(state_words[w], state_words[w + 1u], state_words[w + 2u]);
}
void oit_state_put3(uint w, uvec3 b) {
    state_words[w] = b.x; state_words[w + 1u] = b.y; state_words[w + 2u] = b.z;
}
vec3 oit_state_T(uint p) {
    uint w = oit_state_base(p);
    if (u_mode != 1) return vec3(uintBitsToFloat(state_words[w + 3u] ^ OIT_ONE_BITS));
    return uintBitsToFloat(oit_state_bits3(w + 4u) ^ uvec3(OIT_ONE_BITS));
}
oit_state oit_state_load(uint p) {
    uint w = oit_state_base(p);
    oit_state s;
    s.C = uintBitsToFloat(oit_state_bits3(w));
    s.T = oit_state_T(p);
    if (u_mode != 1) {
        s.t_prev = 0.0; s.nest = 0; s.medium = vec3(0.0); s.nfrag = state_words[w + 4u];
        return s;
    }
    s.t_prev = uintBitsToFloat(state_words[w + 3u]);
    s.nest = int(state_words[w + 7u]);
    s.medium = uintBitsToFloat(oit_state_bits3(w + 8u));
    s.nfrag = state_words[w + 11u];
    return s;
}
void oit_state_store(uint p, oit_state s) {
    uint w = oit_state_base(p);
    oit_state_put3(w, floatBitsToUint(s.C));
    if (u_mode != 1) {
        state_words[w + 3u] = floatBitsToUint(s.T.r) ^ OIT_ONE_BITS;
        state_words[w + 4u] = s.nfrag;
        return;
    }
    state_words[w + 3u] = floatBitsToUint(s.t_prev);
    oit_state_put3(w + 4u, floatBitsToUint(s.T) ^ uvec3(OIT_ONE_BITS));
    state_words[w + 7u] = uint(s.nest);
    oit_state_put3(w + 8u, floatBitsToUint(s.medium));
    state_words[w + 11u] = s.nfrag;
}
