/* Dual depth peeling's geometry pass (dual_peel.h), after
 * oit_glsl_fragment_gen. u_init: the first pass, which only gathers every
 * fragment's (-near, far) pair. A layer fragment stores and is discarded,
 * so the query counts only the fragments left inside, and image stores
 * before a discard still land. */
layout(binding = OIT_TEX_LAYER) uniform sampler2D u_minmax;
layout(rgba32ui, binding = OIT_IMG_FRONT) writeonly uniform uimage2D u_front;
layout(rgba32ui, binding = OIT_IMG_BACK) writeonly uniform uimage2D u_back;
uniform int u_init;
layout(location = OIT_OUT_COLOUR) out vec2 o_minmax;
void main() {
    if (oit_clipped()) discard;
    uvec4 f = oit_fragment();
    float t = uintBitsToFloat(f.x);
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 nf = u_init != 0 ? vec2(-t, t) : texelFetch(u_minmax, px, 0).xy;
    float near = -nf.x, far = nf.y;
    if (t < near || t > far) discard;
    if (u_init != 0 || (t > near && t < far)) { o_minmax = vec2(-t, t); return; }
    if (t == near) imageStore(u_front, px, f); else imageStore(u_back, px, f);
    discard;
}
