/* Capture batches over rectangles that start neither at row 0 nor at column
 * 0, on scenes of screen-aligned quads whose pixel boxes are exact (their
 * edges lie on pixel edges, so each pixel centre is in or out by half a
 * pixel and the per-pixel result is known by hand).
 *
 * usage: test_capture_rects bands | epsilon
 *
 * bands: random rectangles and quads inside them, in 1 to 3 batches, under
 *   store limits forced so small (oit_capture_settings.store_limit) that the
 *   counted capture stores a mesh in bands of rows and first-K's second
 *   pass runs in bands: the image is DFB's and the hand result's, the
 *   fragment total DFB's, and the frame really was taken in more draws
 *   than its batches.
 * epsilon: early termination over 6 batches whose rectangles grow and move
 *   (the second apart from the first, the third over the second only, the
 *   fourth over the first only, ...):
 *   at E = 0 DFB's image and total; at E > 0 within E of DFB, and equal to
 *   a CPU model of the rule (capture.h: from the next batch on, a pixel
 *   whose carried transmittance is below E drops its fragments) in the
 *   image and in the fragment total, batch by batch, so a batch that
 *   wrongly keeps or drops fragments shows whichever batch it is. Array
 *   slots (plain, in screen tiles for a batch wider than K, in tiles under
 *   a slot budget), counted and first-K. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/gl_context.h"
#include "view/render/image/image.h"
#include "tests/lib/gl_test_scene.h"
#include "tests/lib/capture_set.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { MAXQ = 48, MAXB = 6 };

typedef struct rquad {
    float z;
    int box[4]; /* pixels covered: x0, y0, x1, y1, top rows first, exclusive */
    uint8_t rgba[4];
} rquad;

typedef struct scene {
    oit_view v;
    rquad q[MAXQ];    /* front to back: batch b is q[start[b] .. start[b+1]) */
    int start[MAXB + 1], nb;
    int rect[MAXB][4]; /* each batch's rectangle */
} scene;

static uint32_t rng(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static int rnd(uint32_t *s, int lo, int hi) /* [lo, hi] */
{
    return hi <= lo ? lo : lo + (int)(rng(s) % (uint32_t)(hi - lo + 1));
}

/* The quad's two triangles: its box's edges in the plane z (the view of
 * scene_view: 90 degrees, so a pixel edge at NDC u lies at u * d). */
static void quad_triangles(const oit_view *v, const rquad *q, oit_triangle out[2])
{
    float d = -q->z, aspect = (float)v->width / (float)v->height;
    float x0 = ((float)q->box[0] / v->width * 2 - 1) * aspect * d;
    float x1 = ((float)q->box[2] / v->width * 2 - 1) * aspect * d;
    float y1 = (1 - (float)q->box[1] / v->height * 2) * d;
    float y0 = (1 - (float)q->box[3] / v->height * 2) * d;
    const float c[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const int idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; t++)
        for (int k = 0; k < 3; k++) {
            oit_vertex *p = &out[t].v[k];
            p->pos[0] = c[idx[t][k]][0];
            p->pos[1] = c[idx[t][k]][1];
            p->pos[2] = q->z;
            memcpy(p->rgba, q->rgba, 4);
        }
}

static oit_gpu_mesh *make_mesh(const scene *s, int first, int n, oit_error *err)
{
    oit_triangle *t = malloc(sizeof *t * 2 * (size_t)n);
    oit_gpu_mesh *m = NULL;
    if (!t)
        return NULL;
    for (int i = 0; i < n; i++)
        quad_triangles(&s->v, &s->q[first + i], &t[2 * i]);
    if (oit_gpu_mesh_create(t, 2 * (size_t)n, 2u * (uint32_t)first, &m, err) != OIT_OK)
        m = NULL;
    free(t);
    return m;
}

static int inside(const int b[4], int x, int y)
{
    return x >= b[0] && x < b[2] && y >= b[1] && y < b[3];
}

/* The hand result with early termination eps (0: exact): per pixel, batch
 * by batch, a batch whose start finds T below eps is dropped whole. Counts
 * the fragments kept, and pixels where T is too near eps to decide. */
static void hand_image(const scene *s, double eps, oit_image *out, uint64_t *kept,
                       uint64_t *near)
{
    const oit_view *v = &s->v;
    *kept = *near = 0;
    for (int y = 0; y < v->height; y++)
        for (int x = 0; x < v->width; x++) {
            double dx = ((x + 0.5) / v->width * 2 - 1) * v->width / v->height;
            double dy = 1 - (y + 0.5) / v->height * 2;
            double ndv = 1.0 / sqrt(dx * dx + dy * dy + 1.0), light = 0.3 + 0.7 * ndv;
            double C[3] = {0, 0, 0}, T = 1.0;
            for (int b = 0; b < s->nb; b++) {
                if (eps > 0 && fabs(T - eps) < 1e-4)
                    ++*near;
                if (eps > 0 && T < eps)
                    continue;
                for (int i = s->start[b]; i < s->start[b + 1]; i++) {
                    const rquad *q = &s->q[i];
                    if (!inside(q->box, x, y) || !inside(s->rect[b], x, y))
                        continue;
                    double a = q->rgba[3] / 255.0;
                    for (int c = 0; c < 3; c++)
                        C[c] += T * a * (q->rgba[c] / 255.0) * light;
                    T *= 1.0 - a;
                    ++*kept;
                }
            }
            float *p = &out->rgba[4 * ((size_t)y * v->width + x)];
            for (int c = 0; c < 3; c++)
                p[c] = (float)(C[c] + T * v->shading.background[c]);
        }
}

typedef struct capture_cfg {
    const char *name;
    oit_capture_kind kind;
    int K;
    int layers;            /* > K: oit_capture_batch_layers in screen tiles */
    uint64_t slot_budget;  /* 0: none */
    uint64_t store_limit;  /* 0: the driver's */
    int meshes;            /* meshes a batch: one a quad, or 1 */
} capture_cfg;

static oit_capture *capture_new(const capture_cfg *cfg)
{
    oit_error err = {0};
    oit_capture *c = NULL;
    if (oit_capture_create(&(oit_capture_desc){.fill = capture_fill(cfg->kind),
                                               .cut = capture_cut(cfg->kind), .K = cfg->K},
                           &c, &err) != OIT_OK) {
        CHECK(0, "%s: capture: %s", cfg->name, err.message);
        return NULL;
    }
    CAPTURE_SET(c, slot_budget, cfg->slot_budget);
    CAPTURE_SET(c, store_limit, cfg->store_limit);
    return c;
}

/* The frame of the scene's first nb batches through c at eps. */
static int capture_run(oit_capture *c, const capture_cfg *cfg, const scene *s, int nb,
                       float eps, oit_image *img, oit_frame_stats *st, uint64_t *draws)
{
    oit_error err = {0};
    CAPTURE_SET(c, epsilon, eps);
    oit_status r = oit_capture_begin(c, &s->v, &err);
    for (int b = 0; r == OIT_OK && b < nb; b++) {
        oit_gpu_mesh *m[MAXQ] = {0};
        int first = s->start[b], n = s->start[b + 1] - first;
        int nm = cfg->meshes == 1 ? 1 : n;
        for (int i = 0; i < nm && r == OIT_OK; i++)
            if (!(m[i] = make_mesh(s, first + (nm == 1 ? 0 : i), nm == 1 ? n : 1, &err)))
                r = OIT_ERR_GL;
        if (r == OIT_OK)
            r = oit_capture_batch_layers(c, (const oit_gpu_mesh *const *)m, nm, s->rect[b],
                                         cfg->layers, &err);
        for (int i = 0; i < nm; i++)
            oit_gpu_mesh_destroy(m[i]);
    }
    if (r == OIT_OK)
        r = oit_capture_end(c, img, st, &err);
    *draws = oit_capture_draw_calls(c);
    CHECK(r == OIT_OK, "%s: capture of %d batches: %s", cfg->name, nb, err.message);
    return r == OIT_OK;
}

static int dfb_run(const scene *s, oit_image *img, oit_frame_stats *st)
{
    oit_error err = {0};
    oit_dfb *d = NULL;
    oit_gpu_mesh *m = NULL;
    oit_status r = oit_dfb_create(&d, &err);
    if (r == OIT_OK && !(m = make_mesh(s, 0, s->start[s->nb], &err)))
        r = OIT_ERR_GL;
    const oit_gpu_mesh *list[1] = {m};
    if (r == OIT_OK)
        r = oit_dfb_render(d, list, 1, &s->v, img, NULL, st, &err);
    oit_gpu_mesh_destroy(m);
    oit_dfb_destroy(d);
    CHECK(r == OIT_OK, "DFB: %s", err.message);
    return r == OIT_OK;
}

/* Largest channel difference, and where. */
static double image_diff(const oit_image *a, const oit_image *b, int *wx, int *wy)
{
    double worst = 0.0;
    *wx = *wy = -1;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++)
            for (int c = 0; c < 3; c++) {
                size_t i = 4 * ((size_t)y * a->width + x) + (size_t)c;
                double d = fabs((double)a->rgba[i] - b->rgba[i]);
                if (d > worst)
                    worst = d, *wx = x, *wy = y;
            }
    return worst;
}

/* A random box of at least 2 x 2 pixels inside r. */
static void sub_box(uint32_t *seed, const int r[4], int out[4])
{
    out[0] = rnd(seed, r[0], r[2] - 2);
    out[1] = rnd(seed, r[1], r[3] - 2);
    out[2] = rnd(seed, out[0] + 2, r[2]);
    out[3] = rnd(seed, out[1] + 2, r[3]);
}

/* ---- bands ---------------------------------------------------------------- */

/* Fragments of the batch's quads in the fullest row of its rect. */
static uint64_t fullest_row(const scene *s, int b)
{
    uint64_t most = 0;
    for (int y = s->rect[b][1]; y < s->rect[b][3]; y++) {
        uint64_t n = 0;
        for (int i = s->start[b]; i < s->start[b + 1]; i++) {
            const int *q = s->q[i].box;
            if (y >= q[1] && y < q[3])
                n += (uint64_t)(q[2] - q[0]);
        }
        most = n > most ? n : most;
    }
    return most;
}

/* A frame w x h with one rect per batch that starts past row and column 0
 * and (mostly) ends before the last row, quads inside it, deep enough that
 * stores outgrow a few rows (deep: most quads cover most of the rect, so
 * most pixels overflow first-K's slots). */
static void bands_scene(scene *s, uint32_t *seed, int deep)
{
    memset(s, 0, sizeof *s);
    scene_view(&s->v, rnd(seed, 24, 64), rnd(seed, 20, 56), OIT_SHADING_TRANSPARENT);
    int w = s->v.width, h = s->v.height;
    s->nb = rnd(seed, 1, 3);
    float z = -1.5f;
    for (int b = 0; b < s->nb; b++) {
        int *r = s->rect[b];
        r[0] = rnd(seed, 1, w / 2);
        r[1] = rnd(seed, 1, h / 2);
        r[2] = rnd(seed, r[0] + 6, w);
        r[3] = rnd(seed, r[1] + 6, rng(seed) % 4 ? h - 1 : h);
        int n = deep ? rnd(seed, 8, 12) : rnd(seed, 4, 9);
        s->start[b + 1] = s->start[b] + n;
        for (int i = s->start[b]; i < s->start[b + 1]; i++) {
            rquad *q = &s->q[i];
            q->z = z;
            z -= 0.25f;
            sub_box(seed, r, q->box);
            if (deep && rng(seed) % 3)
                for (int k = 0; k < 4; k++)
                    q->box[k] = r[k] + (k < 2 ? 1 : -1) * rnd(seed, 0, 2);
            for (int c = 0; c < 3; c++)
                q->rgba[c] = (uint8_t)rnd(seed, 20, 255);
            q->rgba[3] = (uint8_t)rnd(seed, 40, 120);
        }
    }
}

static void bands_case(oit_capture_kind kind, int meshes, uint32_t seed, int index)
{
    scene s;
    bands_scene(&s, &seed, kind == OIT_CAPTURE_FIRSTK);
    uint64_t row = 0, pixels = 0;
    for (int b = 0; b < s.nb; b++) {
        uint64_t f = fullest_row(&s, b);
        uint64_t p = (uint64_t)(s.rect[b][2] - s.rect[b][0]) * (uint64_t)(s.rect[b][3] - s.rect[b][1]);
        row = f > row ? f : row;
        pixels = p > pixels ? p : pixels;
    }
    /* counted: a few rows a band (a row must fit); first-K: 2 slots a pixel
     * of the largest rect, so its overflow is stored in bands */
    uint64_t limit = kind == OIT_CAPTURE_COUNTED ? 16 * row * (uint64_t)rnd(&seed, 1, 3)
                                                 : 16 * pixels * 2;
    char name[96];
    snprintf(name, sizeof name, "bands %s %d (%dx%d, %d batches, %s, limit %llu)",
             kind == OIT_CAPTURE_COUNTED ? "counted" : "first-k", index, s.v.width,
             s.v.height, s.nb, meshes == 1 ? "one mesh" : "a mesh a quad",
             (unsigned long long)limit);
    capture_cfg cfg = {name, kind, 4, 4, 0, limit, meshes};
    oit_image a = {0}, d = {0}, hand = {0};
    oit_frame_stats sa, sd;
    uint64_t draws = 0, kept = 0, near = 0;
    oit_error err = {0};
    oit_capture *c = capture_new(&cfg);
    if (c && capture_run(c, &cfg, &s, s.nb, 0.0f, &a, &sa, &draws) && dfb_run(&s, &d, &sd) &&
        oit_image_alloc(&hand, s.v.width, s.v.height, &err) == OIT_OK) {
        hand_image(&s, 0.0, &hand, &kept, &near);
        int x, y, hx, hy;
        double dd = image_diff(&a, &d, &x, &y), dh = image_diff(&a, &hand, &hx, &hy);
        printf("%s: vs DFB %.2g, vs hand %.2g; fragments %llu/%llu (hand %llu); %llu draws\n",
               name, dd, dh, (unsigned long long)sa.fragments, (unsigned long long)sd.fragments,
               (unsigned long long)kept, (unsigned long long)draws);
        CHECK(dd <= 1e-5 && dh <= 1e-4, "%s: %.6f from DFB at pixel (%d, %d), %.6f from the "
              "hand result at (%d, %d)", name, dd, x, y, dh, hx, hy);
        CHECK(sa.fragments == sd.fragments && sd.fragments == kept,
              "%s: %llu fragments, DFB %llu, by hand %llu", name,
              (unsigned long long)sa.fragments, (unsigned long long)sd.fragments,
              (unsigned long long)kept);
        /* counted: count and store a batch whole; first-K: one pass, and
         * one more for a batch whose overflow is stored whole */
        uint64_t whole = kind == OIT_CAPTURE_COUNTED ? 2 * (uint64_t)s.nb
                                                     : (uint64_t)s.nb + sa.second_pass_packs;
        CHECK(draws > whole, "%s: %llu draws for %d batches (%u second passes): nothing was "
              "taken in bands", name, (unsigned long long)draws, s.nb, sa.second_pass_packs);
    }
    oit_capture_destroy(c);
    oit_image_free(&a);
    oit_image_free(&d);
    oit_image_free(&hand);
}

static void run_bands(void)
{
    for (int i = 0; i < 6; i++) {
        bands_case(OIT_CAPTURE_COUNTED, 1, 1234u + 77u * (uint32_t)i, i);
        bands_case(OIT_CAPTURE_FIRSTK, i % 2 ? 1 : 0, 999u + 31u * (uint32_t)i, i);
    }
    bands_case(OIT_CAPTURE_COUNTED, 0, 4321u, 6); /* halves first, then bands */
}

/* ---- epsilon -------------------------------------------------------------- */

/* Six batches over rects that grow and move: 0 somewhere, 1 apart from 0,
 * 2 over part of 1 away from 0, 3 back over part of 0 away from 1 and 2,
 * 4 over all so far, 5 anywhere. So the box of the batches before must grow
 * with each (2 meets only 1, 3 only 0, on whichever side 0 lies). Each
 * batch's first two quads cover its rect, which saturates it (T <= 0.04),
 * the others parts of it; alphas of 0.6, 0.8 and 0.9 keep T off E = 0.05. */
static void epsilon_scene(scene *s, uint32_t *seed)
{
    memset(s, 0, sizeof *s);
    scene_view(&s->v, 64, 48, OIT_SHADING_TRANSPARENT);
    int w = 64, h = 48;
    int left = rng(seed) % 2;
    int *r = s->rect[0];
    r[0] = left ? rnd(seed, 1, 6) : rnd(seed, 36, 44), r[2] = r[0] + rnd(seed, 12, 18);
    r[1] = rnd(seed, 1, 20), r[3] = r[1] + rnd(seed, 10, 24);
    r = s->rect[1]; /* the other side: no pixel of batch 0 */
    r[0] = left ? rnd(seed, 34, 40) : rnd(seed, 2, 8), r[2] = r[0] + rnd(seed, 14, 20);
    r[1] = rnd(seed, 3, 18), r[3] = r[1] + rnd(seed, 12, 26);
    for (int k = 2; k <= 3; k++) { /* moved over part of 1, then of 0 */
        const int *p = s->rect[k == 2 ? 1 : 0];
        r = s->rect[k];
        r[0] = p[0] + rnd(seed, 2, 6), r[2] = p[2] + rnd(seed, 0, 2);
        r[1] = p[1] + rnd(seed, 3, 8), r[3] = p[3] + rnd(seed, 1, 6);
    }
    r = s->rect[4]; /* grown over everything so far */
    r[0] = rnd(seed, 1, 3), r[2] = w - rnd(seed, 0, 2);
    r[1] = rnd(seed, 1, 4), r[3] = h - rnd(seed, 1, 3);
    sub_box(seed, (const int[4]){0, 0, w, h}, s->rect[5]);
    s->nb = 6;
    static const uint8_t alpha[3] = {153, 204, 230};
    float z = -1.5f;
    for (int b = 0; b < s->nb; b++) {
        s->rect[b][2] = s->rect[b][2] > w ? w : s->rect[b][2];
        s->rect[b][3] = s->rect[b][3] > h ? h : s->rect[b][3];
        int n = rnd(seed, 2, 4);
        s->start[b + 1] = s->start[b] + n;
        for (int i = s->start[b]; i < s->start[b + 1]; i++) {
            rquad *q = &s->q[i];
            q->z = z;
            z -= 0.3f;
            if (i < s->start[b] + 2)
                memcpy(q->box, s->rect[b], sizeof q->box);
            else
                sub_box(seed, s->rect[b], q->box);
            for (int c = 0; c < 3; c++)
                q->rgba[c] = (uint8_t)rnd(seed, 60, 255);
            q->rgba[3] = i == s->start[b] ? 230 : alpha[rng(seed) % 3];
        }
    }
}

/* The frame of batches [0, nb) at E against the model: the image and the
 * fragments kept. */
static void epsilon_prefix(oit_capture *c, const capture_cfg *cfg, const scene *full, int nb,
                           float E, uint32_t seed)
{
    scene s = *full;
    s.nb = nb;
    oit_image x = {0}, hand = {0};
    oit_frame_stats st;
    uint64_t draws = 0, kept = 0, near = 0;
    oit_error err = {0};
    if (capture_run(c, cfg, &s, nb, E, &x, &st, &draws) &&
        oit_image_alloc(&hand, s.v.width, s.v.height, &err) == OIT_OK) {
        hand_image(&s, E, &hand, &kept, &near);
        int hx, hy;
        double dh = image_diff(&x, &hand, &hx, &hy);
        CHECK(dh <= 1e-4 && st.fragments == kept,
              "%s, seed %u: E = %.2f, batches 0..%d: %.6f from the model of early "
              "termination at pixel (%d, %d); %llu fragments, the model keeps %llu", cfg->name,
              seed, (double)E, nb - 1, dh, hx, hy, (unsigned long long)st.fragments,
              (unsigned long long)kept);
    }
    oit_image_free(&x);
    oit_image_free(&hand);
}

static void epsilon_case(const capture_cfg *cfg, uint32_t seed)
{
    scene s;
    uint32_t seed0 = seed;
    epsilon_scene(&s, &seed);
    const float E = 0.05f;
    oit_image x0 = {0}, xe = {0}, d = {0}, hand = {0};
    oit_frame_stats s0, se, sd;
    uint64_t draws = 0, kept = 0, near = 0, all = 0, near0 = 0;
    oit_error err = {0};
    oit_capture *c = capture_new(cfg);
    if (c && capture_run(c, cfg, &s, s.nb, 0.0f, &x0, &s0, &draws) &&
        capture_run(c, cfg, &s, s.nb, E, &xe, &se, &draws) && dfb_run(&s, &d, &sd) &&
        oit_image_alloc(&hand, s.v.width, s.v.height, &err) == OIT_OK) {
        hand_image(&s, 0.0, &hand, &all, &near0);
        int ax, ay, bx, by;
        double d0 = image_diff(&x0, &d, &ax, &ay);
        hand_image(&s, E, &hand, &kept, &near);
        double de = image_diff(&xe, &d, &bx, &by);
        printf("%s, seed %u: E = 0 vs DFB %.2g (%llu/%llu fragments); E = %.2f vs DFB %.4f, "
               "%llu fragments (model %llu of %llu; %llu undecided)\n", cfg->name, seed0, d0,
               (unsigned long long)s0.fragments, (unsigned long long)sd.fragments, (double)E,
               de, (unsigned long long)se.fragments, (unsigned long long)kept,
               (unsigned long long)all, (unsigned long long)near);
        CHECK(d0 <= 1e-5 && s0.fragments == sd.fragments && sd.fragments == all,
              "%s: E = 0: %.6f from DFB at (%d, %d), %llu fragments, DFB %llu, by hand %llu",
              cfg->name, d0, ax, ay, (unsigned long long)s0.fragments,
              (unsigned long long)sd.fragments, (unsigned long long)all);
        CHECK(de <= E + 1e-5, "%s: E = %.2f: %.6f from DFB at (%d, %d)", cfg->name, (double)E,
              de, bx, by);
        CHECK(near == 0, "%s: the scene leaves %llu pixel(s) with T within 1e-4 of E",
              cfg->name, (unsigned long long)near);
        CHECK(kept < all, "%s: the scene saturates nothing", cfg->name);
        /* every batch checked, not only the last frame's sum of them */
        for (int nb = 1; nb <= s.nb; nb++)
            epsilon_prefix(c, cfg, &s, nb, E, seed0);
    }
    oit_capture_destroy(c);
    oit_image_free(&x0);
    oit_image_free(&xe);
    oit_image_free(&d);
    oit_image_free(&hand);
}

static void run_epsilon(void)
{
    const capture_cfg cfgs[] = {
        {"epsilon array", OIT_CAPTURE_ARRAY, 8, 8, 0, 0, 0},
        {"epsilon array, wide batches", OIT_CAPTURE_ARRAY, 2, 4, 0, 0, 1},
        {"epsilon array, slot budget", OIT_CAPTURE_ARRAY, 4, 4, 64u * 48u * 16u, 0, 0},
        {"epsilon counted", OIT_CAPTURE_COUNTED, 4, 4, 0, 0, 0},
        {"epsilon first-k", OIT_CAPTURE_FIRSTK, 2, 2, 0, 0, 1},
    };
    for (size_t i = 0; i < sizeof cfgs / sizeof *cfgs; i++)
        for (uint32_t k = 0; k < 2; k++)
            epsilon_case(&cfgs[i], 555u + 1000u * (uint32_t)i + 17u * k);
}

int main(int argc, char **argv)
{
    if (argc != 2 || (strcmp(argv[1], "bands") && strcmp(argv[1], "epsilon"))) {
        fprintf(stderr, "usage: test_capture_rects bands | epsilon\n");
        return 2;
    }
    oit_gl *gl = test_gl_open();
    if (!strcmp(argv[1], "bands"))
        run_bands();
    else
        run_epsilon();
    return test_gl_verdict(gl);
}
