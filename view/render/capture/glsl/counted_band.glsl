/* The counted capture's band as its judge left it (capture_counted.c): the
 * store and the resolve read the band's first offset and the store's
 * capacity here, written on the GPU, not from the host. */
layout(std430, binding = OIT_BIND_SUMS) readonly buffer Band { uint band_gate; uint band_short; uint band_deep; uint band_pad; uvec4 band_groups; uint band_base; uint band_cap; };
