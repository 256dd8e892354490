/* Dynamic Fragment Buffer (dfb.h, Maule et al.). Four passes per frame:
 * count (atomic per pixel), exclusive scan of the counts (scan_glsl.h),
 * store (each fragment at its pixel's offset, slot by atomic decrement of the
 * count), resolve (sort each pixel's segment and composite per shade.h).
 * Buffers are in GL row order (bottom first); rows are flipped on readback. */
#include "view/render/capture/dfb.h"

#include "base/clock.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "view/render/capture/opaque_keys.h"
#include "view/render/gl/scan_glsl.h"

#include <stdlib.h>
#include <string.h>

enum { BUF_COUNTS, BUF_OFFSETS, BUF_FRAGS, BUF_OUT, BUF_STATE, BUF_N };
/* PROG_STATE resolves into the state buffer; it is built at first use. */
enum { PROG_COUNT, PROG_STORE, PROG_RESOLVE, PROG_STATE, PROG_N };

struct oit_dfb {
    oit_gpu_timer *timer; /* phases marked (oit_dfb_set_gpu_timer); NULL: none */
    GLuint prog[PROG_N];
    GLuint fbo;
    GLuint buf[BUF_N];
    uint64_t cap[BUF_N];
    oit_scan scan;
    uint64_t bytes_peak;
    oit_opaque_depth opaque; /* oit_dfb_set_opaque; keyed: this frame's */
    oit_opaque_keys *keys;   /* the opaque pre-pass, made on first need */
};

void oit_dfb_set_opaque(oit_dfb *d, const oit_opaque_depth *o)
{
    memset(&d->opaque, 0, sizeof d->opaque);
    if (o && o->enabled)
        d->opaque = *o;
    d->opaque.keyed = 0; /* each frame's own (opaque_pass) */
}

/* The passes' stages, glsl/dfb_*.glsl (CMakeLists.txt). The resolves
 * composite a band of rows; one leaves colours, the other the state. */
extern const char oit_dfb_count_fs[], oit_dfb_store_fs[], oit_dfb_resolve_cs[],
    oit_dfb_resolve_main[], oit_dfb_resolve_state_cs[];

static const oit_glsl_program programs[PROG_N] = {
    [PROG_COUNT] = {"DFB count pass", .fs = {oit_dfb_count_fs}},
    [PROG_STORE] = {"DFB store pass", .fs = {oit_dfb_store_fs}},
    [PROG_RESOLVE] = {"DFB resolve", .cs = {oit_glsl_composite, oit_dfb_resolve_cs,
                                            oit_glsl_segment_composite, oit_dfb_resolve_main}},
    [PROG_STATE] = {"DFB resolve to state",
                    .cs = {"#define OIT_TO_STATE 1\n", oit_glsl_composite, oit_glsl_state_io,
                           oit_dfb_resolve_state_cs, oit_glsl_segment_composite,
                           oit_dfb_resolve_main}},
};

void oit_dfb_glsl_variants(oit_glsl_visit *visit, void *user)
{
    for (int i = 0; i < PROG_N; i++)
        visit(user, &programs[i]);
}

oit_status oit_dfb_create(oit_dfb **out, oit_error *err)
{
    *out = NULL;
    oit_dfb *d = calloc(1, sizeof *d);
    if (!d)
        return oit_error_set(err, OIT_ERR_NOMEM, "DFB: out of memory");
    /* all but PROG_STATE */
    oit_status s = oit_glsl_programs_build(NULL, programs, PROG_STATE, d->prog, err);
    if (s == OIT_OK)
        s = oit_scan_init(&d->scan, NULL, err);
    if (s == OIT_OK)
        s = oit_gl_framebuffer_create(&d->fbo, NULL, "DFB: glCreateFramebuffers", err);
    if (s != OIT_OK) {
        oit_dfb_destroy(d);
        return s;
    }
    *out = d;
    return OIT_OK;
}

void oit_dfb_destroy(oit_dfb *d)
{
    if (!d)
        return;
    oit_glsl_programs_delete(d->prog, PROG_N);
    glDeleteFramebuffers(1, &d->fbo);
    glDeleteBuffers(BUF_N, d->buf);
    oit_scan_release(&d->scan);
    oit_opaque_keys_destroy(d->keys);
    free(d);
}

static uint64_t held_bytes(const oit_dfb *d)
{
    uint64_t b = oit_scan_bytes(&d->scan);
    for (int i = 0; i < BUF_N; i++)
        b += d->cap[i];
    return b + oit_opaque_keys_gpu_bytes(d->keys);
}

static oit_status reserve(oit_dfb *d, int which, uint64_t bytes, oit_error *err)
{
    static const char *names[BUF_N] = {"DFB counts", "DFB offsets", "DFB fragment store",
                                       "DFB output", "DFB state"};
    oit_status s = oit_gl_buffer_reserve(&d->buf[which], &d->cap[which], bytes,
                                         names[which], err);
    uint64_t held = held_bytes(d);
    if (held > d->bytes_peak)
        d->bytes_peak = held;
    return s;
}

static void draw_meshes(GLuint prog, const oit_gpu_mesh *const *meshes, int n)
{
    glUseProgram(prog);
    for (int i = 0; i < n; i++)
        oit_gpu_mesh_draw(meshes[i], prog);
}

/* Count pass plus scan: offsets[0..n] with offsets[n] = total. */
static oit_status count_and_scan(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n,
                                 uint64_t pixels, oit_scan_result *res, oit_error *err)
{
    static const GLuint zero = 0;
    oit_gpu_timer_mark(d->timer, OIT_GPU_PASS1);
    glClearNamedBufferData(d->buf[BUF_COUNTS], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, d->buf[BUF_COUNTS]);
    draw_meshes(d->prog[PROG_COUNT], meshes, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(d->buf[BUF_COUNTS], d->buf[BUF_OFFSETS], 0, 0,
                             (GLsizeiptr)((pixels + 1) * 4));
    return oit_scan_run(&d->scan, d->buf[BUF_OFFSETS], pixels + 1, res, NULL, err);
}

/* Fragments one storage buffer binding can hold here. */
static uint64_t store_capacity(void)
{
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    uint64_t cap = (uint64_t)max_block / 16;
    return cap < UINT32_MAX ? cap : UINT32_MAX;
}

/* Splits the rows into bands whose fragments fit cap: band i covers GL rows
 * [rows[i], rows[i+1]) and fragments [base[i], base[i+1]). One band when the
 * frame fits; otherwise the offsets are read back to find where to cut. A
 * single row over cap cannot be stored and is an error. Returns the band
 * count, 0 on failure. rows and base need height + 1 entries. */
static int plan_bands(oit_dfb *d, const oit_view *v, uint64_t total, uint64_t cap, int *rows,
                      uint32_t *base, oit_error *err)
{
    int w = v->width, h = v->height, nb = 0;
    rows[0] = 0, base[0] = 0;
    if (total <= cap) {
        rows[1] = h, base[1] = (uint32_t)total;
        return 1;
    }
    uint32_t *off = malloc(sizeof *off * ((size_t)w * h + 1));
    if (!off) {
        oit_error_set(err, OIT_ERR_NOMEM, "DFB: cannot read back %dx%d offsets", w, h);
        return 0;
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(d->buf[BUF_OFFSETS], 0, (GLsizeiptr)(sizeof *off * ((size_t)w * h + 1)),
                            off);
    for (int y = 0; y < h; y++) {
        uint32_t end = off[(size_t)(y + 1) * w];
        if (end - off[(size_t)y * w] > cap) {
            oit_error_set(err, OIT_ERR_NOMEM, "DFB: row %d has %llu fragments, more than one "
                          "storage buffer holds here (%llu)", h - 1 - y,
                          (unsigned long long)(end - off[(size_t)y * w]), (unsigned long long)cap);
            free(off);
            return 0;
        }
        if (end - base[nb] > cap) {
            nb++;
            rows[nb] = y, base[nb] = off[(size_t)y * w];
        }
    }
    free(off);
    nb++;
    rows[nb] = h, base[nb] = (uint32_t)total;
    return nb;
}

/* Stores and resolves rows [y0, y1) whose fragments start at base. */
static void band_pass(oit_dfb *d, GLuint resolve, const oit_gpu_mesh *const *meshes, int n,
                      const oit_view *v, int y0, int y1, uint32_t base, uint64_t frags)
{
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, y0, v->width, y1 - y0);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, d->buf[BUF_FRAGS], 0,
                      (GLsizeiptr)(frags ? frags * 16 : 16));
    glProgramUniform1ui(d->prog[PROG_STORE], OIT_LOC_BASE, base);
    oit_gpu_timer_mark(d->timer, OIT_GPU_PASS2);
    draw_meshes(d->prog[PROG_STORE], meshes, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(d->timer, OIT_GPU_RESOLVE);
    glUseProgram(resolve);
    glProgramUniform1ui(resolve, OIT_LOC_BASE, base);
    glProgramUniform2i(resolve, OIT_LOC_ROWS, y0, y1);
    glDispatchCompute(oit_gl_groups((uint64_t)v->width, 8), oit_gl_groups((uint64_t)(y1 - y0), 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

/* A frame whose fragments exceed one storage buffer is stored and resolved
 * in bands of rows (the count pass covers the whole frame once), so depth
 * is limited by what one row holds, not the frame. */
static oit_status render_passes(oit_dfb *d, GLuint resolve, const oit_gpu_mesh *const *meshes,
                                int n, const oit_view *v, uint32_t *counts,
                                oit_scan_result *res, int *bands, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    oit_status s = count_and_scan(d, meshes, n, pixels, res, err);
    if (s == OIT_OK && counts)
        s = oit_gl_read_rows(d->buf[BUF_COUNTS], 0, v->width, v->height, 4, counts, "DFB",
                             err);
    if (s != OIT_OK)
        return s;
    if (res->total > UINT32_MAX)
        return oit_error_set(err, OIT_ERR_NOMEM, "DFB: the frame has %llu fragments, more "
                             "than 32-bit offsets address", (unsigned long long)res->total);
    int *rows = malloc(sizeof *rows * ((size_t)v->height + 1));
    uint32_t *base = malloc(sizeof *base * ((size_t)v->height + 1));
    int nb = rows && base ? plan_bands(d, v, res->total, store_capacity(), rows, base, err) : 0;
    uint64_t most = 0;
    for (int b = 0; b < nb; b++)
        most = base[b + 1] - base[b] > most ? base[b + 1] - base[b] : most;
    if (!rows || !base)
        s = oit_error_set(err, OIT_ERR_NOMEM, "DFB: cannot allocate the band plan");
    else
        s = nb ? reserve(d, BUF_FRAGS, most * 16, err) : OIT_ERR_NOMEM;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, d->buf[BUF_COUNTS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, d->buf[BUF_OFFSETS]);
    if (resolve == d->prog[PROG_STATE])
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, d->buf[BUF_STATE]);
    else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, d->buf[BUF_OUT]);
    for (int b = 0; s == OIT_OK && b < nb; b++)
        band_pass(d, resolve, meshes, n, v, rows[b], rows[b + 1], base[b],
                  base[b + 1] - base[b]);
    free(rows);
    free(base);
    *bands = nb;
    return s == OIT_OK ? oit_gl_check("DFB: passes", err) : s;
}

void oit_dfb_set_gpu_timer(oit_dfb *d, struct oit_gpu_timer *t)
{
    d->timer = t;
}

uint64_t oit_dfb_pixel_bytes(const oit_view *view, int state)
{
    return state ? oit_state_bytes(view->shading.mode == OIT_SHADING_TRANSLUCENT) : 16;
}

/* The opaque pre-pass over the whole frame (opaque_keys.h), when v's
 * shading has opaque triangles: the count and store passes then skip
 * every fragment behind them. */
static oit_status opaque_pass(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n,
                              const oit_view *v, oit_error *err)
{
    d->opaque.keyed = 0;
    if (!oit_shading_opaque(&v->shading))
        return OIT_OK;
    oit_status s = d->keys ? OIT_OK : oit_opaque_keys_create(&d->keys, err);
    int on = 0;
    if (s == OIT_OK)
        s = oit_opaque_keys_begin(d->keys, v, d->opaque.enabled ? &d->opaque : NULL, &on, err);
    if (s != OIT_OK)
        return s;
    const int r[4] = {0, 0, v->width, v->height};
    oit_opaque_keys_draw(d->keys, NULL, meshes, n, r);
    d->opaque.keyed = on;
    return oit_gl_check("DFB: opaque pre-pass", err);
}

/* out: BUF_OUT (colour over the background) or BUF_STATE (the state). */
static oit_status prepare(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n, const oit_view *v,
                          int out, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    uint64_t out_bytes = pixels * oit_dfb_pixel_bytes(v, out == BUF_STATE);
    oit_status s = oit_gl_check_ssbo_size(out_bytes, out == BUF_OUT ? "DFB: the frame's output"
                                                                    : "DFB: the frame's state",
                                          err);
    if (s == OIT_OK)
        s = reserve(d, BUF_COUNTS, (pixels + 1) * 4, err);
    if (s == OIT_OK)
        s = reserve(d, BUF_OFFSETS, (pixels + 1) * 4, err);
    if (s == OIT_OK)
        s = reserve(d, out, out_bytes, err);
    if (s == OIT_OK)
        s = opaque_pass(d, meshes, n, v, err);
    if (s != OIT_OK)
        return s;
    oit_glsl_raster_begin_sized(d->fbo, v->width, v->height);
    oit_glsl_set_view(d->prog[PROG_COUNT], v);
    oit_glsl_set_view(d->prog[PROG_STORE], v);
    oit_glsl_set_view(d->prog[out == BUF_OUT ? PROG_RESOLVE : PROG_STATE], v);
    oit_glsl_set_opaque(d->prog[PROG_COUNT], &d->opaque);
    oit_glsl_set_opaque(d->prog[PROG_STORE], &d->opaque);
    return oit_gl_check("DFB: frame set-up", err);
}

static oit_status check_frame(const oit_view *view, int n, oit_error *err)
{
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_size);
    if (view->width <= 0 || view->height <= 0 || view->width > max_size ||
        view->height > max_size || n < 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "DFB: frame %dx%d (with %d meshes) is "
                             "not renderable (at most %d pixels a side)", view->width,
                             view->height, n, max_size);
    return OIT_OK;
}

/* One frame: its view with the shading defaults resolved, the scan of its
 * counts, the bands it was stored in and its start (oit_time_ms). */
typedef struct dfb_frame {
    oit_view v;
    oit_scan_result res;
    int bands;
    double t0;
} dfb_frame;

static void fill_stats(const oit_dfb *d, const dfb_frame *f, oit_frame_stats *stats)
{
    memset(stats, 0, sizeof *stats);
    stats->ms = oit_time_ms() - f->t0;
    stats->fragments = f->res.total;
    stats->max_layers = f->res.max;
    stats->gpu_bytes_peak = d->bytes_peak;
    stats->batches = (uint32_t)f->bands;
}

/* What the image and the state renders share: the frame checked, program
 * prog built (PROG_STATE is, at first use), the view resolved into f, the
 * buffers sized for it and the passes resolved by prog into buffer buf. */
static oit_status resolve_into(oit_dfb *d, int prog, int buf,
                               const oit_gpu_mesh *const *meshes, int n, const oit_view *view,
                               uint32_t *counts, dfb_frame *f, oit_error *err)
{
    memset(f, 0, sizeof *f);
    oit_status s = check_frame(view, n, err);
    if (s == OIT_OK && !d->prog[prog])
        s = oit_glsl_programs_build(NULL, &programs[prog], 1, &d->prog[prog], err);
    if (s != OIT_OK)
        return s;
    f->t0 = oit_time_ms();
    f->v = *view;
    oit_shading_resolve_defaults(&f->v.shading);
    s = prepare(d, meshes, n, &f->v, buf, err);
    if (s == OIT_OK)
        s = render_passes(d, d->prog[prog], meshes, n, &f->v, counts, &f->res, &f->bands, err);
    return s;
}

oit_status oit_dfb_render(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n,
                          const oit_view *view, oit_image *out,
                          uint32_t *counts, oit_frame_stats *stats,
                          oit_error *err)
{
    dfb_frame f;
    int made = 0;
    oit_status s = resolve_into(d, PROG_RESOLVE, BUF_OUT, meshes, n, view, counts, &f, err);
    if (s == OIT_OK)
        s = oit_image_reserve(out, f.v.width, f.v.height, &made, err);
    oit_gpu_timer_mark(d->timer, OIT_GPU_READBACK);
    if (s == OIT_OK) {
        s = oit_gl_read_rows(d->buf[BUF_OUT], 0, f.v.width, f.v.height, 16, out->rgba, "DFB",
                             err);
        if (s != OIT_OK && made)
            oit_image_free(out);
    }
    glFinish();
    if (s == OIT_OK && stats)
        fill_stats(d, &f, stats);
    return s;
}

oit_status oit_dfb_render_state(oit_dfb *d, const oit_gpu_mesh *const *meshes, int n,
                                const oit_view *view, unsigned *state,
                                oit_frame_stats *stats, oit_error *err)
{
    *state = 0;
    dfb_frame f;
    oit_status s = resolve_into(d, PROG_STATE, BUF_STATE, meshes, n, view, NULL, &f, err);
    if (s != OIT_OK)
        return s;
    *state = d->buf[BUF_STATE];
    if (stats) {
        /* The GPU has finished before the time is taken, as for the image. */
        glFinish();
        fill_stats(d, &f, stats);
    }
    return OIT_OK;
}
