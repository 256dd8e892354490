/* Pass 2's resolve, its declarations: before firstk_totals.glsl,
 * firstk_pass2.glsl, rect_index.glsl and oit_glsl_segment_composite
 * (which sorts the frags declared here), firstk_segment_main.glsl after. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Table { uvec2 table[]; };
layout(std430, binding = OIT_BIND_FRAGS) buffer Frags { uvec4 frags[]; };
