/* Compositing's uniforms (frag_glsl.h, oit_glsl_composite); srgb.glsl,
 * output.glsl, state_struct.glsl and composite.glsl follow. */
layout(location = OIT_LOC_MODE) uniform int u_mode;
uniform int u_colour_space;
layout(location = OIT_LOC_SIGMA) uniform float u_sigma;
layout(location = OIT_LOC_BACKGROUND) uniform vec3 u_background;
