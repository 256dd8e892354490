/* partfile/order.h: the part order is a visibility order from every eye.
 *
 * A part file is written with the writer: a 4x3x2 top grid of unequal cell
 * sizes with one tilted quad per cell, two cells refined by 2x1x1 subgrids
 * (one subcell refined again by a 1x2x1 subgrid), one cell holding a slab
 * (tilted normal: a part below, five inside, one above) and one empty cell.
 * Stacked inside parts seen from below, above and between the planes catch
 * a wrong eye-side test in the inside parts' order.
 * For eyes outside on every side, inside, on cell boundaries and on the
 * slab planes, rays are cast from the eye through points sampled on every
 * part's triangles; the parts hit along each ray, in distance order, must
 * have non-decreasing rank in the order. The checker is shown to catch a
 * reversed order, so the test can fail. The default camera's up axes
 * (oit_camera_default_up) are checked here too. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/partfile.h"
#include "partfile/write.h"
#include "view/render/image/view.h"
#include "partfile/order.h"

#define MAX_PARTS 64
#define SQ2 1.41421356f

typedef struct quad {
    float p[4][3];
} quad;

typedef struct scene {
    quad parts[MAX_PARTS];
    uint32_t n;
} scene;

static int failures;

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "FAIL: %s\n", what);
        failures++;
    }
}

/* A quad spanning the box shrunk by 10%, tilted across it; orient picks
 * which axis the quad contains, so quads of neighbouring cells differ. */
static quad cell_quad(const float lo[3], const float hi[3], int orient)
{
    float a[3], b[3];
    for (int k = 0; k < 3; k++) {
        float m = 0.1f * (hi[k] - lo[k]);
        a[k] = lo[k] + m;
        b[k] = hi[k] - m;
    }
    int u = orient % 3, w = (u + 1) % 3, v = (u + 2) % 3; /* spans u and (v, w) */
    quad q;
    for (int c = 0; c < 4; c++) {
        int su = c == 1 || c == 2, sv = c >= 2;
        q.p[c][u] = su ? b[u] : a[u];
        q.p[c][v] = sv ? b[v] : a[v];
        q.p[c][w] = sv ? b[w] : a[w];
    }
    return q;
}

/* A quad in the plane x + z = s (the slab's frame), y in [y0, y1], clipped
 * to x in [x0, x1] and z in [z0, z1]. */
static quad slab_quad(float s, float y0, float y1, float x0, float x1, float z0, float z1)
{
    float xa = fmaxf(x0, s - z1), xb = fminf(x1, s - z0);
    quad q = {{{xa, y0, s - xa}, {xb, y0, s - xb}, {xb, y1, s - xb}, {xa, y1, s - xa}}};
    return q;
}

/* A level quad (y = const) covering the band x + z in [s0, s1] of the box's
 * x and z ranges, the band's ends clipped to the box. */
static quad level_quad(float y, float s0, float s1, float x0, float x1, float z0, float z1)
{
    float xa = fmaxf(x0, s0 - z1), xb = fminf(x1, s1 - z0);
    quad q = {{{xa, y, fmaxf(z0, s0 - xa)}, {xb, y, fmaxf(z0, s0 - xb)},
               {xb, y, fminf(z1, s1 - xb)}, {xa, y, fminf(z1, s1 - xa)}}};
    return q;
}

static int add_quad(oit_partfile_writer *w, scene *sc, const quad *q, oit_error *err)
{
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    /* Each quad's triangles are their own sources (file positions). */
    uint32_t src[2] = {2 * sc->n, 2 * sc->n + 1};
    oit_partfile_piece_desc piece = {2, 1};
    oit_partfile_part_desc d = {0};
    d.sources = src;
    d.positions = &q->p[0][0];
    d.vertex_count = 4;
    d.indices = idx;
    d.index_count = 6;
    d.pieces = &piece;
    d.piece_count = 1;
    uint32_t index;
    if (oit_partfile_writer_add_part(w, &d, &index, err) != OIT_OK)
        return -1;
    sc->parts[sc->n++] = *q;
    return (int)index;
}

static const float CELL[3] = {1.0f, 1.5f, 2.0f};
enum { SUB_A = 1 + 3 * 1 + 12 * 0, SUB_B = 2 + 12 * 1, SLAB_CELL = 3 + 4 * 2 + 12 * 1,
       EMPTY_CELL = 0 + 4 * 2 + 12 * 1, SLAB_PARTS = 7 };

static void cell_box(const float origin[3], const float size[3], const uint32_t dims[3],
                     uint32_t c, float lo[3], float hi[3])
{
    uint32_t i[3] = {c % dims[0], c / dims[0] % dims[1], c / (dims[0] * dims[1])};
    for (int k = 0; k < 3; k++) {
        lo[k] = origin[k] + (float)i[k] * size[k];
        hi[k] = lo[k] + size[k];
    }
}

/* Writes a grid whose cells hold one quad each (none where skip says),
 * returning the part of each cell in cell_parts. */
static int quad_grid(oit_partfile_writer *w, scene *sc, const oit_partfile_grid_desc *g,
                     const int *skip, uint32_t *counts, uint32_t *list, oit_error *err)
{
    uint32_t n = g->dims[0] * g->dims[1] * g->dims[2], used = 0;
    for (uint32_t c = 0; c < n; c++) {
        counts[c] = 0;
        if (skip && skip[c])
            continue;
        float lo[3], hi[3];
        cell_box(g->origin, g->cell_size, g->dims, c, lo, hi);
        quad q = cell_quad(lo, hi, (int)(c + sc->n));
        int p = add_quad(w, sc, &q, err);
        if (p < 0)
            return -1;
        counts[c] = 1;
        list[used++] = (uint32_t)p;
    }
    return (int)used;
}

typedef struct sub_desc {
    oit_partfile_grid_desc g;
    uint32_t counts[8], list[8];
} sub_desc;

/* The subgrid's parts are written now; its record later (parts come first). */
static int make_subgrid(oit_partfile_writer *w, scene *sc, sub_desc *d, uint32_t parent_grid,
                        uint32_t parent_cell, const float lo[3], const uint32_t dims[3],
                        const float size[3], const int *skip, oit_error *err)
{
    oit_partfile_grid_desc g = {{dims[0], dims[1], dims[2]}, {lo[0], lo[1], lo[2]},
                                {size[0], size[1], size[2]}, parent_grid, parent_cell,
                                d->counts, d->list};
    d->g = g;
    return quad_grid(w, sc, &d->g, skip, d->counts, d->list, err);
}

static oit_status write_slab(oit_partfile_writer *w, scene *sc, uint32_t *cell_list,
                             oit_error *err)
{
    float lo[3], hi[3];
    static const uint32_t dims[3] = {4, 3, 2};
    static const float origin[3] = {0, 0, 0};
    cell_box(origin, CELL, dims, SLAB_CELL, lo, hi);
    /* x + z over the cell spans [lo0+lo2, hi0+hi2]; four sheets across it. */
    float s0 = lo[0] + lo[2], span = hi[0] + hi[2] - s0;
    float ym = 0.5f * (lo[1] + hi[1]);
    /* Inside: two sheets side by side in the slab's middle plane (y 3.1..3.25
     * and 4.25..4.4), and three level sheets (y 3.45, 3.75, 4.05) stacked
     * between them and the slab planes, written middle, top, bottom so that
     * both of must_precede's eye tests decide an insertion. */
    quad qs[SLAB_PARTS] = {
        slab_quad(s0 + 0.3f * span, lo[1] + 0.1f, hi[1] - 0.1f, lo[0], hi[0], lo[2], hi[2]),
        slab_quad(s0 + 0.5f * span, lo[1] + 0.1f, lo[1] + 0.25f, lo[0], hi[0], lo[2], hi[2]),
        slab_quad(s0 + 0.5f * span, hi[1] - 0.25f, hi[1] - 0.1f, lo[0], hi[0], lo[2], hi[2]),
        level_quad(ym, s0 + 0.42f * span, s0 + 0.58f * span, lo[0], hi[0], lo[2], hi[2]),
        level_quad(ym + 0.3f, s0 + 0.42f * span, s0 + 0.58f * span, lo[0], hi[0], lo[2], hi[2]),
        level_quad(ym - 0.3f, s0 + 0.42f * span, s0 + 0.58f * span, lo[0], hi[0], lo[2], hi[2]),
        slab_quad(s0 + 0.7f * span, lo[1] + 0.1f, hi[1] - 0.1f, lo[0], hi[0], lo[2], hi[2])};
    for (int i = 0; i < SLAB_PARTS; i++) {
        int p = add_quad(w, sc, &qs[i], err);
        if (p < 0)
            return err->status;
        cell_list[i] = (uint32_t)p;
    }
    return OIT_OK;
}

static oit_status finish_slab(oit_partfile_writer *w, const uint32_t *parts, oit_error *err)
{
    float lo[3], hi[3];
    static const uint32_t dims[3] = {4, 3, 2};
    static const float origin[3] = {0, 0, 0};
    cell_box(origin, CELL, dims, SLAB_CELL, lo, hi);
    float s0 = lo[0] + lo[2], span = hi[0] + hi[2] - s0;
    oit_partfile_slab_desc sl = {{1.0f / SQ2, 0.0f, 1.0f / SQ2},
                                 (s0 + 0.4f * span) / SQ2, (s0 + 0.6f * span) / SQ2,
                                 0, SLAB_CELL, parts[0], parts[SLAB_PARTS - 1], parts + 1,
                                 SLAB_PARTS - 2};
    uint32_t index;
    return oit_partfile_writer_add_slab(w, &sl, &index, err);
}

/* Parts are written before grids, so every cell's quad is added first; the
 * grid records follow in parent-before-child order. */
static oit_status build(const char *path, scene *sc, oit_error *err)
{
    oit_partfile_writer *w = NULL;
    oit_status s = oit_partfile_writer_create(path, NULL, &w, err);
    if (s != OIT_OK)
        return s;
    static const uint32_t dims[3] = {4, 3, 2};
    int skip[24] = {0};
    skip[SUB_A] = skip[SUB_B] = skip[SLAB_CELL] = skip[EMPTY_CELL] = 1;
    uint32_t counts[24], list[40];
    oit_partfile_grid_desc top = {{4, 3, 2}, {0, 0, 0}, {CELL[0], CELL[1], CELL[2]},
                                  OIT_PARTFILE_NONE, OIT_PARTFILE_NONE, counts, list};
    int used = quad_grid(w, sc, &top, skip, counts, list, err);
    if (used < 0) {
        oit_partfile_writer_abort(w);
        return err->status;
    }
    /* The slab cell's four parts join the top list in cell order. */
    uint32_t slab_parts[SLAB_PARTS];
    s = write_slab(w, sc, slab_parts, err);
    if (s == OIT_OK) {
        counts[SLAB_CELL] = SLAB_PARTS;
        uint32_t at = 0;
        for (uint32_t c = 0; c < SLAB_CELL; c++)
            at += counts[c];
        memmove(list + at + SLAB_PARTS, list + at, (size_t)(used - (int)at) * sizeof *list);
        memcpy(list + at, slab_parts, sizeof slab_parts);
    }
    /* Subgrid parts: grid 1 refines SUB_A, grid 2 SUB_B, grid 3 grid 2's cell 1. */
    static sub_desc sub[3];
    float lo[3], hi[3];
    static const uint32_t d211[3] = {2, 1, 1}, d121[3] = {1, 2, 1};
    static const int skip_b[2] = {0, 1};
    const float half[3] = {CELL[0] / 2, CELL[1], CELL[2]};
    const float quarter[3] = {CELL[0] / 2, CELL[1] / 2, CELL[2]};
    cell_box(top.origin, CELL, dims, SUB_A, lo, hi);
    if (s == OIT_OK && make_subgrid(w, sc, &sub[0], 0, SUB_A, lo, d211, half, NULL, err) < 0)
        s = err->status;
    cell_box(top.origin, CELL, dims, SUB_B, lo, hi);
    if (s == OIT_OK && make_subgrid(w, sc, &sub[1], 0, SUB_B, lo, d211, half, skip_b, err) < 0)
        s = err->status;
    lo[0] += half[0];
    if (s == OIT_OK && make_subgrid(w, sc, &sub[2], 2, 1, lo, d121, quarter, NULL, err) < 0)
        s = err->status;
    if (s == OIT_OK)
        s = oit_partfile_writer_set_grid(w, &top, err);
    for (int i = 0; i < 3 && s == OIT_OK; i++) {
        uint32_t g = 0;
        s = oit_partfile_writer_add_subgrid(w, &sub[i].g, &g, err);
    }
    if (s == OIT_OK)
        s = finish_slab(w, slab_parts, err);
    if (s != OIT_OK) {
        oit_partfile_writer_abort(w);
        return s;
    }
    return oit_partfile_writer_finish(w, NULL, err);
}

/* Ray/triangle distance (Moller-Trumbore, double); <0 when missed. */
static double hit(const double o[3], const double d[3], const float *a, const float *b,
                  const float *c)
{
    double e1[3], e2[3], p[3], t[3], q[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
        t[k] = o[k] - a[k];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabs(det) < 1e-14)
        return -1.0;
    double u = (t[0] * p[0] + t[1] * p[1] + t[2] * p[2]) / det;
    q[0] = t[1] * e1[2] - t[2] * e1[1];
    q[1] = t[2] * e1[0] - t[0] * e1[2];
    q[2] = t[0] * e1[1] - t[1] * e1[0];
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    if (u < -1e-9 || v < -1e-9 || u + v > 1 + 1e-9)
        return -1.0;
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
}

static double quad_hit(const double o[3], const double d[3], const quad *q)
{
    double t0 = hit(o, d, q->p[0], q->p[1], q->p[2]), t1 = hit(o, d, q->p[0], q->p[2], q->p[3]);
    return t0 > 0 ? t0 : t1;
}

/* Sample s (0..8) of a 3 x 3 grid on quad q, inset from its edges. */
static void quad_sample(const quad *q, int s, double out[3])
{
    double u = 0.1 + 0.4 * (s % 3), v = 0.1 + 0.4 * (s / 3);
    for (int k = 0; k < 3; k++) {
        double a = q->p[0][k] + u * (q->p[1][k] - q->p[0][k]);
        double b = q->p[3][k] + u * (q->p[2][k] - q->p[3][k]);
        out[k] = a + v * (b - a);
    }
}

/* Every pair of hits along the ray from o along d, by distance: a part hit
 * nearer than another but ranked after it is a violation. */
static int ray_violations(const scene *sc, const double o[3], const double d[3],
                          const uint32_t *rank)
{
    int bad = 0;
    for (uint32_t r = 0; r < sc->n; r++) {
        double t = quad_hit(o, d, &sc->parts[r]);
        if (t <= 1e-9)
            continue;
        for (uint32_t x = 0; x < sc->n; x++) {
            double tx = quad_hit(o, d, &sc->parts[x]);
            if (tx > 1e-9 && tx < t - 1e-6 && rank[x] > rank[r])
                bad++;
        }
    }
    return bad;
}

/* Rays through points of every quad: returns the violations (a part hit
 * clearly before another but ranked after it). */
static int violations(const scene *sc, const float eye[3], const uint32_t *rank)
{
    int bad = 0;
    double o[3] = {eye[0], eye[1], eye[2]};
    for (uint32_t p = 0; p < sc->n; p++)
        for (int s = 0; s < 9; s++) {
            double pt[3], d[3], len = 0;
            quad_sample(&sc->parts[p], s, pt);
            for (int k = 0; k < 3; k++) {
                d[k] = pt[k] - o[k];
                len += d[k] * d[k];
            }
            if (len >= 1e-12)
                bad += ray_violations(sc, o, d, rank);
        }
    return bad;
}

/* The same for parallel rays along dir (orthographic): through points of
 * every quad, from far behind them. */
static int violations_parallel(const scene *sc, const float dir[3], const uint32_t *rank)
{
    int bad = 0;
    double len = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] + (double)dir[2] * dir[2]);
    double d[3] = {dir[0] / len, dir[1] / len, dir[2] / len};
    for (uint32_t p = 0; p < sc->n; p++)
        for (int s = 0; s < 9; s++) {
            double o[3];
            quad_sample(&sc->parts[p], s, o);
            for (int k = 0; k < 3; k++)
                o[k] -= 100.0 * d[k];
            bad += ray_violations(sc, o, d, rank);
        }
    return bad;
}

/* Orthographic orders (oit_order_compute_parallel) along the axes, the
 * diagonals and random directions, some on the slab's planes (x + z): no
 * violation on any parallel ray; the reverse of one is caught. */
static void check_parallel(oit_order *o, const scene *sc, uint32_t n)
{
    float dirs[64][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                         {1, 0, -1}, {-1, 0, 1}, {1, 1, -1}, {-1, 2, 1}, {1, 1, 1}, {-1, -1, -1},
                         {0.3f, -0.8f, 0.5f}, {-0.6f, 0.1f, -0.7f}};
    int nd = 14;
    uint32_t r = 777u;
    while (nd < 64) {
        for (int k = 0; k < 3; k++) {
            r = r * 1664525u + 1013904223u;
            dirs[nd][k] = (float)(r >> 8) / 16777216.0f * 2.0f - 1.0f;
        }
        nd++;
    }
    uint32_t order[MAX_PARTS], rank[MAX_PARTS], count = 0;
    oit_error err = {0};
    int total = 0, incomplete = 0;
    for (int i = 0; i < nd; i++) {
        if (oit_order_compute_parallel(o, dirs[i], NULL, order, &count, &err) != OIT_OK) {
            check(0, err.message);
            return;
        }
        incomplete += count != n;
        memset(rank, 0xff, sizeof rank);
        for (uint32_t k = 0; k < count; k++)
            if (order[k] < n)
                rank[order[k]] = k;
        int bad = violations_parallel(sc, dirs[i], rank);
        if (bad)
            printf("parallel rays along %g,%g,%g: %d violations\n", dirs[i][0], dirs[i][1],
                   dirs[i][2], bad);
        total += bad;
    }
    printf("parallel orders: %d directions, %d order violations, %d incomplete\n", nd, total,
           incomplete);
    check(total == 0 && incomplete == 0, "parallel-ray (orthographic) order violations");
    /* The checker sees a wrong parallel order: the reverse of a valid one. */
    oit_order_compute_parallel(o, dirs[12], NULL, order, &count, &err);
    for (uint32_t k = 0; k < count; k++)
        rank[order[k]] = count - 1 - k;
    int rev = violations_parallel(sc, dirs[12], rank);
    printf("reversed parallel order: %d violations (must be > 0)\n", rev);
    check(rev > 0, "the parallel checker misses a reversed order");
    float zero[3] = {0, 0, 0};
    check(oit_order_compute_parallel(o, zero, NULL, order, &count, &err) == OIT_ERR_ARGUMENT,
          "a zero view direction is not refused");
}

static int eyes(float out[][3], int cap)
{
    int n = 0;
    const float c[3] = {2.0f, 2.25f, 2.0f};
    for (int dx = -1; dx <= 1; dx++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dz = -1; dz <= 1; dz++)
                if ((dx || dy || dz) && n < cap) {
                    float e[3] = {c[0] + 9.0f * dx, c[1] + 8.0f * dy, c[2] + 7.0f * dz};
                    memcpy(out[n++], e, sizeof e);
                }
    uint32_t r = 12345u;
    for (int i = 0; i < 40 && n < cap; i++)
        for (int k = 0; k < 3; k++) {
            r = r * 1664525u + 1013904223u;
            out[n][k] = -0.5f + (float)(r >> 8) / 16777216.0f * (k == 0 ? 5.0f : k == 1 ? 5.5f : 5.0f);
            if (k == 2)
                n++;
        }
    /* On cell planes, subgrid planes, corners and the slab planes. */
    const float on[][3] = {{1, 1.5f, 2}, {2, 3, 2}, {3, 0.7f, 1}, {1.5f, 1.2f, 0.5f},
                           {2.5f, 0.2f, 3}, {2.75f, 0.375f, 3}, {0, 0, 0}, {4, 4.5f, 4},
                           {3.5f, 3.7f, 2 + 0.5f * 3}, {3.2f, 3.5f, 3.4f}, {3.5f, 3.2f, 3.0f},
                           {1.5f, 2.25f, -3}, {2, -2, 2}, {-1, 3, 2.0f}};
    for (size_t i = 0; i < sizeof on / sizeof on[0] && n < cap; i++)
        memcpy(out[n++], on[i], sizeof on[i]);
    /* The slab's stacked inside sheets seen from below, between and above
     * them in y, each from below, between and above the slab planes
     * (x + z = 6.2 and 6.8). */
    const float xz[3][2] = {{3.2f, 2.5f}, {3.4f, 2.95f}, {3.8f, 3.5f}};
    const float ys[4] = {2.0f, 3.6f, 3.9f, 5.5f};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 4 && n < cap; b++) {
            float e[3] = {xz[a][0], ys[b], xz[a][1]};
            memcpy(out[n++], e, sizeof e);
        }
    return n;
}

/* oit_camera_default_up: y up is oit_camera_default, bit for bit, and the
 * formula it always had; z up (CAD) looks from -y at azimuth 0 with x to
 * the right and z up, from +x at azimuth 90, and down from +z at elevation
 * 90 with +y up on screen; x up looks from +z with x up. */
static void check_camera_up(void)
{
    const float lo[3] = {-1, -2, -3}, hi[3] = {3, 2, 1};
    const float az[] = {0, 30, 90, -135, 200}, el[] = {0, 20, -45, 90, -90};
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) {
            oit_camera a, b;
            oit_camera_default(&a, lo, hi, az[i], el[j]);
            oit_camera_default_up(&b, lo, hi, az[i], el[j], 1);
            check(!memcmp(&a, &b, sizeof a), "camera: y up differs from oit_camera_default");
            const double pi = 3.14159265358979323846;
            double r = sqrt(4.0 + 4.0 + 4.0), d = r / sin(22.5 * pi / 180.0);
            double A = az[i] * pi / 180.0, E = el[j] * pi / 180.0;
            double want[3] = {1 + d * (cos(E) * sin(A)), 0 + d * sin(E), -1 + d * (cos(E) * cos(A))};
            for (int k = 0; k < 3; k++)
                check(a.eye[k] == (float)want[k], "camera: y-up eye moved");
        }
    oit_camera c;
    oit_camera_default_up(&c, lo, hi, 0, 0, 2);
    float off[3] = {c.eye[0] - c.target[0], c.eye[1] - c.target[1], c.eye[2] - c.target[2]};
    check(fabsf(off[0]) < 1e-4f && off[1] < -1.0f && fabsf(off[2]) < 1e-4f,
          "camera: z up, azimuth 0 is not seen from -y");
    check(c.up[0] == 0 && c.up[1] == 0 && c.up[2] == 1, "camera: z up has not z up");
    /* right = forward x up: forward is +y, so right must be +x */
    float fwd[3] = {-off[0], -off[1], -off[2]};
    float right[3] = {fwd[1] * c.up[2] - fwd[2] * c.up[1], fwd[2] * c.up[0] - fwd[0] * c.up[2],
                      fwd[0] * c.up[1] - fwd[1] * c.up[0]};
    check(right[0] > 1.0f && fabsf(right[1]) < 1e-4f && fabsf(right[2]) < 1e-4f,
          "camera: z up, azimuth 0 has not x to the right");
    oit_camera_default_up(&c, lo, hi, 90, 0, 2);
    check(c.eye[0] - c.target[0] > 1.0f && fabsf(c.eye[1] - c.target[1]) < 1e-4f,
          "camera: z up, azimuth 90 is not seen from +x");
    oit_camera_default_up(&c, lo, hi, 0, 90, 2);
    check(c.eye[2] - c.target[2] > 1.0f && c.up[1] == 1 && c.up[2] == 0,
          "camera: z up, elevation 90 is not from +z with y up");
    oit_camera_default_up(&c, lo, hi, 0, 0, 0);
    check(c.up[0] == 1 && c.eye[2] - c.target[2] > 1.0f && fabsf(c.eye[0] - c.target[0]) < 1e-4f,
          "camera: x up, azimuth 0 is not seen from +z with x up");
}

/* The frustum planes against the projection they stand for: a point well
 * inside the clip volume passes every plane, one well outside fails one. */
static void check_frustum_planes_of(oit_camera cam, const char *what)
{
    float aspect = 1.5f, view[16], proj[16], planes[6][4];
    oit_camera_view_matrix(&cam, view);
    oit_camera_proj_matrix(&cam, aspect, proj);
    oit_camera_frustum(&cam, aspect, planes);
    uint32_t r = 12345;
    int wrong = 0, inside = 0, outside = 0;
    for (int i = 0; i < 20000; i++) {
        double p[4] = {0, 0, 0, 1}, e[4] = {0}, c[4] = {0};
        /* A cube of 40 around a point 20 ahead: inside, outside and across
         * every plane, the far one included. */
        double dir[3] = {cam.target[0] - cam.eye[0], cam.target[1] - cam.eye[1], cam.target[2] - cam.eye[2]};
        double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (int k = 0; k < 3; k++) {
            r = r * 1664525u + 1013904223u;
            p[k] = cam.eye[k] + 20.0 * dir[k] / len + 40.0 * ((double)(r >> 8) / 16777216.0 - 0.5);
        }
        for (int row = 0; row < 4; row++)
            for (int k = 0; k < 4; k++)
                e[row] += view[k * 4 + row] * p[k];
        for (int row = 0; row < 4; row++)
            for (int k = 0; k < 4; k++)
                c[row] += proj[k * 4 + row] * e[k];
        double m = 0; /* how far inside the clip volume, in units of w */
        m = c[3] > 0 ? fmin(fmin(c[3] - fabs(c[0]), c[3] - fabs(c[1])), c[3] - fabs(c[2])) / c[3] : -1;
        int pass = 1;
        for (int j = 0; j < 6; j++)
            pass &= planes[j][0] * p[0] + planes[j][1] * p[1] + planes[j][2] * p[2] + planes[j][3] >= 0;
        if (m > 0.01) {
            inside++;
            wrong += !pass;
        } else if (m < -0.05 && -e[2] > cam.znear) {
            outside++;
            wrong += pass;
        }
    }
    printf("frustum planes (%s): %d points inside, %d outside, %d on the wrong side\n", what,
           inside, outside, wrong);
    check(wrong == 0 && inside > 100 && outside > 100, "frustum planes disagree with the projection");
}

/* Every projection a camera can have: symmetric, off-centre, infinite far,
 * orthographic (centred and off-centre). */
static void check_frustum_planes(void)
{
    oit_camera cam = {{1, 2, 3}, {-2, 0.5f, -1}, {0, 1, 0}, 50, 0.1f, 40, .projection = 0};
    check_frustum_planes_of(cam, "symmetric");
    oit_camera off = cam;
    off.window[0] = -0.2f;
    off.window[1] = 0.6f;
    off.window[2] = -0.5f;
    off.window[3] = 0.1f;
    check_frustum_planes_of(off, "off-centre");
    oit_camera inf = off;
    inf.zfar = INFINITY;
    check_frustum_planes_of(inf, "off-centre, infinite far");
    oit_camera ortho = cam;
    ortho.projection = OIT_PROJ_ORTHOGRAPHIC;
    ortho.ortho_height = 18.0f;
    check_frustum_planes_of(ortho, "orthographic");
    ortho.window[0] = -4.0f;
    ortho.window[1] = 12.0f;
    ortho.window[2] = -9.0f;
    ortho.window[3] = 3.0f;
    check_frustum_planes_of(ortho, "orthographic, off-centre");
}

/* Culled orders: the kept parts in the full order's relative order, and
 * every part left out outside one plane (tested on its own box corners). */
static void check_culled(oit_order *o, const oit_partfile *pf, const float (*ev)[3], int ne)
{
    enum { MAXP = MAX_PARTS };
    uint32_t full[MAXP], kept[MAXP], n = oit_partfile_part_count(pf), nf = 0, nk = 0;
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    static const float dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}, {0.6f, 0.3f, 0.7f}, {-0.5f, -0.2f, 0.8f}};
    int views = 0, some_culled = 0, none_culled = 0, bad = 0, ortho_views = 0;
    oit_error err = {0};
    for (int i = 0; i < ne; i++)
        for (int d = 0; d < 6; d++) {
            oit_camera cam = {{ev[i][0], ev[i][1], ev[i][2]},
                              {ev[i][0] + dirs[d][0], ev[i][1] + dirs[d][1], ev[i][2] + dirs[d][2]},
                              {0, 1, 0}, d & 1 ? 30.0f : 70.0f, 0.05f, d == 3 ? 2.0f : 100.0f,
                              .projection = 0};
            /* Each view also orthographic (3 high, the near plane behind
             * the eye): parallel orders, culled and full. */
            for (int po = 0; po < 2; po++) {
                if (po) {
                    cam.projection = OIT_PROJ_ORTHOGRAPHIC;
                    cam.ortho_height = 3.0f;
                    cam.znear = -1.0f;
                }
                float planes[6][4];
                oit_camera_frustum(&cam, 1.3f, planes);
                oit_status s1 = po ? oit_order_compute_parallel(o, dirs[d], NULL, full, &nf, &err)
                                   : oit_order_compute(o, cam.eye, full, &nf, &err);
                const float(*pl)[4] = (const float(*)[4])planes;
                oit_status s2 = s1   ? s1
                                : po ? oit_order_compute_parallel(o, dirs[d], pl, kept, &nk, &err)
                                     : oit_order_compute_culled(o, cam.eye, pl, kept, &nk, &err);
                if (s2) {
                    check(0, err.message);
                    return;
                }
                uint32_t j = 0;
                for (uint32_t k = 0; k < nf; k++) {
                    if (j < nk && kept[j] == full[k]) {
                        j++;
                        continue;
                    }
                    const oit_partfile_part *p = &parts[full[k]];
                    int out = 0;
                    for (int q = 0; q < 6 && !out; q++) {
                        int all = 1;
                        for (int c = 0; c < 8; c++) {
                            double x = c & 1 ? p->bounds_max[0] : p->bounds_min[0];
                            double y = c & 2 ? p->bounds_max[1] : p->bounds_min[1];
                            double z = c & 4 ? p->bounds_max[2] : p->bounds_min[2];
                            all &= planes[q][0] * x + planes[q][1] * y + planes[q][2] * z + planes[q][3] < 0;
                        }
                        out = all;
                    }
                    bad += !out;
                }
                bad += j != nk; /* a kept part out of order or not in the full order */
                views++;
                some_culled += nk < nf;
                none_culled += nk == nf;
                ortho_views += po;
            }
        }
    printf("culled orders: %d views (%d orthographic; %d with parts left out, %d with none), "
           "%d wrong\n", views, ortho_views, some_culled, none_culled, bad);
    check(bad == 0, "a culled order drops a part inside the view or reorders the rest");
    check(some_culled > 0 && none_culled > 0, "culling never (or always) leaves parts out");
    (void)n;
}

int main(void)
{
    const char *tmp = getenv("OIT_TEST_TMP");
    char path[4096];
    snprintf(path, sizeof path, "%s/test_order.oitp", tmp ? tmp : ".");
    static scene sc;
    oit_error err = {0};
    if (build(path, &sc, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: writing %s: %s\n", path, err.message);
        return 1;
    }
    oit_partfile *pf = NULL;
    oit_order *o = NULL;
    if (oit_partfile_open(path, NULL, &pf, &err) != OIT_OK ||
        oit_order_create(pf, &o, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    uint32_t n = oit_partfile_part_count(pf), order[MAX_PARTS], rank[MAX_PARTS], count = 0;
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    printf("part file: %u parts, %llu cells, %llu subgrids (depth %u), %llu slabs\n", n,
           (unsigned long long)sum.cells, (unsigned long long)sum.subgrids, sum.subgrid_depth,
           (unsigned long long)sum.slabs);
    check(n == sc.n && sum.subgrid_depth == 2 && sum.slabs == 1, "scene shape");
    float ev[128][3];
    int ne = eyes(ev, 128), total_bad = 0, rays_checked = 0;
    for (int i = 0; i < ne; i++) {
        if (oit_order_compute(o, ev[i], order, &count, &err) != OIT_OK) {
            fprintf(stderr, "FAIL: %s\n", err.message);
            return 1;
        }
        char what[160];
        snprintf(what, sizeof what, "eye %g,%g,%g: %u of %u parts ordered", ev[i][0], ev[i][1],
                 ev[i][2], count, n);
        check(count == n, what);
        memset(rank, 0xff, sizeof rank);
        for (uint32_t k = 0; k < count; k++) {
            check(order[k] < n && rank[order[k]] == 0xffffffffu, "a part emitted twice");
            if (order[k] < n)
                rank[order[k]] = k;
        }
        int bad = violations(&sc, ev[i], rank);
        snprintf(what, sizeof what, "eye %g,%g,%g: %d ray order violations", ev[i][0], ev[i][1],
                 ev[i][2], bad);
        check(bad == 0, what);
        total_bad += bad;
        rays_checked += (int)n * 9;
    }
    printf("%d eyes, %d rays: %d order violations\n", ne, rays_checked, total_bad);
    check_frustum_planes();
    check_camera_up();
    check_culled(o, pf, (const float(*)[3])ev, ne);
    check_parallel(o, &sc, n);
    /* The checker must see a wrong order: the reverse of a valid one. */
    float far_eye[3] = {-7.0f, 2.25f, 2.0f};
    oit_order_compute(o, far_eye, order, &count, &err);
    for (uint32_t k = 0; k < count; k++)
        rank[order[k]] = count - 1 - k;
    int rev = violations(&sc, far_eye, rank);
    printf("reversed order from %g,%g,%g: %d violations (must be > 0)\n", far_eye[0], far_eye[1],
           far_eye[2], rev);
    check(rev > 0, "the checker misses a reversed order");
    oit_order_destroy(o);
    oit_partfile_close(pf);
    remove(path);
    return failures ? 1 : 0;
}
