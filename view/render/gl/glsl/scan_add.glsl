/* The prefix sum's last pass (scan_glsl.h): the scanned block sums added back. */
layout(local_size_x = 256) in;
layout(std430, binding = OIT_BIND_COUNTS) buffer Data { uint data[]; };
layout(std430, binding = OIT_BIND_SUMS) readonly buffer Sums { uint sums[]; };
layout(location = OIT_LOC_COUNT) uniform uint u_count;
uniform uint u_group0;
void main() {
    uint i = (gl_WorkGroupID.x + u_group0) * 256u + gl_LocalInvocationID.x;
    if (i < u_count) data[i] += sums[i / 1024u];
}
