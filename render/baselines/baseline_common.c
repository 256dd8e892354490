/* Shared pieces of the baseline methods (baseline_common.h). */
#include "render/baselines/baseline_common.h"

#include "base/clock.h"
#include "render/image/image.h"

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

void oit_baseline_dispatch_to_texture(GLuint prog, GLuint out, int w, int h)
{
    glBindImageTexture(OIT_IMG_OUT, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    oit_baseline_dispatch_frame(prog, w, h);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
}

uint64_t oit_baseline_pixel_bytes(const void *impl, const oit_view *view)
{
    (void)impl;
    (void)view;
    return OIT_BASELINE_PIXEL_BYTES;
}

oit_status oit_baseline_begin(const char *method, const oit_view *view, int n,
                              oit_baseline_frame *fr, oit_error *err)
{
    memset(fr, 0, sizeof *fr);
    fr->t0 = oit_time_ms();
    fr->view = *view;
    oit_view *v = &fr->view;
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

oit_status oit_baseline_end(oit_baseline_frame *fr, oit_frame_stats *stats, oit_status s)
{
    if (s == OIT_OK && stats) {
        *stats = fr->stats;
        stats->ms = oit_time_ms() - fr->t0;
    }
    return s;
}

GLuint oit_baseline_texture(GLenum format, int w, int h)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    oit_gl_poison_texture(t, format);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

static oit_status read_any(const char *method, GLuint obj, int is_texture, int w, int h,
                           oit_image *out, oit_error *err)
{
    oit_status s = oit_image_alloc(out, w, h, err);
    if (s == OIT_OK)
        s = oit_gl_read_rows(obj, is_texture, w, h, 16, out->rgba, method, err);
    if (s != OIT_OK) {
        oit_image_free(out);
        return s;
    }
    for (size_t i = 3; i < (size_t)w * h * 4; i += 4)
        out->rgba[i] = 1.0f;
    return OIT_OK;
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

oit_status oit_blend_passes_init(oit_blend_passes *p, const char *method,
                                 const oit_glsl_program *programs, int n_prog,
                                 const GLenum *formats, int n_tex, int attached, oit_error *err)
{
    p->method = method;
    p->n_prog = n_prog;
    p->n_tex = n_tex;
    p->attached = attached;
    memcpy(p->format, formats, sizeof *formats * (size_t)n_tex);
    char what[96];
    snprintf(what, sizeof what, "%s: framebuffer and query", method);
    oit_status s = oit_glsl_programs_build(NULL, programs, n_prog, p->prog, err);
    if (s == OIT_OK)
        s = oit_gl_framebuffer_create(&p->fbo, &p->query, what, err);
    return s;
}

void oit_blend_passes_release(oit_blend_passes *p)
{
    oit_glsl_programs_delete(p->prog, p->n_prog);
    glDeleteFramebuffers(1, &p->fbo);
    glDeleteQueries(1, &p->query);
    glDeleteTextures(p->n_tex, p->tex);
}

static oit_status blend_targets(oit_blend_passes *p, int w, int h, oit_error *err)
{
    if (p->tex[0] && p->w == w && p->h == h)
        return OIT_OK;
    static const GLenum colour[OIT_BLEND_TARGETS_MAX] = {
        GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glDeleteTextures(p->n_tex, p->tex);
    p->bytes = 0;
    for (int i = 0; i < p->n_tex; i++) {
        p->tex[i] = oit_baseline_texture(p->format[i], w, h);
        p->bytes += (uint64_t)w * h * (p->format[i] == GL_R32F ? 4 : 16);
    }
    for (int i = 0; i < p->attached; i++)
        glNamedFramebufferTexture(p->fbo, colour[i], p->tex[i], 0);
    glNamedFramebufferDrawBuffers(p->fbo, p->attached, colour);
    p->w = w;
    p->h = h;
    if (p->bytes > p->peak)
        p->peak = p->bytes;
    char what[96];
    snprintf(what, sizeof what, "%s: float targets", p->method);
    return oit_gl_check(what, err);
}

oit_status oit_blend_passes_begin(oit_blend_passes *p, const oit_view *v, oit_error *err)
{
    oit_status s = blend_targets(p, v->width, v->height, err);
    if (s == OIT_OK)
        oit_glsl_set_view_all(p->prog, p->n_prog, v);
    return s;
}

oit_status oit_blend_passes_end(oit_blend_passes *p, int result, uint64_t bytes_peak,
                                oit_image *out, oit_frame_stats *stats, oit_error *err)
{
    char what[96];
    snprintf(what, sizeof what, "%s: passes", p->method);
    oit_status s = oit_gl_check(what, err);
    if (s == OIT_OK)
        s = oit_baseline_read_texture(p->method, p->tex[result], p->w, p->h, out, err);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(p->query, GL_QUERY_RESULT, &samples);
    *stats = (oit_frame_stats){.fragments = samples, .gpu_bytes_peak = bytes_peak, .batches = 1};
    return s;
}
