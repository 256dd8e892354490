/* B3D's deepest pixel (b3d.h): the slot array's layers. One global atomic
 * per group rather than per pixel. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(std430, binding = OIT_BIND_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_STATE) buffer Stats { uint counter; uint max_len; uint total; };
shared uint group_max;
void main() {
    if (gl_LocalInvocationIndex == 0u) group_max = 0u;
    barrier();
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x < u_size.x && px.y < u_size.y)
        atomicMax(group_max, counts[px.y * u_size.x + px.x]);
    barrier();
    if (gl_LocalInvocationIndex == 0u) atomicMax(max_len, group_max);
}
