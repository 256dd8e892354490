/* Depth peeling's merge (depth_peel.h), after oit_glsl_composite: the
 * layer joins the state of its pixel; u_first starts the state. A layer
 * texel of t = +inf bits is a pixel the pass kept nothing at. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
uniform int u_first;
layout(binding = OIT_TEX_LAYER) uniform usampler2D u_layer;
layout(std430, binding = OIT_BIND_STATE) buffer State { oit_state states[]; };
layout(std430, binding = OIT_BIND_COUNTS) buffer Count { uint count; };
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = u_first != 0 ? oit_state_begin() : states[p];
    uvec4 f = texelFetch(u_layer, px, 0);
    if (f.x != 0x7f800000u) { oit_composite(s, f); atomicAdd(count, 1u); }
    states[p] = s;
}
