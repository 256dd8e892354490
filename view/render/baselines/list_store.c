/* The list baselines' frame machinery (list_store.h). Buffers are in GL row
 * order; a slot's payload (16 bytes) and its unit's link (4 bytes) live in
 * two arrays so the payload keeps frag_glsl.h's packing. */
#include "view/render/baselines/list_store.h"

#include "view/render/baselines/baseline_common.h"
#include "view/render/image/image.h"

#include <stdio.h>
#include <stdlib.h>

/* heads, slots, links, {counter, max_len, total}, output. */
enum { BUF_HEADS, BUF_SLOTS, BUF_LINKS, BUF_STATS, BUF_OUT, BUF_N };

static const char *const buffer_names[BUF_N] = {"heads", "fragment slots", "links",
                                                "counters", "output"};

/* The append and resolve programs of desc into out, named in the caller's
 * append and resolve (LIST_NAME_MAX bytes each). */
enum { LIST_NAME_MAX = 96 };
static void list_programs(const oit_list_desc *desc, char *append, char *resolve,
                          oit_glsl_program out[OIT_LIST_PROG_N])
{
    snprintf(append, LIST_NAME_MAX, "%s append pass", desc->method);
    snprintf(resolve, LIST_NAME_MAX, "%s resolve", desc->method);
    out[OIT_LIST_PROG_APPEND] =
        (oit_glsl_program){append, .fs = {oit_glsl_premultiplied, desc->append_fs}};
    out[OIT_LIST_PROG_RESOLVE] =
        (oit_glsl_program){resolve, .cs = {oit_glsl_composite, oit_glsl_sorted_resolve,
                                           desc->walk[0], desc->walk[1]}};
}

void oit_list_store_glsl_variants(const oit_list_desc *desc, oit_glsl_visit *visit, void *user)
{
    char append[LIST_NAME_MAX], resolve[LIST_NAME_MAX];
    oit_glsl_program programs[OIT_LIST_PROG_N];
    list_programs(desc, append, resolve, programs);
    for (int i = 0; i < OIT_LIST_PROG_N; i++)
        visit(user, &programs[i]);
}

oit_status oit_list_store_init(oit_list_store *ls, const oit_list_desc *desc, oit_error *err)
{
    char append[LIST_NAME_MAX], resolve[LIST_NAME_MAX];
    oit_glsl_program programs[OIT_LIST_PROG_N];
    list_programs(desc, append, resolve, programs);
    ls->d = *desc;
    ls->b.method = desc->method;
    ls->b.names = buffer_names;
    oit_status s = oit_glsl_programs_build(NULL, programs, OIT_LIST_PROG_N, ls->prog, err);
    if (s == OIT_OK)
        s = oit_gl_framebuffer_create(&ls->fbo, NULL, "list store: glCreateFramebuffers", err);
    return s;
}

void oit_list_store_release(oit_list_store *ls)
{
    oit_glsl_programs_delete(ls->prog, OIT_LIST_PROG_N);
    glDeleteFramebuffers(1, &ls->fbo);
    oit_gpu_buffers_release(&ls->b);
}

unsigned oit_list_store_append_program(const oit_list_store *ls)
{
    return ls->prog[OIT_LIST_PROG_APPEND];
}

uint64_t oit_list_store_capacity(const oit_list_store *ls)
{
    return ls->units * ls->d.slots_per_unit;
}

void oit_list_store_frame(oit_list_store *ls, uint64_t limit, int *split)
{
    ls->limit = limit;
    ls->split = split;
}

/* The most bytes one binding takes this frame. */
static uint64_t binding_bytes(const oit_list_store *ls)
{
    uint64_t driver = oit_gl_ssbo_max_bytes();
    return ls->limit && ls->limit < driver ? ls->limit : driver;
}

/* A pool past one binding: the frame asks to be split in bands of rows
 * that would each hold their share (one more than the even split: the
 * fragments need not be even), when it can ask. */
static oit_status pool_too_big(oit_list_store *ls, uint64_t bytes, uint64_t bind, oit_error *err)
{
    if (ls->split)
        *ls->split = (int)((bytes + bind - 1) / bind + 1);
    return oit_error_set(err, OIT_ERR_NOMEM, "%s fragment pool: needs %llu bytes in one "
                         "storage buffer, more than this driver binds (%llu)", ls->d.method,
                         (unsigned long long)bytes, (unsigned long long)bind);
}

/* A pool of at least 'units', within one storage block. */
static oit_status reserve_units(oit_list_store *ls, uint64_t units, oit_error *err)
{
    uint64_t unit_bytes = 16ull * ls->d.slots_per_unit, bind = binding_bytes(ls);
    if (units > ls->d.max_units)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: %llu storage units do not fit the "
                             "method's %llu-unit indices", ls->d.method,
                             (unsigned long long)units, (unsigned long long)ls->d.max_units);
    if (units * unit_bytes > bind)
        return pool_too_big(ls, units * unit_bytes, bind, err);
    oit_status s = oit_gpu_buffers_reserve_all(&ls->b, BUF_N, (const uint64_t[BUF_N]){
        [BUF_SLOTS] = units * unit_bytes, [BUF_LINKS] = units * 4}, err);
    if (s == OIT_OK) {
        /* The margin reserve added is usable, within one block. */
        uint64_t have = ls->b.cap[BUF_LINKS] / 4;
        uint64_t block = bind / unit_bytes;
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
    glProgramUniform1ui(ls->prog[OIT_LIST_PROG_APPEND], OIT_LOC_CAPACITY, (GLuint)ls->units);
    oit_baseline_draw(ls->prog[OIT_LIST_PROG_APPEND], 0, 0, meshes, n);
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
    /* The pool an earlier frame grew may pass this frame's binding. */
    uint64_t fit = binding_bytes(ls) / (16ull * ls->d.slots_per_unit);
    ls->units = ls->units < fit ? ls->units : fit;
    if (s == OIT_OK && ls->units == 0)
        s = reserve_units(ls, (pixels + ls->d.slots_per_unit - 1) / ls->d.slots_per_unit, err);
    if (s != OIT_OK)
        return s;
    oit_glsl_raster_begin_sized(ls->fbo, v->width, v->height);
    oit_glsl_set_view_all(ls->prog, OIT_LIST_PROG_N, v);
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
    oit_baseline_dispatch_frame(ls->prog[OIT_LIST_PROG_RESOLVE], v->width, v->height);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(ls->b.buf[BUF_STATS], 0, 12, figures);
    return oit_gl_check("list store: resolve", err);
}

oit_status oit_list_store_render(oit_list_store *ls, const oit_gpu_mesh *const *meshes, int n,
                                 const oit_view *v, oit_image *out, oit_frame_stats *stats,
                                 oit_error *err)
{
    uint32_t passes = 0;
    GLuint figures[3] = {0, 0, 0}; /* counter, max_len, total */
    oit_status s = prepare(ls, v, err);
    if (s == OIT_OK)
        s = build_lists(ls, meshes, n, &passes, err);
    if (s == OIT_OK)
        s = resolve(ls, v, figures, err);
    if (s == OIT_OK)
        s = oit_baseline_read_buffer(ls->d.method, ls->b.buf[BUF_OUT], v->width, v->height, out,
                                     err);
    *stats = (oit_frame_stats){.fragments = figures[2], .max_layers = figures[1],
                               .gpu_bytes_peak = ls->b.peak, .batches = passes};
    return s;
}
