/* The vertex stage's bindings and transforms, which the compute capture's
 * triangle set-up shares (frag_glsl.h, oit_glsl_vertex_lib; srgb.glsl and
 * tie_plane.glsl follow it). */
layout(std430, binding = OIT_BIND_VERTS) readonly buffer Verts { uvec4 verts[]; };
layout(location = OIT_LOC_VIEW) uniform mat4 u_view;
layout(location = OIT_LOC_PROJ) uniform mat4 u_proj;
/* Source indices of sourced draws (frag_glsl.h, "Primitive id"). */
layout(std430, binding = OIT_BIND_PRIMS) readonly buffer Prims { uint prims[]; };
layout(location = OIT_LOC_EYE) uniform dvec3 u_eye;
/* Model to world (oit_view.model; the identity changes no bit). */
layout(location = OIT_LOC_MODEL) uniform mat4 u_model;
vec3 oit_world(uvec4 v) { return (u_model * vec4(uintBitsToFloat(v.xyz), 1.0)).xyz; }
layout(location = OIT_LOC_MODE) uniform int u_mode;
layout(location = OIT_LOC_ATTRS) uniform uint u_attrs;
/* oit_shading.colour_space (shade.h, "Colour space"); set by name. */
uniform int u_colour_space;
