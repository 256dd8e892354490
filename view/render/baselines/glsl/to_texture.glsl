/* The head of a pass that writes a frame's colour into an RGBA32F texture
 * (baseline_common.h, oit_glsl_to_texture): F2B's final pass and WBOIT's
 * resolve end in the image's encoding over the background as every other
 * method does, so they share the declarations that srgb.glsl and
 * output.glsl (view/render/gl/glsl/), concatenated after this, need. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(location = OIT_LOC_BACKGROUND) uniform vec3 u_background;
uniform int u_colour_space;
layout(rgba32f, binding = OIT_IMG_OUT) writeonly uniform image2D u_out;
