/* A predicted band (capture_counted.h): the last frame's offsets of the
 * batch at OIT_BIND_OFFSETS give each pixel its segment, the band's
 * fragments from the offset at pixel u_band_pixel on, in a store of u_cap;
 * a pixel whose count outgrew its segment was not held, and the band's
 * spill pass takes it. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
uniform uint u_band_pixel;
uniform uint u_cap;
bool oit_predicted_holds(uint p, uint n) {
    return n <= offsets[p + 1u] - offsets[p] &&
           offsets[p + 1u] - offsets[u_band_pixel] <= u_cap;
}
