/* shade.c's oit_srgb_decode / oit_srgb_encode, per channel. */
vec3 oit_srgb_decode(vec3 c) {
    c = max(c, vec3(0.0));
    return mix(pow((c + 0.055) / 1.055, vec3(2.4)), c / 12.92,
               lessThanEqual(c, vec3(0.04045)));
}
vec3 oit_srgb_encode(vec3 c) {
    c = max(c, vec3(0.0));
    return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c,
               lessThanEqual(c, vec3(0.0031308)));
}
