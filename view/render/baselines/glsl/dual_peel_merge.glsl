/* Dual peeling's merge (dual_peel.h), after oit_glsl_composite,
 * oit_glsl_premultiplied and dual_back_acc.glsl. The pair read is the one
 * the pass peeled against: its nearest names the front layer, its
 * farthest the back one unless both are the same. */
layout(local_size_x = 8, local_size_y = 8) in;
layout(location = OIT_LOC_SIZE) uniform ivec2 u_size;
uniform int u_first;
layout(binding = OIT_TEX_LAYER) uniform sampler2D u_minmax;
layout(rgba32ui, binding = OIT_IMG_FRONT) readonly uniform uimage2D u_front;
layout(rgba32ui, binding = OIT_IMG_BACK) readonly uniform uimage2D u_back;
layout(std430, binding = OIT_BIND_STATE) buffer State { oit_state states[]; };
layout(std430, binding = OIT_BIND_SUMS) buffer Back { back_acc backs[]; };
void main() {
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    uint p = uint(px.y * u_size.x + px.x);
    oit_state s = u_first != 0 ? oit_state_begin() : states[p];
    back_acc b = u_first != 0 ? back_acc(vec3(0.0), 1.0, 0u) : backs[p];
    vec2 nf = texelFetch(u_minmax, px, 0).xy;
    if (-nf.x <= nf.y) {
        oit_composite(s, imageLoad(u_front, px));
        b.n++;
        if (nf.y > -nf.x) {
            vec4 c = oit_premultiplied(imageLoad(u_back, px));
            b.C = c.rgb + (1.0 - c.a) * b.C;
            b.T *= 1.0 - c.a;
            b.n++;
        }
    }
    states[p] = s;
    backs[p] = b;
}
