/* A predicted band's resolve, its declarations: before
 * counted_predicted.glsl and oit_glsl_segment_composite,
 * counted_predicted_main.glsl after. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
layout(std430, binding = OIT_BIND_FRAGS) buffer Frags { uvec4 frags[]; };
layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Next { uint next_counts[]; };
