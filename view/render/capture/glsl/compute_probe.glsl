/* Whether the driver cuts loops short (compute_tiles.glsl says why that
 * matters): the iterations a loop of u_probe ran. */
layout(local_size_x = 1) in;
layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Probe { uint ran; };
uniform int u_probe;
void main() {
    int i = 0;
    while (i < u_probe) i++;
    ran = uint(i);
}
