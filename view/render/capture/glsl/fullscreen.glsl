/* A triangle over the whole viewport (three vertices, no buffer): the
 * stencil target's per-sample passes, which touch every pixel the scissor
 * lets through. */
void main() {
    vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1);
    gl_Position = vec4(p, 0.0, 1.0);
}
