/* Saturated screen tiles (saturation.h), after mode.glsl and
 * oit_glsl_state_io: one workgroup per OIT_SATURATION_TILE-square tile,
 * the largest channel of T over its pixels, so that the stream can skip a
 * part whose every pixel is below epsilon. T >= 0, so its float bits
 * order like the floats and atomicMax on uint works. */
layout(local_size_x = OIT_SATURATION_TILE, local_size_y = OIT_SATURATION_TILE) in;
layout(std430, binding = OIT_BIND_SUMS) writeonly buffer Tiles { uint tiles[]; };
layout(location = OIT_LOC_TILES_SIZE) uniform ivec2 u_size;
/* x, y of the first tile; tiles a row */
layout(location = OIT_LOC_TILE0) uniform ivec3 u_tile0;
shared uint m;
void main() {
    if (gl_LocalInvocationIndex == 0u) m = 0u;
    barrier();
    ivec2 tile = ivec2(gl_WorkGroupID.xy) + u_tile0.xy;
    ivec2 px = tile * OIT_SATURATION_TILE + ivec2(gl_LocalInvocationID.xy);
    if (px.x < u_size.x && px.y < u_size.y) {
        vec3 T = oit_state_T(uint(px.y * u_size.x + px.x));
        atomicMax(m, floatBitsToUint(max(T.x, max(T.y, T.z))));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) tiles[tile.y * u_tile0.z + tile.x] = m;
}
