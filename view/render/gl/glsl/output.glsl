/* The background in the compositing space, and the compositing space's
 * result in the image's encoding (shade.c, oit_pixel_end); they need
 * u_colour_space and u_background declared (composite_uniforms.glsl). */
vec3 oit_background() {
    return u_colour_space == 1 ? oit_srgb_decode(u_background) : u_background;
}
vec3 oit_output(vec3 c) {
    return u_colour_space == 1 ? oit_srgb_encode(c) : c;
}
