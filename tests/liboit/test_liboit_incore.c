/* In-core scenes and offscreen rendering through liboit's public API:
 *
 * - a mesh file (PLY) opened with oit_scene_open is held in core and drawn
 *   with DFB; its part file (converted here with oitprep) is streamed; the
 *   two images agree within the stream-vs-DFB tolerance of test_liboit
 *   (at most 0.1% of pixels more than 1/255 apart), in both shadings;
 * - the same triangles from caller arrays (indexed and soup, per-vertex and
 *   per-triangle colour, 8-bit and float) give the file's image exactly;
 *   an STL of them (no colour) gives the image of the arrays without colour;
 * - a red square of alpha 128/255 facing the camera, over white, is
 *   (255, 127, 127) at its centre and white elsewhere, in RGBA8 and float;
 * - in linear light (OIT_RENDER_COLOUR_LINEAR) the square's centre is
 *   encode(1 - 128/255) = 187.19: (255, 187, 187) in RGBA8, 0.73406 in float
 *   (sRGB-encoded in both), the white background still 255;
 * - bad arrays, unknown extensions and missing files fail naming the input.
 *
 * usage: test_liboit_incore OITPREP WORKDIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/ply_writer.h"
#include "oit/mesh.h"
#include "oit/offscreen.h"
#include "tests/lib/test_check.h"

enum { W = 160, H = 120, QUADS = 6 * 6, LAYERS = 5 };

/* LAYERS tilted slabs of 6x6 separate quads (apart: coplanar overlaps
 * would make the order a tie that clipping renumbers), one colour a quad with alpha
 * 0.25..0.75: 4 vertices and 2 triangles a quad, so colour is uniform per
 * triangle and per vertex at once. */
typedef struct scene_arrays {
    float pos[LAYERS * QUADS * 4 * 3];
    uint8_t vrgba[LAYERS * QUADS * 4 * 4];
    uint32_t idx[LAYERS * QUADS * 6];
} scene_arrays;

enum { NV = LAYERS * QUADS * 4, NT = LAYERS * QUADS * 2 };

static void make_scene(scene_arrays *a)
{
    int v = 0, t = 0;
    for (int l = 0; l < LAYERS; l++)
        for (int q = 0; q < QUADS; q++) {
            int qx = q % 6, qy = q / 6;
            float x0 = -1.0f + qx / 3.0f, y0 = -1.0f + qy / 3.0f, s = 0.3f;
            float z = -0.8f + 0.4f * l;
            float corners[4][2] = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
            uint8_t rgba[4] = {(uint8_t)(40 * l + 30), (uint8_t)(7 * q), (uint8_t)(250 - 6 * q),
                               (uint8_t)(64 + (q * 37 + l * 11) % 128)};
            for (int c = 0; c < 4; c++) {
                a->pos[(v + c) * 3 + 0] = corners[c][0] + 0.05f * l;
                a->pos[(v + c) * 3 + 1] = corners[c][1];
                a->pos[(v + c) * 3 + 2] = z + 0.15f * corners[c][0];
                memcpy(a->vrgba + (v + c) * 4, rgba, 4);
            }
            uint32_t ids[6] = {v, v + 1, v + 2, v, v + 2, v + 3};
            memcpy(a->idx + t * 3, ids, sizeof ids);
            v += 4;
            t += 2;
        }
}

static int write_ply(const scene_arrays *a, const char *path)
{
    oit_error err = {0};
    oit_ply_writer *w = NULL;
    oit_ply_writer_desc d = {.path = path, .vertex_rgba = 1};
    oit_status s = oit_ply_writer_open(&d, &w, &err);
    if (s == OIT_OK)
        s = oit_ply_writer_add_vertices(w, a->pos, a->vrgba, NV, NULL, &err);
    if (s == OIT_OK)
        s = oit_ply_writer_add_faces(w, a->idx, NULL, NT, &err);
    if (s == OIT_OK)
        s = oit_ply_writer_close(w, NULL, &err);
    else
        oit_ply_writer_abort(w);
    CHECK(s == OIT_OK, "writing %s: %s", path, err.message);
    return s == OIT_OK;
}

/* The same triangles as a binary STL: no colour. */
static int write_stl(const scene_arrays *a, const char *path)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        CHECK(0, "cannot create %s", path);
        return 0;
    }
    char header[80] = "liboit_incore";
    uint32_t n = NT;
    fwrite(header, 1, sizeof header, f);
    fwrite(&n, 4, 1, f);
    for (int t = 0; t < NT; t++) {
        float rec[12] = {0};
        for (int c = 0; c < 3; c++)
            memcpy(rec + 3 + 3 * c, a->pos + a->idx[t * 3 + c] * 3, 12);
        uint16_t attr = 0;
        fwrite(rec, 4, 12, f);
        fwrite(&attr, 2, 1, f);
    }
    return fclose(f) == 0;
}

static float *render(oit_offscreen *o, oit_scene *scene, const char *what)
{
    float *px = malloc((size_t)W * H * 4 * sizeof *px);
    oit_offscreen_view v = {.width = W, .height = H, .format = OIT_PIXELS_RGBA32F,
                            .background = {0.2f, 0.4f, 0.6f, 1.0f}};
    oit_error err = {0};
    oit_draw_stats st = {0};
    oit_status s = oit_offscreen_render(o, scene, &v, px, (size_t)W * H * 4 * sizeof *px, &st,
                                        &err);
    CHECK(s == OIT_OK, "%s: %s", what, err.message);
    printf("%s: %llu fragments, %u packs, %llu bytes uploaded, %.1f ms\n", what,
           (unsigned long long)st.fragments, st.packs, (unsigned long long)st.bytes_uploaded,
           st.ms);
    if (s != OIT_OK) {
        free(px);
        return NULL;
    }
    return px;
}

/* tolerance < 0: bit-identical; else at most 0.1% of pixels over it. */
static void compare(const char *what, const float *a, const float *b, double tolerance)
{
    if (!a || !b)
        return;
    uint64_t over = 0, covered = 0;
    double max_abs = 0.0;
    for (size_t p = 0; p < (size_t)W * H; p++) {
        double d = 0.0;
        for (int c = 0; c < 4; c++)
            d = fmax(d, fabs((double)a[p * 4 + c] - b[p * 4 + c]));
        max_abs = fmax(max_abs, d);
        over += d > (tolerance < 0 ? 0.0 : tolerance);
        covered += fabsf(a[p * 4] - 0.2f) + fabsf(a[p * 4 + 1] - 0.4f) > 1.0f / 255.0f;
    }
    double pct = 100.0 * (double)over / (W * H), cov = 100.0 * (double)covered / (W * H);
    printf("%s: max_abs %.6f, %.4f%% pixels over %s, %.1f%% covered\n", what, max_abs, pct,
           tolerance < 0 ? "0 (exact)" : "1/255", cov);
    CHECK(tolerance < 0 ? over == 0 : pct <= 0.1, "%s: %llu pixels differ (%.4f%%), max %.6f",
          what, (unsigned long long)over, pct, max_abs);
    CHECK(cov >= 20.0, "%s: only %.1f%% covered: the view misses the scene", what, cov);
}

static oit_scene *from_arrays(const oit_scene_mesh_desc *d)
{
    oit_error err = {0};
    oit_scene *s = NULL;
    oit_status st = oit_scene_create_mesh(d, &s, &err);
    CHECK(st == OIT_OK, "%s: %s", d->name, err.message);
    return s;
}

/* How many of two W x H float images' values differ (0 when one is
 * missing). */
static uint64_t values_differ(const float *a, const float *b)
{
    uint64_t n = 0;
    for (size_t i = 0; a && b && i < (size_t)W * H * 4; i++)
        n += a[i] != b[i];
    return n;
}

/* The scene d describes, drawn and compared with the file's image. */
static void arrays_vs_file(oit_offscreen *o, const oit_scene_mesh_desc *d, const float *file_img)
{
    oit_scene *s = from_arrays(d);
    float *img = s ? render(o, s, d->name) : NULL;
    compare(d->name, img, file_img, -1.0);
    free(img);
    oit_scene_close(s);
}

static void check_arrays(oit_offscreen *o, const scene_arrays *a, const float *file_img)
{
    /* Indexed, per-vertex 8-bit colour: the PLY's own arrays. */
    oit_scene_mesh_desc d = {.positions = a->pos, .vertex_count = NV, .indices = a->idx,
                             .index_count = NT * 3, .colours = a->vrgba,
                             .name = "indexed per-vertex u8"};
    arrays_vs_file(o, &d, file_img);

    /* Indexed, per-triangle float colour. */
    float *tri_f = malloc(NT * 4 * sizeof *tri_f);
    uint8_t *tri_u8 = malloc(NT * 4);
    for (int t = 0; t < NT; t++)
        for (int c = 0; c < 4; c++) {
            tri_u8[t * 4 + c] = a->vrgba[a->idx[t * 3] * 4 + c];
            tri_f[t * 4 + c] = tri_u8[t * 4 + c] / 255.0f;
        }
    d.colours = tri_f;
    d.colour_type = OIT_COLOUR_FLOAT;
    d.colour_rate = OIT_COLOUR_PER_TRIANGLE;
    d.name = "indexed per-triangle float";
    arrays_vs_file(o, &d, file_img);

    /* Soups: per-vertex float, per-triangle 8-bit. */
    float *soup = malloc(NT * 9 * sizeof *soup), *soup_f = malloc(NT * 12 * sizeof *soup_f);
    for (int t = 0; t < NT; t++)
        for (int c = 0; c < 3; c++) {
            uint32_t v = a->idx[t * 3 + c];
            memcpy(soup + (t * 3 + c) * 3, a->pos + v * 3, 12);
            for (int k = 0; k < 4; k++)
                soup_f[(t * 3 + c) * 4 + k] = a->vrgba[v * 4 + k] / 255.0f;
        }
    oit_scene_mesh_desc sd = {.positions = soup, .vertex_count = NT * 3, .colours = soup_f,
                              .colour_type = OIT_COLOUR_FLOAT, .name = "soup per-vertex float"};
    arrays_vs_file(o, &sd, file_img);
    sd.colours = tri_u8;
    sd.colour_type = OIT_COLOUR_UINT8;
    sd.colour_rate = OIT_COLOUR_PER_TRIANGLE;
    sd.name = "soup per-triangle u8";
    arrays_vs_file(o, &sd, file_img);

    /* A different colour must show: the comparison can fail. */
    tri_u8[0] ^= 0xff;
    tri_u8[3] = 255;
    sd.name = "soup, one triangle recoloured";
    oit_scene *s = from_arrays(&sd);
    float *img = s ? render(o, s, sd.name) : NULL;
    CHECK(values_differ(img, file_img) > 0,
          "recolouring a triangle changed no pixel: the comparison is blind");
    free(img);
    oit_scene_close(s);
    free(soup);
    free(soup_f);
    free(tri_f);
    free(tri_u8);
}

static const float square[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};

/* The quad of corners pos (4 xyz, counter-clockwise), red of alpha
 * 128/255. */
static oit_scene *red_quad(const float pos[12], const char *name)
{
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    static const uint8_t red[8] = {255, 0, 0, 128, 255, 0, 0, 128};
    oit_scene_mesh_desc d = {.positions = pos, .vertex_count = 4, .indices = idx,
                             .index_count = 6, .colours = red,
                             .colour_rate = OIT_COLOUR_PER_TRIANGLE, .name = name};
    return from_arrays(&d);
}

/* A red square of alpha 128/255 facing the camera over white. At the
 * centre the view direction is the normal (light 1): r = a + (1 - a) = 1,
 * g = b = 1 - a = 127/255. */
static void check_square(oit_offscreen *o)
{
    oit_scene *s = red_quad(square, "red square");
    if (!s)
        return;
    enum { S = 64 };
    uint8_t px[S * S * 4];
    float pf[S * S * 4];
    oit_offscreen_view v = {.width = S, .height = S, .eye = {0, 0, 4}, .fovy_deg = 30.0f};
    oit_error err = {0};
    oit_status st = oit_offscreen_render(o, s, &v, px, sizeof px, NULL, &err);
    CHECK(st == OIT_OK, "red square: %s", err.message);
    v.format = OIT_PIXELS_RGBA32F;
    oit_status st2 = oit_offscreen_render(o, s, &v, pf, sizeof pf, NULL, &err);
    CHECK(st2 == OIT_OK, "red square (float): %s", err.message);
    if (st == OIT_OK && st2 == OIT_OK) {
        const uint8_t *c = px + ((S / 2) * S + S / 2) * 4, *corner = px;
        const float *cf = pf + ((S / 2) * S + S / 2) * 4;
        printf("red square: centre %u %u %u %u (float %.4f %.4f %.4f %.4f), corner %u %u %u "
               "%u\n", c[0], c[1], c[2], c[3], cf[0], cf[1], cf[2], cf[3], corner[0],
               corner[1], corner[2], corner[3]);
        CHECK(c[0] == 255 && c[1] == 127 && c[2] == 127 && c[3] == 255,
              "centre %u %u %u %u, expected 255 127 127 255", c[0], c[1], c[2], c[3]);
        CHECK(fabsf(cf[1] - 127.0f / 255.0f) < 2e-3f && fabsf(cf[0] - 1.0f) < 1e-5f,
              "float centre %.5f %.5f", cf[0], cf[1]);
        CHECK(corner[0] == 255 && corner[1] == 255 && corner[2] == 255 && corner[3] == 255,
              "corner %u %u %u %u, expected the white background", corner[0], corner[1],
              corner[2], corner[3]);
        /* The square's edge at distance 4 with fovy 30: half-height
         * 4 tan 15 = 1.07, so the square spans 1/1.07 of the frame. */
        int inside = px[((S / 2) * S + 4) * 4 + 1] == 127, outside = px[((S / 2) * S + 1) * 4 + 1] == 255;
        CHECK(inside && outside, "edge: x=4 g %u, x=1 g %u", px[((S / 2) * S + 4) * 4 + 1],
              px[((S / 2) * S + 1) * 4 + 1]);
    }
    /* A transparent black background keeps the alpha of the square. */
    v.format = OIT_PIXELS_RGBA8;
    for (int k = 0; k < 4; k++)
        v.background[k] = -1.0f;
    st = oit_offscreen_render(o, s, &v, px, sizeof px, NULL, &err);
    CHECK(st == OIT_OK, "red square over transparent: %s", err.message);
    const uint8_t *c = px + ((S / 2) * S + S / 2) * 4;
    CHECK(st != OIT_OK || (c[0] == 128 && c[1] == 0 && c[3] == 128 && px[3] == 0),
          "over transparent black: centre %u %u %u %u, corner alpha %u", c[0], c[1], c[2],
          c[3], px[3]);
    /* Released, the scene's triangles are uploaded again at the next draw;
     * kept, they are not. */
    oit_draw_stats ds[3] = {{0}};
    oit_offscreen_render(o, s, &v, px, sizeof px, &ds[0], &err);
    oit_offscreen_release_scene(o, s);
    oit_offscreen_render(o, s, &v, px, sizeof px, &ds[1], &err);
    oit_offscreen_render(o, s, &v, px, sizeof px, &ds[2], &err);
    CHECK(ds[0].bytes_uploaded == 0 && ds[1].bytes_uploaded == 2 * sizeof(oit_triangle) &&
              ds[2].bytes_uploaded == 0,
          "uploads kept, released, kept: %llu %llu %llu bytes", (unsigned long long)ds[0].bytes_uploaded,
          (unsigned long long)ds[1].bytes_uploaded, (unsigned long long)ds[2].bytes_uploaded);
    /* Row 0 is the top: a quad above the centre shows in the upper rows. */
    const float upper[12] = {-1, 0.3f, 0, 1, 0.3f, 0, 1, 1, 0, -1, 1, 0};
    oit_scene *us = red_quad(upper, "upper quad");
    v.background[0] = v.background[1] = v.background[2] = v.background[3] = 0.0f;
    if (us && oit_offscreen_render(o, us, &v, px, sizeof px, NULL, &err) == OIT_OK) {
        unsigned top = px[((S / 4) * S + S / 2) * 4 + 1], bottom = px[((3 * S / 4) * S + S / 2) * 4 + 1];
        printf("upper quad: green %u at row %d, %u at row %d\n", top, S / 4, bottom, 3 * S / 4);
        CHECK(top == 127 && bottom == 255, "upper quad: green %u at the top, %u at the bottom: "
              "rows upside down", top, bottom);
    } else {
        CHECK(0, "upper quad: %s", err.message);
    }
    oit_scene_close(us);
    for (int k = 0; k < 4; k++)
        v.background[k] = -1.0f;
    /* Too small a buffer. */
    st = oit_offscreen_render(o, s, &v, px, sizeof px - 1, NULL, &err);
    CHECK(st == OIT_ERR_ARGUMENT && strstr(err.message, "bytes"), "short buffer gave %s: %s",
          oit_status_name(st), err.message);
    oit_scene_close(s);
}

/* Scenes closed without oit_renderer_release_scene, each followed by a new
 * one of the same sizes, which the allocator tends to put where a closed
 * one was (glibc does at once with its per-thread cache off: CMake runs
 * this test with GLIBC_TUNABLES=glibc.malloc.tcache_count=0). Every frame
 * must show its own scene, an upper and a lower quad in turn, never the
 * triangles of the scene the renderer drew before. */
static void check_closed_scenes(oit_offscreen *o)
{
    enum { S = 32, ROUNDS = 24 };
    const float upper[12] = {-1, 0.3f, 0, 1, 0.3f, 0, 1, 1, 0, -1, 1, 0};
    const float lower[12] = {-1, -1, 0, 1, -1, 0, 1, -0.3f, 0, -1, -0.3f, 0};
    uint8_t px[S * S * 4];
    oit_offscreen_view v = {.width = S, .height = S, .eye = {0, 0, 4}, .fovy_deg = 30.0f};
    const oit_scene *closed[ROUNDS];
    int reused = 0, wrong = 0;
    for (int k = 0; k < ROUNDS; k++) {
        int up = k % 2 == 0;
        oit_scene *s = red_quad(up ? upper : lower, up ? "upper quad" : "lower quad");
        if (!s)
            return;
        int at = -1; /* the latest closed scene at s's address */
        for (int j = 0; j < k; j++)
            at = closed[j] == s ? j : at;
        reused += at >= 0;
        oit_error err = {0};
        oit_status st = oit_offscreen_render(o, s, &v, px, sizeof px, NULL, &err);
        unsigned top = px[((S / 4) * S + S / 2) * 4 + 1], bottom = px[((3 * S / 4) * S + S / 2) * 4 + 1];
        int ok = st == OIT_OK && (up ? top == 127 && bottom == 255 : top == 255 && bottom == 127);
        CHECK(ok || wrong, "closed scenes: round %d (%s quad, at the address of round %d): green "
              "%u at the top, %u at the bottom: %s", k, up ? "upper" : "lower", at, top, bottom,
              st == OIT_OK ? "another scene's image" : err.message);
        wrong += !ok;
        closed[k] = s;
        oit_scene_close(s);
    }
    printf("closed scenes: %d rounds, %d at a closed scene's address, %d wrong\n", ROUNDS,
           reused, wrong);
}

/* The red square of check_square composited in linear light. */
static void check_square_linear(void)
{
    oit_error err = {0};
    oit_offscreen *o = NULL;
    oit_offscreen_desc od = {.renderer.shading.colour_space = OIT_RENDER_COLOUR_LINEAR};
    if (oit_offscreen_create(&od, &o, &err) != OIT_OK) {
        CHECK(0, "linear offscreen: %s", err.message);
        return;
    }
    oit_scene *s = red_quad(square, "red square");
    enum { S = 64 };
    static uint8_t px[S * S * 4];
    static float pf[S * S * 4];
    oit_offscreen_view v = {.width = S, .height = S, .eye = {0, 0, 4}, .fovy_deg = 30.0f};
    if (s && oit_offscreen_render(o, s, &v, px, sizeof px, NULL, &err) == OIT_OK &&
        (v.format = OIT_PIXELS_RGBA32F,
         oit_offscreen_render(o, s, &v, pf, sizeof pf, NULL, &err) == OIT_OK)) {
        const uint8_t *c = px + ((S / 2) * S + S / 2) * 4;
        const float *cf = pf + ((S / 2) * S + S / 2) * 4;
        double want = 1.055 * pow(127.0 / 255.0, 1.0 / 2.4) - 0.055;
        printf("red square, linear light: centre %u %u %u %u (float %.5f %.5f, want %.5f), "
               "corner %u %u %u\n", c[0], c[1], c[2], c[3], cf[0], cf[1], want, px[0], px[1],
               px[2]);
        CHECK(c[0] == 255 && c[1] == 187 && c[2] == 187 && c[3] == 255,
              "linear: centre %u %u %u %u, expected 255 187 187 255", c[0], c[1], c[2], c[3]);
        CHECK(fabs(cf[1] - want) < 1e-3 && fabsf(cf[0] - 1.0f) < 1e-5f && cf[3] == 1.0f,
              "linear: float centre %.5f %.5f %.5f, want 1 %.5f 1", cf[0], cf[1], cf[3], want);
        CHECK(px[0] == 255 && px[1] == 255 && px[2] == 255, "linear: corner %u %u %u", px[0],
              px[1], px[2]);
    } else {
        CHECK(0, "linear red square: %s", err.message);
    }
    oit_scene_close(s);
    oit_offscreen_destroy(o);
}

static void check_errors(const char *dir)
{
    oit_error err = {0};
    oit_scene *s = NULL;
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t idx[3] = {0, 1, 3};
    oit_scene_mesh_desc d = {.positions = pos, .vertex_count = 3, .indices = idx,
                             .index_count = 3, .name = "bad"};
    oit_status st = oit_scene_create_mesh(&d, &s, &err);
    printf("bad index: %s: %s\n", oit_status_name(st), err.message);
    CHECK(st == OIT_ERR_ARGUMENT && !s && strstr(err.message, "indices[2] = 3"),
          "index 3 of 3 vertices gave %s: %s", oit_status_name(st), err.message);
    d.indices = NULL;
    d.index_count = 0;
    pos[4] = NAN;
    st = oit_scene_create_mesh(&d, &s, &err);
    CHECK(st == OIT_ERR_ARGUMENT && strstr(err.message, "positions[4]"),
          "NaN position gave %s: %s", oit_status_name(st), err.message);
    pos[4] = 0.0f;
    d.vertex_count = 4;
    st = oit_scene_create_mesh(&d, &s, &err);
    CHECK(st == OIT_ERR_ARGUMENT && strstr(err.message, "multiple of 3"),
          "a soup of 4 vertices gave %s: %s", oit_status_name(st), err.message);

    char path[1024];
    snprintf(path, sizeof path, "%s/no-such-mesh.ply", dir);
    st = oit_scene_open(path, NULL, &s, &err);
    printf("missing mesh: %s: %s\n", oit_status_name(st), err.message);
    CHECK(st == OIT_ERR_IO && strstr(err.message, path), "missing PLY gave %s: %s",
          oit_status_name(st), err.message);
    snprintf(path, sizeof path, "%s/scene.xyz", dir);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs("1 2 3\n", f);
        fclose(f);
    }
    st = oit_scene_open(path, NULL, &s, &err);
    printf("unknown extension: %s: %s\n", oit_status_name(st), err.message);
    CHECK(st == OIT_ERR_UNSUPPORTED && strstr(err.message, path),
          "a .xyz file gave %s: %s", oit_status_name(st), err.message);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_liboit_incore OITPREP WORKDIR\n");
        return 2;
    }
    char ply[1024], oitp[1024], cmd[4096];
    snprintf(ply, sizeof ply, "%s/liboit_incore.ply", argv[2]);
    snprintf(oitp, sizeof oitp, "%s/liboit_incore.oitp", argv[2]);
    static scene_arrays a;
    make_scene(&a);
    if (!write_ply(&a, ply))
        return 1;
    /* Small parts, so that the streamer's ordering, packing and clipping
     * (planes crossing quads) are what is compared. */
    snprintf(cmd, sizeof cmd, "'%s' '%s' -o '%s' --part-triangles 24 > /dev/null", argv[1], ply,
             oitp);
    if (system(cmd) != 0) {
        fprintf(stderr, "FAIL: %s\n", cmd);
        return 1;
    }
    oit_error err = {0};
    oit_offscreen *o = NULL;
    if (oit_offscreen_create(NULL, &o, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    printf("renderer: %s\n", oit_offscreen_gl_renderer(o));
    oit_scene *mesh = NULL, *part = NULL;
    if (oit_scene_open(ply, NULL, &mesh, &err) != OIT_OK ||
        oit_scene_open(oitp, NULL, &part, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    oit_scene_info mi, pi;
    oit_scene_get_info(mesh, &mi, &err);
    oit_scene_get_info(part, &pi, &err);
    printf("mesh: %llu triangles, in core %u; part file: %llu triangles, %llu parts\n",
           (unsigned long long)mi.triangles, mi.in_core, (unsigned long long)pi.triangles,
           (unsigned long long)pi.parts);
    CHECK(mi.in_core == 1 && mi.parts == 0 && mi.triangles == NT &&
              mi.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA),
          "mesh info: in_core %u, %llu parts, %llu triangles, attributes %u", mi.in_core,
          (unsigned long long)mi.parts, (unsigned long long)mi.triangles, mi.attributes);
    CHECK(pi.in_core == 0 && pi.parts > 0 && pi.triangles >= NT,
          "part info: in_core %u, %llu parts, %llu triangles", pi.in_core,
          (unsigned long long)pi.parts, (unsigned long long)pi.triangles);
    for (int k = 0; k < 3; k++)
        CHECK(mi.bounds_min[k] == pi.bounds_min[k] && mi.bounds_max[k] == pi.bounds_max[k],
              "bounds differ on axis %d: %g..%g and %g..%g", k, mi.bounds_min[k],
              mi.bounds_max[k], pi.bounds_min[k], pi.bounds_max[k]);

    float *file_img = render(o, mesh, "mesh file, in core");
    float *part_img = render(o, part, "part file, streamed");
    compare("in core vs part file", file_img, part_img, 1.0 / 255.0);
    check_arrays(o, &a, file_img);
    free(part_img);

    /* Another reader (STL, no colour: the default colour and alpha) gives
     * the image of the same arrays without colours. */
    char stl[1024];
    snprintf(stl, sizeof stl, "%s/liboit_incore.stl", argv[2]);
    oit_scene *stl_scene = NULL, *plain = NULL;
    oit_scene_mesh_desc pd = {.positions = a.pos, .vertex_count = NV, .indices = a.idx,
                              .index_count = NT * 3, .name = "indexed, no colour"};
    if (write_stl(&a, stl) && oit_scene_open(stl, NULL, &stl_scene, &err) == OIT_OK &&
        (plain = from_arrays(&pd)) != NULL) {
        oit_scene_info si;
        oit_scene_get_info(stl_scene, &si, &err);
        CHECK(si.in_core && si.attributes == 0 && si.triangles == NT,
              "STL info: in_core %u, attributes %u, %llu triangles", si.in_core, si.attributes,
              (unsigned long long)si.triangles);
        float *si_img = render(o, stl_scene, "STL file, in core");
        float *pl_img = render(o, plain, "arrays without colour");
        compare("STL vs arrays without colour", si_img, pl_img, -1.0);
        free(si_img);
        free(pl_img);
    } else {
        CHECK(0, "STL: %s", err.message);
    }
    oit_scene_close(stl_scene);
    oit_scene_close(plain);
    oit_offscreen_destroy(o);

    /* Translucent shading, through a renderer descriptor. */
    oit_offscreen_desc od = {.renderer.shading.mode = OIT_RENDER_TRANSLUCENT};
    if (oit_offscreen_create(&od, &o, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    float *t_file = render(o, mesh, "translucent mesh file");
    float *t_part = render(o, part, "translucent part file");
    compare("translucent: in core vs part file", t_file, t_part, 1.0 / 255.0);
    CHECK(values_differ(t_file, file_img) > 0, "translucent shading gave the transparent image");
    free(t_file);
    free(t_part);
    free(file_img);
    oit_offscreen_destroy(o);

    if (oit_offscreen_create(NULL, &o, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    check_square(o);
    check_closed_scenes(o);
    check_square_linear();
    check_errors(argv[2]);
    oit_offscreen_destroy(o);
    oit_scene_close(mesh);
    oit_scene_close(part);
    return test_verdict();
}
