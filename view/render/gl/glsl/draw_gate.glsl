/* The multi-draw gate (gpu_mesh.h): every command's instance count set to 1
 * where the gate word is nonzero, else 0, so that the GPU decides whether
 * the draws rasterize anything. */
layout(local_size_x = 64) in;
layout(std430, binding = OIT_BIND_OUT) buffer Cmds { uvec4 cmds[]; };
layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Gate { uint gate_words[]; };
uniform uint u_word;
uniform uint u_count;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < u_count) cmds[i].y = gate_words[u_word] != 0u ? 1u : 0u;
}
