/* The counted capture's predicted batches (capture_counted_steps.h,
 * capture_counted.h: "Predicted batches"). */
#include "view/render/capture/capture_counted.h"
#include "view/render/capture/capture_counted_steps.h"

#include "view/render/gl/gpu_timer.h"

#include <string.h>

/* Predictions (4 bytes a pixel each, and the next frame's counts beside
 * them) take only what the stores leave of the budget: they save a pass,
 * a band more would cost one. held: the bytes the stores hold. */
static int prediction_fits(const oit_counted *k, uint64_t pixels, size_t j, uint64_t budget,
                           uint64_t held)
{
    if (budget == UINT64_MAX)
        return 1;
    uint64_t want = held + 2 * (pixels + 1) * 4;
    for (size_t i = 0; i < OIT_COUNTED_PREDICTED_BATCHES; i++)
        want += i != j && k->predicted_ok[i] ? k->predicted_cap[i] : 0;
    return want <= budget;
}

static void drop_prediction(oit_counted *k, size_t j)
{
    k->predicted_ok[j] = 0;
    oit_gl_buffer_release(&k->predicted[j], &k->predicted_cap[j]);
}

void oit_counted_keep_prediction(oit_counted *k, const oit_counted_frame *f, size_t j,
                                 GLuint *offsets, uint64_t *cap)
{
    if (j >= OIT_COUNTED_PREDICTED_BATCHES)
        return;
    uint64_t pixels = (uint64_t)f->width * f->height;
    if (pixels != k->predicted_pixels) {
        for (size_t i = 0; i < OIT_COUNTED_PREDICTED_BATCHES; i++)
            drop_prediction(k, i);
        k->predicted_pixels = pixels;
    }
    if (!prediction_fits(k, pixels, j, k->budget, k->frags_cap + k->offsets_cap)) {
        drop_prediction(k, j);
        if (offsets == &k->next) /* scratch of predictions alone */
            oit_gl_buffer_release(&k->next, &k->next_cap);
        return;
    }
    GLuint b = k->predicted[j];
    uint64_t c = k->predicted_cap[j];
    k->predicted[j] = *offsets, k->predicted_cap[j] = *cap;
    *offsets = b, *cap = c;
    k->predicted_ok[j] = 1;
    k->predicted_view[j] = f->view_key;
}

/* Only for the view that made the prediction: one that moved spills
 * pixels throughout (the 1M plant at 256x256, 10 degrees a frame: 440-730
 * ms a frame predicted, 360-375 counted), a pass more than counting costs. */
int oit_counted_predicts(const oit_counted *k, const oit_counted_frame *f, size_t j)
{
    return j < OIT_COUNTED_PREDICTED_BATCHES && k->predicted_ok[j] &&
           k->predicted_view[j] == f->view_key && k->prog[OIT_COUNTED_PREDICTED] &&
           k->predicted_pixels == (uint64_t)f->width * f->height;
}

static void set_band(GLuint prog, GLuint band_pixel, GLuint cap)
{
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_band_pixel"), band_pixel);
    glProgramUniform1ui(prog, glGetUniformLocation(prog, "u_cap"), cap);
}

/* Band r of batch j at the last frame's offsets of its batch j: one pass
 * stores what they hold and counts every fragment; the resolve composites
 * the pixels they held and keeps every count in next; the pixels they did
 * not hold (spilled) are scanned and stored as a band of their own, the
 * judge's gate shut where none did. */
static oit_status predicted_band(oit_counted *k, const oit_counted_frame *f,
                                 const oit_gpu_mesh *const *meshes, int n, size_t j, const int r[4],
                                 int first, oit_error *err)
{
    GLuint cap = (GLuint)(k->frags_cap / 16 < UINT32_MAX ? k->frags_cap / 16 : UINT32_MAX);
    GLuint band_pixel = (GLuint)((uint64_t)r[1] * f->width);
    GLuint store = k->prog[OIT_COUNTED_PREDICTED], resolve = k->prog[OIT_COUNTED_PREDICTED_RESOLVE];
    set_band(store, band_pixel, cap);
    set_band(resolve, band_pixel, cap);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, f->counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, f->state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OFFSETS, k->predicted[j]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_FRAGS, k->frags);
    oit_gpu_timer_mark(f->timer, OIT_GPU_PASS1);
    oit_glsl_draw_scissored(f->fbo, f->width, f->height, store, f->draws, meshes, n, r);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    oit_gpu_timer_mark(f->timer, OIT_GPU_RESOLVE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, k->next);
    glUseProgram(resolve);
    glProgramUniform2i(resolve, OIT_LOC_SIZE, f->width, f->height);
    glProgramUniform4i(resolve, OIT_LOC_RECT, r[0], r[1], r[2], r[3]);
    glDispatchCompute(oit_gl_groups((uint64_t)(r[2] - r[0]), 8),
                      oit_gl_groups((uint64_t)(r[3] - r[1]), 8), 1);
    /* the spilled pixels' scan counts no deep pixels: the batch's own
     * does, once */
    oit_status s = oit_counted_scan_counts(k, f, UINT32_MAX, err);
    return s == OIT_OK ? oit_counted_judged_store(k, f, meshes, n, r, first, err) : s;
}

/* A batch drawn in the bands the last frame cut it in, each at the
 * offsets the last frame's counts gave (predicted_band): one geometry pass
 * a band where the view held still, two where it moved. Its counts, kept
 * in next, are scanned and cut in bands for the next frame, as a counted
 * batch's are. */
oit_status oit_counted_predicted_batch(oit_counted *k, const oit_counted_frame *f,
                                       const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                       uint64_t fit, uint64_t target, oit_error *err)
{
    uint64_t pixels = (uint64_t)f->width * f->height;
    size_t j = k->batch;
    oit_status s = oit_counted_reserve_need(k, err);
    if (s == OIT_OK)
        s = oit_gl_buffer_reserve(&k->next, &k->next_cap, (pixels + 1) * 4,
                                  "counted capture next counts", err);
    if (s != OIT_OK)
        return s;
    static const GLuint zero = 0;
    glClearNamedBufferSubData(k->next, GL_R32UI, 0, (GLsizeiptr)((pixels + 1) * 4), GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    int ends[OIT_COUNTED_BANDS + 1], nb = oit_counted_foreseen_bands(k, j, r, ends);
    for (int b = 0, y = r[1]; b < nb && s == OIT_OK; y = ends[b++]) {
        int band[4] = {r[0], y, r[2], ends[b]};
        s = predicted_band(k, f, meshes, n, j, band, b == 0, err);
    }
    if (s != OIT_OK)
        return s;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    k->scan.over = k->deep_over;
    s = oit_scan_run(&k->scan, k->next, pixels + 1, NULL, f->waits, err);
    if (s != OIT_OK)
        return s;
    oit_counted_split(k, f, k->next, j, r[1], r[3], fit, target);
    /* no rows: the judge adds the batch's deep pixels and flags a batch
     * past 32-bit offsets, whose bands the next frame must not trust */
    const int none[4] = {r[0], r[1], r[2], r[1]};
    oit_counted_judge(k, f, k->next, none, 1);
    k->predicted_batches++;
    oit_counted_keep_prediction(k, f, j, &k->next, &k->next_cap);
    return oit_gl_check("counted capture: predicted batch", err);
}

oit_status oit_counted_predict_target(oit_counted *k, const oit_counted_frame *f, size_t j,
                                      uint64_t budget, GLuint *copy, oit_error *err)
{
    uint64_t pixels = (uint64_t)f->width * f->height;
    *copy = 0;
    k->budget = budget;
    if (j >= OIT_COUNTED_PREDICTED_BATCHES ||
        !prediction_fits(k, pixels, j, budget, k->frags_cap + k->offsets_cap))
        return OIT_OK;
    oit_status s = oit_gl_buffer_reserve(&k->next, &k->next_cap, (pixels + 1) * 4,
                                         "counted capture next counts", err);
    *copy = s == OIT_OK ? k->next : 0;
    return s;
}

oit_status oit_counted_predict(oit_counted *k, const oit_counted_frame *f, size_t j, oit_error *err)
{
    uint64_t pixels = (uint64_t)f->width * f->height;
    static const GLuint zero = 0;
    glClearNamedBufferSubData(k->next, GL_R32UI, (GLintptr)(pixels * 4), 4, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    k->scan.over = UINT32_MAX;
    oit_status s = oit_scan_run(&k->scan, k->next, pixels + 1, NULL, f->waits, err);
    if (s == OIT_OK)
        oit_counted_keep_prediction(k, f, j, &k->next, &k->next_cap);
    /* in this frame, which the other capture's first frame of a view
     * pays, not in the next, the view's second (the one users see) */
    oit_counted_build_predicted(k);
    return s;
}
