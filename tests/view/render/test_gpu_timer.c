/* The GPU timer (view/render/gl/gpu_timer.h) through the method layer and alone:
 * figures per frame and phase that add up and stay within the frame's wall
 * time, frame numbers in order, results that wait for nobody until asked
 * (a ring that keeps the newest, says how many it dropped), and a timer
 * without timestamps that gives no figure at all. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/clock.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "view/render/method.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

#define FRAMES 3

/* 40 overlapping quads at 64x64: a scene every pass of DFB and the array
 * capture has work in. */
static oit_mesh scene(void)
{
    enum { N = 40 };
    quad_spec q[N];
    for (int i = 0; i < N; i++)
        q[i] = (quad_spec){.z = -2.0f - 0.05f * (float)i, .half = 1.0f + 0.01f * (float)i,
                           .rgba = {(uint8_t)(60 + i * 4), 100, (uint8_t)(200 - i * 3), 40},
                           .front = i & 1};
    oit_mesh m = {.tris = scene_tris(q, N), .count = 2 * N};
    return m;
}

/* FRAMES frames of method m; every frame's figures, matched by number. */
static void timed_frames(oit_gl *gl, const oit_method *m, const oit_mesh *mesh)
{
    oit_error err = {0};
    oit_method_options opt = {.max_layers = 8, .gl = gl};
    oit_method_state *st = NULL;
    if (oit_method_open(m, mesh, &opt, &st, &err) != OIT_OK) {
        CHECK(0, "%s: open: %s", m->name, err.message);
        return;
    }
    CHECK(oit_method_gpu_absent(st) == NULL, "%s: llvmpipe has timestamps, yet: %s", m->name,
          oit_method_gpu_absent(st));
    oit_view v;
    scene_view(&v, 64, 64, OIT_SHADING_TRANSPARENT);
    double wall[FRAMES + 1] = {0};
    oit_gpu_times got[FRAMES + 1] = {{0}};
    int seen = 0;
    for (int f = 1; f <= FRAMES; f++) {
        oit_image img = {0};
        oit_frame_stats fs = {0};
        double t0 = oit_time_ms();
        oit_status s = oit_method_render(st, &v, &img, NULL, NULL, &fs, &err);
        CHECK(s == OIT_OK, "%s: frame %d: %s", m->name, f, err.message);
        CHECK(fs.gpu_frame == (uint64_t)f, "%s: frame %d numbered %llu", m->name, f,
              (unsigned long long)fs.gpu_frame);
        oit_image_free(&img);
        /* Waited for here, so that the wall time spans the frame's last
         * timestamp too: GL runs it after the read-back, when it will (a
         * busy llvmpipe thread: milliseconds later). The ring test below
         * takes figures without waiting. */
        oit_gpu_times t;
        while (oit_method_gpu_poll(st, &t, 1))
            got[seen < FRAMES ? ++seen : FRAMES] = t;
        wall[f] = oit_time_ms() - t0;
    }
    CHECK(seen == FRAMES, "%s: %d frames' figures for %d frames", m->name, seen, FRAMES);
    for (int f = 1; f <= seen; f++) {
        const oit_gpu_times *g = &got[f];
        double sum = 0;
        for (int p = 0; p < OIT_GPU_PHASES; p++) {
            sum += g->phase_ms[p];
            CHECK(g->phase_ms[p] >= 0, "%s: %s %.3f ms", m->name,
                  oit_gpu_phase_name((oit_gpu_phase)p), g->phase_ms[p]);
        }
        printf("%s frame %llu: wall %.3f ms, gpu %.3f ms (pass1 %.3f pass2 %.3f resolve %.3f "
               "readback %.3f other %.3f)\n", m->name, (unsigned long long)g->frame, wall[f],
               g->ms, g->phase_ms[OIT_GPU_PASS1], g->phase_ms[OIT_GPU_PASS2],
               g->phase_ms[OIT_GPU_RESOLVE], g->phase_ms[OIT_GPU_READBACK],
               g->phase_ms[OIT_GPU_OTHER]);
        CHECK(g->frame == (uint64_t)f, "%s: figures of frame %llu where %d comes", m->name,
              (unsigned long long)g->frame, f);
        CHECK(g->ms > 0, "%s: frame %d took %.6f ms on the GPU", m->name, f, g->ms);
        CHECK(fabs(sum - g->ms) <= 1e-6 * (1 + g->ms), "%s: phases add to %.6f, frame %.6f",
              m->name, sum, g->ms);
        /* The GPU's span sits inside the wall time from the call to its
         * figures; 2% and 1 ms for the two clocks. */
        CHECK(g->ms <= wall[f] * 1.02 + 1.0, "%s: frame %d: gpu %.3f ms > wall %.3f ms", m->name, f,
              g->ms, wall[f]);
        /* A frame with geometry spends GPU time on the geometry and the
         * resolve, not all of it in "other". */
        CHECK(g->phase_ms[OIT_GPU_PASS1] > 0 && g->phase_ms[OIT_GPU_RESOLVE] > 0,
              "%s: pass1 %.6f, resolve %.6f ms", m->name, g->phase_ms[OIT_GPU_PASS1],
              g->phase_ms[OIT_GPU_RESOLVE]);
        CHECK(g->phase_ms[OIT_GPU_OTHER] < g->ms, "%s: all %.3f ms unattributed", m->name,
              g->ms);
    }
    oit_method_close(st);
}

/* Without timestamps: no frame number, nothing polled, a reason. */
static void absent(oit_gl *gl, const oit_mesh *mesh)
{
    oit_error err = {0};
    oit_method_options opt = {.max_layers = 8, .gl = gl, .no_gpu_timer = 1};
    oit_method_state *st = NULL;
    if (oit_method_open(&oit_method_dfb, mesh, &opt, &st, &err) != OIT_OK) {
        CHECK(0, "absent: open: %s", err.message);
        return;
    }
    oit_view v;
    scene_view(&v, 32, 32, OIT_SHADING_TRANSPARENT);
    oit_image img = {0};
    oit_frame_stats fs = {.gpu_frame = 99};
    CHECK(oit_method_render(st, &v, &img, NULL, NULL, &fs, &err) == OIT_OK, "absent: %s",
          err.message);
    oit_image_free(&img);
    oit_gpu_times t;
    CHECK(fs.gpu_frame == 0, "absent: frame numbered %llu", (unsigned long long)fs.gpu_frame);
    CHECK(!oit_method_gpu_poll(st, &t, 1), "absent: figures of frame %llu",
          (unsigned long long)t.frame);
    CHECK(oit_method_gpu_absent(st) != NULL, "absent: no reason given");
    printf("absent: %s\n", oit_method_gpu_absent(st) ? oit_method_gpu_absent(st) : "(null)");
    oit_method_close(st);
}

/* A ring of 2 that nobody polls for 5 frames: frames 1 and 2 are read when
 * their slots are needed, frame 1 is dropped when frame 3's result comes
 * in, and the rest come out in order at the end. */
static void ring(void)
{
    oit_error err = {0};
    oit_gpu_timer *t = NULL;
    if (oit_gpu_timer_create(&(oit_gpu_timer_desc){.frames = 2}, &t, &err) != OIT_OK) {
        CHECK(0, "ring: %s", err.message);
        return;
    }
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, 1 << 20, NULL, GL_DYNAMIC_STORAGE_BIT);
    for (int f = 1; f <= 5; f++) {
        oit_gpu_timer_begin_frame(t);
        oit_gpu_timer_mark(t, OIT_GPU_UPLOAD);
        static const GLuint zero = 0;
        glClearNamedBufferData(buf, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        CHECK(oit_gpu_timer_end_frame(t) == (uint64_t)f, "ring: frame %d numbered wrong", f);
    }
    CHECK(oit_gpu_timer_dropped(t) == 1, "ring: %llu dropped, 1 expected",
          (unsigned long long)oit_gpu_timer_dropped(t));
    uint64_t want = 2;
    oit_gpu_times x;
    while (oit_gpu_timer_poll(t, &x, 1)) {
        CHECK(x.frame == want, "ring: frame %llu where %llu comes", (unsigned long long)x.frame,
              (unsigned long long)want);
        CHECK(x.phase_ms[OIT_GPU_UPLOAD] > 0 && x.ms >= x.phase_ms[OIT_GPU_UPLOAD],
              "ring: upload %.6f of %.6f ms", x.phase_ms[OIT_GPU_UPLOAD], x.ms);
        want++;
    }
    CHECK(want == 6, "ring: figures up to frame %llu, 5 made", (unsigned long long)want - 1);
    glDeleteBuffers(1, &buf);
    oit_gpu_timer_destroy(t);

    /* Switched off: every call a no-op. */
    if (oit_gpu_timer_create(&(oit_gpu_timer_desc){.no_queries = 1}, &t, &err) != OIT_OK) {
        CHECK(0, "ring: %s", err.message);
        return;
    }
    oit_gpu_timer_begin_frame(t);
    oit_gpu_timer_mark(t, OIT_GPU_PASS1);
    CHECK(oit_gpu_timer_end_frame(t) == 0, "off: a frame number");
    CHECK(!oit_gpu_timer_poll(t, &x, 1), "off: figures");
    oit_gpu_timer_destroy(t);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_mesh mesh = scene();
    timed_frames(gl, &oit_method_dfb, &mesh);
    timed_frames(gl, &oit_method_array, &mesh);
    absent(gl, &mesh);
    ring();
    free(mesh.tris);
    return test_gl_verdict(gl);
}
