/* Front-to-back blending with early discarding (f2b.h). Per frame: key
 * pass, CPU sort, gather pass, blend pass (in chunks, each reading a copy
 * of what the chunks before left), final pass. Triangle indices count
 * across the frame's meshes (u_mesh_base: triangles of the meshes
 * before). */
#include "view/render/baselines/f2b.h"
#include "view/render/baselines/methods.h"

#include "base/grow.h"
#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/image/image.h"

#include <stdlib.h>

enum { BUF_KEYS, BUF_RANK, BUF_SORTED, BUF_N };
/* TEX_SEEN: the accumulation as the chunks before the current one left
 * it, the only target the blend shader reads. */
enum { TEX_ACCUM, TEX_OUT, TEX_SEEN, TEX_N };
enum { PROG_BLEND, PROG_KEY, PROG_GATHER, PROG_FINAL, PROG_N };
enum { TRI_BYTES = 48 };

struct oit_f2b {
    oit_blend_passes p;
    oit_gpu_buffers b;
    oit_gpu_mesh *sorted;       /* a view of buf[BUF_SORTED] */
    uint64_t *pairs, *scratch;  /* CPU sort: key << 32 | triangle */
    uint32_t *words;            /* keys read back, then ranks sent */
    size_t host_cap;            /* entries of the three above */
};

static const char *const buffer_names[BUF_N] = {"sort keys", "ranks", "sorted triangles"};

/* glsl/f2b_*.glsl: the blend pass's fragment stage, the sort keys and the
 * gather (each after glsl/f2b_per_triangle.glsl), and the final pass
 * (after oit_glsl_to_texture). */
extern const char oit_f2b_blend_fs[], oit_f2b_key_cs[], oit_f2b_gather_cs[], oit_f2b_final_cs[];

static const oit_glsl_program programs[PROG_N] = {
    [PROG_BLEND] = {"F2B blend pass", .fs = {oit_glsl_premultiplied, oit_f2b_blend_fs}},
    [PROG_KEY] = {"F2B sort keys", .cs = {oit_f2b_key_cs}},
    [PROG_GATHER] = {"F2B gather", .cs = {oit_f2b_gather_cs}},
    [PROG_FINAL] = {"F2B final", .cs = {oit_glsl_to_texture, oit_f2b_final_cs}},
};

void oit_f2b_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_baseline_visit_table(programs, PROG_N, visit, user);
}

static oit_status oit_f2b_init(oit_f2b *f, oit_error *err)
{
    f->b.method = "F2B";
    f->b.names = buffer_names;
    static const GLenum formats[TEX_N] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA32F};
    oit_status s = oit_blend_passes_init(&f->p, "F2B", programs, PROG_N, formats, TEX_N, 1, err);
    if (s == OIT_OK)
        s = oit_f2b_set_threshold(f, OIT_F2B_DEFAULT_THRESHOLD, err);
    return s;
}

static void oit_f2b_release(oit_f2b *f)
{
    oit_blend_passes_release(&f->p);
    oit_gpu_mesh_destroy(f->sorted);
    oit_gpu_buffers_release(&f->b);
    free(f->pairs);
    free(f->scratch);
    free(f->words);
}

oit_status oit_f2b_set_threshold(oit_f2b *f, float threshold, oit_error *err)
{
    if (!(threshold >= 0.0f && threshold < 1.0f))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "F2B: alpha threshold %g is outside "
                             "[0, 1)", (double)threshold);
    GLuint blend = f->p.prog[PROG_BLEND];
    glProgramUniform1f(blend, glGetUniformLocation(blend, "u_threshold"), threshold);
    return oit_gl_check("F2B: threshold", err);
}

static oit_status reserve_host(oit_f2b *f, size_t n, oit_error *err)
{
    if (n <= f->host_cap)
        return OIT_OK;
    int ok = 1;
    f->pairs = oit_grow(f->pairs, n, sizeof *f->pairs, &ok);
    f->scratch = oit_grow(f->scratch, n, sizeof *f->scratch, &ok);
    f->words = oit_grow(f->words, n, sizeof *f->words, &ok);
    if (!ok)
        return oit_error_set(err, OIT_ERR_NOMEM, "F2B: cannot allocate the sort of %zu "
                             "triangles", n);
    f->host_cap = n;
    return OIT_OK;
}

/* Buffers for 'tris' triangles; the keys and ranks must fit one binding. */
static oit_status reserve_triangles(oit_f2b *f, uint64_t tris, oit_error *err)
{
    if (tris >= 0xffffffffull)
        return oit_error_set(err, OIT_ERR_NOMEM, "F2B: %llu triangles exceed 32-bit ranks",
                             (unsigned long long)tris);
    oit_status s = oit_gl_check_ssbo_size(tris * 4, "F2B sort keys", err);
    if (s == OIT_OK)
        s = reserve_host(f, (size_t)tris, err);
    if (s == OIT_OK)
        s = oit_gpu_buffers_reserve_all(&f->b, BUF_N, (const uint64_t[BUF_N]){
            tris * 4, tris * 4, tris * TRI_BYTES}, err);
    if (s == OIT_OK && !f->sorted)
        s = oit_gpu_mesh_create_view(f->b.buf[BUF_SORTED], &f->sorted, err);
    return s;
}

/* Runs prog once per triangle of every mesh. */
static void per_triangle(GLuint prog, const oit_gpu_mesh *const *meshes, int n)
{
    GLint base_loc = glGetUniformLocation(prog, "u_mesh_base");
    uint64_t base = 0;
    for (int i = 0; i < n; i++) {
        glProgramUniform1ui(prog, base_loc, (GLuint)base);
        oit_gpu_mesh_dispatch(meshes[i], prog, 64);
        base += oit_gpu_mesh_triangles(meshes[i]);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* Stable LSD radix sort of v[0..n) by bits 32..63; an even number of
 * passes leaves the result in v. */
static void sort_by_key(uint64_t *v, uint64_t *tmp, size_t n)
{
    for (int shift = 32; shift < 64; shift += 8) {
        size_t start[257] = {0};
        for (size_t i = 0; i < n; i++)
            start[((v[i] >> shift) & 255) + 1]++;
        for (int b = 0; b < 256; b++)
            start[b + 1] += start[b];
        for (size_t i = 0; i < n; i++)
            tmp[start[(v[i] >> shift) & 255]++] = v[i];
        uint64_t *swap = v;
        v = tmp;
        tmp = swap;
    }
}

/* Keys down, ranks up: rank[triangle] = its place front to back. */
static oit_status sort_triangles(oit_f2b *f, size_t tris, oit_error *err)
{
    glGetNamedBufferSubData(f->b.buf[BUF_KEYS], 0, (GLsizeiptr)(tris * 4), f->words);
    for (size_t i = 0; i < tris; i++)
        f->pairs[i] = (uint64_t)f->words[i] << 32 | i;
    sort_by_key(f->pairs, f->scratch, tris);
    for (size_t j = 0; j < tris; j++)
        f->words[(uint32_t)f->pairs[j]] = (uint32_t)j;
    glNamedBufferSubData(f->b.buf[BUF_RANK], 0, (GLsizeiptr)(tris * 4), f->words);
    return oit_gl_check("F2B: sort", err);
}

static oit_status order(oit_f2b *f, const oit_gpu_mesh *const *meshes, int n, uint64_t tris,
                        oit_error *err)
{
    oit_status s = reserve_triangles(f, tris, err);
    if (s != OIT_OK)
        return s;
    oit_gpu_mesh_set_range(f->sorted, 0, (size_t)tris, 0);
    if (tris == 0)
        return OIT_OK;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->b.buf[BUF_KEYS]);
    per_triangle(f->p.prog[PROG_KEY], meshes, n);
    s = sort_triangles(f, (size_t)tris, err);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, f->b.buf[BUF_RANK]);
    size_t window = oit_gpu_triangle_window();
    for (uint64_t lo = 0; s == OIT_OK && lo < tris; lo += window) {
        uint64_t count = tris - lo < window ? tris - lo : window;
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, f->b.buf[BUF_SORTED],
                          (GLintptr)(lo * TRI_BYTES), (GLsizeiptr)(count * TRI_BYTES));
        GLuint gather = f->p.prog[PROG_GATHER];
        glProgramUniform1ui(gather, glGetUniformLocation(gather, "u_out_first"), (GLuint)lo);
        glProgramUniform1ui(gather, glGetUniformLocation(gather, "u_out_count"), (GLuint)count);
        per_triangle(gather, meshes, n);
    }
    return s == OIT_OK ? oit_gl_check("F2B: ordering passes", err) : s;
}

uint64_t oit_f2b_chunk_triangles(uint64_t tris)
{
    /* triangles whose bytes keep a chunk's offset aligned */
    uint64_t unit = oit_gpu_triangle_step(oit_gl_ssbo_align());
    uint64_t share = (tris + OIT_F2B_CHUNKS - 1) / OIT_F2B_CHUNKS;
    return share == 0 ? unit : (share + unit - 1) / unit * unit;
}

/* The sorted triangles in chunks: each draw's termination test reads
 * TEX_SEEN, the accumulation copied after the chunk before (T = 1 for the
 * first), so no draw samples the texture it blends into. Copies are not
 * shader writes: GL orders them with the draws around them. */
static void blend(oit_f2b *f, uint64_t tris)
{
    static const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    oit_glsl_raster_begin(f->p.fbo, f->p.w, f->p.h);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferfv(f->p.fbo, GL_COLOR, 0, clear);
    glClearTexImage(f->p.tex[TEX_SEEN], 0, GL_RGBA, GL_FLOAT, clear);
    glBindTextureUnit(OIT_TEX_ACCUM, f->p.tex[TEX_SEEN]);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_SRC_ALPHA);
    glUseProgram(f->p.prog[PROG_BLEND]);
    glBeginQuery(GL_SAMPLES_PASSED, f->p.query);
    uint64_t chunk = oit_f2b_chunk_triangles(tris);
    for (uint64_t lo = 0; lo < tris; lo += chunk) {
        if (lo > 0)
            glCopyImageSubData(f->p.tex[TEX_ACCUM], GL_TEXTURE_2D, 0, 0, 0, 0,
                               f->p.tex[TEX_SEEN], GL_TEXTURE_2D, 0, 0, 0, 0, f->p.w, f->p.h, 1);
        uint64_t n = tris - lo < chunk ? tris - lo : chunk;
        oit_gpu_mesh_set_range(f->sorted, lo * TRI_BYTES, (size_t)n, (uint32_t)lo);
        oit_gpu_mesh_draw(f->sorted, f->p.prog[PROG_BLEND]);
    }
    glEndQuery(GL_SAMPLES_PASSED);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
}

static void finish(oit_f2b *f)
{
    glTextureBarrier();
    glBindTextureUnit(OIT_TEX_ACCUM, f->p.tex[TEX_ACCUM]);
    oit_baseline_dispatch_to_texture(f->p.prog[PROG_FINAL], f->p.tex[TEX_OUT], f->p.w, f->p.h);
}

static oit_status oit_f2b_render(oit_f2b *f, const oit_gpu_mesh *const *meshes, int n,
                                 const oit_view *v, oit_image *out, oit_frame_stats *stats,
                                 oit_error *err)
{
    oit_status s = oit_blend_passes_begin(&f->p, v, err);
    f->b.texture_bytes = f->p.bytes;
    oit_gpu_buffers_note(&f->b);
    uint64_t tris = 0;
    for (int i = 0; i < n; i++)
        tris += oit_gpu_mesh_triangles(meshes[i]);
    if (s == OIT_OK)
        s = order(f, meshes, n, tris, err);
    if (s != OIT_OK)
        return s;
    blend(f, tris);
    finish(f);
    return oit_blend_passes_end(&f->p, TEX_OUT, f->b.peak, out, stats, err);
}

OIT_BASELINE_METHOD(f2b, oit_f2b, "F2B", OIT_RENDER_METHOD_EPSILON, OIT_THRESHOLD);
