/* Early termination: a pixel whose carried transmittance is below
 * u_epsilon in every channel can gain at most epsilon from anything behind
 * it, so its later fragments are dropped before they take a slot. A fill
 * stage cannot include oit_glsl_composite (its uniforms clash with the
 * fragment generator's); its program puts oit_glsl_state_io before this. */
uniform float u_epsilon;
bool oit_saturated(uint p) {
    if (u_epsilon <= 0.0) return false;
    vec3 T = oit_state_T(p);
    return max(T.r, max(T.g, T.b)) < u_epsilon;
}
/* The capture fills' first tests of a fragment, in this order: outside a
 * section plane, behind the caller's opaque depth, on a saturated pixel.
 * false: the fragment is neither counted nor stored; else p is its
 * pixel. */
bool oit_capture_keeps(out uint p) {
    if (oit_clipped()) return false;
    p = oit_pixel_index();
    if (oit_behind_opaque()) return false;
    return !oit_saturated(p);
}
