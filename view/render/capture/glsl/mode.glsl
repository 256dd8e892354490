/* The shading mode (1: translucent), which oit_glsl_state_io reads for a
 * pixel's state layout, for a compute stage without oit_glsl_composite
 * (which declares it too). */
layout(location = OIT_LOC_MODE) uniform int u_mode;
