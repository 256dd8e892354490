/* The compute capture (capture_compute.h). */
#include "render/capture/capture_compute.h"

#include "render/capture/capture_backend.h"
#include "render/capture/compute_glsl.h"
#include "render/gl/gpu_timer.h"

#include <string.h>

static const char u_mode_decl[] = "layout(location = 3) uniform int u_mode;\n";

static const oit_glsl_program programs[OIT_COMPUTE_PROGS] = {
    [OIT_COMPUTE_SETUP] = {"compute capture set-up",
                           .cs = {oit_glsl_vertex_lib, oit_compute_setup_cs}},
    [OIT_COMPUTE_SCATTER] = {"compute capture scatter", .cs = {oit_compute_scatter_cs}},
    [OIT_COMPUTE_LIVE] = {"compute capture live tiles",
                          .cs = {u_mode_decl, oit_glsl_state_io, oit_compute_live_cs}},
    [OIT_COMPUTE_TILES] = {"compute capture sweep",
                           .cs = {oit_glsl_composite, oit_glsl_state_io, oit_compute_frag_inputs,
                                  oit_glsl_fragment_lib, oit_compute_tiles_cs}},
};

static oit_status compute_init(oit_compute *k, oit_error *err)
{
    memset(k, 0, sizeof *k);
    k->align = oit_gl_ssbo_align();
    oit_status s = oit_glsl_programs_build(programs, OIT_COMPUTE_PROGS, k->prog, err);
    if (s == OIT_OK)
        s = oit_scan_init(&k->scan, err);
    return s;
}

static void compute_destroy(void *be)
{
    oit_compute *k = be;
    oit_glsl_programs_delete(k->prog, OIT_COMPUTE_PROGS);
    GLuint bufs[] = {k->recs, k->tiles, k->list, k->dead, k->resume, k->pending};
    glDeleteBuffers(6, bufs);
    oit_scan_release(&k->scan);
    memset(k, 0, sizeof *k);
}

static uint64_t compute_bytes(const void *be)
{
    const oit_compute *k = be;
    return k->recs_cap + k->tiles_cap + k->list_cap + k->dead_cap + k->resume_cap +
           k->pending_cap + oit_scan_bytes(&k->scan);
}

static void set_rect(const oit_compute *k, const oit_compute_frame *f, const int r[4])
{
    for (int i = 0; i < OIT_COMPUTE_PROGS; i++) {
        glProgramUniform2i(k->prog[i], glGetUniformLocation(k->prog[i], "u_size"), f->width,
                           f->height);
        glProgramUniform4i(k->prog[i], glGetUniformLocation(k->prog[i], "u_rect"), r[0], r[1],
                           r[2], r[3]);
    }
}

/* Invocations i in [0, count) of a 64-wide program, in rows of 65535
 * groups (the shaders rebuild i from x and y). */
static void dispatch_linear(uint64_t count)
{
    GLuint groups = oit_gl_groups(count, 64);
    glDispatchCompute(groups < 65535 ? groups : 65535, oit_gl_groups(groups, 65535), 1);
}

/* The prims of a sourced mesh's triangles [start, start + count) bound at
 * OIT_BIND_PRIMS from an aligned offset; returns the word of the first
 * within the binding. Other meshes bind their triangles there (never
 * read: the binding is just not left absent). */
static GLuint bind_prims(const oit_compute *k, const oit_gpu_mesh *m, size_t start, size_t count)
{
    uint64_t prims = 0;
    GLuint buf = oit_gpu_mesh_buffer(m);
    if (!oit_gpu_mesh_sourced(m, &prims)) {
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, buf,
                          (GLintptr)(oit_gpu_mesh_offset(m) + start * sizeof(oit_triangle)),
                          (GLsizeiptr)(count * sizeof(oit_triangle)));
        return 0;
    }
    uint64_t first = prims + start * 4, base = first - first % k->align;
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, buf, (GLintptr)base,
                      (GLsizeiptr)(first - base + count * 4));
    return (GLuint)((first - base) / 4);
}

/* Set-up and tile counts of every triangle, records in batch order. */
static void setup(oit_compute *k, const oit_gpu_mesh *const *meshes, int n)
{
    GLuint p = k->prog[OIT_COMPUTE_SETUP];
    GLint l_first = glGetUniformLocation(p, "u_window_first"),
          l_count = glGetUniformLocation(p, "u_window_count"),
          l_base = glGetUniformLocation(p, "u_rec_base"),
          l_prim = glGetUniformLocation(p, "u_first_prim"),
          l_sourced = glGetUniformLocation(p, "u_sourced"),
          l_word = glGetUniformLocation(p, "u_prim_word0");
    glUseProgram(p);
    size_t window = oit_gpu_triangle_window(), base = 0;
    for (int i = 0; i < n; i++) {
        const oit_gpu_mesh *m = meshes[i];
        size_t count = oit_gpu_mesh_triangles(m);
        uint64_t unused;
        glProgramUniform1ui(p, l_prim, oit_gpu_mesh_first_prim(m));
        glProgramUniform1ui(p, l_sourced, (GLuint)oit_gpu_mesh_sourced(m, &unused));
        for (size_t start = 0; start < count; start += window) {
            size_t c = count - start < window ? count - start : window;
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, oit_gpu_mesh_buffer(m),
                              (GLintptr)(oit_gpu_mesh_offset(m) + start * sizeof(oit_triangle)),
                              (GLsizeiptr)(c * sizeof(oit_triangle)));
            glProgramUniform1ui(p, l_word, bind_prims(k, m, start, c));
            glProgramUniform1ui(p, l_first, (GLuint)start);
            glProgramUniform1ui(p, l_count, (GLuint)c);
            glProgramUniform1ui(p, l_base, (GLuint)(base + start));
            dispatch_linear(c);
        }
        base += count;
    }
}

/* Dispatches prog over the tiles that meet the GL rect r. */
static void dispatch_tiles(GLuint prog, const int r[4])
{
    int tx0 = r[0] / OIT_COMPUTE_TILE, ty0 = r[1] / OIT_COMPUTE_TILE;
    int tx1 = (r[2] - 1) / OIT_COMPUTE_TILE, ty1 = (r[3] - 1) / OIT_COMPUTE_TILE;
    glUseProgram(prog);
    glProgramUniform2i(prog, glGetUniformLocation(prog, "u_tile0"), tx0, ty0);
    glDispatchCompute((GLuint)(tx1 - tx0 + 1), (GLuint)(ty1 - ty0 + 1), 1);
}

static oit_status reserve(GLuint *buf, uint64_t *cap, uint64_t bytes, const char *what,
                          oit_error *err)
{
    return oit_gl_buffer_reserve(buf, cap, bytes ? bytes : 4, what, err);
}

/* The tiles of the rect whose pixels are all below epsilon marked dead
 * (1) in k->dead, the others 0. */
static void mark_live(oit_compute *k, const oit_compute_frame *f, const int r[4])
{
    static const GLuint one = 1;
    glClearNamedBufferData(k->dead, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &one);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GLuint p = k->prog[OIT_COMPUTE_LIVE];
    glProgramUniform1f(p, glGetUniformLocation(p, "u_epsilon"), f->epsilon);
    dispatch_tiles(p, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

static oit_status too_large(const char *what, uint64_t bytes, uint64_t bind, oit_error *err)
{
    return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                         "compute capture: the batch's %s take %llu bytes, more than one "
                         "storage binding spans (%llu); capture it in smaller packs",
                         what, (unsigned long long)bytes, (unsigned long long)bind);
}

/* The sweep over the rect, dispatched again for the pixels a driver's loop
 * limit cut short (compute_glsl.c) until none is pending. */
static oit_status sweep(oit_compute *k, const oit_compute_frame *f, const int r[4],
                        uint64_t entries, oit_error *err)
{
    uint64_t pixels = (uint64_t)f->width * f->height;
    oit_status s = reserve(&k->resume, &k->resume_cap, pixels * 16, "compute capture resume", err);
    if (s == OIT_OK)
        s = reserve(&k->pending, &k->pending_cap, 8, "compute capture pending", err);
    if (s != OIT_OK)
        return s;
    if (pixels * 16 > f->bind)
        return too_large("resume cursors", pixels * 16, f->bind, err);
    GLuint tp = k->prog[OIT_COMPUTE_TILES];
    glProgramUniform1f(tp, glGetUniformLocation(tp, "u_epsilon"), f->epsilon);
    glProgramUniform1i(tp, glGetUniformLocation(tp, "u_probe"), 2);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, k->resume);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->pending);
    static const GLuint zero = 0;
    for (k->rounds = 1;; k->rounds++) {
        glClearNamedBufferData(k->pending, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glProgramUniform1i(tp, glGetUniformLocation(tp, "u_resume"), k->rounds > 1);
        dispatch_tiles(tp, r);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint pend[2] = {0, 0};
        glGetNamedBufferSubData(k->pending, 0, sizeof pend, pend);
        if (pend[0] == 0)
            return OIT_OK;
        if (pend[1] == 0)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "compute capture: this driver cuts shader loops short and %u "
                                 "pixels could not finish one sweep of their tile's triangles "
                                 "(%llu tile entries in the batch); capture it in smaller packs",
                                 pend[0], (unsigned long long)entries);
    }
}

/* A batch's meshes are in visibility order, so its halves, captured one
 * after the other, give the same image. */
static oit_status halves(oit_compute *k, const oit_compute_frame *f,
                         const oit_gpu_mesh *const *meshes, int n, const int r[4],
                         oit_error *err)
{
    oit_status s = oit_compute_batch(k, f, meshes, n / 2, r, err);
    return s == OIT_OK ? oit_compute_batch(k, f, meshes + n / 2, n - n / 2, r, err) : s;
}

oit_status oit_compute_batch(oit_compute *k, const oit_compute_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4],
                             oit_error *err)
{
    uint64_t tris = 0;
    for (int i = 0; i < n; i++)
        tris += oit_gpu_mesh_triangles(meshes[i]);
    if (tris == 0)
        return OIT_OK;
    uint64_t rec_bytes = tris * OIT_COMPUTE_RECORD_WORDS * 16;
    if (rec_bytes > f->bind || tris > UINT32_MAX / OIT_COMPUTE_RECORD_WORDS)
        return n > 1 ? halves(k, f, meshes, n, r, err)
                     : too_large("triangle records", rec_bytes, f->bind, err);
    uint64_t tx = (uint64_t)(f->width + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE;
    uint64_t tiles = tx * ((uint64_t)(f->height + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE);
    oit_status s = reserve(&k->recs, &k->recs_cap, rec_bytes, "compute capture records", err);
    if (s == OIT_OK)
        s = reserve(&k->tiles, &k->tiles_cap, tiles * 4, "compute capture tile counts", err);
    if (s == OIT_OK)
        s = reserve(&k->dead, &k->dead_cap, tiles * 4, "compute capture tile flags", err);
    if (s != OIT_OK)
        return s;
    oit_gpu_timer_mark(f->timer, OIT_GPU_BINNING);
    set_rect(k, f, r);
    int live = f->epsilon > 0.0f;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->dead);
    if (live)
        mark_live(k, f, r);
    for (int i = 0; i < OIT_COMPUTE_PROGS; i++)
        glProgramUniform1i(k->prog[i], glGetUniformLocation(k->prog[i], "u_live"), live);
    static const GLuint zero = 0;
    glClearNamedBufferData(k->tiles, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->recs, 0,
                      (GLsizeiptr)rec_bytes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->tiles);
    setup(k, meshes, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_scan_result sum;
    s = oit_scan_run(&k->scan, k->tiles, tiles, &sum, err);
    if (s != OIT_OK)
        return s;
    if (sum.total * 4 > f->bind || sum.total > UINT32_MAX)
        return n > 1 ? halves(k, f, meshes, n, r, err)
                     : too_large("tile lists", sum.total * 4, f->bind, err);
    s = reserve(&k->list, &k->list_cap, sum.total * 4, "compute capture tile lists", err);
    if (s != OIT_OK)
        return s;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->tiles);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->dead);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, k->list, 0,
                      (GLsizeiptr)(sum.total ? sum.total * 4 : 4));
    GLuint sc = k->prog[OIT_COMPUTE_SCATTER];
    glUseProgram(sc);
    glProgramUniform1ui(sc, glGetUniformLocation(sc, "u_count"), (GLuint)tris);
    dispatch_linear(tris);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(f->timer, OIT_GPU_SWEEP);
    s = sweep(k, f, r, sum.total, err);
    if (s != OIT_OK)
        return s;
    return oit_gl_check("compute capture: batch", err);
}

/* ---- the compute backend (OIT_CAPTURE_COMPUTE) ------------------------------ */

static oit_status compute_create(oit_capture *c, int stencil_k, oit_error *err)
{
    return compute_init(c->be, err);
}

/* The resume cursors, a pixel's 16 bytes, held for the whole frame: the
 * output passes through them at its end (compute_end). */
static oit_status compute_begin(oit_capture *c, oit_error *err)
{
    oit_compute *k = c->be;
    uint64_t pixels = (uint64_t)c->view.width * c->view.height;
    return oit_capture_reserve(c, &k->resume, &k->resume_cap, pixels * 16,
                               "compute capture resume", err);
}

static void compute_uniforms(oit_capture *c)
{
    oit_capture_set_frame_uniforms(c, ((oit_compute *)c->be)->prog, OIT_COMPUTE_PROGS);
}

/* Nothing to set: each batch passes the threshold it tests
 * (c->frame.applied) to its programs. */
static void compute_epsilon(oit_capture *c, float e)
{
    (void)c;
    (void)e;
}

static void compute_bind(const oit_capture *c)
{
    const oit_compute *k = c->be;
    oit_capture_bind_within(c, OIT_BIND_OUT, k->resume, k->resume_cap);
}

/* No per-pixel limit: a batch of any number of layers is an ordinary one. */
static oit_status compute_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                const int rect[4], int layers, oit_error *err)
{
    int r[4] = {0}, empty = 1;
    oit_status s = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    const oit_compute_frame f = {.state = c->buf[OIT_CAPTURE_STATE],
                                 .width = c->view.width,
                                 .height = c->view.height,
                                 .bind = c->frame.bind,
                                 .epsilon = c->frame.applied,
                                 .timer = c->set.timer};
    s = oit_compute_batch(c->be, &f, meshes, n, r, err);
    oit_capture_note_peak(c);
    oit_capture_bind_buffers(c);
    return s;
}

/* The resume cursors are idle at the frame's end and hold a pixel's
 * 16 bytes: the output passes through them. */
static oit_status compute_end(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                              oit_error *err)
{
    oit_compute *k = c->be;
    return oit_capture_store_out(c, &k->resume, &k->resume_cap, "compute capture resume", want,
                                 row, out, err);
}

static void compute_stats(const oit_capture *c, oit_frame_stats *stats)
{
    stats->capture = c->ops->name;
}

OIT_CAPTURE_OPS(compute, OIT_CAPTURE_COMPUTE, "compute", oit_compute, NULL);
