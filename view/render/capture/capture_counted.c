/* The counted capture (capture_counted.h). */
#include "view/render/capture/capture_counted.h"
#include "view/render/capture/capture_counted_steps.h"

#include "view/render/capture/capture_backend.h"
#include "view/render/capture/capture_glsl.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/gl/frag_glsl.h"

#include <stdlib.h>
#include <string.h>

/* A band of a batch's rows, judged after the scan (glsl/counted_judge.glsl):
 * whether the store holds its fragments, where they start, and the
 * frame's figures; its words the host names. */
extern const char oit_counted_judge_cs[], oit_counted_split_cs[]; /* glsl/counted_*.glsl */
static const oit_glsl_program judge_program = {"counted capture judge",
                                               .cs = {oit_counted_judge_cs}};
enum { J_GATE, J_SHORT, J_DEEP, J_GROUPS = 4, J_BASE = 8, J_CAP, J_WORDS = 12 };

/* A batch's bands of rows, cut on the GPU after the scan: from row
 * u_rows.x on, one band where the rows' fragments fit the store (u_fit),
 * else each band the most rows whose fragments stay within u_target (a
 * row that alone passes it is a band of its own), at most BANDS of them. Its slot of the band
 * table: the bands (BANDS_LEFT set where rows were left), the scan's high word, the first row's
 * offset, then each band's end row and the offset there. The host reads the slot where it splits a
 * batch itself; the next frame's ahead batches draw the bands this one cut (oit_counted_ended). */
enum { BANDS = OIT_COUNTED_BANDS, SLOT = 128, S_BANDS = 0, S_HI, S_START, S_ENDS };
#define BANDS_LEFT 0x80000000u
static const oit_glsl_program split_program = {"counted capture bands",
                                               .cs = {oit_counted_split_cs}};

static const oit_glsl_program programs[OIT_COUNTED_PROGS] = {
    [OIT_COUNTED_COUNT] = {"counted capture count",
                           .fs = {oit_glsl_state_io, oit_capture_counted_count_fs}},
    [OIT_COUNTED_STORE] = {"counted capture store",
                           .fs = {oit_glsl_state_io, oit_capture_counted_store_fs}},
    [OIT_COUNTED_RESOLVE] = {"counted capture resolve",
                             .cs = {oit_glsl_composite, oit_glsl_state_io,
                                    oit_capture_counted_resolve_cs, oit_glsl_segment_composite,
                                    oit_capture_counted_resolve_main}},
    [OIT_COUNTED_PREDICTED] = {"counted capture predicted store",
                               .fs = {oit_glsl_state_io, oit_capture_counted_predicted_fs}},
    [OIT_COUNTED_PREDICTED_RESOLVE] = {"counted capture predicted resolve",
                                       .cs = {oit_glsl_composite, oit_glsl_state_io,
                                              oit_capture_counted_predicted_cs,
                                              oit_glsl_segment_composite,
                                              oit_capture_counted_predicted_main}},
};

void oit_counted_glsl_variants(oit_glsl_visit *visit, void *user)
{
    for (int i = 0; i < OIT_COUNTED_PROGS; i++)
        visit(user, &programs[i]);
    visit(user, &judge_program);
    visit(user, &split_program);
}

/* The judge's frame figures (gate to groups) to zero. */
static void zero_figures(oit_counted *k)
{
    static const GLuint zero[J_GROUPS] = {0};
    glNamedBufferSubData(k->words, 0, sizeof zero, zero);
}

oit_status oit_counted_init(oit_counted *k, oit_program_cache *pc, oit_error *err)
{
    memset(k, 0, sizeof *k);
    k->pc = pc;
    /* the predicted passes wait for a frame that predicts */
    oit_status s = oit_glsl_programs_build(pc, programs, OIT_COUNTED_PREDICTED, k->prog, err);
    if (s == OIT_OK)
        s = oit_glsl_programs_build(pc, &programs[OIT_COUNTED_RESOLVE], 1,
                                    &k->prog[OIT_COUNTED_RESOLVE], err);
    if (s == OIT_OK)
        s = oit_glsl_programs_build(pc, &judge_program, 1, &k->judge, err);
    if (s == OIT_OK)
        s = oit_glsl_programs_build(pc, &split_program, 1, &k->split, err);
    if (s == OIT_OK)
        s = oit_scan_init(&k->scan, pc, err);
    if (s != OIT_OK)
        return s;
    glCreateBuffers(1, &k->words);
    glNamedBufferData(k->words, J_WORDS * 4, NULL, GL_DYNAMIC_COPY);
    oit_gl_poison_buffer(k->words);
    zero_figures(k); /* built mid-frame (first-K's wide packs): no begin before */
    return oit_gl_check("counted capture: set-up", err);
}

void oit_counted_release(oit_counted *k)
{
    oit_glsl_programs_delete(k->prog, OIT_COUNTED_PROGS);
    oit_glsl_programs_delete(&k->judge, 1);
    oit_glsl_programs_delete(&k->split, 1);
    glDeleteBuffers(1, &k->offsets);
    glDeleteBuffers(1, &k->frags);
    glDeleteBuffers(1, &k->words);
    glDeleteBuffers(1, &k->table);
    glDeleteBuffers(OIT_COUNTED_PREDICTED_BATCHES, k->predicted);
    glDeleteBuffers(1, &k->next);
    oit_scan_release(&k->scan);
    free(k->pred);
    memset(k, 0, sizeof *k);
}

uint64_t oit_counted_bytes(const oit_counted *k)
{
    uint64_t predicted = k->next_cap;
    for (int j = 0; j < OIT_COUNTED_PREDICTED_BATCHES; j++)
        predicted += k->predicted_cap[j];
    return k->offsets_cap + k->frags_cap + oit_scan_bytes(&k->scan) + (k->words ? J_WORDS * 4 : 0) +
           k->table_slots * SLOT * 4 + predicted;
}

/* The predicted passes' programs where they are not built yet; a
 * driver that refuses them leaves every batch counted. */
void oit_counted_build_predicted(oit_counted *k)
{
    if (k->prog[OIT_COUNTED_PREDICTED] || k->predicted_failed)
        return;
    k->predicted_failed =
        oit_glsl_programs_build(k->pc, &programs[OIT_COUNTED_PREDICTED], 1,
                                &k->prog[OIT_COUNTED_PREDICTED], NULL) != OIT_OK ||
        oit_glsl_programs_build(k->pc, &programs[OIT_COUNTED_PREDICTED_RESOLVE], 1,
                                &k->prog[OIT_COUNTED_PREDICTED_RESOLVE], NULL) != OIT_OK;
    if (k->predicted_failed)
        oit_glsl_programs_delete(&k->prog[OIT_COUNTED_PREDICTED], 1);
}

void oit_counted_begin(oit_counted *k, int no_wait, uint64_t fit)
{
    k->splits = 0;
    k->deep_pixels = 0;
    k->batch = 0;
    k->ended_short = 0;
    k->ahead = no_wait && k->measured && !k->unbanded && k->need <= fit;
    k->unbanded = 0;
    k->predicted_batches = 0;
    zero_figures(k);
    /* the predicted passes, once a frame ahead has a prediction to draw
     * by; before the frame's uniforms are set */
    int any = 0;
    for (int j = 0; j < OIT_COUNTED_PREDICTED_BATCHES; j++)
        any |= k->predicted_ok[j];
    if (k->ahead && any)
        oit_counted_build_predicted(k);
}

/* A band of `seen` fragments, the most of a frame: the need, with room
 * for an eighth more, so that a view that deepens a little does not draw
 * its frames twice. The last frame's, not the most of all frames: the
 * store only grows, and the judge weighs a band against what it holds. */
static void note_need(oit_counted *k, uint64_t seen)
{
    k->need = seen + seen / 8;
    k->measured = 1;
}

/* The bands this frame's batches were cut in, for the next frame's, and
 * the most fragments one of them holds: the need. A batch cut in more
 * bands than a slot holds (or past 32-bit offsets) leaves the next frame
 * to the host. */
static void keep_bands(oit_counted *k)
{
    if (k->batch > k->pred_cap) {
        uint32_t *p = realloc(k->pred, k->batch * SLOT * 4);
        if (!p) {
            k->pred_n = 0;
            k->unbanded = 1;
            return;
        }
        k->pred = p, k->pred_cap = k->batch;
    }
    k->pred_n = k->batch;
    /* a frame that drew no batch counted (first-K's) measured nothing:
     * the need stays (seeded or the last counted frame's) */
    if (!k->batch)
        return;
    oit_host_read(NULL, k->table, 0, k->batch * SLOT * 4, k->pred);
    uint64_t most = 0;
    for (size_t j = 0; j < k->pred_n; j++) {
        const uint32_t *slot = k->pred + j * SLOT;
        k->unbanded |= (slot[S_BANDS] & BANDS_LEFT) || slot[S_HI];
        for (uint32_t b = 0, at = slot[S_START]; b < (slot[S_BANDS] & ~BANDS_LEFT); b++) {
            uint32_t e = slot[S_ENDS + 2 * b + 1];
            most = e - at > most ? e - at : most;
            at = e;
        }
    }
    /* a batch the store held whole may take it all */
    note_need(k, most);
    k->need = most <= k->fit && k->need > k->fit ? k->fit : k->need;
}

int oit_counted_ended(oit_counted *k)
{
    GLuint w[J_GROUPS];
    oit_host_read(NULL, k->words, 0, sizeof w, w);
    k->ended_short = k->ahead && w[J_SHORT] != 0;
    k->deep_pixels = w[J_DEEP];
    keep_bands(k);
    return k->ended_short;
}

void oit_counted_seed(oit_counted *k, uint64_t fragments, uint64_t fit)
{
    note_need(k, fragments);
    if (k->need && k->need <= fit && k->need <= UINT32_MAX)
        oit_gl_buffer_reserve(&k->frags, &k->frags_cap, k->need * 16, "counted capture fragments",
                              NULL);
}

/* Fragments one store holds: the budget where it can keep to it, one
 * storage binding at most. */
static uint64_t store_fit(const oit_counted *k, const oit_counted_frame *f)
{
    return k->budget / 16 < f->bind / 16 ? k->budget / 16 : f->bind / 16;
}

/* Batch j's slot of the band table, the table grown (what it held kept). */
static oit_status table_slot(oit_counted *k, size_t j, oit_error *err)
{
    if (j < k->table_slots)
        return OIT_OK;
    size_t slots = j < 32 ? 64 : 2 * j;
    GLuint t = 0;
    glCreateBuffers(1, &t);
    glNamedBufferData(t, (GLsizeiptr)(slots * SLOT * 4), NULL, GL_DYNAMIC_COPY);
    oit_gl_poison_buffer(t);
    if (k->table)
        glCopyNamedBufferSubData(k->table, t, 0, 0, (GLsizeiptr)(k->table_slots * SLOT * 4));
    glDeleteBuffers(1, &k->table);
    k->table = t, k->table_slots = slots;
    return oit_gl_check("counted capture: band table", err);
}

/* offsets = the exclusive scan of the frame's counts (pixels + 1 entries,
 * the last = the fragments), the counts over `over` counted, nothing read
 * back. */
oit_status oit_counted_scan_counts(oit_counted *k, const oit_counted_frame *f, uint32_t over,
                                   oit_error *err)
{
    uint64_t pixels = (uint64_t)f->width * f->height;
    oit_status s = oit_gl_buffer_reserve(&k->offsets, &k->offsets_cap, (pixels + 1) * 4,
                                         "counted capture offsets", err);
    if (s != OIT_OK)
        return s;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    static const GLuint zero = 0;
    glCopyNamedBufferSubData(f->counts, k->offsets, 0, 0, (GLsizeiptr)(pixels * 4));
    glClearNamedBufferSubData(k->offsets, GL_R32UI, (GLintptr)(pixels * 4), 4, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    k->scan.over = over;
    return oit_scan_run(&k->scan, k->offsets, pixels + 1, NULL, f->waits, err);
}

/* Count pass, then its scan into offsets. */
static oit_status count(oit_counted *k, const oit_counted_frame *f,
                        const oit_gpu_mesh *const *meshes, int n, const int r[4], oit_error *err)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS1);
    oit_glsl_draw_scissored(f->fbo, f->width, f->height, k->prog[OIT_COUNTED_COUNT], f->draws,
                            meshes, n, r);
    return oit_counted_scan_counts(k, f, k->deep_over, err);
}

/* Cuts the rows [y0, y1) of batch j's count in bands into its slot of
 * the band table: one where they fit, else of at most target fragments. */
void oit_counted_split(oit_counted *k, const oit_counted_frame *f, GLuint offsets, size_t j, int y0,
                       int y1, uint64_t fit, uint64_t target)
{
    GLuint p = k->split;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->scan.totals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, k->table);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_width"), (GLuint)f->width);
    glProgramUniform2ui(p, glGetUniformLocation(p, "u_rows"), (GLuint)y0, (GLuint)y1);
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_fit"),
                        (GLuint)(fit < UINT32_MAX ? fit : UINT32_MAX));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_target"),
                        (GLuint)(target < UINT32_MAX ? target : UINT32_MAX));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_slot"), (GLuint)(j * SLOT));
    glProgramUniform1ui(p, glGetUniformLocation(p, "u_bands"), BANDS);
    glUseProgram(p);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* The band of rows r of the scan in offsets judged against the store (its
 * capacity), into the judge's words; with first, the scan's counts over
 * K added to the frame's deep pixels. */
void oit_counted_judge(oit_counted *k, const oit_counted_frame *f, GLuint offsets, const int r[4],
                       int first)
{
    uint64_t cap = k->frags_cap / 16 < UINT32_MAX ? k->frags_cap / 16 : UINT32_MAX;
    GLuint j = k->judge;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->scan.totals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, offsets);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, k->words);
    glProgramUniform1ui(j, glGetUniformLocation(j, "u_cap"), (GLuint)cap);
    glProgramUniform1ui(j, glGetUniformLocation(j, "u_width"), (GLuint)f->width);
    glProgramUniform2ui(j, glGetUniformLocation(j, "u_rows"), (GLuint)r[1], (GLuint)r[3]);
    glProgramUniform2ui(j, glGetUniformLocation(j, "u_groups"),
                        oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                        oit_gl_groups((uint64_t)(r[3] - r[1]), 8));
    glProgramUniform1ui(j, glGetUniformLocation(j, "u_first"), (GLuint)first);
    glUseProgram(j);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

/* The band of rows r judged: the store pass gated and the resolve
 * dispatched by the judge's verdict, both at the offset the judge read.
 * Every band of both modes goes this way, so that the first frame already
 * builds and runs what the next, ahead, runs (stack80 at 128x128: that
 * frame took 95 ms against 38 warm when only it judged). */
oit_status oit_counted_judged_store(oit_counted *k, const oit_counted_frame *f,
                                    const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                    int first, oit_error *err)
{
    oit_counted_judge(k, f, k->offsets, r, first);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->frags);
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS2);
    oit_glsl_draw_scissored_gated(f->fbo, f->width, f->height, k->prog[OIT_COUNTED_STORE], f->draws,
                                  meshes, n, r, k->words, J_GATE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(f->timer, OIT_GPU_RESOLVE);
    GLuint resolve = k->prog[OIT_COUNTED_RESOLVE];
    glUseProgram(resolve);
    glProgramUniform2i(resolve, OIT_LOC_SIZE, f->width, f->height);
    glProgramUniform4i(resolve, OIT_LOC_RECT, r[0], r[1], r[2], r[3]);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, k->words);
    glDispatchComputeIndirect(J_GROUPS * 4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    k->splits += !first;
    return oit_gl_check("counted capture: band", err);
}

/* The bands the last frame cut batch j in, clipped to r's rows (a view
 * that moved a little keeps them; the judge finds out where it did not):
 * their end rows into ends, the last r's end. */
int oit_counted_foreseen_bands(const oit_counted *k, size_t j, const int r[4], int ends[BANDS + 1])
{
    int nb = 0;
    if (j < k->pred_n) {
        const uint32_t *slot = k->pred + j * SLOT;
        uint32_t bands = slot[S_BANDS] & ~BANDS_LEFT;
        for (uint32_t b = 0; b < bands && b < BANDS; b++) {
            int e = (int)slot[S_ENDS + 2 * b];
            if (e > (nb ? ends[nb - 1] : r[1]) && e < r[3])
                ends[nb++] = e;
        }
    }
    ends[nb++] = r[3];
    return nb;
}

/* The store sized for the need, ahead of the frame's read-back. */
oit_status oit_counted_reserve_need(oit_counted *k, oit_error *err)
{
    uint64_t cap = k->need < UINT32_MAX ? k->need : UINT32_MAX;
    if (cap * 16 <= k->frags_cap)
        return OIT_OK;
    return oit_gl_buffer_reserve(&k->frags, &k->frags_cap, cap ? cap * 16 : 16,
                                 "counted capture fragments", err);
}

/* A batch without the host (ahead mode): counted, scanned and cut for the
 * next frame on the GPU, its bands those the last frame cut, each judged
 * against the store sized ahead. */
static oit_status ahead_batch(oit_counted *k, const oit_counted_frame *f,
                              const oit_gpu_mesh *const *meshes, int n, const int r[4],
                              uint64_t fit, uint64_t target, oit_error *err)
{
    oit_status s = oit_counted_reserve_need(k, err);
    if (s == OIT_OK)
        s = count(k, f, meshes, n, r, err);
    if (s != OIT_OK)
        return s;
    oit_counted_split(k, f, k->offsets, k->batch, r[1], r[3], fit, target);
    int ends[BANDS + 1], nb = oit_counted_foreseen_bands(k, k->batch, r, ends);
    for (int b = 0, y = r[1]; b < nb && s == OIT_OK; y = ends[b++]) {
        int band[4] = {r[0], y, r[2], ends[b]};
        s = oit_counted_judged_store(k, f, meshes, n, band, b == 0, err);
    }
    return s;
}

/* The host's own bands of one slot (read back: one wait), each stored
 * with a store that holds it. A row that alone outgrows the budget gets
 * what it needs within one storage binding; one past that is refused.
 * *next: the row the slot's bands left off at (r's end: none left). */
static oit_status host_bands(oit_counted *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4], int y0,
                             uint64_t fit, int *next, oit_error *err)
{
    uint32_t w[SLOT];
    oit_host_read(f->waits, k->table, k->batch * SLOT * 4, sizeof w, w);
    if (w[S_HI] != 0)
        return oit_error_set(err, OIT_ERR_NOMEM,
                             "counted capture: more than 2^32 fragments "
                             "in one batch, more than 32-bit offsets address");
    uint32_t bands = w[S_BANDS] & ~BANDS_LEFT;
    uint64_t most = f->bind / 16;
    int first = y0 == r[1];
    oit_status s = OIT_OK;
    int y = y0;
    for (uint32_t b = 0; b < bands && b < BANDS && s == OIT_OK; b++) {
        int e = (int)w[S_ENDS + 2 * b];
        uint64_t frags = w[S_ENDS + 2 * b + 1] - (b ? w[S_ENDS + 2 * b - 1] : w[S_START]);
        if (frags > most)
            return oit_error_set(err, OIT_ERR_NOMEM,
                                 "counted capture: row %d holds %llu "
                                 "fragments, more than one storage buffer binds (%llu bytes)",
                                 y, (unsigned long long)frags, (unsigned long long)f->bind);
        /* with the need's margin, so that the next frame, ahead, finds its
         * store already there */
        uint64_t room = frags + frags / 8 < fit ? frags + frags / 8 : fit;
        room = room > frags ? room : frags;
        if (frags && room * 16 > k->frags_cap)
            s = oit_gl_buffer_reserve(&k->frags, &k->frags_cap, room * 16,
                                      "counted capture fragments", err);
        int band[4] = {r[0], y, r[2], e};
        if (s == OIT_OK && frags)
            s = oit_counted_judged_store(k, f, meshes, n, band, first, err);
        first &= !frags;
        y = e;
    }
    *next = y;
    return s;
}

oit_status oit_counted_batch(oit_counted *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4],
                             oit_error *err)
{
    /* A batch split is cut in bands an eighth under the store, so that the
     * next frame's view may deepen them a little and still draw them ahead. */
    uint64_t fit = store_fit(k, f), target = fit - fit / 8;
    k->fit = fit;
    oit_status s = table_slot(k, k->batch, err);
    if (s == OIT_OK && k->ahead && oit_counted_predicts(k, f, k->batch)) {
        s = oit_counted_predicted_batch(k, f, meshes, n, r, fit, target, err);
        k->batch += s == OIT_OK;
        return s;
    }
    if (s == OIT_OK && k->ahead)
        s = ahead_batch(k, f, meshes, n, r, fit, target, err);
    else if (s == OIT_OK)
        s = count(k, f, meshes, n, r, err);
    /* host mode: a slot's bands at a time, the rows left cut again (the
     * slot then holds the last cut's: no bands for the next frame) */
    for (int y = r[1]; s == OIT_OK && !k->ahead && y < r[3];) {
        k->unbanded |= y > r[1];
        oit_counted_split(k, f, k->offsets, k->batch, y, r[3], fit, target);
        s = host_bands(k, f, meshes, n, r, y, fit, &y, err);
    }
    if (s == OIT_OK)
        oit_counted_keep_prediction(k, f, k->batch, &k->offsets, &k->offsets_cap);
    k->batch += s == OIT_OK; /* a failed batch's slot may hold nothing */
    return s;
}
