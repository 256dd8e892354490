/* The stencil self-test's read-back (capture_stencil.h): each pixel's K
 * samples' primitives (.y without the facing bit), in GL rows, pixel by
 * pixel, so that the host can check where routing put each fragment. */
layout(local_size_x = 1) in;
layout(binding = OIT_TEX_SAMPLES) uniform usampler2DMS u_samples;
layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { uint prims[]; };
layout(location = OIT_LOC_K) uniform int u_K;
void main() {
    ivec2 px = ivec2(gl_WorkGroupID.xy);
    uint p = uint(px.y) * gl_NumWorkGroups.x + uint(px.x);
    for (int i = 0; i < u_K; i++)
        prims[p * uint(u_K) + uint(i)] = texelFetch(u_samples, px, i).y & 0x7fffffffu;
}
