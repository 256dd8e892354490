/* liboit through a sequence of frame sizes with one renderer kept across
 * them, as a viewer whose window is resized keeps it: sizes that grow,
 * shrink, grow only in height or only in width, odd sizes (97x131), then
 * seeded random ones. Each frame of the kept renderer must equal the frame
 * a fresh renderer draws at that size first (its buffers and textures made
 * for it), for a part file streamed (FILE.oitp) and an in-core scene with
 * opaque quads (DFB and its opaque pre-pass): what a renderer keeps from
 * an earlier frame (key textures, capture buffers, the ring) must never
 * show in a later one's pixels.
 *
 * usage: test_liboit_frames FILE.oitp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/liboit.h"
#include "oit/offscreen.h"
#include "tests/lib/test_check.h"

/* Front to back: a transparent quad, an opaque one (smaller), a
 * transparent one behind it, an opaque backdrop; x, y half sizes and z. */
static const float QUADS[4][4] = {
    {0.9f, 0.6f, 0.0f, 0}, {0.4f, 0.7f, -0.5f, 1}, {1.2f, 0.9f, -1.0f, 0}, {1.6f, 1.4f, -1.5f, 1}};

static oit_scene *opaque_quads(void)
{
    float pos[4 * 4 * 3];
    uint8_t rgba[4 * 2 * 4];
    uint32_t idx[4 * 6];
    for (int q = 0; q < 4; q++) {
        const float c[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (int k = 0; k < 4; k++) {
            pos[(q * 4 + k) * 3 + 0] = c[k][0] * QUADS[q][0] + 0.1f * q;
            pos[(q * 4 + k) * 3 + 1] = c[k][1] * QUADS[q][1];
            pos[(q * 4 + k) * 3 + 2] = QUADS[q][2];
        }
        for (int t = 0; t < 2; t++) {
            uint8_t *p = rgba + (q * 2 + t) * 4;
            p[0] = (uint8_t)(60 * q + 30);
            p[1] = (uint8_t)(200 - 40 * q);
            p[2] = (uint8_t)(90 + 30 * t);
            p[3] = QUADS[q][3] != 0 ? 255 : 110;
        }
        uint32_t ids[6] = {4u * q, 4u * q + 1, 4u * q + 2, 4u * q, 4u * q + 2, 4u * q + 3};
        memcpy(idx + q * 6, ids, sizeof ids);
    }
    oit_scene_mesh_desc d = {.positions = pos, .vertex_count = 16, .indices = idx,
                             .index_count = 24, .colours = rgba,
                             .colour_rate = OIT_COLOUR_PER_TRIANGLE, .name = "opaque quads"};
    oit_scene *s = NULL;
    oit_error err = {0};
    CHECK(oit_scene_create_mesh(&d, &s, &err) == OIT_OK, "opaque quads: %s", err.message);
    return s;
}

static float *draw(oit_offscreen *o, oit_scene *s, int w, int h, int in_core)
{
    size_t bytes = (size_t)w * h * 4 * sizeof(float);
    float *px = malloc(bytes);
    oit_offscreen_view v = {.width = w, .height = h, .format = OIT_PIXELS_RGBA32F,
                            .background = {0.2f, 0.4f, 0.6f, 1.0f}};
    if (in_core) { /* head on, the quads filling most of the frame */
        v.eye[2] = 3.0f;
        v.fovy_deg = 60.0f;
    }
    oit_error err = {0};
    oit_status st = px ? oit_offscreen_render(o, s, &v, px, bytes, NULL, &err) : OIT_ERR_NOMEM;
    CHECK(st == OIT_OK, "%dx%d: %s", w, h, err.message);
    if (st != OIT_OK) {
        free(px);
        return NULL;
    }
    return px;
}

/* The kept renderer's frame against a fresh one's; 1 when they differ. */
static int frame(oit_offscreen *kept, oit_scene *s, const char *what, int w, int h,
                 int in_core)
{
    oit_offscreen *fresh = NULL;
    oit_error err = {0};
    if (oit_offscreen_create(NULL, &fresh, &err) != OIT_OK) {
        CHECK(0, "fresh renderer: %s", err.message);
        return 1;
    }
    float *want = draw(fresh, s, w, h, in_core);
    oit_offscreen_release_scene(fresh, s);
    oit_offscreen_destroy(fresh);
    float *got = draw(kept, s, w, h, in_core);
    double worst = 0.0;
    int where = 0;
    for (int i = 0; got && want && i < w * h * 4; i++)
        if (fabs((double)got[i] - want[i]) > worst) {
            worst = fabs((double)got[i] - want[i]);
            where = i / 4;
        }
    int bad = !got || !want || worst > 1e-5;
    if (bad)
        CHECK(0, "%s at %dx%d: the kept renderer differs from a fresh one by %.6f at pixel "
              "(%d, %d)", what, w, h, worst, where % w, where / w);
    free(got);
    free(want);
    return bad;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s FILE.oitp\n", argv[0]);
        return 2;
    }
    oit_offscreen *kept = NULL;
    oit_error err = {0};
    oit_scene *file = NULL, *quads = NULL;
    if (oit_offscreen_create(NULL, &kept, &err) != OIT_OK ||
        oit_scene_open(argv[1], NULL, &file, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    printf("renderer: %s\n", oit_offscreen_gl_renderer(kept));
    quads = opaque_quads();
    static const int sizes[][2] = {{32, 24}, {48, 40}, {20, 16}, {20, 60}, {64, 60},
                                   {97, 131}, {131, 97}, {40, 140}, {17, 17}, {18, 150}};
    int n = (int)(sizeof sizes / sizeof *sizes), bad = 0, frames = 0;
    uint32_t seed = 0x85ebca6bu;
    for (int i = 0; i < n + 4 && quads; i++) {
        int w, h;
        if (i < n) {
            w = sizes[i][0];
            h = sizes[i][1];
        } else {
            seed = seed * 1664525u + 1013904223u;
            w = 8 + (int)(seed >> 8) % 120;
            seed = seed * 1664525u + 1013904223u;
            h = 8 + (int)(seed >> 8) % 160;
        }
        bad += frame(kept, file, "part file", w, h, 0);
        bad += frame(kept, quads, "opaque quads", w, h, 1);
        frames += 2;
    }
    printf("%d frames of a kept renderer against fresh ones: %d differ\n", frames, bad);
    oit_scene_close(quads);
    oit_scene_close(file);
    oit_offscreen_destroy(kept);
    return test_verdict();
}
