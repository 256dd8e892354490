/* Per-tile early termination, after mode.glsl, oit_glsl_state_io and
 * compute_common.glsl, so that the set-up and the scatter skip dead tiles:
 * tile_dead starts all 1 (a buffer clear); a pixel of the rect whose
 * carried T is not below epsilon in some channel marks its tile live
 * (every writer writes 0). */
layout(local_size_x = CS_TILE, local_size_y = CS_TILE) in;
layout(std430, binding = OIT_BIND_TOTALS) buffer TileDead { uint tile_dead[]; };
uniform ivec2 u_tile0;
uniform float u_epsilon;
void main() {
    ivec2 tile = u_tile0 + ivec2(gl_WorkGroupID.xy);
    ivec2 px = tile * CS_TILE + ivec2(gl_LocalInvocationID.xy);
    if (any(lessThan(px, u_rect.xy)) || any(greaterThanEqual(px, u_rect.zw))) return;
    vec3 T = oit_state_T(uint(px.y) * uint(u_size.x) + uint(px.x));
    if (max(T.r, max(T.g, T.b)) >= u_epsilon)
        tile_dead[uint(tile.y) * cs_tiles_x() + uint(tile.x)] = 0u;
}
