/* The list baselines' frame machinery (list_store.h). Buffers are in GL row
 * order; a slot's payload (16 bytes) and its unit's link (4 bytes) live in
 * two arrays so the payload keeps frag_glsl.h's packing. */
#include "render/baselines/list_store.h"

#include "render/baselines/baseline_common.h"
#include "render/image.h"

#include <stdio.h>
#include <stdlib.h>

/* heads, slots, links, {counter, max_len, total}, output. */
enum { BUF_HEADS, BUF_SLOTS, BUF_LINKS, BUF_STATS, BUF_OUT, BUF_N };

struct oit_list_store {
    oit_list_desc d;
    GLuint append_prog, resolve_prog, fbo;
    oit_gpu_buffers b;
    uint64_t units; /* pool capacity in units */
};

static const char *const buffer_names[BUF_N] = {"heads", "fragment slots", "links",
                                                "counters", "output"};

static oit_status build_programs(oit_list_store *ls, oit_error *err)
{
    char what[96];
    const char *vs[] = {oit_glsl_version, oit_glsl_vertex, NULL};
    const char *afs[] = {oit_glsl_version, oit_glsl_fragment_gen, oit_glsl_premultiplied,
                         ls->d.append_fs, NULL};
    const char *rcs[] = {oit_glsl_version, oit_glsl_composite, oit_glsl_sorted_resolve,
                         ls->d.walk_glsl, NULL};
    snprintf(what, sizeof what, "%s append pass", ls->d.method);
    oit_status s = oit_gl_program_graphics(what, vs, afs, &ls->append_prog, err);
    snprintf(what, sizeof what, "%s resolve", ls->d.method);
    if (s == OIT_OK)
        s = oit_gl_program_compute(what, rcs, &ls->resolve_prog, err);
    return s;
}

oit_status oit_list_store_create(const oit_list_desc *desc, oit_list_store **out,
                                 oit_error *err)
{
    *out = NULL;
    oit_list_store *ls = calloc(1, sizeof *ls);
    if (!ls)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", desc->method);
    ls->d = *desc;
    ls->b.method = desc->method;
    ls->b.names = buffer_names;
    oit_status s = build_programs(ls, err);
    if (s == OIT_OK) {
        glCreateFramebuffers(1, &ls->fbo);
        s = oit_gl_check("list store: glCreateFramebuffers", err);
    }
    if (s != OIT_OK) {
        oit_list_store_destroy(ls);
        return s;
    }
    *out = ls;
    return OIT_OK;
}

void oit_list_store_destroy(oit_list_store *ls)
{
    if (!ls)
        return;
    glDeleteProgram(ls->append_prog);
    glDeleteProgram(ls->resolve_prog);
    glDeleteFramebuffers(1, &ls->fbo);
    oit_gpu_buffers_release(&ls->b);
    free(ls);
}

unsigned oit_list_store_append_program(const oit_list_store *ls)
{
    return ls->append_prog;
}

uint64_t oit_list_store_capacity(const oit_list_store *ls)
{
    return ls->units * ls->d.slots_per_unit;
}

/* A pool of at least 'units', within one storage block. */
static oit_status reserve_units(oit_list_store *ls, uint64_t units, oit_error *err)
{
    uint64_t unit_bytes = 16ull * ls->d.slots_per_unit;
    if (units > ls->d.max_units)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: %llu storage units do not fit the "
                             "method's %llu-unit indices", ls->d.method,
                             (unsigned long long)units, (unsigned long long)ls->d.max_units);
    char what[96];
    snprintf(what, sizeof what, "%s fragment pool", ls->d.method);
    oit_status s = oit_gl_check_ssbo_size(units * unit_bytes, what, err);
    if (s == OIT_OK)
        s = oit_gpu_buffers_reserve_all(&ls->b, BUF_N, (const uint64_t[BUF_N]){
            [BUF_SLOTS] = units * unit_bytes, [BUF_LINKS] = units * 4}, err);
    if (s == OIT_OK) {
        /* The margin reserve added is usable, within one block. */
        GLint64 max_block = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
        uint64_t have = ls->b.cap[BUF_LINKS] / 4;
        uint64_t block = (uint64_t)max_block / unit_bytes;
        have = have < block ? have : block;
        ls->units = have < ls->d.max_units ? have : ls->d.max_units;
    }
    return s;
}

/* One geometry pass; *need receives the units the frame asked for, which
 * exceeds ls->units when the pool overflowed. */
static oit_status append_pass(oit_list_store *ls, const oit_gpu_mesh *const *meshes, int n,
                              uint64_t *need, oit_error *err)
{
    static const GLuint end = 0xffffffffu, zero = 0;
    glClearNamedBufferData(ls->b.buf[BUF_HEADS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    glClearNamedBufferData(ls->b.buf[BUF_STATS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, ls->b.buf[BUF_HEADS]);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, ls->b.buf[BUF_SLOTS], 0,
                      (GLsizeiptr)(ls->units * ls->d.slots_per_unit * 16));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, ls->b.buf[BUF_LINKS], 0,
                      (GLsizeiptr)(ls->units * 4));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, ls->b.buf[BUF_STATS]);
    glProgramUniform1ui(ls->append_prog, OIT_LOC_COUNT, (GLuint)ls->units);
    oit_baseline_draw(ls->append_prog, 0, 0, meshes, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint count = 0;
    glGetNamedBufferSubData(ls->b.buf[BUF_STATS], 0, 4, &count);
    *need = count;
    return oit_gl_check("list store: append pass", err);
}

static oit_status prepare(oit_list_store *ls, const oit_view *v, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    char what[96];
    snprintf(what, sizeof what, "%s: the frame's output", ls->d.method);
    oit_status s = oit_gl_check_ssbo_size(pixels * 16, what, err);
    if (s == OIT_OK)
        s = oit_gpu_buffers_reserve_all(&ls->b, BUF_N, (const uint64_t[BUF_N]){
            [BUF_HEADS] = pixels * 4 * ls->d.words_per_pixel, [BUF_STATS] = 16,
            [BUF_OUT] = pixels * 16}, err);
    if (s == OIT_OK && ls->units == 0)
        s = reserve_units(ls, (pixels + ls->d.slots_per_unit - 1) / ls->d.slots_per_unit, err);
    if (s != OIT_OK)
        return s;
    glNamedFramebufferParameteri(ls->fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, v->width);
    glNamedFramebufferParameteri(ls->fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, v->height);
    oit_glsl_raster_begin(ls->fbo, v->width, v->height);
    oit_glsl_set_view(ls->append_prog, v);
    oit_glsl_set_view(ls->resolve_prog, v);
    return oit_gl_check("list store: frame set-up", err);
}

/* Appends, growing the pool and drawing again while a pass overflowed. */
static oit_status build_lists(oit_list_store *ls, const oit_gpu_mesh *const *meshes, int n,
                              uint32_t *passes, oit_error *err)
{
    uint64_t need = 0;
    oit_status s = OIT_OK;
    for (*passes = 1; s == OIT_OK; ++*passes) {
        s = append_pass(ls, meshes, n, &need, err);
        if (s != OIT_OK || need <= ls->units)
            return s;
        if (*passes == OIT_LIST_MAX_PASSES)
            break;
        uint64_t cap = ls->units * ls->d.growth_cap;
        s = reserve_units(ls, ls->d.growth_cap && need > cap ? cap : need, err);
    }
    if (s != OIT_OK)
        return s;
    return oit_error_set(err, OIT_ERR_GL, "%s: pass %u still asked for %llu storage units, "
                         "more than the %llu the passes before it left", ls->d.method,
                         (unsigned)*passes, (unsigned long long)need,
                         (unsigned long long)ls->units);
}

static oit_status resolve(oit_list_store *ls, const oit_view *v, GLuint figures[3],
                          oit_error *err)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, ls->b.buf[BUF_OUT]);
    oit_baseline_dispatch_frame(ls->resolve_prog, v->width, v->height);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(ls->b.buf[BUF_STATS], 0, 12, figures);
    return oit_gl_check("list store: resolve", err);
}

oit_status oit_list_store_render(oit_list_store *ls, const oit_gpu_mesh *const *meshes, int n,
                                 const oit_view *view, oit_image *out,
                                 oit_frame_stats *stats, oit_error *err)
{
    oit_view v;
    double t0;
    oit_status s = oit_baseline_begin(ls->d.method, view, n, &v, &t0, err);
    if (s != OIT_OK)
        return s;
    uint32_t passes = 0;
    GLuint figures[3] = {0, 0, 0}; /* counter, max_len, total */
    s = prepare(ls, &v, err);
    if (s == OIT_OK)
        s = build_lists(ls, meshes, n, &passes, err);
    if (s == OIT_OK)
        s = resolve(ls, &v, figures, err);
    if (s == OIT_OK)
        s = oit_baseline_read_buffer(ls->d.method, ls->b.buf[BUF_OUT], v.width, v.height, out,
                                     err);
    if (s != OIT_OK || !stats)
        return s;
    oit_baseline_stats(stats, t0, figures[2], figures[1], ls->b.peak, passes);
    return OIT_OK;
}
