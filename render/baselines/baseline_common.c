/* Shared pieces of the baseline methods (baseline_common.h). */
#include "render/baselines/baseline_common.h"

#include "base/clock.h"
#include "render/image.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Mirrors the decoding in oit_composite (frag_glsl.c). */
const char oit_glsl_premultiplied[] =
    "vec4 oit_premultiplied(uvec4 f) {\n"
    "    if (u_mode == 1) {\n"
    "        vec2 la = unpackUnorm2x16(f.z);\n"
    "        return vec4(vec3(la.x * la.y), la.y);\n"
    "    }\n"
    "    vec2 rg = unpackUnorm2x16(f.z), ba = unpackUnorm2x16(f.w);\n"
    "    return vec4(vec3(rg, ba.x) * ba.y, ba.y);\n"
    "}\n";

const char oit_glsl_sorted_resolve[] =
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(location = 11) uniform ivec2 u_size;\n"
    "layout(std430, binding = OIT_BIND_STATE) "
    "buffer Stats { uint counter; uint max_len; uint total; };\n"
    "layout(std430, binding = OIT_BIND_OUT) writeonly buffer Out { vec4 out_rgba[]; };\n"
    "#define LOCAL_MAX 32u\n"
    "#define OIT_LIST_END 0xffffffffu\n"
    "uint oit_list_first(uint p);\n"
    "uint oit_list_next(uint it);\n"
    "uvec4 oit_list_load(uint it);\n"
    "bool oit_list_can_relink();\n"
    "void oit_list_relink(uint it, uint next);\n"
    "bool oit_list_index(uint first, uint n);\n"
    "uint oit_list_at(uint k);\n"
    "void oit_list_store(uint it, uvec4 f);\n"
    /* In-place heap sort over the walk's k-th positions, for stores that can
     * reach them directly (oit_list_index true): O(n log n), as above. */
    "void oit_list_sift(uint root, uint n) {\n"
    "    for (;;) {\n"
    "        uint child = 2u * root + 1u;\n"
    "        if (child >= n) return;\n"
    "        uint a = oit_list_at(child);\n"
    "        if (child + 1u < n && oit_frag_less(oit_list_load(a), oit_list_load(oit_list_at(child + 1u)))) {\n"
    "            child++;\n"
    "            a = oit_list_at(child);\n"
    "        }\n"
    "        uint r = oit_list_at(root);\n"
    "        uvec4 x = oit_list_load(r), y = oit_list_load(a);\n"
    "        if (!oit_frag_less(x, y)) return;\n"
    "        oit_list_store(r, y);\n"
    "        oit_list_store(a, x);\n"
    "        root = child;\n"
    "    }\n"
    "}\n"
    "void oit_list_heap_sort(uint n) {\n"
    "    for (uint i = n / 2u; i > 0u; i--) oit_list_sift(i - 1u, n);\n"
    "    for (uint e = n - 1u; e > 0u; e--) {\n"
    "        uint a = oit_list_at(0u), b = oit_list_at(e);\n"
    "        uvec4 x = oit_list_load(a);\n"
    "        oit_list_store(a, oit_list_load(b));\n"
    "        oit_list_store(b, x);\n"
    "        oit_list_sift(0u, e);\n"
    "    }\n"
    "}\n"
    /* Bottom-up merge sort of a list by relinking (stable, O(n log n)), for
     * stores whose every fragment has its own link. llvmpipe ends a
     * shader's loops after 65535 iterations in all, so the quadratic walk
     * below stops early, silently, beyond about 256 fragments a pixel. */
    "uint oit_list_sort(uint head) {\n"
    "    for (uint k = 1u;; k *= 2u) {\n"
    "        uint p = head, tail = OIT_LIST_END, merges = 0u;\n"
    "        head = OIT_LIST_END;\n"
    "        while (p != OIT_LIST_END) {\n"
    "            merges++;\n"
    "            uint q = p, psize = 0u, qsize = k;\n"
    "            while (psize < k && q != OIT_LIST_END) { psize++; q = oit_list_next(q); }\n"
    "            while (psize > 0u || (qsize > 0u && q != OIT_LIST_END)) {\n"
    "                bool take_p = qsize == 0u || q == OIT_LIST_END;\n"
    "                if (!take_p && psize > 0u) take_p = !oit_frag_less(oit_list_load(q), oit_list_load(p));\n"
    "                uint e;\n"
    "                if (take_p) { e = p; p = oit_list_next(p); psize--; }\n"
    "                else { e = q; q = oit_list_next(q); qsize--; }\n"
    "                if (tail == OIT_LIST_END) head = e; else oit_list_relink(tail, e);\n"
    "                tail = e;\n"
    "            }\n"
    "            p = q;\n"
    "        }\n"
    "        oit_list_relink(tail, OIT_LIST_END);\n"
    "        if (merges <= 1u) return head;\n"
    "    }\n"
    "    return head;\n"
    "}\n"
    "void composite_long(inout oit_state s, uint first, uint n) {\n"
    "    uvec4 last = uvec4(0u);\n"
    "    for (uint k = 0u; k < n; k++) {\n"
    "        uvec4 best = uvec4(0xffffffffu);\n"
    "        for (uint i = first; i != OIT_LIST_END; i = oit_list_next(i)) {\n"
    "            uvec4 x = oit_list_load(i);\n"
    "            if ((k == 0u || oit_frag_less(last, x)) && oit_frag_less(x, best)) best = x;\n"
    "        }\n"
    "        oit_composite(s, best);\n"
    "        last = best;\n"
    "    }\n"
    "}\n"
    "void main() {\n"
    "    ivec2 px = ivec2(gl_GlobalInvocationID.xy);\n"
    "    if (px.x >= u_size.x || px.y >= u_size.y) return;\n"
    "    uint p = uint(px.y * u_size.x + px.x);\n"
    "    uint first = oit_list_first(p), n = 0u;\n"
    "    for (uint i = first; i != OIT_LIST_END; i = oit_list_next(i)) n++;\n"
    "    atomicMax(max_len, n);\n"
    "    atomicAdd(total, n);\n"
    "    oit_state s = oit_state_begin();\n"
    "    if (n <= LOCAL_MAX) {\n"
    "        uvec4 f[LOCAL_MAX];\n"
    "        uint m = 0u;\n"
    "        for (uint i = first; i != OIT_LIST_END; i = oit_list_next(i)) {\n"
    "            uvec4 x = oit_list_load(i);\n"
    "            OIT_SORTED_INSERT(f, m, x)\n"
    "            m++;\n"
    "        }\n"
    "        for (uint i = 0u; i < m; i++) oit_composite(s, f[i]);\n"
    "    } else if (oit_list_can_relink()) {\n"
    "        for (uint i = oit_list_sort(first); i != OIT_LIST_END; i = oit_list_next(i))\n"
    "            oit_composite(s, oit_list_load(i));\n"
    "    } else if (oit_list_index(first, n)) {\n"
    "        oit_list_heap_sort(n);\n"
    "        for (uint k = 0u; k < n; k++) oit_composite(s, oit_list_load(oit_list_at(k)));\n"
    "    } else {\n"
    "        composite_long(s, first, n);\n"
    "    }\n"
    "    out_rgba[p] = oit_state_final(s);\n"
    "}\n";

oit_status oit_gpu_buffers_reserve(oit_gpu_buffers *b, int which, uint64_t bytes,
                                   oit_error *err)
{
    char what[96];
    snprintf(what, sizeof what, "%s %s", b->method, b->names[which]);
    oit_status s = oit_gl_buffer_reserve(&b->buf[which], &b->cap[which], bytes, what, err);
    oit_gpu_buffers_note(b);
    return s;
}

oit_status oit_gpu_buffers_reserve_all(oit_gpu_buffers *b, int n, const uint64_t *bytes,
                                       oit_error *err)
{
    oit_status s = OIT_OK;
    for (int i = 0; i < n && s == OIT_OK; i++)
        if (bytes[i])
            s = oit_gpu_buffers_reserve(b, i, bytes[i], err);
    return s;
}

void oit_gpu_buffers_note(oit_gpu_buffers *b)
{
    uint64_t held = b->texture_bytes;
    for (int i = 0; i < OIT_GPU_BUFFERS_MAX; i++)
        held += b->cap[i];
    if (held > b->peak)
        b->peak = held;
}

void oit_gpu_buffers_release(oit_gpu_buffers *b)
{
    glDeleteBuffers(OIT_GPU_BUFFERS_MAX, b->buf);
    memset(b->buf, 0, sizeof b->buf);
    memset(b->cap, 0, sizeof b->cap);
}

oit_status oit_peel_passes_create(oit_peel_passes *p, const char *method, const char *peel_fs,
                                  const char *const *merge_cs, const char *const *final_cs,
                                  oit_error *err)
{
    char what[96];
    const char *vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    const char *fs[] = {oit_glsl_version, oit_glsl_fragment_gen, peel_fs, NULL};
    snprintf(what, sizeof what, "%s pass", method);
    oit_status s = oit_gl_program_graphics(what, vs, fs, &p->peel, err);
    snprintf(what, sizeof what, "%s merge", method);
    if (s == OIT_OK)
        s = oit_gl_program_compute(what, merge_cs, &p->merge, err);
    snprintf(what, sizeof what, "%s final", method);
    if (s == OIT_OK)
        s = oit_gl_program_compute(what, final_cs, &p->final, err);
    if (s != OIT_OK)
        return s;
    glCreateFramebuffers(2, p->fbo);
    glCreateQueries(GL_ANY_SAMPLES_PASSED, 1, &p->query);
    snprintf(what, sizeof what, "%s: framebuffers and query", method);
    return oit_gl_check(what, err);
}

void oit_peel_passes_release(oit_peel_passes *p)
{
    glDeleteProgram(p->peel);
    glDeleteProgram(p->merge);
    glDeleteProgram(p->final);
    glDeleteFramebuffers(2, p->fbo);
    glDeleteQueries(1, &p->query);
    memset(p, 0, sizeof *p);
}

void oit_peel_passes_set_view(const oit_peel_passes *p, const oit_view *v)
{
    oit_glsl_set_view(p->peel, v);
    oit_glsl_set_view(p->merge, v);
    oit_glsl_set_view(p->final, v);
}

int oit_peel_passes_draw(const oit_peel_passes *p, const oit_gpu_mesh *const *meshes, int n)
{
    oit_baseline_draw(p->peel, GL_ANY_SAMPLES_PASSED, p->query, meshes, n);
    GLuint any = 0;
    glGetQueryObjectuiv(p->query, GL_QUERY_RESULT, &any);
    return any != 0;
}

void oit_peel_passes_merge(const oit_peel_passes *p, int first, int w, int h)
{
    glProgramUniform1i(p->merge, glGetUniformLocation(p->merge, "u_first"), first);
    oit_baseline_dispatch_frame(p->merge, w, h);
}

void oit_baseline_draw(GLuint prog, GLenum query_target, GLuint query,
                       const oit_gpu_mesh *const *meshes, int n)
{
    glUseProgram(prog);
    if (query)
        glBeginQuery(query_target, query);
    for (int i = 0; i < n; i++)
        oit_gpu_mesh_draw(meshes[i], prog);
    if (query)
        glEndQuery(query_target);
}

void oit_baseline_dispatch_frame(GLuint prog, int w, int h)
{
    glUseProgram(prog);
    glDispatchCompute(oit_gl_groups((uint64_t)w, 8), oit_gl_groups((uint64_t)h, 8), 1);
}

void oit_baseline_stats(oit_frame_stats *stats, double t0, uint64_t fragments,
                        uint32_t max_layers, uint64_t bytes_peak, uint32_t batches)
{
    memset(stats, 0, sizeof *stats);
    stats->ms = oit_time_ms() - t0;
    stats->fragments = fragments;
    stats->max_layers = max_layers;
    stats->gpu_bytes_peak = bytes_peak;
    stats->batches = batches;
}

oit_status oit_baseline_begin(const char *method, const oit_view *view, int n, oit_view *v,
                              double *t0, oit_error *err)
{
    *t0 = oit_time_ms();
    *v = *view;
    oit_shading_resolve_defaults(&v->shading);
    GLint max_w = 0, max_h = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_w);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_h);
    if (v->width <= 0 || v->height <= 0 || v->width > max_w || v->height > max_h || n < 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: frame %dx%d (with %d meshes) is "
                             "not renderable (at most %dx%d pixels)", method, v->width,
                             v->height, n, max_w, max_h);
    return OIT_OK;
}

/* tmp holds w*h RGBA floats, bottom row first. */
static void flip_into(const float *tmp, oit_image *out)
{
    size_t row = (size_t)out->width * 4;
    for (int y = 0; y < out->height; y++) {
        float *dst = out->rgba + (size_t)y * row;
        memcpy(dst, tmp + (size_t)(out->height - 1 - y) * row, row * sizeof *dst);
        for (int x = 0; x < out->width; x++)
            dst[4 * x + 3] = 1.0f;
    }
}

static oit_status read_any(const char *method, GLuint obj, int is_texture, int w, int h,
                           oit_image *out, oit_error *err)
{
    size_t bytes = (size_t)w * h * 16;
    float *tmp = malloc(bytes);
    if (!tmp)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate %zu bytes for the "
                             "readback", method, bytes);
    oit_status s = oit_image_alloc(out, w, h, err);
    if (s == OIT_OK) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        if (is_texture)
            glGetTextureImage(obj, 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, tmp);
        else
            glGetNamedBufferSubData(obj, 0, (GLsizeiptr)bytes, tmp);
        s = oit_gl_check(is_texture ? "readback: glGetTextureImage"
                                    : "readback: glGetNamedBufferSubData", err);
        if (s == OIT_OK)
            flip_into(tmp, out);
        else
            oit_image_free(out);
    }
    free(tmp);
    return s;
}

oit_status oit_baseline_read_texture(const char *method, GLuint tex, int w, int h,
                                     oit_image *out, oit_error *err)
{
    return read_any(method, tex, 1, w, h, out, err);
}

oit_status oit_baseline_read_buffer(const char *method, GLuint buf, int w, int h,
                                    oit_image *out, oit_error *err)
{
    return read_any(method, buf, 0, w, h, out, err);
}
