/* Dual peeling's last pass (dual_peel.h), after oit_glsl_composite and
 * dual_back_acc.glsl: front state over back accumulation over the
 * background, and the figures. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(std430, binding = OIT_BIND_STATE) readonly buffer State { oit_state states[]; };
layout(std430, binding = OIT_BIND_SUMS) readonly buffer Back { back_acc backs[]; };
layout(std430, binding = OIT_BIND_COUNTS) buffer Count { uint fragments; uint max_len; };
layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = states[p];
    back_acc b = backs[p];
    atomicAdd(fragments, b.n);
    atomicMax(max_len, b.n);
    out_rgba[p] = vec4(oit_output(s.C + s.T * (b.C + b.T * oit_background())), 1.0);
}
