/* Many meshes in few draw calls (oit_gpu_mesh_draw_many, gpu_mesh.h).
 *
 * Per draw call a driver validates state and sets up the pipeline; on
 * llvmpipe that is ~55 us, which a pack of thousands of small parts paid
 * per part. A multi-draw pays it once per group. Core GL 4.5 has no draw
 * index in the shader (gl_DrawID needs ARB_shader_draw_parameters, core only
 * in 4.6), so every command carries its index as baseInstance, and a vertex
 * attribute with divisor 1 fetches that command's record, (first vertex,
 * first prim): where its triangles start in the binding, and what to add to
 * gl_PrimitiveID (frag_glsl.h); for a sourced mesh, where its prims start
 * in the group's OIT_BIND_PRIMS binding. The commands of one group share
 * one SSBO binding (and one of prims), hence the grouping by buffer and
 * window.
 *
 * What the driver may do least (GL 4.5 core leaves it open): a new buffer
 * holds garbage, so only written commands and records are ever read; the
 * records buffer is given to the vertex array again whenever it is
 * replaced; every storage block the vertex stage declares is backed on
 * every draw. */
#include "view/render/gl/gpu_mesh.h"

#include "base/grow.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_draw_record.h"

#include <stdlib.h>

/* GL's DrawArraysIndirectCommand. */
typedef struct draw_cmd {
    GLuint count, instances, first, base_instance;
} draw_cmd;

/* Commands [first, first + count) drawn with buffer bound from lo, rounded
 * down to the unit, to hi. A solo group is bound from lo itself: its one
 * command starts off the 16-byte grid that first vertices count in. */
typedef struct draw_group {
    GLuint buffer;
    uint64_t lo, hi;
    uint64_t plo, phi; /* its sourced commands' prims; plo > phi: none */
    size_t first, count;
    int solo;
} draw_group;

struct oit_gpu_draws {
    GLuint vao, cmd_buf, rec_buf;
    /* oit_gpu_mesh_draw_many_gated's pass over the commands, built on
     * first use; gate_failed: it could not be, the draws go ungated */
    GLuint gate_prog;
    int gate_failed;
    uint64_t cmd_bytes, rec_bytes; /* capacities of the GL buffers */
    /* CPU staging, cap commands each: at[k] is command k's byte offset in
     * its buffer until its group's base is known. */
    draw_cmd *cmds;
    oit_draw_rec *recs;
    uint64_t *at;
    uint64_t *prims_at; /* command k's prims' byte offset; NO_PRIMS: not sourced */
    draw_group *groups;
    size_t cap;
    size_t window, driver_window; /* triangles a group may span */
    size_t asked_window;          /* the test's (oit_gpu_draws_set_window), or 0 */
    /* Group bases: multiples of the SSBO offset alignment and of the 16
     * bytes of a vertex, which first vertices count in. */
    uint64_t unit, align;
    uint64_t calls;
};

enum { INITIAL_DRAWS = 256 };
#define NO_PRIMS UINT64_MAX

/* A buffer of at least `bytes` in *buf: a new one when it is short, whose
 * immutable store is then the only one that name ever has. */
static oit_status grow_gl(GLuint *buf, uint64_t *cap, uint64_t bytes, const char *what,
                          oit_error *err)
{
    if (*buf && *cap >= bytes)
        return OIT_OK;
    GLuint b = 0;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    oit_gl_poison_buffer(b);
    oit_status s = oit_gl_check(what, err);
    if (s != OIT_OK) {
        glDeleteBuffers(1, &b);
        return s;
    }
    glDeleteBuffers(1, buf);
    *buf = b;
    *cap = bytes;
    return OIT_OK;
}

static oit_status reserve_gl(oit_gpu_draws *d, size_t n, oit_error *err)
{
    GLuint recs = d->rec_buf;
    oit_status s = grow_gl(&d->cmd_buf, &d->cmd_bytes, n * sizeof(draw_cmd),
                           "multi-draw commands", err);
    if (s == OIT_OK)
        s = grow_gl(&d->rec_buf, &d->rec_bytes, n * sizeof(oit_draw_rec), "multi-draw records",
                    err);
    if (d->rec_buf != recs)
        oit_draw_records_attach(d->vao, d->rec_buf);
    return s;
}

/* Room for n commands, CPU and GL; on failure the room stays as it was. */
static int reserve(oit_gpu_draws *d, size_t n)
{
    if (n <= d->cap)
        return 1;
    size_t want = d->cap + d->cap / 2 > n ? d->cap + d->cap / 2 : n;
    int ok = 1;
    d->cmds = oit_grow(d->cmds, want, sizeof *d->cmds, &ok);
    d->recs = oit_grow(d->recs, want, sizeof *d->recs, &ok);
    d->at = oit_grow(d->at, want, sizeof *d->at, &ok);
    d->prims_at = oit_grow(d->prims_at, want, sizeof *d->prims_at, &ok);
    d->groups = oit_grow(d->groups, want, sizeof *d->groups, &ok);
    if (!ok || reserve_gl(d, want, NULL) != OIT_OK)
        return 0;
    d->cap = want;
    return 1;
}

oit_status oit_gpu_draws_create(oit_gpu_draws **out, oit_error *err)
{
    *out = NULL;
    oit_gpu_draws *d = calloc(1, sizeof *d);
    if (!d)
        return oit_error_set(err, OIT_ERR_NOMEM, "multi-draw: out of memory");
    d->align = oit_gl_ssbo_align();
    oit_gpu_draws_set_align(d, 0);
    glCreateVertexArrays(1, &d->vao);
    oit_status s = reserve(d, INITIAL_DRAWS)
                       ? OIT_OK
                       : oit_error_set(err, OIT_ERR_NOMEM, "multi-draw: cannot allocate room "
                                       "for %d draws", INITIAL_DRAWS);
    if (s == OIT_OK)
        s = oit_gl_check("multi-draw: vertex array", err);
    if (s == OIT_OK && d->window == 0)
        s = oit_error_set(err, OIT_ERR_GL, "multi-draw: GL_MAX_SHADER_STORAGE_BLOCK_SIZE is "
                          "smaller than one triangle");
    if (s != OIT_OK) {
        oit_gpu_draws_destroy(d);
        return s;
    }
    *out = d;
    return OIT_OK;
}

void oit_gpu_draws_destroy(oit_gpu_draws *d)
{
    if (!d)
        return;
    glDeleteVertexArrays(1, &d->vao);
    glDeleteBuffers(1, &d->cmd_buf);
    glDeleteBuffers(1, &d->rec_buf);
    glDeleteProgram(d->gate_prog);
    free(d->cmds);
    free(d->recs);
    free(d->at);
    free(d->prims_at);
    free(d->groups);
    free(d);
}

uint64_t oit_gpu_draws_calls(const oit_gpu_draws *d)
{
    return d->calls;
}

uint64_t oit_gpu_draws_bytes(const oit_gpu_draws *d)
{
    return d ? d->cmd_bytes + d->rec_bytes : 0;
}

/* The driver's window with starts on the unit, or the test's below it. */
static void fit_window(oit_gpu_draws *d)
{
    /* Window starts inside a mesh stay on the unit, as group bases must. */
    size_t step = oit_gpu_triangle_step(d->unit);
    size_t driver = oit_gpu_triangle_window() / step * step;
    d->driver_window = driver;
    size_t t = d->asked_window;
    if (t == 0 || t > driver)
        d->window = driver;
    else
        d->window = t > step ? t / step * step : step;
}

void oit_gpu_draws_set_window(oit_gpu_draws *d, size_t triangles)
{
    d->asked_window = triangles;
    fit_window(d);
}

void oit_gpu_draws_set_align(oit_gpu_draws *d, uint64_t bytes)
{
    uint64_t a = bytes && bytes % d->align == 0 ? bytes : d->align;
    for (d->unit = a; d->unit % 16 != 0;)
        d->unit += a;
    fit_window(d);
}

/* Adds command k for `count` triangles at byte offset `at` of buffer (its
 * prims at prims_at, or NO_PRIMS), to the last group when the group's spans
 * stay within a window, else to a new one. */
static void add_command(oit_gpu_draws *d, size_t *groups, size_t k, GLuint buffer, uint64_t at,
                        size_t count, uint32_t first_prim, uint64_t prims_at)
{
    uint64_t end = at + (uint64_t)count * sizeof(oit_triangle),
             window = (uint64_t)d->window * sizeof(oit_triangle);
    uint64_t plo = prims_at, phi = prims_at == NO_PRIMS ? 0 : prims_at + (uint64_t)count * 4;
    d->cmds[k] = (draw_cmd){(GLuint)(count * 3), 1, 0, (GLuint)k};
    d->recs[k] = (oit_draw_rec){0, first_prim};
    d->at[k] = at;
    d->prims_at[k] = prims_at;
    draw_group *g = *groups ? &d->groups[*groups - 1] : NULL;
    int solo = at % 16 != 0;
    if (g && !g->solo && !solo && g->buffer == buffer) {
        uint64_t lo = at < g->lo ? at : g->lo, hi = end > g->hi ? end : g->hi;
        uint64_t pl = plo < g->plo ? plo : g->plo, ph = phi > g->phi ? phi : g->phi;
        if (hi - (lo - lo % d->unit) <= window &&
            (pl > ph || ph - (pl - pl % d->unit) <= window)) {
            g->lo = lo;
            g->hi = hi;
            g->plo = pl;
            g->phi = ph;
            g->count++;
            return;
        }
    }
    d->groups[(*groups)++] = (draw_group){buffer, at, end, plo, phi, k, 1, solo};
}

static uint64_t group_base(const oit_gpu_draws *d, const draw_group *g)
{
    return g->solo ? g->lo : g->lo - g->lo % d->unit;
}

static int group_sourced(const draw_group *g)
{
    return g->plo < g->phi;
}

static uint64_t group_prims_base(const oit_gpu_draws *d, const draw_group *g)
{
    return g->plo - g->plo % d->unit;
}

/* Commands [0, k) get their first vertices (and prims' indices) from each
 * of their groups' bases. */
static void place_commands(oit_gpu_draws *d, size_t groups)
{
    for (size_t g = 0; g < groups; g++) {
        const draw_group *gr = &d->groups[g];
        uint64_t base = group_base(d, gr);
        for (size_t c = gr->first; c < gr->first + gr->count; c++) {
            GLuint first = (GLuint)((d->at[c] - base) / 16);
            d->cmds[c].first = first;
            d->recs[c].first_vertex = first;
            if (d->prims_at[c] != NO_PRIMS)
                d->recs[c].first_prim =
                    0x80000000u | (GLuint)((d->prims_at[c] - group_prims_base(d, gr)) / 4);
        }
    }
}

/* Binds group g's triangles at OIT_BIND_VERTS and its prims at
 * OIT_BIND_PRIMS, or, without any, its triangles there too: a block the
 * vertex stage declares is never left unbound or bound to a stale range. */
static void bind_group(const oit_gpu_draws *d, const draw_group *gr)
{
    uint64_t base = group_base(d, gr);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, gr->buffer, (GLintptr)base,
                      (GLsizeiptr)(gr->hi - base));
    uint64_t plo = group_sourced(gr) ? group_prims_base(d, gr) : base;
    uint64_t phi = group_sourced(gr) ? gr->phi : gr->hi;
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, gr->buffer, (GLintptr)plo,
                      (GLsizeiptr)(phi - plo));
}

extern const char oit_glsl_draw_gate[]; /* glsl/draw_gate.glsl */
static const oit_glsl_program gate_program = {"multi-draw gate", .cs = {oit_glsl_draw_gate}};

void oit_gpu_draws_glsl_variants(oit_glsl_visit *visit, void *user)
{
    visit(user, &gate_program);
}

/* A storage binding as it was, to put back. */
typedef struct ssbo_binding {
    GLint buf;
    GLint64 start, size;
} ssbo_binding;

static ssbo_binding binding_get(GLuint index)
{
    ssbo_binding b = {0, 0, 0};
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, index, &b.buf);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, index, &b.start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, index, &b.size);
    return b;
}

static void binding_put(GLuint index, ssbo_binding b)
{
    if (b.buf && b.size > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, index, (GLuint)b.buf, (GLintptr)b.start,
                          (GLsizeiptr)b.size);
    else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, index, (GLuint)b.buf);
}

/* Commands [0, k) gated by word `word` of buffer gate; the caller's
 * program and storage bindings are left as they were. */
static void gate_commands(oit_gpu_draws *d, size_t k, GLuint gate, GLuint word)
{
    if (!d->gate_prog && !d->gate_failed) {
        d->gate_failed = oit_glsl_programs_build(NULL, &gate_program, 1, &d->gate_prog, NULL) != OIT_OK;
    }
    if (d->gate_failed)
        return; /* ungated: the draws rasterize, the caller's shader still decides */
    GLint prog = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    ssbo_binding out = binding_get(OIT_BIND_OUT), totals = binding_get(OIT_BIND_TOTALS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, d->cmd_buf);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, gate);
    glUseProgram(d->gate_prog);
    glProgramUniform1ui(d->gate_prog, glGetUniformLocation(d->gate_prog, "u_word"), word);
    glProgramUniform1ui(d->gate_prog, glGetUniformLocation(d->gate_prog, "u_count"),
                        (GLuint)k);
    glDispatchCompute((GLuint)((k + 63) / 64), 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    binding_put(OIT_BIND_OUT, out);
    binding_put(OIT_BIND_TOTALS, totals);
    glUseProgram((GLuint)prog);
}

/* Draws commands [0, k) in their groups [0, groups): one upload, one
 * multi-draw a group; gated by word `word` of buffer gate (0: not). */
static void flush(oit_gpu_draws *d, size_t k, size_t groups, GLuint gate, GLuint word)
{
    if (k == 0)
        return;
    place_commands(d, groups);
    /* Rewriting the buffers between groups could make a driver wait for
     * the draws before: all of them go up at once. */
    glNamedBufferSubData(d->cmd_buf, 0, (GLsizeiptr)(k * sizeof(draw_cmd)), d->cmds);
    glNamedBufferSubData(d->rec_buf, 0, (GLsizeiptr)(k * sizeof(oit_draw_rec)), d->recs);
    if (gate)
        gate_commands(d, k, gate, word);
    glBindVertexArray(d->vao);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, d->cmd_buf);
    for (size_t g = 0; g < groups; g++) {
        const draw_group *gr = &d->groups[g];
        bind_group(d, gr);
        glMultiDrawArraysIndirect(GL_TRIANGLES,
                                  (const void *)(uintptr_t)(gr->first * sizeof(draw_cmd)),
                                  (GLsizei)gr->count, 0);
        d->calls++;
    }
}

static void draw_many(oit_gpu_draws *d, const oit_gpu_mesh *const *meshes, int n, GLuint gate,
                      GLuint word)
{
    size_t total = 0, k = 0, groups = 0;
    for (int i = 0; i < n; i++)
        total += (oit_gpu_mesh_triangles(meshes[i]) + d->window - 1) / d->window;
    /* Without room for all, it draws what fits at a time. */
    reserve(d, total);
    for (int i = 0; i < n; i++) {
        const oit_gpu_mesh *m = meshes[i];
        size_t count = oit_gpu_mesh_triangles(m);
        uint64_t prims = NO_PRIMS;
        int sourced = oit_gpu_mesh_sourced(m, &prims);
        for (size_t start = 0; start < count; start += d->window) {
            if (k == d->cap) {
                flush(d, k, groups, gate, word);
                k = groups = 0;
            }
            add_command(d, &groups, k++, oit_gpu_mesh_buffer(m),
                        oit_gpu_mesh_offset(m) + start * sizeof(oit_triangle),
                        count - start < d->window ? count - start : d->window,
                        oit_gpu_mesh_first_prim(m) + (uint32_t)start,
                        sourced ? prims + (uint64_t)start * 4 : NO_PRIMS);
        }
    }
    flush(d, k, groups, gate, word);
}

void oit_gpu_mesh_draw_many(oit_gpu_draws *d, const oit_gpu_mesh *const *meshes, int n)
{
    draw_many(d, meshes, n, 0, 0);
}

void oit_gpu_mesh_draw_many_gated(oit_gpu_draws *d, const oit_gpu_mesh *const *meshes, int n,
                                  unsigned gate, unsigned word)
{
    draw_many(d, meshes, n, gate, word);
}

void oit_glsl_draw_scissored(GLuint fbo, int w, int h, GLuint prog, oit_gpu_draws *draws,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4])
{
    oit_glsl_raster_begin(fbo, w, h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r[0], r[1], r[2] - r[0], r[3] - r[1]);
    glUseProgram(prog);
    oit_gpu_mesh_draw_many(draws, meshes, n);
    glDisable(GL_SCISSOR_TEST);
}

void oit_glsl_draw_scissored_gated(GLuint fbo, int w, int h, GLuint prog,
                                   oit_gpu_draws *draws,
                                   const oit_gpu_mesh *const *meshes, int n,
                                   const int r[4], GLuint gate, unsigned word)
{
    oit_glsl_raster_begin(fbo, w, h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r[0], r[1], r[2] - r[0], r[3] - r[1]);
    glUseProgram(prog);
    oit_gpu_mesh_draw_many_gated(draws, meshes, n, gate, word);
    glDisable(GL_SCISSOR_TEST);
}
