/* The tie rule's plane (shade.h, oit_depth_plane): in double from the
 * float vertices, rounded to float, so that every triangle of one plane
 * carries the same numbers; the normal is then rotated into view space. */
vec4 oit_tie_plane(vec3 p0, vec3 p1, vec3 p2) {
    dvec3 q0 = dvec3(p0);
    dvec3 nn = cross(dvec3(p1) - q0, dvec3(p2) - q0);
    double len = sqrt(dot(nn, nn));
    if (!(len > 0.0lf)) return vec4(0.0);
    dvec3 nu = nn / len;
    vec3 n = vec3(nu);
    /* Rotated term by term, in shade.c's order (reference.c key_hits):
     * precise forbids the compiler to fuse or reorder (GLSL 4.50 4.7.1). */
    precise vec3 r;
    r.x = u_view[0].x * n.x + u_view[1].x * n.y + u_view[2].x * n.z;
    r.y = u_view[0].y * n.x + u_view[1].y * n.y + u_view[2].y * n.z;
    r.z = u_view[0].z * n.x + u_view[1].z * n.y + u_view[2].z * n.z;
    return vec4(r, float(dot(nu, q0 - u_eye)));
}
