/* The prefix sum's first pass (scan_glsl.h): each 1024-element block scanned in
 * shared memory; the first level also sums the 64-bit total, the largest
 * element and the elements over the threshold. */
layout(local_size_x = 256) in;
layout(std430, binding = OIT_BIND_COUNTS) buffer Data { uint data[]; };
layout(std430, binding = OIT_BIND_SUMS) writeonly buffer Sums { uint sums[]; };
layout(std430, binding = OIT_BIND_TOTALS) buffer Totals {
    uint t_lo; uint t_hi; uint t_max; uint t_over;
};
layout(location = OIT_LOC_COUNT) uniform uint u_count;
layout(location = OIT_LOC_FIRST_LEVEL) uniform int u_first_level;
uniform uint u_group0;
uniform uint u_over;
shared uint part[256];
void main() {
    uint lid = gl_LocalInvocationID.x, group = gl_WorkGroupID.x + u_group0;
    uint base = group * 1024u + lid * 4u;
    uint v[4]; uint sum = 0u, mx = 0u, over = 0u;
    for (uint i = 0u; i < 4u; i++) {
        v[i] = base + i < u_count ? data[base + i] : 0u;
        sum += v[i]; mx = max(mx, v[i]);
        over += v[i] > u_over ? 1u : 0u;
    }
    part[lid] = sum;
    barrier();
    for (uint off = 1u; off < 256u; off <<= 1) {
        uint add = lid >= off ? part[lid - off] : 0u;
        barrier();
        part[lid] += add;
        barrier();
    }
    uint run = part[lid] - sum;
    for (uint i = 0u; i < 4u; i++) {
        if (base + i < u_count) data[base + i] = run;
        run += v[i];
    }
    if (u_first_level != 0) {
        atomicMax(t_max, mx);
        if (over != 0u) atomicAdd(t_over, over);
        /* 64-bit total from 32-bit atomics: a wrap of the low word carries. */
        if (lid == 255u) {
            uint old = atomicAdd(t_lo, part[255]);
            if (old + part[255] < old) atomicAdd(t_hi, 1u);
        }
    }
    if (lid == 255u) sums[group] = part[255];
}
