/* The caller's opaque depth and the opaque triangles' least keys
 * (frag_glsl.h, oit_behind_opaque). A fragment at the least key is kept:
 * the opaque one itself, and coplanar ones the tie rule orders. */
layout(binding = OIT_TEX_OPAQUE_DEPTH) uniform sampler2D u_opaque_depth;
layout(binding = OIT_TEX_OPAQUE_KEYS) uniform sampler2D u_opaque_keys;
layout(location = OIT_LOC_OPAQUE) uniform int u_opaque;
layout(location = OIT_LOC_OPAQUE_ORIGIN) uniform ivec2 u_opaque_origin;
uniform int u_opaque_keyed;
bool oit_behind_opaque() {
    if (u_opaque_keyed != 0 && oit_fragment_key() >
        floatBitsToUint(texelFetch(u_opaque_keys, ivec2(OIT_FRAG_COORD.xy), 0).r))
        return true;
    if (u_opaque == 0) return false;
    ivec2 q = ivec2(OIT_FRAG_COORD.xy) + u_opaque_origin;
    return OIT_FRAG_COORD.z >= texelFetch(u_opaque_depth, q, 0).r;
}
