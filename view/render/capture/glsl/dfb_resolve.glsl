/* Both DFB resolves' declarations: the band of rows u_rows whose fragments
 * start at offset u_base in the store (before oit_glsl_segment_composite,
 * which sorts the frags declared here). */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_BASE) uniform uint u_base;
layout(location = OIT_LOC_ROWS) uniform ivec2 u_rows;
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = OIT_BIND_FRAGS) buffer Frags { uvec4 frags[]; };
