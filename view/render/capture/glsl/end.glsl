/* The frame's end, after count_flag.glsl: pixels [u_first, u_first +
 * u_count) give their totals and (u_out 1) their final colour at
 * out_rgba[0..u_count), or (u_out 2) only their fragment count, in
 * out_rgba[i].x (a heat map's: exact below 2^24), so that a frame's output can be read in bands
 * through a buffer smaller than the frame. The totals are summed in the
 * workgroup first: a million invocations adding to one word serialise on
 * it. */
layout(local_size_x = 64) in;
layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };
layout(location = OIT_LOC_COUNT) uniform uint u_count;
uniform uint u_first;
uniform int u_out;
uniform uint u_group0;
shared uint g_lo, g_hi, g_max;
void main() {
    if (gl_LocalInvocationIndex == 0u) { g_lo = 0u; g_hi = 0u; g_max = 0u; }
    barrier();
    uint i = (gl_WorkGroupID.x + u_group0) * 64u + gl_LocalInvocationID.x;
    if (i < u_count && u_out == 2) { /* the counts alone: read after the colours */
        out_rgba[i] = vec4(float(oit_state_load(u_first + i).nfrag), 0.0, 0.0, 0.0);
    } else if (i < u_count) {
        oit_state s = oit_state_load(u_first + i);
        if (u_out != 0) out_rgba[i] = oit_state_final(s);
        atomicMax(g_max, s.nfrag);
        uint old = atomicAdd(g_lo, s.nfrag);
        if (old + s.nfrag < old) atomicAdd(g_hi, 1u);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && (g_lo | g_hi) != 0u) {
        atomicMax(f_max, g_max);
        uint old = atomicAdd(f_lo, g_lo);
        atomicAdd(f_hi, g_hi + (old + g_lo < old ? 1u : 0u));
    }
}
