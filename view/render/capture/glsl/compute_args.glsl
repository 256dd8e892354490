/* A work list's tiles into its indirect dispatch's groups, on the GPU so
 * that the host reads nothing back: rows of 65535 (the least
 * GL_MAX_COMPUTE_WORK_GROUP_COUNT), none when it is empty. */
layout(local_size_x = 1) in;
layout(std430, binding = OIT_BIND_OUT) buffer Work { uvec4 work_hdr; };
void main() {
    uint c = work_hdr.w;
    work_hdr.xyz = uvec3(min(c, 65535u), (c + 65534u) / 65535u, 1u);
}
