/* The counted capture's count pass, after saturated.glsl: each pixel's
 * fragments that are not clipped, behind the opaque depth or saturated.
 * The store runs the same rasterization with the same tests, so every
 * counted fragment finds its slot. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
void main() {
    if (oit_clipped()) discard;
    uint p = oit_pixel_index();
    if (oit_behind_opaque()) discard;
    if (oit_saturated(p)) discard;
    atomicAdd(counts[p], 1u);
}
