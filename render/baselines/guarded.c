/* Guarded OIT (guarded.h) on the list store (list_store.h): a unit is one
 * node; pixel p's head words are [2p] the list (newest node) and [2p + 1]
 * the nearest stored node. */
#include "render/baselines/guarded.h"
#include "render/baselines/methods.h"

#include "render/gl/gl_util.h"
#include "render/baselines/list_store.h"

/* A node is written before it is published (exchange or swap), and Nodes
 * is coherent, so a node a guard reads through either head word is whole.
 * Nodes at or past u_capacity were never written (an overflowing pass that
 * is drawn again): a guard that would need one does not cull. */
static const char append_fs[] =
    "layout(std430, binding = OIT_BIND_COUNTS) coherent buffer Heads { uint heads[]; };\n"
    "layout(std430, binding = OIT_BIND_FRAGS) coherent buffer Nodes { uvec4 nodes[]; };\n"
    "layout(std430, binding = OIT_BIND_TOTALS) writeonly buffer Next { uint next[]; };\n"
    "layout(std430, binding = OIT_BIND_STATE) "
    "buffer Stats { uint counter; uint max_len; uint total; };\n"
    "layout(location = 13) uniform uint u_capacity;\n"
    "uniform float u_threshold;\n"
    "bool nearer(uvec4 a, uvec4 b) {\n"
    "    return a.x < b.x || (a.x == b.x && (a.y & 0x7fffffffu) < (b.y & 0x7fffffffu));\n"
    "}\n"
    "bool culled(uvec4 f, uint p) {\n"
    "    uint h = heads[2u * p + 1u];\n"
    "    if (h >= u_capacity) return false;\n"
    "    uvec4 H = nodes[h];\n"
    "    if (!nearer(H, f)) return false;\n"
    "    float imp = oit_premultiplied(f).a * (1.0 - oit_premultiplied(H).a);\n"
    "    if (imp < u_threshold) return true;\n"
    "    uint k = heads[2u * p];\n"
    "    if (k == h || k >= u_capacity) return false;\n"
    "    uvec4 K = nodes[k];\n"
    "    return nearer(K, f) && imp * (1.0 - oit_premultiplied(K).a) < u_threshold;\n"
    "}\n"
    "void main() {\n"
    "    if (oit_clipped()) discard;\n"
    "    uvec4 f = oit_fragment();\n"
    "    uint p = oit_pixel_index();\n"
    "    if (culled(f, p)) return;\n"
    "    uint n = atomicAdd(counter, 1u);\n"
    "    if (n >= u_capacity) return;\n"
    "    nodes[n] = f;\n"
    "    memoryBarrierBuffer();\n"
    "    next[n] = atomicExchange(heads[2u * p], n);\n"
    "    uint h = heads[2u * p + 1u];\n"
    "    while (h == 0xffffffffu || (h < u_capacity && nearer(f, nodes[h]))) {\n"
    "        uint seen = atomicCompSwap(heads[2u * p + 1u], h, n);\n"
    "        if (seen == h) break;\n"
    "        h = seen;\n"
    "    }\n"
    "}\n";

/* 0xffffffff means no node, so it is no node index. A pass that overflows
 * counts as if guards past the pool never culled, so the pool doubles at
 * most per pass rather than growing to PLL's size at once. */
static const oit_list_desc desc = {"guarded OIT", append_fs, OIT_LIST_NODE_WALK(2u), 1, 2,
                                   0xfffffffeull, 2};

static oit_status oit_guarded_init(oit_guarded *g, oit_error *err)
{
    oit_status s = oit_list_store_init(g, &desc, err);
    if (s == OIT_OK)
        s = oit_guarded_set_threshold(g, OIT_GUARDED_DEFAULT_THRESHOLD, err);
    return s;
}

oit_status oit_guarded_set_threshold(oit_guarded *g, float threshold, oit_error *err)
{
    if (!(threshold >= 0.0f && threshold < 1.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "guarded OIT: threshold %g is outside "
                             "[0, 1)", (double)threshold);
    GLuint prog = oit_list_store_append_program(g);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_threshold"), threshold);
    return oit_gl_check("guarded OIT: threshold", err);
}

OIT_BASELINE_METHOD_FRAMED(guarded, oit_guarded, desc.method, oit_guarded_init,
                           oit_list_store_release, oit_list_store_render, OIT_LIST_FRAME,
                           OIT_METHOD_EPSILON, OIT_THRESHOLD);
