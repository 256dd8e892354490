/* The counted capture's count pass, after saturated.glsl: each pixel's
 * fragments that are not clipped, behind the opaque depth or saturated.
 * The store runs the same rasterization with the same tests, so every
 * counted fragment finds its slot. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
void main() {
    uint p;
    if (!oit_capture_keeps(p)) discard;
    atomicAdd(counts[p], 1u);
}
