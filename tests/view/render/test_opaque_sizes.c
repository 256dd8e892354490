/* The opaque pre-pass (opaque_keys.h) keeps its key texture across frames;
 * here one DFB and one capture of each kind, each made once, draw
 * test_opaque's scene (screen-aligned quads, two of them opaque) through a
 * sequence of frame sizes that grows, shrinks, grows only in height, only
 * in width, and takes odd sizes (97x131), then seeded random sizes. Every
 * frame against the hand result (gl_test_scene.h) and the exact number of
 * fragments stored (the quads in front of a pixel's nearest opaque one and
 * that one): a key texture kept from a smaller frame loses or hides
 * fragments in the rows or columns it lacks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/image/image.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/capture_set.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"
#include "tests/view/render/opaque_scene.h"

/* The captures share capture.c's pre-pass; two backends keep it quick. */
enum { N_CAPTURES = 2 };
static const oit_capture_kind KINDS[N_CAPTURES] = {OIT_CAPTURE_ARRAY, OIT_CAPTURE_FIRSTK};

/* 1 when a pixel centre of v lies within rounding of a quad's edge, where
 * the tie rule, not the hand model, decides (e.g. 32x24: row 1 on the
 * edge of the quad at z = -4). */
static int on_edge(const oit_view *v)
{
    double tanh = tan(0.5 * v->camera.fovy_deg * 3.14159265358979323846 / 180.0);
    for (int i = 0; i < NQ; i++) {
        double d = -QUADS[i].z;
        for (int x = 0; x < v->width; x++) {
            double dx = ((x + 0.5) / v->width * 2 - 1) * tanh * v->width / v->height;
            if (fabs(fabs(dx * d) - QUADS[i].half) < 1e-4)
                return 1;
        }
        for (int y = 0; y < v->height; y++) {
            double dy = (1 - (y + 0.5) / v->height * 2) * tanh;
            if (fabs(fabs(dy * d) - QUADS[i].half) < 1e-4)
                return 1;
        }
    }
    return 0;
}

typedef struct kept {
    oit_dfb *dfb;
    oit_capture *cap[N_CAPTURES];
    oit_gpu_mesh *mesh;
} kept;

static void check(const char *who, const oit_view *v, oit_status s, const oit_error *err,
                  oit_image *img, const oit_frame_stats *st, int *bad)
{
    CHECK(s == OIT_OK, "%s at %dx%d: %s", who, v->width, v->height, err->message);
    if (s == OIT_OK) {
        uint64_t want = expect_stored(v, 0);
        double diff = hand_max_diff(img, v, QUADS, NQ);
        int wrong = st->fragments != want || !(diff <= 1.0 / 255);
        if (wrong && (*bad)++ < 6)
            CHECK(0, "%s at %dx%d: %llu fragments (expected %llu), max_abs %.6f against the "
                  "hand result", who, v->width, v->height, (unsigned long long)st->fragments,
                  (unsigned long long)want, diff);
    }
    oit_image_free(img);
}

static void frame(kept *k, int w, int h, int *bad)
{
    oit_view v;
    scene_view(&v, w, h, OIT_SHADING_TRANSPARENT);
    v.shading.attributes |= OIT_ATTR_OPAQUE;
    while (on_edge(&v)) /* the next size up whose centres the model decides */
        scene_view(&v, w, ++h, OIT_SHADING_TRANSPARENT), v.shading.attributes |= OIT_ATTR_OPAQUE;
    const oit_gpu_mesh *list[1] = {k->mesh};
    oit_error err = {0};
    oit_image img = {0};
    oit_frame_stats st = {0};
    oit_status s = oit_dfb_render(k->dfb, list, 1, &v, &img, NULL, &st, &err);
    check("dfb", &v, s, &err, &img, &st, bad);
    for (int i = 0; i < N_CAPTURES; i++) {
        st = (oit_frame_stats){0};
        s = oit_capture_begin(k->cap[i], &v, &err);
        if (s == OIT_OK)
            s = oit_capture_batch(k->cap[i], list, 1, NULL, &err);
        if (s == OIT_OK)
            s = oit_capture_end(k->cap[i], &img, &st, &err);
        check(oit_capture_kind_name(KINDS[i]), &v, s, &err, &img, &st, bad);
    }
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    kept k = {0};
    oit_error err = {0};
    oit_triangle *t = scene_tris(QUADS, NQ);
    oit_status s = oit_gpu_mesh_create(t, 2 * (size_t)NQ, 0, &k.mesh, &err);
    free(t);
    if (s == OIT_OK)
        s = oit_dfb_create(&k.dfb, &err);
    for (int i = 0; i < N_CAPTURES && s == OIT_OK; i++)
        s = oit_capture_create(&(oit_capture_desc){.fill = capture_fill(KINDS[i]),
                                                   .cut = capture_cut(KINDS[i]), .K = 8},
            &k.cap[i], &err);
    CHECK(s == OIT_OK, "set-up: %s", err.message);
    /* grow, shrink, taller only, wider only, odd, then both down and up */
    static const int sizes[][2] = {{32, 24}, {48, 40}, {20, 16}, {20, 60}, {64, 60},
                                   {97, 131}, {131, 97}, {40, 140}, {17, 17}, {18, 150}};
    int bad = 0, frames = 0;
    for (size_t i = 0; s == OIT_OK && i < sizeof sizes / sizeof *sizes; i++, frames++)
        frame(&k, sizes[i][0], sizes[i][1], &bad);
    uint32_t seed = 0x9e3779b9u;
    for (int i = 0; s == OIT_OK && i < 8; i++, frames++) {
        seed = seed * 1664525u + 1013904223u;
        int w = 8 + (int)(seed >> 8) % 120;
        seed = seed * 1664525u + 1013904223u;
        int h = 8 + (int)(seed >> 8) % 160;
        frame(&k, w, h, &bad);
    }
    printf("%d frames through dfb and %d captures kept across sizes: %d wrong\n", frames,
           N_CAPTURES, bad);
    for (int i = 0; i < N_CAPTURES; i++)
        oit_capture_destroy(k.cap[i]);
    oit_dfb_destroy(k.dfb);
    oit_gpu_mesh_destroy(k.mesh);
    return test_gl_verdict(gl);
}
