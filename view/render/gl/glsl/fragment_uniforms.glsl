/* The fragment library's uniforms but u_mode (frag_glsl.h). */
layout(location = OIT_LOC_ATTRS) uniform uint u_attrs;
layout(location = OIT_LOC_ALPHA) uniform float u_alpha;
layout(location = OIT_LOC_DEFAULT_RGB) uniform vec3 u_default_rgb;
layout(location = OIT_LOC_WIDTH) uniform int u_width;
