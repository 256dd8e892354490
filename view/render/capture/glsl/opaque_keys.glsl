/* The opaque pre-pass (opaque_keys.h): each opaque fragment's tie-rule key
 * as a float, which GL_MIN blending keeps the least of per pixel (a
 * positive key orders as its bits do), exact and order-free. */
layout(location = OIT_OUT_COLOUR) out float o_key;
void main() {
    if (v_opaque == 0u || oit_clipped()) discard;
    o_key = uintBitsToFloat(oit_fragment_key());
}
