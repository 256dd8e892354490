/* F2B's sort keys (f2b.h), after f2b_per_triangle.glsl: the key orders
 * like the float view depth of the centroid (sign flipped into order), so
 * the CPU sorts plain integers. */
layout(std430, binding = OIT_BIND_COUNTS) writeonly buffer Keys { uint keys[]; };
layout(location = OIT_LOC_VIEW) uniform mat4 u_view;
vec3 corner(uint v) { return uintBitsToFloat(verts[v].xyz); }
void main() {
    uint i = triangle();
    if (i >= u_window_count) return;
    vec3 c = (corner(3u * i) + corner(3u * i + 1u) + corner(3u * i + 2u)) / 3.0;
    uint b = floatBitsToUint(-(u_view * vec4(c, 1.0)).z);
    keys[u_mesh_base + u_window_first + i] = (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}
