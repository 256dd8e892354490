/* The counted capture (capture_counted.h). */
#include "render/capture/capture_counted.h"

#include "render/capture/capture_backend.h"
#include "render/capture/capture_glsl.h"
#include "render/gl/frag_glsl.h"

#include <stdlib.h>
#include <string.h>

/* Ahead mode's judge of a batch, after the scan: whether the store holds
 * it (the store pass and the resolve run only then) and the frame's
 * figures. The scan's totals: the fragments (lo, hi), the largest count,
 * the counts over K. */
static const char judge_cs[] =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Scan { uint lo; uint hi; "
    "uint most; uint over; };\n"
    "layout(std430, binding = OIT_BIND_SUMS) buffer Judge { uint gate; uint frame_short; "
    "uint need; uint deep; uvec4 groups; };\n"
    "uniform uint u_cap;\n"
    "uniform uvec2 u_groups;\n"
    "void main() {\n"
    "    bool fits = hi == 0u && lo <= u_cap;\n"
    "    gate = fits && lo != 0u ? 1u : 0u;\n"
    "    if (!fits) frame_short = 1u;\n"
    "    need = max(need, hi != 0u ? 0xffffffffu : lo);\n"
    "    deep += over;\n"
    "    groups = uvec4(gate != 0u ? u_groups : uvec2(0u), 1u, 0u);\n"
    "}\n";
static const oit_glsl_program judge_program = {"counted capture judge", .cs = {judge_cs}};
enum { J_GATE, J_SHORT, J_NEED, J_DEEP, J_GROUPS, J_WORDS = 8 };

static const oit_glsl_program programs[OIT_COUNTED_PROGS] = {
    [OIT_COUNTED_COUNT] = {"counted capture count",
                           .fs = {oit_glsl_state_io, oit_capture_counted_count_fs}},
    [OIT_COUNTED_STORE] = {"counted capture store",
                           .fs = {oit_glsl_state_io, oit_capture_counted_store_fs}},
    [OIT_COUNTED_RESOLVE] = {"counted capture resolve",
                             .cs = {oit_glsl_composite, oit_glsl_state_io,
                                    oit_capture_counted_resolve_cs, oit_glsl_segment_composite,
                                    oit_capture_counted_resolve_main}},
};

oit_status oit_counted_init(oit_counted *k, oit_program_cache *pc, oit_error *err)
{
    memset(k, 0, sizeof *k);
    oit_status s = oit_glsl_programs_build(pc, programs, OIT_COUNTED_PROGS, k->prog, err);
    if (s == OIT_OK)
        s = oit_glsl_programs_build(pc, &judge_program, 1, &k->judge, err);
    if (s == OIT_OK)
        s = oit_scan_init(&k->scan, pc, err);
    if (s != OIT_OK)
        return s;
    glCreateBuffers(1, &k->words);
    glNamedBufferData(k->words, J_WORDS * 4, NULL, GL_DYNAMIC_COPY);
    oit_gl_poison_buffer(k->words);
    return oit_gl_check("counted capture: set-up", err);
}

void oit_counted_release(oit_counted *k)
{
    oit_glsl_programs_delete(k->prog, OIT_COUNTED_PROGS);
    oit_glsl_programs_delete(&k->judge, 1);
    glDeleteBuffers(1, &k->offsets);
    glDeleteBuffers(1, &k->frags);
    glDeleteBuffers(1, &k->words);
    oit_scan_release(&k->scan);
    memset(k, 0, sizeof *k);
}

uint64_t oit_counted_bytes(const oit_counted *k)
{
    return k->offsets_cap + k->frags_cap + oit_scan_bytes(&k->scan) + (k->words ? J_WORDS * 4 : 0);
}

void oit_counted_begin(oit_counted *k, int no_wait, uint64_t fit)
{
    k->splits = 0;
    k->deep_pixels = 0;
    k->seen = 0;
    k->ended_short = 0;
    k->ahead = no_wait && k->measured && k->need <= fit;
    static const GLuint zero[J_GROUPS] = {0};
    glNamedBufferSubData(k->words, 0, sizeof zero, zero);
}

/* A batch of `seen` fragments measured: the need, with room for an eighth
 * more, so that a view that deepens a little does not draw its frames
 * twice. */
static void note_need(oit_counted *k, uint64_t seen)
{
    uint64_t need = seen + seen / 8;
    k->need = need > k->need ? need : k->need;
    k->measured = 1;
}

int oit_counted_ended(oit_counted *k)
{
    uint64_t seen = k->seen;
    if (k->ahead) {
        GLuint w[J_GROUPS];
        oit_host_read(NULL, k->words, 0, sizeof w, w);
        k->ended_short = w[J_SHORT] != 0;
        k->deep_pixels = w[J_DEEP];
        seen = w[J_NEED];
    }
    note_need(k, seen);
    return k->ended_short;
}

void oit_counted_seed(oit_counted *k, uint64_t fragments, uint64_t fit)
{
    note_need(k, fragments);
    if (k->need && k->need <= fit && k->need <= UINT32_MAX)
        oit_gl_buffer_reserve(&k->frags, &k->frags_cap, k->need * 16,
                              "counted capture fragments", NULL);
}


/* Count pass, then offsets = exclusive scan of the counts (pixels + 1
 * entries, the last = the batch's fragments). */
static oit_status count(oit_counted *k, const oit_counted_frame *f,
                        const oit_gpu_mesh *const *meshes, int n, const int r[4],
                        oit_scan_result *res, oit_error *err)
{
    uint64_t pixels = (uint64_t)f->width * f->height;
    oit_status s = oit_gl_buffer_reserve(&k->offsets, &k->offsets_cap, (pixels + 1) * 4,
                                         "counted capture offsets", err);
    if (s != OIT_OK)
        return s;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    oit_glsl_draw_scissored(f->fbo, f->width, f->height, k->prog[OIT_COUNTED_COUNT], f->draws,
                            meshes, n, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    static const GLuint zero = 0;
    glCopyNamedBufferSubData(f->counts, k->offsets, 0, 0, (GLsizeiptr)(pixels * 4));
    glClearNamedBufferSubData(k->offsets, GL_R32UI, (GLintptr)(pixels * 4), 4, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    k->scan.over = k->deep_over;
    s = oit_scan_run(&k->scan, k->offsets, pixels + 1, res, f->waits, err);
    if (s == OIT_OK && res) {
        k->deep_pixels += res->over;
        k->seen = res->total > k->seen ? res->total : k->seen;
    }
    return s;
}

/* Stores the fragments of the rows of r whose offsets start at base (0: the
 * whole batch; a band of rows otherwise, whose pixels' offsets are
 * consecutive) and composites them behind the state. */
static oit_status store_and_resolve(oit_counted *k, const oit_counted_frame *f,
                                    const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                    uint64_t base, uint64_t frags, oit_error *err)
{
    oit_status s = oit_gl_check_ssbo_size(frags * 16, "counted capture: one part's fragments",
                                          err);
    if (s == OIT_OK)
        s = oit_gl_buffer_reserve(&k->frags, &k->frags_cap, frags ? frags * 16 : 16,
                                  "counted capture fragments", err);
    if (s != OIT_OK)
        return s;
    /* the scan bound its data at the counts' binding */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->frags);
    GLuint store = k->prog[OIT_COUNTED_STORE], resolve = k->prog[OIT_COUNTED_RESOLVE];
    glProgramUniform1ui(store, glGetUniformLocation(store, "u_base"), (GLuint)base);
    glProgramUniform1ui(resolve, glGetUniformLocation(resolve, "u_base"), (GLuint)base);
    oit_glsl_draw_scissored(f->fbo, f->width, f->height, store, f->draws, meshes, n, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(resolve);
    glProgramUniform2i(resolve, 11, f->width, f->height);
    glProgramUniform4i(resolve, 12, r[0], r[1], r[2], r[3]);
    glDispatchCompute(oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                      oit_gl_groups((uint64_t)(r[3] - r[1]), 8), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return oit_gl_check("counted capture: batch", err);
}

/* A batch whose fragments over r outgrow fit fragments is stored and
 * composited in bands of rows, from the one count: a pixel's offsets
 * follow the frame's rows, so a band's fragments are the difference of the
 * offsets at its first pixels, and pixels are independent. Each band draws
 * the batch again, scissored to its rows, so the bands together rasterize
 * what one store pass would (splitting by meshes instead counted them
 * again at every halving: 22 parts of a 300-layer stack took 43 count
 * passes). A row that alone outgrows fit gets what it needs within one
 * storage binding; one past that is refused. The row starts are read back
 * at once (one wait). */
static oit_status bands(oit_counted *k, const oit_counted_frame *f,
                        const oit_gpu_mesh *const *meshes, int n, const int r[4], uint64_t fit,
                        oit_error *err)
{
    int rows = r[3] - r[1];
    size_t span = (size_t)rows * (size_t)f->width + 1;
    uint32_t *off = malloc(span * 4);
    if (!off)
        return oit_error_set(err, OIT_ERR_NOMEM, "counted capture: no memory for the offsets "
                             "of %d rows", rows);
    oit_host_read(f->waits, k->offsets, (uint64_t)r[1] * f->width * 4, span * 4, off);
    uint64_t most = f->bind / 16;
    oit_status s = OIT_OK;
#define AT(i) off[(size_t)(i) * (size_t)f->width]
    for (int y = 0; y < rows && s == OIT_OK;) {
        int e = y + 1;
        while (e < rows && (uint64_t)AT(e + 1) - AT(y) <= fit)
            e++;
        if ((uint64_t)AT(e) - AT(y) > most) {
            s = oit_error_set(err, OIT_ERR_NOMEM, "counted capture: row %d holds %u fragments, "
                              "more than one storage buffer binds (%llu bytes)", r[1] + y,
                              AT(e) - AT(y), (unsigned long long)f->bind);
            break;
        }
        int b[4] = {r[0], r[1] + y, r[2], r[1] + e};
        k->splits += y > 0;
        s = store_and_resolve(k, f, meshes, n, b, AT(y), AT(e) - AT(y), err);
        y = e;
    }
#undef AT
    free(off);
    return s;
}

/* The counted batch over r judged against a store of cap fragments: the
 * store pass gated and the resolve dispatched by the judge's verdict.
 * Ahead mode's path, and host mode's where the batch fits one store (cap
 * then the count it read), so that the first frame already builds and
 * runs what the next, ahead, runs (stack80 at 128x128: that frame took
 * 95 ms against 38 warm when only it judged). */
static oit_status judged_store(oit_counted *k, const oit_counted_frame *f,
                               const oit_gpu_mesh *const *meshes, int n, const int r[4],
                               uint64_t cap, oit_error *err)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->scan.totals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, k->words);
    glProgramUniform1ui(k->judge, glGetUniformLocation(k->judge, "u_cap"), (GLuint)cap);
    glProgramUniform2ui(k->judge, glGetUniformLocation(k->judge, "u_groups"),
                        oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                        oit_gl_groups((uint64_t)(r[3] - r[1]), 8));
    glUseProgram(k->judge);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->frags);
    GLuint store = k->prog[OIT_COUNTED_STORE], resolve = k->prog[OIT_COUNTED_RESOLVE];
    glProgramUniform1ui(store, glGetUniformLocation(store, "u_base"), 0);
    glProgramUniform1ui(resolve, glGetUniformLocation(resolve, "u_base"), 0);
    oit_glsl_draw_scissored_gated(f->fbo, f->width, f->height, store, f->draws, meshes, n, r,
                                  k->words, J_GATE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(resolve);
    glProgramUniform2i(resolve, 11, f->width, f->height);
    glProgramUniform4i(resolve, 12, r[0], r[1], r[2], r[3]);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, k->words);
    glDispatchComputeIndirect(J_GROUPS * 4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    return oit_gl_check("counted capture: judged batch", err);
}

/* A batch without the host (ahead mode): counted and scanned on the GPU,
 * judged against the store sized ahead. */
static oit_status ahead_batch(oit_counted *k, const oit_counted_frame *f,
                              const oit_gpu_mesh *const *meshes, int n, const int r[4],
                              oit_error *err)
{
    uint64_t cap = k->frags_cap / 16 > k->need ? k->frags_cap / 16 : k->need;
    cap = cap < UINT32_MAX ? cap : UINT32_MAX;
    oit_status s = oit_gl_buffer_reserve(&k->frags, &k->frags_cap, cap ? cap * 16 : 16,
                                         "counted capture fragments", err);
    if (s == OIT_OK)
        s = count(k, f, meshes, n, r, NULL, err);
    return s == OIT_OK ? judged_store(k, f, meshes, n, r, cap, err) : s;
}

oit_status oit_counted_batch(oit_counted *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4],
                             oit_error *err)
{
    if (k->ahead)
        return ahead_batch(k, f, meshes, n, r, err);
    oit_scan_result res = {0};
    oit_status s = count(k, f, meshes, n, r, &res, err);
    if (s != OIT_OK)
        return s;
    if (res.total == 0)
        return OIT_OK; /* nothing drawn here: the counts are still zero */
    if (res.total > UINT32_MAX)
        return oit_error_set(err, OIT_ERR_NOMEM, "counted capture: %llu fragments in one "
                             "batch, more than 32-bit offsets address",
                             (unsigned long long)res.total);
    /* The budget is the batch's store where it can keep to it; one storage
     * binding is what the store cannot pass. */
    uint64_t fit = k->budget / 16 < f->bind / 16 ? k->budget / 16 : f->bind / 16;
    if (res.total > fit)
        return bands(k, f, meshes, n, r, fit, err);
    s = oit_gl_check_ssbo_size(res.total * 16, "counted capture: one part's fragments", err);
    /* with the need's margin (oit_counted_ended), so that the next frame,
     * ahead, finds its store already there */
    uint64_t room = res.total + res.total / 8 < fit ? res.total + res.total / 8 : fit;
    if (s == OIT_OK)
        s = oit_gl_buffer_reserve(&k->frags, &k->frags_cap, room * 16,
                                  "counted capture fragments", err);
    return s == OIT_OK ? judged_store(k, f, meshes, n, r, res.total, err) : s;
}

/* ---- the counted backend (OIT_CAPTURE_COUNTED) ------------------------------ */

oit_status oit_capture_counted_batch(oit_capture *c, oit_counted *k,
                                     const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                     oit_error *err)
{
    oit_counted_frame f = oit_capture_counted_frame(c);
    /* the slot budget bounds its fragment store; deep pixels are those
     * first-K's K slots would not hold */
    k->budget = c->set.slot_budget ? c->set.slot_budget : UINT64_MAX;
    k->deep_over = (uint32_t)c->K;
    /* count, store, sort and composite: not split into phases */
    oit_gpu_timer_mark(c->set.timer, OIT_GPU_PASS1);
    oit_status s = oit_counted_batch(k, &f, meshes, n, r, err);
    oit_capture_note_peak(c);
    oit_capture_bind_buffers(c);
    return s;
}

/* The whole frame in one band where the budget allows: each band is a pass
 * and a read-back of its own. */
oit_status oit_capture_store_out(oit_capture *c, GLuint *buf, uint64_t *cap, const char *name,
                                 uint64_t want, uint64_t row, oit_capture_out *out,
                                 oit_error *err)
{
    uint64_t budget = c->set.slot_budget;
    if (budget && want > budget)
        want = budget > row ? budget : row;
    want = oit_capture_within_binding(c, want, row);
    oit_status s = oit_capture_reserve(c, buf, cap, want, name, err);
    *out = (oit_capture_out){*buf, *cap};
    return s;
}

static oit_status counted_create(oit_capture *c, int stencil_k, oit_error *err)
{
    return oit_counted_init(c->be, c->programs, err);
}

static void counted_destroy(void *be)
{
    oit_counted_release(be);
}

/* Fragments one store holds: the slot budget where set, one binding. */
uint64_t oit_capture_counted_fit(const oit_capture *c)
{
    uint64_t budget = c->set.slot_budget ? c->set.slot_budget : UINT64_MAX;
    return (budget < c->frame.bind ? budget : c->frame.bind) / 16;
}

static oit_status counted_begin(oit_capture *c, oit_error *err)
{
    oit_counted_begin(c->be, c->set.no_wait, oit_capture_counted_fit(c));
    return OIT_OK;
}

static int counted_ended(oit_capture *c)
{
    return oit_counted_ended(c->be);
}

static void counted_uniforms(oit_capture *c)
{
    oit_counted *k = c->be;
    oit_glsl_set_view_all(k->prog, OIT_COUNTED_PROGS, &c->view);
    /* the opaque depth's projection replaces the view's */
    oit_glsl_set_opaque_all(k->prog, OIT_COUNTED_PROGS, &c->opaque);
}

static void counted_epsilon(oit_capture *c, float e)
{
    oit_glsl_set_epsilon_all(((oit_counted *)c->be)->prog, 2, e); /* the geometry passes */
}

/* Nothing at OIT_BIND_OUT within the frame: its output passes through the
 * fragment store at the end. */
static void counted_bind(const oit_capture *c)
{
    oit_capture_bind_within(c, OIT_BIND_OUT, 0, 0);
}

/* No per-pixel limit: a batch of any number of layers is an ordinary one. */
static oit_status counted_batch(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                const int rect[4], int layers, oit_error *err)
{
    int r[4] = {0}, empty = 1;
    oit_status s = oit_capture_batch_start(c, meshes, rect, n, r, &empty, err);
    if (s != OIT_OK || empty)
        return s;
    return oit_capture_counted_batch(c, c->be, meshes, n, r, err);
}

static oit_status counted_end(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                              oit_error *err)
{
    oit_counted *k = c->be;
    return oit_capture_store_out(c, &k->frags, &k->frags_cap, "counted capture fragments", want,
                                 row, out, err);
}

static uint64_t counted_bytes(const void *be)
{
    return oit_counted_bytes(be);
}

static void counted_stats(const oit_capture *c, oit_frame_stats *stats)
{
    const oit_counted *k = c->be;
    stats->capture = c->ops->name;
    stats->batches += k->splits;
    stats->deep_pixels = k->deep_pixels;
}

OIT_CAPTURE_OPS(counted, OIT_CAPTURE_COUNTED, "counted", oit_counted, NULL, NULL,
                counted_ended);
