/* Unsorted blending (unsorted.h), after oit_glsl_fragment_gen and
 * premultiplied.glsl: premultiplied "over" in whatever order the
 * fragments come. */
layout(location = OIT_OUT_COLOUR) out vec4 o_colour;
void main() { if (oit_clipped()) discard; o_colour = oit_premultiplied(oit_fragment()); }
