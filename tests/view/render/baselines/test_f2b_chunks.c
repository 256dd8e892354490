/* F2B's chunks (f2b.h, "Chunks") as a property over triangle counts of
 * every residue mod OIT_F2B_CHUNKS, against an expectation computed here
 * from f2b.h's words, not by oit_f2b_chunk_triangles: a chunk is the
 * smallest multiple of the alignment unit (the fewest triangles whose 48
 * bytes are a multiple of GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, read
 * here from GL) that is at least ceil(tris / OIT_F2B_CHUNKS), and at least
 * one unit. The same chunk then decides what a frame blends: on tris
 * full-frame triangles of one alpha a (T after k layers (1 - a)^k), chunk c
 * blends when the transmittance before c is at or above the threshold, so
 * every pixel blends min(tris, ceil(k0 / chunk) * chunk) layers, k0 being
 * the first k with (1 - a)^k below it. Seeded, so a failure reproduces. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/lib/gl_test_scene.h"
#include "view/render/baselines/f2b.h"
#include "view/render/baselines/methods.h"
#include "view/render/image/image.h"
#include "view/render/gl/gl_context.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 8, H = 8, CASES = 48 };

static uint32_t rnd(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* The chunk f2b.h promises, from the driver's alignment read here. */
static uint64_t model_chunk(uint64_t tris)
{
    GLint align = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    uint64_t unit = 1;
    while (align > 0 && unit * sizeof(oit_triangle) % (uint64_t)align != 0)
        unit++;
    uint64_t share = tris / OIT_F2B_CHUNKS + (tris % OIT_F2B_CHUNKS != 0);
    uint64_t chunk = unit;
    while (chunk < share)
        chunk += unit;
    return chunk;
}

/* The pure property over every count up to 40 chunks' worth: the size and
 * that the chunks cover the frame in at most OIT_F2B_CHUNKS draws. */
static void check_sizes(void)
{
    uint64_t bad = 0;
    for (uint64_t t = 0; t <= 40 * OIT_F2B_CHUNKS + 1; t++) {
        uint64_t got = oit_f2b_chunk_triangles(t), want = model_chunk(t);
        if (got != want || (got * OIT_F2B_CHUNKS < t)) {
            if (bad++ < 4)
                CHECK(0, "f2b chunk of %llu triangles: %llu, f2b.h says %llu",
                      (unsigned long long)t, (unsigned long long)got,
                      (unsigned long long)want);
        }
    }
    printf("chunk sizes: %llu of %d counts wrong (unit for 1 triangle: %llu)\n",
           (unsigned long long)bad, 40 * OIT_F2B_CHUNKS + 2, (unsigned long long)model_chunk(1));
}

/* Triangle i: a full-frame triangle at depth 1 + i / 64 (the frame at
 * depth d spans [-d, d] in x and y with the 90-degree view). */
static oit_triangle *layers(uint64_t n, uint8_t alpha, uint32_t *seed)
{
    oit_triangle *t = calloc(n, sizeof *t);
    static const float corner[3][2] = {{-4, -4}, {8, -4}, {-4, 8}};
    for (uint64_t i = 0; t && i < n; i++) {
        float d = 1.0f + (float)i / 64.0f;
        for (int k = 0; k < 3; k++) {
            t[i].v[k].pos[0] = corner[k][0] * d;
            t[i].v[k].pos[1] = corner[k][1] * d;
            t[i].v[k].pos[2] = -d;
            t[i].v[k].rgba[0] = (uint8_t)(40 + i % 200);
            t[i].v[k].rgba[1] = 90;
            t[i].v[k].rgba[2] = 200;
            t[i].v[k].rgba[3] = alpha;
        }
    }
    for (uint64_t i = n; t && i > 1; i--) { /* F2B must sort them itself */
        uint64_t j = rnd(seed) % i;
        oit_triangle x = t[i - 1];
        t[i - 1] = t[j];
        t[j] = x;
    }
    return t;
}

/* k0 (the first layer count whose transmittance is below thr), or 0 when
 * some (1 - a)^k lies too near thr for a float blend to decide. */
static uint64_t first_below(double a, double thr, uint64_t n)
{
    double T = 1.0;
    for (uint64_t k = 0; k <= n; k++) {
        if (fabs(T - thr) < 1e-4)
            return 0;
        if (T < thr)
            return k;
        T *= 1.0 - (double)(float)a;
    }
    return n + 1;
}

static void check_frames(void *f2b)
{
    uint32_t seed = 0x2f6b1c3du;
    oit_view v;
    scene_view(&v, W, H, OIT_SHADING_TRANSPARENT);
    uint64_t bad = 0, runs = 0;
    for (int c = 0; c < CASES; c++) {
        /* residue c mod 64 (and a few beyond), 1..9 chunks' worth */
        uint64_t n = (uint64_t)(c % OIT_F2B_CHUNKS) + OIT_F2B_CHUNKS * (1 + rnd(&seed) % 9);
        if (c == 0)
            n = 1 + rnd(&seed) % 63; /* fewer triangles than chunks */
        uint8_t alpha = (uint8_t)(8 + rnd(&seed) % 60);
        uint64_t k0 = first_below(alpha / 255.0, OIT_F2B_DEFAULT_THRESHOLD, n);
        if (k0 == 0)
            continue;
        uint64_t chunk = model_chunk(n);
        uint64_t want_layers = (k0 + chunk - 1) / chunk * chunk;
        if (want_layers > n)
            want_layers = n;
        oit_triangle *t = layers(n, alpha, &seed);
        oit_error err = {0};
        oit_gpu_mesh *mesh = NULL;
        oit_image img = {0};
        oit_frame_stats st = {0};
        oit_status s = oit_gpu_mesh_create(t, n, 0, &mesh, &err);
        if (s == OIT_OK) {
            oit_method_frame fr = {.gpu = mesh, .view = &v, .out = &img, .stats = &st};
            s = oit_method_f2b.render(f2b, &fr, &err);
        }
        CHECK(s == OIT_OK, "f2b on %llu triangles: %s", (unsigned long long)n, err.message);
        uint64_t want = want_layers * W * H;
        runs++;
        if (s == OIT_OK && st.fragments != want && bad++ < 4)
            CHECK(0, "f2b on %llu triangles (residue %llu, alpha %u, below the threshold "
                  "after %llu): blended %llu fragments, chunks of %llu blend %llu",
                  (unsigned long long)n, (unsigned long long)(n % OIT_F2B_CHUNKS), alpha,
                  (unsigned long long)k0, (unsigned long long)st.fragments,
                  (unsigned long long)chunk, (unsigned long long)want);
        oit_image_free(&img);
        oit_gpu_mesh_destroy(mesh);
        free(t);
    }
    printf("frames: %llu of %llu wrong\n", (unsigned long long)bad, (unsigned long long)runs);
    CHECK(runs >= CASES / 2, "only %llu of %d cases decidable", (unsigned long long)runs, CASES);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    void *f2b = NULL;
    check_sizes();
    if (oit_method_f2b.create(NULL, NULL, &f2b, &err) == OIT_OK)
        check_frames(f2b);
    else
        CHECK(0, "f2b create: %s", err.message);
    if (f2b)
        oit_method_f2b.destroy(f2b);
    return test_gl_verdict(gl);
}
