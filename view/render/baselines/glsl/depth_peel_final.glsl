/* Depth peeling's last pass (depth_peel.h), after oit_glsl_composite:
 * each pixel's state over the background, in the image's encoding. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
layout(std430, binding = OIT_BIND_STATE) readonly buffer State { oit_state states[]; };
layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    out_rgba[p] = oit_state_final(states[p]);
}
