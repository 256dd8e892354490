/* The counted capture (capture_counted.h). */
#include "render/capture/capture_counted.h"

#include "render/capture/capture_backend.h"
#include "render/capture/capture_glsl.h"
#include "render/gl/frag_glsl.h"

#include <stdlib.h>
#include <string.h>

/* A band of a batch's rows, judged after the scan: whether the store holds
 * its fragments (the store pass and the resolve run only then), where they
 * start (the store and the resolve read base and cap here, not from the
 * host), and the frame's figures. The scan's totals: the fragments (lo,
 * hi), the largest count, the counts over K (added once a batch, at its
 * first band). Offsets follow the frame's rows, so a band's fragments are
 * the difference of the offsets at its first pixels. */
static const char judge_cs[] =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Scan { uint lo; uint hi; "
    "uint most; uint over; };\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };\n"
    "layout(std430, binding = OIT_BIND_SUMS) buffer Judge { uint gate; uint frame_short; "
    "uint deep; uint pad; uvec4 groups; uint base; uint cap; };\n"
    "uniform uint u_cap;\n"
    "uniform uint u_width;\n"
    "uniform uvec2 u_rows;\n"
    "uniform uvec2 u_groups;\n"
    "uniform uint u_first;\n"
    "void main() {\n"
    "    uint start = offsets[u_rows.x * u_width];\n"
    "    uint n = offsets[u_rows.y * u_width] - start;\n"
    "    bool fits = hi == 0u && n <= u_cap;\n"
    "    gate = fits && n != 0u ? 1u : 0u;\n"
    "    if (!fits) frame_short = 1u;\n"
    "    if (u_first != 0u) deep += over;\n"
    "    groups = uvec4(gate != 0u ? u_groups : uvec2(0u), 1u, 0u);\n"
    "    base = start;\n"
    "    cap = u_cap;\n"
    "}\n";
static const oit_glsl_program judge_program = {"counted capture judge", .cs = {judge_cs}};
enum { J_GATE, J_SHORT, J_DEEP, J_GROUPS = 4, J_BASE = 8, J_CAP, J_WORDS = 12 };

/* A batch's bands of rows, cut on the GPU after the scan: from row
 * u_rows.x on, one band where the rows' fragments fit the store (u_fit),
 * else each band the most rows whose fragments stay within u_target (a
 * row that alone passes it is a band of its own), at most BANDS of them. Its slot of the band table: the bands (BANDS_LEFT set
 * where rows were left), the scan's high word, the first row's offset,
 * then each band's end row and the offset there. The host reads the slot
 * where it splits a batch itself; the next frame's ahead batches draw
 * the bands this one cut (oit_counted_ended). */
enum { BANDS = 62, SLOT = 128, S_BANDS = 0, S_HI, S_START, S_ENDS };
#define BANDS_LEFT 0x80000000u
static const char split_cs[] =
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = OIT_BIND_TOTALS) readonly buffer Scan { uint lo; uint hi; "
    "uint most; uint over; };\n"
    "layout(std430, binding = OIT_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };\n"
    "layout(std430, binding = OIT_BIND_SUMS) writeonly buffer Table { uint table[]; };\n"
    "uniform uint u_width;\n"
    "uniform uvec2 u_rows;\n"
    "uniform uint u_fit;\n"
    "uniform uint u_target;\n"
    "uniform uint u_slot;\n"
    "uniform uint u_bands;\n"
    "void main() {\n"
    "    uint y = u_rows.x, n = 0u, at = u_slot + 3u;\n"
    "    table[u_slot + 1u] = hi;\n"
    "    table[u_slot + 2u] = offsets[y * u_width];\n"
    "    uint all = offsets[u_rows.y * u_width] - offsets[y * u_width];\n"
    "    uint target = hi == 0u && all <= u_fit ? u_fit : u_target;\n"
    "    while (y < u_rows.y && n < u_bands) {\n"
    "        uint start = offsets[y * u_width], a = y + 1u, b = u_rows.y;\n"
    "        while (a < b) {\n"
    "            uint m = b - (b - a) / 2u;\n"
    "            if (offsets[m * u_width] - start <= target) a = m; else b = m - 1u;\n"
    "        }\n"
    "        table[at] = a;\n"
    "        table[at + 1u] = offsets[a * u_width];\n"
    "        at += 2u;\n"
    "        y = a;\n"
    "        n++;\n"
    "    }\n"
    "    table[u_slot] = y < u_rows.y ? n | 0x80000000u : n;\n"
    "}\n";
static const oit_glsl_program split_program = {"counted capture bands", .cs = {split_cs}};

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

/* The judge's frame figures (gate to groups) to zero. */
static void zero_figures(oit_counted *k)
{
    static const GLuint zero[J_GROUPS] = {0};
    glNamedBufferSubData(k->words, 0, sizeof zero, zero);
}

oit_status oit_counted_init(oit_counted *k, oit_program_cache *pc, oit_error *err)
{
    memset(k, 0, sizeof *k);
    oit_status s = oit_glsl_programs_build(pc, programs, OIT_COUNTED_PROGS, k->prog, err);
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
    oit_scan_release(&k->scan);
    free(k->pred);
    memset(k, 0, sizeof *k);
}

uint64_t oit_counted_bytes(const oit_counted *k)
{
    return k->offsets_cap + k->frags_cap + oit_scan_bytes(&k->scan) +
           (k->words ? J_WORDS * 4 : 0) + k->table_slots * SLOT * 4;
}

void oit_counted_begin(oit_counted *k, int no_wait, uint64_t fit)
{
    k->splits = 0;
    k->deep_pixels = 0;
    k->batch = 0;
    k->ended_short = 0;
    k->ahead = no_wait && k->measured && !k->unbanded && k->need <= fit;
    k->unbanded = 0;
    zero_figures(k);
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
    if (k->batch)
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
        oit_gl_buffer_reserve(&k->frags, &k->frags_cap, k->need * 16,
                              "counted capture fragments", NULL);
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

/* Count pass, then offsets = exclusive scan of the counts (pixels + 1
 * entries, the last = the batch's fragments), nothing read back. */
static oit_status count(oit_counted *k, const oit_counted_frame *f,
                        const oit_gpu_mesh *const *meshes, int n, const int r[4],
                        oit_error *err)
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
    return oit_scan_run(&k->scan, k->offsets, pixels + 1, NULL, f->waits, err);
}

/* Cuts the rows [y0, y1) of batch j's count in bands into its slot of
 * the band table: one where they fit, else of at most target fragments. */
static void split(oit_counted *k, const oit_counted_frame *f, size_t j, int y0, int y1,
                  uint64_t fit, uint64_t target)
{
    GLuint p = k->split;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->scan.totals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->offsets);
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

/* The band of rows r judged against the store (its capacity): the store
 * pass gated and the resolve dispatched by the judge's verdict, both at
 * the offset the judge read. Every band of both modes goes this way, so
 * that the first frame already builds and runs what the next, ahead,
 * runs (stack80 at 128x128: that frame took 95 ms against 38 warm when
 * only it judged). */
static oit_status judged_store(oit_counted *k, const oit_counted_frame *f,
                               const oit_gpu_mesh *const *meshes, int n, const int r[4],
                               int first, oit_error *err)
{
    uint64_t cap = k->frags_cap / 16 < UINT32_MAX ? k->frags_cap / 16 : UINT32_MAX;
    GLuint j = k->judge;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->scan.totals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->offsets);
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
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->frags);
    oit_glsl_draw_scissored_gated(f->fbo, f->width, f->height, k->prog[OIT_COUNTED_STORE],
                                  f->draws, meshes, n, r, k->words, J_GATE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GLuint resolve = k->prog[OIT_COUNTED_RESOLVE];
    glUseProgram(resolve);
    glProgramUniform2i(resolve, 11, f->width, f->height);
    glProgramUniform4i(resolve, 12, r[0], r[1], r[2], r[3]);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, k->words);
    glDispatchComputeIndirect(J_GROUPS * 4);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    k->splits += !first;
    return oit_gl_check("counted capture: band", err);
}

/* The bands the last frame cut batch j in, clipped to r's rows (a view
 * that moved a little keeps them; the judge finds out where it did not):
 * their end rows into ends, the last r's end. */
static int foreseen_bands(const oit_counted *k, size_t j, const int r[4], int ends[BANDS + 1])
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

/* A batch without the host (ahead mode): counted, scanned and cut for the
 * next frame on the GPU, its bands those the last frame cut, each judged
 * against the store sized ahead. */
static oit_status ahead_batch(oit_counted *k, const oit_counted_frame *f,
                              const oit_gpu_mesh *const *meshes, int n, const int r[4],
                              uint64_t fit, uint64_t target, oit_error *err)
{
    uint64_t cap = k->need < UINT32_MAX ? k->need : UINT32_MAX;
    oit_status s = OIT_OK;
    if (cap * 16 > k->frags_cap)
        s = oit_gl_buffer_reserve(&k->frags, &k->frags_cap, cap ? cap * 16 : 16,
                                  "counted capture fragments", err);
    if (s == OIT_OK)
        s = count(k, f, meshes, n, r, err);
    if (s != OIT_OK)
        return s;
    split(k, f, k->batch, r[1], r[3], fit, target);
    int ends[BANDS + 1], nb = foreseen_bands(k, k->batch, r, ends);
    for (int b = 0, y = r[1]; b < nb && s == OIT_OK; y = ends[b++]) {
        int band[4] = {r[0], y, r[2], ends[b]};
        s = judged_store(k, f, meshes, n, band, b == 0, err);
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
        return oit_error_set(err, OIT_ERR_NOMEM, "counted capture: more than 2^32 fragments "
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
            return oit_error_set(err, OIT_ERR_NOMEM, "counted capture: row %d holds %llu "
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
            s = judged_store(k, f, meshes, n, band, first, err);
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
    if (s == OIT_OK && k->ahead)
        s = ahead_batch(k, f, meshes, n, r, fit, target, err);
    else if (s == OIT_OK)
        s = count(k, f, meshes, n, r, err);
    /* host mode: a slot's bands at a time, the rows left cut again (the
     * slot then holds the last cut's: no bands for the next frame) */
    for (int y = r[1]; s == OIT_OK && !k->ahead && y < r[3];) {
        k->unbanded |= y > r[1];
        split(k, f, k->batch, y, r[3], fit, target);
        s = host_bands(k, f, meshes, n, r, y, fit, &y, err);
    }
    k->batch += s == OIT_OK; /* a failed batch's slot may hold nothing */
    return s;
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
