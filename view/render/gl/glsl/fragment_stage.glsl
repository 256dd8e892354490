/* The fragment stage's inputs from vertex.glsl, and what the library
 * reads as the pixel and the primitive (frag_glsl.h, oit_glsl_fragment_gen). */
layout(location = OIT_LOC_MODE) uniform int u_mode;
in vec3 v_pos;
in vec4 v_rgba;
flat in vec3 v_normal;
flat in uint v_first_prim;
flat in vec4 v_plane;
flat in uint v_opaque;
#define OIT_FRAG_COORD gl_FragCoord
#define OIT_PRIMITIVE_ID gl_PrimitiveID
