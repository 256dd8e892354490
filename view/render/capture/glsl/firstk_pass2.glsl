/* Pass 2's own rect, after firstk_totals.glsl: the pack's overflow box
 * (ahead mode, dispatched by the GPU over it, so that the host need not
 * read the box back) or the band u_rect the host gave. */
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_RECT) uniform ivec4 u_rect;
uniform int u_from_box;
ivec4 oit_pass2_rect() { return u_from_box != 0 ? oit_box() : u_rect; }
