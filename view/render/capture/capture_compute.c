/* The compute capture (capture_compute.h). */
#include "view/render/capture/capture_compute.h"

#include "view/render/capture/capture_backend.h"
#include "view/render/capture/compute_blocks.h"
#include "view/render/capture/compute_glsl.h"
#include "view/render/gl/gpu_timer.h"

#include <string.h>

_Static_assert(OIT_COMPUTE_CAPTURE_TRIANGLE_BYTES == OIT_COMPUTE_RECORD_WORDS * 16 + 4 * 4,
               "capture.h's figure: a record and four list entries");

/* Iterations of the probe's loop: past llvmpipe's 65535. */
#define PROBE_LOOP (1 << 17)

static oit_status compute_init(oit_compute *k, oit_program_cache *pc, oit_error *err)
{
    memset(k, 0, sizeof *k);
    k->align = oit_gl_ssbo_align();
    k->blocks = oit_compute_record_blocks();
    oit_compute_blocks_define(k->blocks, k->blocks_decl, sizeof k->blocks_decl);
    oit_glsl_program table[OIT_COMPUTE_PROGS];
    oit_compute_programs(k->blocks_decl, table);
    oit_status s = oit_glsl_programs_build(pc, table, OIT_COMPUTE_PROGS, k->prog, err);
    if (s == OIT_OK)
        s = oit_scan_init(&k->scan, pc, err);
    return s;
}

static void compute_destroy(void *be)
{
    oit_compute *k = be;
    oit_glsl_programs_delete(k->prog, OIT_COMPUTE_PROGS);
    GLuint bufs[] = {k->recs,    k->tiles,   k->list,    k->dead,
                     k->resume,  k->pending, k->work[0], k->work[1], k->late};
    glDeleteBuffers((GLsizei)(sizeof bufs / sizeof bufs[0]), bufs);
    oit_scan_release(&k->scan);
    memset(k, 0, sizeof *k);
}

static uint64_t compute_bytes(const void *be)
{
    const oit_compute *k = be;
    return k->recs_cap + k->tiles_cap + k->list_cap + k->dead_cap + k->resume_cap +
           k->pending_cap + k->work_cap[0] + k->work_cap[1] + k->late_cap +
           oit_scan_bytes(&k->scan);
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

/* Its args from its count (OIT_BIND_OUT), ready for an indirect dispatch. */
static void work_args(const oit_compute *k, GLuint list)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, list);
    glUseProgram(k->prog[OIT_COMPUTE_ARGS]);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

static void clear_header(GLuint list)
{
    static const GLuint zero = 0;
    glClearNamedBufferSubData(list, GL_R32UI, 0, 16, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

/* The first work list: the rect's tiles with list entries, in work[0]. */
static void first_work(const oit_compute *k, const int r[4])
{
    int tx0 = r[0] / OIT_COMPUTE_TILE, ty0 = r[1] / OIT_COMPUTE_TILE;
    int tx1 = (r[2] - 1) / OIT_COMPUTE_TILE, ty1 = (r[3] - 1) / OIT_COMPUTE_TILE;
    GLuint p = k->prog[OIT_COMPUTE_WORK];
    clear_header(k->work[0]);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->tiles);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, k->work[0]);
    glUseProgram(p);
    glProgramUniform2i(p, glGetUniformLocation(p, "u_tile0"), tx0, ty0);
    glProgramUniform2i(p, glGetUniformLocation(p, "u_tile1"), tx1, ty1);
    glDispatchCompute(oit_gl_groups((uint64_t)(tx1 - tx0 + 1), 8),
                      oit_gl_groups((uint64_t)(ty1 - ty0 + 1), 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    work_args(k, k->work[0]);
}

/* One round over the tiles of work list `from`, those with pixels left
 * pending appended to `to`. */
static void sweep_round(oit_compute *k, GLuint from, GLuint to, int resume)
{
    GLuint tp = k->prog[OIT_COMPUTE_TILES];
    clear_header(to);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, from);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, to);
    glUseProgram(tp);
    glProgramUniform1i(tp, glGetUniformLocation(tp, "u_resume"), resume);
    glProgramUniform1ui(tp, glGetUniformLocation(tp, "u_round"), ++k->round);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, from);
    glDispatchComputeIndirect(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    work_args(k, to);
}

/* The sweep over the batch's tiles (one indirect dispatch), and where the
 * driver cuts loops short (compute_glsl.c), further rounds over the tiles
 * left pending, read back once per chunk of them until none is. */
static oit_status sweep(oit_compute *k, const oit_compute_frame *f, const int r[4],
                        uint64_t tris, uint64_t list_cap, oit_error *err)
{
    uint64_t tiles = (uint64_t)(f->width + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE *
                     ((f->height + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE);
    oit_status s = OIT_OK;
    for (int i = 0; i < 2 && s == OIT_OK; i++)
        s = reserve(&k->work[i], &k->work_cap[i], 16 + tiles * 4, "compute capture work", err);
    if (s != OIT_OK)
        return s;
    uint64_t pixels = (uint64_t)f->width * f->height;
    if (pixels * 16 > f->bind)
        return too_large("resume cursors", pixels * 16, f->bind, err);
    GLuint tp = k->prog[OIT_COMPUTE_TILES];
    glProgramUniform1f(tp, glGetUniformLocation(tp, "u_epsilon"), f->epsilon);
    glProgramUniform1i(tp, glGetUniformLocation(tp, "u_probe"), 2);
    glProgramUniform1ui(tp, glGetUniformLocation(tp, "u_list_cap"), (GLuint)list_cap);
    glProgramUniform1ui(tp, glGetUniformLocation(tp, "u_recs"), (GLuint)tris);
    first_work(k, r);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, k->resume);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->pending);
    static const GLuint zero = 0;
    for (int round = 0;;) {
        for (uint32_t i = 0; i < (k->cuts ? k->chunk : 1); i++, round++) {
            /* where loops are cut, the counts are the round's; elsewhere
             * the frame's, for its end to check */
            if (k->cuts)
                glClearNamedBufferSubData(k->pending, GL_R32UI, 0, 8, GL_RED_INTEGER,
                                          GL_UNSIGNED_INT, &zero);
            sweep_round(k, k->work[round & 1], k->work[(round + 1) & 1], round > 0);
        }
        if (!k->cuts)
            return OIT_OK;
        GLuint pend[2] = {0, 0};
        oit_host_read(f->waits, k->pending, 0, sizeof pend, pend);
        if (pend[0] == 0)
            return OIT_OK;
        if (pend[1] == 0)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "compute capture: this driver cuts shader loops short and %u "
                                 "pixels could not finish one sweep of their tile's triangles "
                                 "(%llu triangles in the batch); capture it in smaller packs",
                                 pend[0], (unsigned long long)tris);
        k->chunk = k->chunk < 16 ? k->chunk * 2 : 16;
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

/* Tile-list entries for a batch of tris triangles, sized without the
 * scan's total: 4 a triangle, or the most an earlier frame's batch
 * needed, or what the buffer holds already; within one binding and what
 * the budget leaves beside the records (at least one). */
static uint64_t list_entries(const oit_compute *k, const oit_compute_frame *f, uint64_t tris)
{
    if (k->test & OIT_CAPTURE_TEST_COMPUTE_LIST_SHORT)
        return 1;
    uint64_t want = tris * 4;
    want = want > k->list_seen ? want : k->list_seen;
    want = want > k->list_cap / 4 ? want : k->list_cap / 4;
    uint64_t most = f->bind / 4 < UINT32_MAX ? f->bind / 4 : UINT32_MAX;
    uint64_t recs = tris * OIT_COMPUTE_RECORD_WORDS * 16;
    if (f->budget) {
        uint64_t room = f->budget > recs ? (f->budget - recs) / 4 : 0;
        most = room < most ? room : most;
        most = most ? most : 1;
    }
    return want < most ? want : most;
}

/* buf grown to bytes; under a budget to bytes exactly, so that the
 * geometric margin does not take what the budget does not have. */
static oit_status reserve_within(GLuint *buf, uint64_t *cap, uint64_t bytes, uint64_t budget,
                                 const char *what, oit_error *err)
{
    if (budget && *cap < bytes) {
        glDeleteBuffers(1, buf);
        *buf = 0;
        *cap = 0;
    }
    return reserve(buf, cap, bytes, what, err);
}

/* Each record's index into the lists of its tiles, no more than cap. */
static void scatter(oit_compute *k, uint64_t tris, uint64_t cap)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->tiles);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->dead);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, k->late);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, k->list, 0,
                      (GLsizeiptr)(cap * 4));
    GLuint sc = k->prog[OIT_COMPUTE_SCATTER];
    glUseProgram(sc);
    glProgramUniform1ui(sc, glGetUniformLocation(sc, "u_count"), (GLuint)tris);
    glProgramUniform1ui(sc, glGetUniformLocation(sc, "u_list_cap"), (GLuint)cap);
    dispatch_linear(tris);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    k->late_armed = 1;
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
    if (n > 1 && ((f->budget && tris * OIT_COMPUTE_CAPTURE_TRIANGLE_BYTES > f->budget) ||
                  (k->cuts && tris > OIT_COMPUTE_CUT_BATCH)))
        return halves(k, f, meshes, n, r, err);
    uint64_t per = oit_compute_block_records(k->align, f->bind);
    if (tris > per * (uint64_t)k->blocks || tris > UINT32_MAX)
        return n > 1 ? halves(k, f, meshes, n, r, err)
                     : oit_compute_too_many(k->blocks, tris, per, f->bind, err);
    uint64_t tx = (uint64_t)(f->width + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE;
    uint64_t tiles = tx * ((uint64_t)(f->height + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE);
    uint64_t cap = list_entries(k, f, tris);
    oit_status s = reserve_within(&k->recs, &k->recs_cap, rec_bytes, f->budget,
                                  "compute capture records", err);
    if (s == OIT_OK)
        s = reserve(&k->tiles, &k->tiles_cap, tiles * 4, "compute capture tile counts", err);
    if (s == OIT_OK)
        s = reserve(&k->dead, &k->dead_cap, tiles * 4, "compute capture tile flags", err);
    if (s == OIT_OK)
        s = reserve_within(&k->list, &k->list_cap, cap * 4, f->budget,
                           "compute capture tile lists", err);
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
    oit_compute_bind_records(k->recs, k->blocks, tris, per);
    static const int with_recs[] = {OIT_COMPUTE_SETUP, OIT_COMPUTE_SCATTER, OIT_COMPUTE_TILES};
    for (int i = 0; i < 3; i++)
        glProgramUniform1ui(k->prog[with_recs[i]],
                            glGetUniformLocation(k->prog[with_recs[i]], "u_block_recs"),
                            (GLuint)per);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->tiles);
    setup(k, meshes, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    s = oit_scan_run(&k->scan, k->tiles, tiles, NULL, NULL, err);
    if (s != OIT_OK)
        return s;
    scatter(k, tris, cap);
    oit_gpu_timer_mark(f->timer, OIT_GPU_SWEEP);
    s = sweep(k, f, r, tris, cap, err);
    if (s != OIT_OK)
        return s;
    return oit_gl_check("compute capture: batch", err);
}

/* ---- the compute backend (OIT_CAPTURE_COMPUTE) ------------------------------ */

/* Whether the driver stops a loop short of its end (llvmpipe: 65535
 * iterations an invocation), once, so that a driver that runs loops to
 * their end, as GL says, never waits on the sweep. */
static oit_status probe_loops(oit_compute *k, oit_error *err)
{
    oit_status s = reserve(&k->late, &k->late_cap, 16, "compute capture late", err);
    if (s != OIT_OK)
        return s;
    GLuint p = k->prog[OIT_COMPUTE_PROBE], ran = 0;
    glProgramUniform1i(p, glGetUniformLocation(p, "u_probe"), PROBE_LOOP);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->late);
    glUseProgram(p);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(k->late, 0, 4, &ran);
    k->cuts = ran != PROBE_LOOP;
    return oit_gl_check("compute capture: loop probe", err);
}

static oit_status compute_create(oit_capture *c, int stencil_k, oit_error *err)
{
    oit_compute *k = c->be;
    oit_status s = compute_init(k, c->programs, err);
    k->test = c->faults & (OIT_CAPTURE_TEST_COMPUTE_LIST_SHORT | OIT_CAPTURE_TEST_COMPUTE_NO_PROBE);
    k->chunk = 2;
    if (s == OIT_OK && !(k->test & OIT_CAPTURE_TEST_COMPUTE_NO_PROBE))
        s = probe_loops(k, err);
    return s;
}

/* What the last frame's batches needed of the tile lists, read now that
 * it is over (its end read its totals back), then cleared. */
static void read_late(oit_compute *k, oit_host_waits *waits)
{
    static const GLuint zero = 0;
    if (k->late_armed && !(k->test & OIT_CAPTURE_TEST_COMPUTE_LIST_SHORT)) {
        GLuint need = 0;
        oit_host_read(waits, k->late, 0, 4, &need);
        k->list_seen = need > k->list_seen ? need : k->list_seen;
    }
    k->late_armed = 0;
    glClearNamedBufferData(k->late, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

/* The resume cursors, a pixel's 16 bytes, held for the whole frame: the
 * output passes through them at its end (compute_end). The pending counts
 * and tile stamps start at 0; where the last frame left pixels pending on
 * a driver taken for one that runs loops to the end, the sweeps read back
 * from now on. */
static oit_status compute_begin(oit_capture *c, oit_error *err)
{
    oit_compute *k = c->be;
    int w = c->view.width, h = c->view.height;
    uint64_t pixels = (uint64_t)w * h, tiles = (uint64_t)(w + OIT_COMPUTE_TILE - 1) /
                                               OIT_COMPUTE_TILE *
                                               ((h + OIT_COMPUTE_TILE - 1) / OIT_COMPUTE_TILE);
    oit_status s = oit_capture_reserve(c, &k->resume, &k->resume_cap, pixels * 16,
                                       "compute capture resume", err);
    if (s == OIT_OK)
        s = oit_capture_reserve(c, &k->late, &k->late_cap, 16, "compute capture late", err);
    if (s == OIT_OK)
        s = oit_capture_reserve(c, &k->pending, &k->pending_cap, 16 + tiles * 4,
                                "compute capture pending", err);
    if (s != OIT_OK)
        return s;
    GLuint pend = 0;
    if (k->round && !k->cuts)
        oit_host_read(&c->frame.waits, k->pending, 0, 4, &pend);
    k->cuts |= pend != 0;
    read_late(k, &c->frame.waits);
    static const GLuint zero = 0;
    glClearNamedBufferData(k->pending, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    k->round = 0;
    return OIT_OK;
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
                                 .budget = c->set.slot_budget,
                                 .epsilon = c->frame.applied,
                                 .timer = c->set.timer,
                                 .waits = &c->frame.waits};
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
    GLuint pend = 0;
    if (k->round && !k->cuts) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        oit_host_read(&c->frame.waits, k->pending, 0, 4, &pend);
    }
    if (pend)
        return oit_error_set(err, OIT_ERR_GL, "compute capture: the driver cut shader loops "
                             "short at %u pixels though its probe ran to the end; this frame "
                             "is incomplete, the next ones resume them", pend);
    return oit_capture_store_out(c, &k->resume, &k->resume_cap, "compute capture resume", want,
                                 row, out, err);
}

static void compute_stats(const oit_capture *c, oit_frame_stats *stats)
{
    stats->capture = c->ops->name;
}

OIT_CAPTURE_OPS(compute, OIT_CAPTURE_COMPUTE, "compute", oit_compute, NULL, NULL, NULL);
