/* Per-pixel linked lists (ppll.h). Buffers are in GL row order; the node
 * payload (packed fragment, 16 bytes) and its link (4 bytes) live in two
 * arrays so the payload keeps frag_glsl.h's packing. */
#include "render/ppll.h"

#include "render/baseline_common.h"
#include "render/image.h"

#include <stdlib.h>
#include <string.h>

/* heads, node payloads, links, {counter, max list length}, output. */
enum { BUF_HEADS, BUF_NODES, BUF_NEXT, BUF_STATS, BUF_OUT, BUF_N };
/* Two bindings of frag_glsl.h that no PLL program uses for their own sake. */
enum { BIND_NEXT = OIT_BIND_TOTALS, BIND_STATS = OIT_BIND_STATE };

#define END_OF_LIST 0xffffffffu

struct oit_pll {
    GLuint append_prog, resolve_prog, fbo;
    GLuint buf[BUF_N];
    uint64_t cap[BUF_N];
    uint64_t nodes; /* capacity in nodes */
    uint64_t bytes_peak;
};

static const char append_fs[] =
    "layout(std430, binding = 1) buffer Heads { uint heads[]; };\n"
    "layout(std430, binding = 3) writeonly buffer Nodes { uvec4 nodes[]; };\n"
    "layout(std430, binding = 5) writeonly buffer Next { uint next[]; };\n"
    "layout(std430, binding = 6) buffer Stats { uint counter; uint max_len; };\n"
    "layout(location = 13) uniform uint u_capacity;\n"
    "void main() {\n"
    "    uint n = atomicAdd(counter, 1u);\n"
    "    if (n >= u_capacity) return;\n"
    "    nodes[n] = oit_fragment();\n"
    "    next[n] = atomicExchange(heads[oit_pixel_index()], n);\n"
    "}\n";

static const char resolve_cs[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(std430, binding = 1) readonly buffer Heads { uint heads[]; };\n"
    "layout(std430, binding = 3) readonly buffer Nodes { uvec4 nodes[]; };\n"
    "layout(std430, binding = 5) buffer Next { uint next[]; };\n"
    "layout(std430, binding = 6) buffer Stats { uint counter; uint max_len; };\n"
    "layout(std430, binding = 4) writeonly buffer Out { vec4 out_rgba[]; };\n"
    "#define LOCAL_MAX 32u\n"
    "#define END 0xffffffffu\n"
    /* Bottom-up merge sort of the list by relinking (stable, O(n log n)):
     * llvmpipe ends a shader's loops after 65535 iterations in all, so a
     * quadratic walk silently stops early beyond ~256 fragments. */
    "uint sort_list(uint head) {\n"
    "    for (uint k = 1u;; k *= 2u) {\n"
    "        uint p = head, tail = END, merges = 0u;\n"
    "        head = END;\n"
    "        while (p != END) {\n"
    "            merges++;\n"
    "            uint q = p, psize = 0u, qsize = k;\n"
    "            while (psize < k && q != END) { psize++; q = next[q]; }\n"
    "            while (psize > 0u || (qsize > 0u && q != END)) {\n"
    "                bool take_p = qsize == 0u || q == END;\n"
    "                if (!take_p && psize > 0u) take_p = !oit_frag_less(nodes[q], nodes[p]);\n"
    "                uint e;\n"
    "                if (take_p) { e = p; p = next[p]; psize--; }\n"
    "                else { e = q; q = next[q]; qsize--; }\n"
    "                if (tail == END) head = e; else next[tail] = e;\n"
    "                tail = e;\n"
    "            }\n"
    "            p = q;\n"
    "        }\n"
    "        next[tail] = END;\n"
    "        if (merges <= 1u) return head;\n"
    "    }\n"
    "    return head;\n"
    "}\n"
    "void main() {\n"
    "    ivec2 px = ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_size.x || px.y >= u_size.y) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint n = 0u;\n"
    "    for (uint i = heads[p]; i != END; i = next[i]) n++;\n"
    "    atomicMax(max_len, n);\n"
    "    oit_state s = oit_state_begin();\n"
    "    if (n <= LOCAL_MAX) {\n"
    "        uvec4 f[LOCAL_MAX];\n"
    "        uint m = 0u;\n"
    "        for (uint i = heads[p]; i != END; i = next[i]) {\n"
    "            uvec4 x = nodes[i];\n"
    "            OIT_SORTED_INSERT(f, m, x)\n"
    "            m++;\n"
    "        }\n"
    "        for (uint i = 0u; i < m; i++) oit_composite(s, f[i]);\n"
    "    } else {\n"
    "        for (uint i = sort_list(heads[p]); i != END; i = next[i]) oit_composite(s, nodes[i]);\n"
    "    }\n"
    "    out_rgba[p] = oit_state_final(s);\n"
    "}\n";

static oit_status build_programs(oit_pll *p, oit_error *err)
{
    const char *vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    const char *afs[] = {oit_glsl_version, oit_glsl_fragment_gen, append_fs, NULL};
    const char *rcs[] = {oit_glsl_version, oit_glsl_composite, resolve_cs, NULL};
    oit_status s = oit_gl_program_graphics("PLL append pass", vs, afs, &p->append_prog, err);
    if (s == OIT_OK)
        s = oit_gl_program_compute("PLL resolve", rcs, &p->resolve_prog, err);
    return s;
}

oit_status oit_pll_create(oit_pll **out, oit_error *err)
{
    *out = NULL;
    oit_pll *p = calloc(1, sizeof *p);
    if (!p)
        return oit_error_set(err, OIT_ERR_NOMEM, "PLL: out of memory");
    oit_status s = build_programs(p, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &p->fbo);
        s = oit_gl_check("PLL: glCreateFramebuffers", err);
    }
    if (s != OIT_OK) {
        oit_pll_destroy(p);
        return s;
    }
    *out = p;
    return OIT_OK;
}

void oit_pll_destroy(oit_pll *p)
{
    if (!p)
        return;
    glDeleteProgram(p->append_prog);
    glDeleteProgram(p->resolve_prog);
    glDeleteFramebuffers(1, &p->fbo);
    glDeleteBuffers(BUF_N, p->buf);
    free(p);
}

uint64_t oit_pll_capacity(const oit_pll *p)
{
    return p->nodes;
}

static oit_status reserve(oit_pll *p, int which, uint64_t bytes, oit_error *err)
{
    static const char *names[BUF_N] = {"PLL heads", "PLL nodes", "PLL links",
                                       "PLL counters", "PLL output"};
    oit_status s = oit_gl_buffer_reserve(&p->buf[which], &p->cap[which], bytes,
                                         names[which], err);
    uint64_t held = 0;
    for (int i = 0; i < BUF_N; i++)
        held += p->cap[i];
    if (held > p->bytes_peak)
        p->bytes_peak = held;
    return s;
}

/* Node buffer of at least 'nodes' entries, within one storage block. */
static oit_status reserve_nodes(oit_pll *p, uint64_t nodes, oit_error *err)
{
    if (nodes > UINT32_MAX - 1)
        return oit_error_set(err, OIT_ERR_NOMEM, "PLL: %llu fragments do not fit 32-bit "
                             "node indices", (unsigned long long)nodes);
    oit_status s = oit_gl_check_ssbo_size(nodes * 16, "PLL node buffer", err);
    if (s == OIT_OK)
        s = reserve(p, BUF_NODES, nodes * 16, err);
    if (s == OIT_OK)
        s = reserve(p, BUF_NEXT, nodes * 4, err);
    if (s == OIT_OK) {
        /* The margin reserve added is usable, within one block. */
        GLint64 max_block = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
        uint64_t have = p->cap[BUF_NEXT] / 4;
        uint64_t block = (uint64_t)max_block / 16;
        p->nodes = have < block ? have : block;
    }
    return s;
}

/* One geometry pass; *total receives the frame's fragment count, which
 * exceeds p->nodes when the node buffer overflowed. */
static oit_status append_pass(oit_pll *p, const oit_gpu_mesh *const *meshes, int n,
                              uint64_t *total, oit_error *err)
{
    static const GLuint end = END_OF_LIST, zero = 0;
    glClearNamedBufferData(p->buf[BUF_HEADS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    glClearNamedBufferData(p->buf[BUF_STATS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, p->buf[BUF_HEADS]);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, p->buf[BUF_NODES], 0,
                      (GLsizeiptr)(p->nodes * 16));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, BIND_NEXT, p->buf[BUF_NEXT], 0,
                      (GLsizeiptr)(p->nodes * 4));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_STATS, p->buf[BUF_STATS]);
    glProgramUniform1ui(p->append_prog, OIT_LOC_COUNT, (GLuint)p->nodes);
    glUseProgram(p->append_prog);
    for (int i = 0; i < n; i++)
        oit_gpu_mesh_draw(meshes[i], p->append_prog);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint count = 0;
    glGetNamedBufferSubData(p->buf[BUF_STATS], 0, 4, &count);
    *total = count;
    return oit_gl_check("PLL: append pass", err);
}

static oit_status prepare(oit_pll *p, const oit_view *v, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    oit_status s = oit_gl_check_ssbo_size(pixels * 16, "PLL: the frame's output", err);
    if (s == OIT_OK)
        s = reserve(p, BUF_HEADS, pixels * 4, err);
    if (s == OIT_OK)
        s = reserve(p, BUF_STATS, 16, err);
    if (s == OIT_OK)
        s = reserve(p, BUF_OUT, pixels * 16, err);
    if (s == OIT_OK && p->nodes == 0)
        s = reserve_nodes(p, pixels, err);
    if (s != OIT_OK)
        return s;
    glNamedFramebufferParameteri(p->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, v->width);
    glNamedFramebufferParameteri(p->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, v->height);
    oit_glsl_raster_begin(p->fbo, v->width, v->height);
    oit_glsl_set_view(p->append_prog, v);
    oit_glsl_set_view(p->resolve_prog, v);
    return oit_gl_check("PLL: frame set-up", err);
}

/* Append, and once more with a grown node buffer when it overflowed. */
static oit_status build_lists(oit_pll *p, const oit_gpu_mesh *const *meshes, int n,
                              uint64_t *total, uint32_t *passes, oit_error *err)
{
    *passes = 1;
    oit_status s = append_pass(p, meshes, n, total, err);
    if (s != OIT_OK || *total <= p->nodes)
        return s;
    s = reserve_nodes(p, *total, err);
    if (s == OIT_OK) {
        *passes = 2;
        s = append_pass(p, meshes, n, total, err);
    }
    if (s == OIT_OK && *total > p->nodes)
        s = oit_error_set(err, OIT_ERR_GL, "PLL: the second pass made %llu fragments, more "
                          "than the %llu the first counted", (unsigned long long)*total,
                          (unsigned long long)p->nodes);
    return s;
}

static oit_status resolve(oit_pll *p, const oit_view *v, uint32_t *max_len, oit_error *err)
{
    glUseProgram(p->resolve_prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, p->buf[BUF_OUT]);
    glDispatchCompute(oit_gl_groups((uint64_t)v->width, 8),
                      oit_gl_groups((uint64_t)v->height, 8), 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(p->buf[BUF_STATS], 4, 4, max_len);
    return oit_gl_check("PLL: resolve", err);
}

oit_status oit_pll_render(oit_pll *p, const oit_gpu_mesh *const *meshes, int n,
                          const oit_view *view, oit_image *out, oit_frame_stats *stats,
                          oit_error *err)
{
    oit_status s = oit_baseline_check_frame("PLL", view, n, err);
    if (s != OIT_OK)
        return s;
    double t0 = oit_time_ms();
    oit_view v = *view;
    oit_shading_resolve_defaults(&v.shading);
    uint64_t total = 0;
    uint32_t passes = 0, max_len = 0;
    s = prepare(p, &v, err);
    if (s == OIT_OK)
        s = build_lists(p, meshes, n, &total, &passes, err);
    if (s == OIT_OK)
        s = resolve(p, &v, &max_len, err);
    if (s == OIT_OK)
        s = oit_baseline_read_buffer("PLL", p->buf[BUF_OUT], v.width, v.height, out, err);
    if (s != OIT_OK || !stats)
        return s;
    memset(stats, 0, sizeof *stats);
    stats->ms = oit_time_ms() - t0;
    stats->fragments = total;
    stats->max_layers = max_len;
    stats->gpu_bytes_peak = p->bytes_peak;
    stats->batches = passes;
    return OIT_OK;
}
