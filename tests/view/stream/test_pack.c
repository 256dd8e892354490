/* view/stream/pack.h: the packer against a CPU model of its rules, over random
 * parts, rectangles, layer bounds, K and byte budgets.
 *
 * Each round writes a part file of 20-150 flat parts (fans of 1-12
 * triangles at distinct depths; measured layer bounds 1..K, exactly K, or
 * wide, above K) whose screen rectangles, under an orthographic view of one
 * world unit a pixel, are known: the box's pixel span and one pixel of
 * margin, clipped to the screen; many end at or beside 32-pixel tile edges,
 * some lie partly or wholly off screen. The model, written from pack.h's
 * rules and nothing else, packs the same order:
 *   - budget: a part joins the open pack while the bytes fit, neither it
 *     nor the pack is wide and every 32x32 tile its rectangle touches keeps
 *     the sum of the pack's layer bounds there <= K, the pack's first part
 *     counted too; a wide part is a pack of its own, of its bound's layers;
 *   - disjoint: the same, with "its rectangle misses the pack's bounding
 *     rectangle" for the tile sums;
 *   - counted and first-k: bytes only; front first: pack i also caps the
 *     tile sums at K * 2^i, its first part counted even above the cap;
 *   - disjoint on the wave: by level, a part's level 1 + the highest of the
 *     earlier parts whose rectangle overlaps its own (pairs compared, no
 *     cells), the parts sorted by level stably and cut where the level
 *     changes, the bytes overflow or a part is wide or follows one;
 * and the packer's packs must be the model's exactly (parts, pack starts,
 * layers, bytes, rectangles, culled count). The budget and counted wave
 * schedules reorder, so there only the rules are checked on what they made.
 * On every packing: every kept part once, bytes within the budget, a wide
 * part alone, the budget rule's tile sums <= K, the disjoint rule's no two
 * rectangles of a pack overlapping, and two overlapping parts never in
 * packs against their order (the disjoint rule: never in one pack). */
#include "oit/partfile.h"
#include "partfile/write.h"
#include "view/stream/pack.h"
#include "tests/lib/test_rng.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_files.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_PARTS = 150, MAX_FAN = 12, TILE = 32, ROUNDS = 40, W_MAX = 400, H_MAX = 300 };

typedef struct scene {
    uint32_t n, w, h, K;
    uint32_t tris[MAX_PARTS], layers[MAX_PARTS];
    double px[MAX_PARTS][4]; /* the box in pixels: x0, y0 (top), x1, y1 */
    float z[MAX_PARTS];
} scene;

/* A pixel coordinate near a tile edge (31, 32 or 33 mod 32, give or take
 * the margin) or anywhere, a quarter pixel or more from an integer so that
 * no rounding decides its floor or ceiling. */
static double pixel(rng *r, int lo, int hi)
{
    double q = 0.25 + 0.5 * rnd(r, 1000) / 1000.0;
    if (rnd(r, 2)) {
        int edge = TILE * (int)rnd(r, (uint32_t)(hi / TILE + 2)) + (int)rnd(r, 5) - 2;
        return edge + q;
    }
    return lo + (int)rnd(r, (uint32_t)(hi - lo)) + q;
}

static void make_scene(rng *r, scene *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->w = 2 * (60 + rnd(r, (W_MAX - 120) / 2));
    sc->h = 2 * (50 + rnd(r, (H_MAX - 100) / 2));
    sc->K = 2 + rnd(r, 15);
    sc->n = 20 + rnd(r, MAX_PARTS - 19);
    for (uint32_t i = 0; i < sc->n; i++) {
        double a = pixel(r, -40, (int)sc->w + 40), b = pixel(r, -40, (int)sc->w + 40);
        double c = pixel(r, -40, (int)sc->h + 40), d = pixel(r, -40, (int)sc->h + 40);
        if (rnd(r, 3) == 0) /* a small one */
            b = a + 0.5 + rnd(r, 20), d = c + 0.5 + rnd(r, 20);
        sc->px[i][0] = fmin(a, b), sc->px[i][2] = fmax(a, b);
        sc->px[i][1] = fmin(c, d), sc->px[i][3] = fmax(c, d);
        if (sc->px[i][2] - sc->px[i][0] < 0.5)
            sc->px[i][2] += 0.5;
        if (sc->px[i][3] - sc->px[i][1] < 0.5)
            sc->px[i][3] += 0.5;
        sc->tris[i] = 1 + rnd(r, MAX_FAN);
        uint32_t kind = rnd(r, 20);
        sc->layers[i] = kind < 3 ? sc->K + 1 + rnd(r, sc->K + 3) : kind < 6 ? sc->K
                                                                           : 1 + rnd(r, sc->K);
        sc->z[i] = -5.0f + 10.0f * (float)i / (float)sc->n;
    }
}

/* Pixel (x, y from the top) of a w x h screen as world (x, y) under the
 * view below: one unit a pixel, the screen centred on the origin. */
static float world_x(const scene *sc, double x) { return (float)(x - 0.5 * sc->w); }
static float world_y(const scene *sc, double y) { return (float)(0.5 * sc->h - y); }

/* A fan of t triangles from the box's corner (x0, y0) to points along its
 * other sides: its bounds are the box. */
static oit_status write_scene(const char *path, const scene *sc, oit_error *err)
{
    oit_partfile_writer_desc wd = {.K = 16, .part_align = 64, .measured_bounds = true};
    oit_partfile_writer *w = NULL;
    oit_status s = oit_partfile_writer_create(path, &wd, &w, err);
    uint32_t list[MAX_PARTS];
    for (uint32_t i = 0; !s && i < sc->n; i++) {
        float pos[3 * (MAX_FAN + 2)], x0 = world_x(sc, sc->px[i][0]), x1 = world_x(sc, sc->px[i][2]);
        float y0 = world_y(sc, sc->px[i][1]), y1 = world_y(sc, sc->px[i][3]);
        uint32_t t = sc->tris[i], idx[3 * MAX_FAN], src[MAX_FAN];
        pos[0] = x0, pos[1] = y0, pos[2] = sc->z[i];
        for (uint32_t j = 0; j <= t; j++) {
            /* along (x1, y0) -> (x1, y1) -> (x0, y1) */
            double u = 2.0 * j / t;
            float *v = pos + 3 * (j + 1);
            v[0] = u <= 1.0 ? x1 : (float)(x1 + (u - 1.0) * (x0 - x1));
            v[1] = u <= 1.0 ? (float)(y0 + u * (y1 - y0)) : y1;
            v[2] = sc->z[i];
        }
        for (uint32_t j = 0; j < t; j++) {
            idx[3 * j] = 0, idx[3 * j + 1] = j + 1, idx[3 * j + 2] = j + 2;
            src[j] = i * MAX_FAN + j;
        }
        oit_partfile_piece_desc piece = {t, 1};
        oit_partfile_part_desc d = {.positions = pos, .vertex_count = t + 2, .indices = idx,
                                    .index_count = 3 * t, .sources = src, .pieces = &piece,
                                    .piece_count = 1, .layer_bound = sc->layers[i]};
        s = oit_partfile_writer_add_part(w, &d, &list[i], err);
    }
    uint32_t count = sc->n;
    oit_partfile_grid_desc g = {{1, 1, 1}, {-1000, -1000, -10}, {2000, 2000, 20},
                                OIT_PARTFILE_NONE, OIT_PARTFILE_NONE, &count, list};
    if (!s)
        s = oit_partfile_writer_set_grid(w, &g, err);
    if (s) {
        if (w)
            oit_partfile_writer_abort(w);
        return s;
    }
    oit_partfile_stats st = {.triangles_in = MAX_PARTS * MAX_FAN};
    return oit_partfile_writer_finish(w, &st, err);
}

static void make_view(const scene *sc, oit_view *v)
{
    memset(v, 0, sizeof *v);
    v->width = (int)sc->w;
    v->height = (int)sc->h;
    oit_camera *c = &v->camera;
    c->eye[2] = 10.0f;
    c->up[1] = 1.0f;
    c->znear = 0.1f;
    c->zfar = 100.0f;
    c->projection = OIT_PROJ_ORTHOGRAPHIC;
    c->ortho_height = (float)sc->h;
}

/* ---- the model ------------------------------------------------------------------- */

typedef struct config {
    oit_render_pack mode;
    int front_first, wave;
    uint64_t budget;
} config;

typedef struct model {
    uint32_t parts[MAX_PARTS], drawn, culled;
    int rect[MAX_PARTS][4];              /* per part */
    uint32_t pack_first[MAX_PARTS + 1], packs;
    uint32_t layers[MAX_PARTS];
    uint64_t bytes[MAX_PARTS];
    int pack_rect[MAX_PARTS][4];
    uint32_t tile[(W_MAX / TILE + 1) * (H_MAX / TILE + 1)]; /* the open pack's sums */
    uint32_t parts_level, levels; /* run_model_levels: the last part placed, levels */
    int cell;                     /* and the cells' side */
} model;

/* The rectangle as pack.h says: the span and a pixel of margin, on screen. */
static int part_rect(const scene *sc, uint32_t i, int r[4])
{
    r[0] = (int)fmax(floor(sc->px[i][0]) - 1, 0);
    r[1] = (int)fmax(floor(sc->px[i][1]) - 1, 0);
    r[2] = (int)fmin(ceil(sc->px[i][2]) + 1, sc->w);
    r[3] = (int)fmin(ceil(sc->px[i][3]) + 1, sc->h);
    return r[2] > r[0] && r[3] > r[1];
}

static uint64_t part_bytes(const scene *sc, uint32_t i)
{
    uint64_t b = sc->tris[i] * (48u + 4u); /* oit_triangle and its source index */
    return (b + 255) / 256 * 256;
}

/* The most the open pack's tiles under r hold, plus add, and (when add is
 * not 0) adds it. */
static uint32_t tiles(model *m, const scene *sc, const int r[4], uint32_t add, int apply)
{
    uint32_t tx = (sc->w + TILE - 1) / TILE, most = 0;
    for (int y = r[1] / TILE; y <= (r[3] - 1) / TILE; y++)
        for (int x = r[0] / TILE; x <= (r[2] - 1) / TILE; x++) {
            uint32_t *t = &m->tile[(uint32_t)y * tx + (uint32_t)x];
            most = *t + add > most ? *t + add : most;
            if (apply)
                *t += add;
        }
    return most;
}

static int overlaps(const int a[4], const int b[4])
{
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

static uint32_t cap_of(const config *c, uint32_t K, uint32_t pack)
{
    return c->mode == OIT_RENDER_PACK_BUDGET ? K : K << (pack < 12 ? pack : 12);
}

static void run_model(const scene *sc, const config *c, model *m)
{
    memset(m, 0, sizeof *m);
    int unbounded = c->mode == OIT_RENDER_PACK_COUNTED || c->mode == OIT_RENDER_PACK_FIRSTK;
    int tiled = c->mode == OIT_RENDER_PACK_BUDGET || (unbounded && c->front_first);
    for (uint32_t i = 0; i < sc->n; i++) {
        int r[4];
        if (!part_rect(sc, i, r)) {
            m->culled++;
            continue;
        }
        uint32_t L = sc->layers[i], p = m->packs - 1;
        uint64_t b = part_bytes(sc, i);
        int join = m->packs > 0 && m->bytes[p] + b <= c->budget;
        if (join && !unbounded)
            join = L <= sc->K && m->layers[p] <= sc->K;
        if (join && tiled)
            join = tiles(m, sc, r, L, 0) <= cap_of(c, sc->K, p);
        else if (join && c->mode == OIT_RENDER_PACK_DISJOINT)
            join = !overlaps(m->pack_rect[p], r);
        if (!join) {
            p = m->packs++;
            m->pack_first[p] = m->drawn;
            m->layers[p] = L > sc->K ? L : sc->K;
            m->bytes[p] = 0;
            memcpy(m->pack_rect[p], r, sizeof r);
            memset(m->tile, 0, sizeof m->tile);
        }
        /* a wide first part under a K-slot rule stays out of the sums: nothing joins it */
        if (tiled && (unbounded || L <= sc->K))
            tiles(m, sc, r, L, 1);
        m->bytes[p] += b;
        for (int k = 0; k < 2; k++) {
            m->pack_rect[p][k] = r[k] < m->pack_rect[p][k] ? r[k] : m->pack_rect[p][k];
            m->pack_rect[p][k + 2] = r[k + 2] > m->pack_rect[p][k + 2] ? r[k + 2]
                                                                       : m->pack_rect[p][k + 2];
        }
        memcpy(m->rect[m->drawn], r, sizeof r);
        m->parts[m->drawn++] = i;
    }
    m->pack_first[m->packs] = m->drawn;
}

/* The disjoint rule on the wave: levels from the pairs, then packs cut as
 * the tree's are but by level, bytes and wide parts only. */
static int share_cell(const int a[4], const int b[4], int c)
{
    return a[0] / c <= (b[2] - 1) / c && b[0] / c <= (a[2] - 1) / c &&
           a[1] / c <= (b[3] - 1) / c && b[1] / c <= (a[3] - 1) / c;
}

static void run_model_levels(const scene *sc, const config *c, model *m)
{
    memset(m, 0, sizeof *m);
    uint32_t level[MAX_PARTS], kept[MAX_PARTS], n = 0, levels = 0;
    int rect[MAX_PARTS][4];
    double area = 0;
    for (uint32_t i = 0; i < sc->n; i++) {
        if (!part_rect(sc, i, rect[n])) {
            m->culled++;
            continue;
        }
        area += (double)(rect[n][2] - rect[n][0]) * (rect[n][3] - rect[n][1]);
        kept[n++] = i;
    }
    /* pack.c's cells: the finest power of two visiting <= 16 a screen pixel */
    int cell = 1;
    while (cell < 64 && area / ((double)cell * cell) > 16.0 * sc->w * sc->h)
        cell *= 2;
    m->cell = cell;
    for (uint32_t k = 0; k < n; k++) {
        level[k] = 0;
        for (uint32_t j = 0; j < k; j++)
            if (share_cell(rect[j], rect[k], cell) && level[j] + 1 > level[k])
                level[k] = level[j] + 1;
        levels = level[k] + 1 > levels ? level[k] + 1 : levels;
    }
    for (uint32_t v = 0; v < levels; v++)
        for (uint32_t k = 0; k < n; k++) {
            if (level[k] != v)
                continue;
            uint32_t i = kept[k], L = sc->layers[i], p = m->packs - 1;
            uint64_t b = part_bytes(sc, i);
            int join = m->packs > 0 && m->drawn > m->pack_first[p] &&
                       level[m->parts_level] == v && m->bytes[p] + b <= c->budget &&
                       L <= sc->K && m->layers[p] <= sc->K;
            if (!join) {
                p = m->packs++;
                m->pack_first[p] = m->drawn;
                m->layers[p] = L > sc->K ? L : sc->K;
                m->bytes[p] = 0;
                memcpy(m->pack_rect[p], rect[k], sizeof rect[k]);
            }
            m->bytes[p] += b;
            for (int e = 0; e < 2; e++) {
                m->pack_rect[p][e] = rect[k][e] < m->pack_rect[p][e] ? rect[k][e]
                                                                     : m->pack_rect[p][e];
                m->pack_rect[p][e + 2] = rect[k][e + 2] > m->pack_rect[p][e + 2]
                                             ? rect[k][e + 2] : m->pack_rect[p][e + 2];
            }
            memcpy(m->rect[m->drawn], rect[k], sizeof rect[k]);
            m->parts_level = k;
            m->parts[m->drawn++] = i;
        }
    m->pack_first[m->packs] = m->drawn;
    m->levels = levels;
}

/* ---- the checks ----------------------------------------------------------------- */

static const char *mode_name(const config *c)
{
    static char buf[64];
    const char *m = c->mode == OIT_RENDER_PACK_BUDGET     ? "budget"
                    : c->mode == OIT_RENDER_PACK_DISJOINT ? "disjoint"
                    : c->mode == OIT_RENDER_PACK_COUNTED  ? "counted"
                                                   : "first-k";
    snprintf(buf, sizeof buf, "%s%s%s", m, c->front_first ? " front-first" : "",
             c->wave ? " wave" : "");
    return buf;
}

/* The tree schedule's packs against the model's, field by field. */
static int same_as_model(const oit_packing *pk, const model *m, const char *what)
{
    int ok = pk->part_count == m->drawn && pk->pack_count == m->packs && pk->culled == m->culled;
    CHECK(ok, "%s: %u parts in %u packs, %u culled; the model: %u in %u, %u culled", what,
          pk->part_count, pk->pack_count, pk->culled, m->drawn, m->packs, m->culled);
    for (uint32_t j = 0; ok && j < m->drawn; j++) {
        ok = pk->parts[j] == m->parts[j] && !memcmp(pk->part_rects[j], m->rect[j], sizeof m->rect[j]);
        CHECK(ok, "%s: drawn part %u is %u, rect (%d %d %d %d); the model: %u (%d %d %d %d)",
              what, j, pk->parts[j], pk->part_rects[j][0], pk->part_rects[j][1],
              pk->part_rects[j][2], pk->part_rects[j][3], m->parts[j], m->rect[j][0],
              m->rect[j][1], m->rect[j][2], m->rect[j][3]);
    }
    for (uint32_t p = 0; ok && p < m->packs; p++) {
        ok = pk->pack_first[p] == m->pack_first[p] && pk->layers[p] == m->layers[p] &&
             pk->bytes[p] == m->bytes[p] && !memcmp(pk->rects[p], m->pack_rect[p], 16);
        CHECK(ok, "%s: pack %u starts at part %u, %u layers, %llu bytes; the model: %u, %u, "
              "%llu", what, p, pk->pack_first[p], pk->layers[p],
              (unsigned long long)pk->bytes[p], m->pack_first[p], m->layers[p],
              (unsigned long long)m->bytes[p]);
    }
    return ok;
}

/* What any schedule must keep: the kept parts once each, and per pack the
 * bytes, the wide rule and the tile rule (budget: sums <= K; disjoint: one
 * part a tile on the wave, rectangles that miss each other on the tree). */
static void check_rules(const oit_packing *pk, const scene *sc, const config *c,
                        const model *m, const char *what)
{
    unsigned char seen[MAX_PARTS] = {0};
    int ok = pk->part_count == m->drawn && pk->pack_first[0] == 0 &&
             pk->pack_first[pk->pack_count] == pk->part_count;
    for (uint32_t j = 0; ok && j < pk->part_count; j++)
        ok = pk->parts[j] < sc->n && !seen[pk->parts[j]]++;
    CHECK(ok, "%s: the packs do not hold each of the %u kept parts once", what, m->drawn);
    int kslots = c->mode == OIT_RENDER_PACK_BUDGET || c->mode == OIT_RENDER_PACK_DISJOINT;
    uint32_t tx = (sc->w + TILE - 1) / TILE, ty = (sc->h + TILE - 1) / TILE;
    for (uint32_t p = 0; ok && p < pk->pack_count; p++) {
        uint32_t a = pk->pack_first[p], e = pk->pack_first[p + 1];
        uint64_t bytes = 0;
        uint32_t wide = 0, sum[(W_MAX / TILE + 1) * (H_MAX / TILE + 1)] = {0};
        uint32_t on[(W_MAX / TILE + 1) * (H_MAX / TILE + 1)] = {0};
        for (uint32_t j = a; j < e; j++) {
            uint32_t i = pk->parts[j];
            int r[4];
            part_rect(sc, i, r);
            bytes += part_bytes(sc, i);
            wide += sc->layers[i] > sc->K;
            for (int y = r[1] / TILE; y <= (r[3] - 1) / TILE; y++)
                for (int x = r[0] / TILE; x <= (r[2] - 1) / TILE; x++) {
                    sum[(uint32_t)y * tx + (uint32_t)x] += sc->layers[i];
                    on[(uint32_t)y * tx + (uint32_t)x]++;
                }
        }
        uint32_t worst = 0, crowded = 0;
        for (uint32_t t = 0; t < tx * ty; t++)
            worst = sum[t] > worst ? sum[t] : worst;
        /* the disjoint rule: no pixel gets fragments of two parts of a pack */
        for (uint32_t j = a; c->mode == OIT_RENDER_PACK_DISJOINT && j < e; j++)
            for (uint32_t k = a; k < j; k++)
                crowded += overlaps(pk->part_rects[j], pk->part_rects[k]);
        ok = e > a && bytes <= c->budget && (!kslots || !wide || e - a == 1) &&
             (c->mode != OIT_RENDER_PACK_BUDGET || wide || worst <= sc->K) &&
             (c->mode != OIT_RENDER_PACK_DISJOINT || crowded == 0);
        CHECK(ok, "%s: pack %u of %u parts: %llu bytes (budget %llu), %u wide, most layers on "
              "a tile %u (K %u); disjoint: %u pairs of rectangles overlap", what, p, e - a,
              (unsigned long long)bytes, (unsigned long long)c->budget, wide, worst, sc->K,
              crowded);
    }
    /* Order: of two parts whose rectangles overlap, the earlier in the input
     * is drawn first (the disjoint rule: in an earlier pack). */
    uint32_t pack_of[MAX_PARTS], pos[MAX_PARTS];
    for (uint32_t p = 0; ok && p < pk->pack_count; p++)
        for (uint32_t j = pk->pack_first[p]; j < pk->pack_first[p + 1]; j++) {
            pack_of[pk->parts[j]] = p;
            pos[pk->parts[j]] = j;
        }
    uint32_t reversed = 0;
    for (uint32_t j = 0; ok && j < pk->part_count; j++)
        for (uint32_t k = 0; k < pk->part_count; k++) {
            uint32_t a = pk->parts[j], b = pk->parts[k];
            if (a >= b || !overlaps(pk->part_rects[j], pk->part_rects[k]))
                continue;
            reversed += pos[a] > pos[b] ||
                        (c->mode == OIT_RENDER_PACK_DISJOINT && pack_of[a] == pack_of[b]);
        }
    CHECK(reversed == 0, "%s: %u overlapping pairs drawn against the order or (disjoint) in "
          "one pack", what, reversed);
}

typedef struct tally {
    unsigned long runs, packs, wide_packs, joined_after_first;
    unsigned long level_packings, level_packs, tree_packs; /* disjoint: wave, and tree alike */
    unsigned long coarse; /* of those, at cells wider than a pixel */
} tally;

/* The tree's disjoint packs of the same scene, beside the levels'. */
static uint32_t tree_packs(const oit_partfile *pf, const scene *sc, const config *c,
                           const oit_view *view)
{
    oit_packer *pk = NULL;
    oit_error err = {0};
    oit_packing out = {0};
    uint32_t order[MAX_PARTS];
    for (uint32_t i = 0; i < sc->n; i++)
        order[i] = i;
    if (oit_packer_create(pf, OIT_RENDER_PACK_DISJOINT, (int)sc->K, c->budget, &pk, &err) ||
        oit_packer_run(pk, view, order, sc->n, &out, &err))
        CHECK(0, "tree packer: %s", err.message);
    uint32_t n = out.pack_count;
    oit_packer_destroy(pk);
    return n;
}

static void run_config(tally *t, const oit_partfile *pf, const scene *sc, const config *c,
                       int round)
{
    oit_packer *pk = NULL;
    oit_error err = {0};
    oit_view view;
    make_view(sc, &view);
    uint32_t order[MAX_PARTS];
    for (uint32_t i = 0; i < sc->n; i++)
        order[i] = i;
    if (oit_packer_create(pf, c->mode, (int)sc->K, c->budget, &pk, &err)) {
        CHECK(0, "round %d: packer: %s", round, err.message);
        return;
    }
    oit_packer_set_front_first(pk, c->front_first);
    oit_packer_set_schedule(pk, c->wave ? OIT_RENDER_SCHEDULE_WAVE : OIT_RENDER_SCHEDULE_TREE);
    oit_packing out;
    char what[160];
    snprintf(what, sizeof what, "round %d (%ux%u, %u parts, K %u, budget %llu), %s", round,
             sc->w, sc->h, sc->n, sc->K, (unsigned long long)c->budget, mode_name(c));
    /* twice: the second run reuses the packer's stamped tiles */
    for (int rep = 0; rep < 2; rep++) {
        if (oit_packer_run(pk, &view, order, sc->n, &out, &err)) {
            CHECK(0, "%s: %s", what, err.message);
            break;
        }
        model m;
        int levels = c->wave && c->mode == OIT_RENDER_PACK_DISJOINT;
        if (levels)
            run_model_levels(sc, c, &m);
        else
            run_model(sc, c, &m);
        check_rules(&out, sc, c, &m, what);
        if (!c->wave || levels)
            same_as_model(&out, &m, what);
        if (levels && !rep) {
            t->level_packings++;
            t->coarse += m.cell > 1;
            t->level_packs += out.pack_count;
            t->tree_packs += tree_packs(pf, sc, c, &view);
        }
        if (rep)
            continue;
        t->runs++;
        t->packs += out.pack_count;
        for (uint32_t p = 0; p < out.pack_count; p++) {
            t->wide_packs += out.layers[p] > sc->K;
            t->joined_after_first += out.pack_first[p + 1] - out.pack_first[p] > 1 &&
                                     sc->layers[out.parts[out.pack_first[p]]] == sc->K;
        }
    }
    oit_packer_destroy(pk);
}

/* A known layout: two pairs of overlapping parts, P0 and P1 at the left, P2
 * and P3 at the right, in the order P0 P1 P2 P3. The tree's disjoint rule
 * cuts [P0] [P1 P2] [P3]; by level, [P0 P2] [P1 P3]: the overlapping pairs
 * never share a pack, and P0 comes before P1, P2 before P3. */
static void known_layout(const char *path)
{
    static scene sc;
    memset(&sc, 0, sizeof sc);
    sc.w = 100, sc.h = 40, sc.K = 8, sc.n = 4;
    const double x0[4] = {10.25, 15.25, 40.25, 45.25};
    for (uint32_t i = 0; i < 4; i++) {
        sc.px[i][0] = x0[i], sc.px[i][2] = x0[i] + 10.0;
        sc.px[i][1] = 10.25, sc.px[i][3] = 20.25;
        sc.tris[i] = 2, sc.layers[i] = 8, sc.z[i] = -1.0f - (float)i;
    }
    oit_error err = {0};
    oit_partfile *pf = NULL;
    oit_packer *tree = NULL, *wave = NULL;
    if (write_scene(path, &sc, &err) || oit_partfile_open(path, NULL, &pf, &err) ||
        oit_packer_create(pf, OIT_RENDER_PACK_DISJOINT, 8, 1u << 30, &tree, &err) ||
        oit_packer_create(pf, OIT_RENDER_PACK_DISJOINT, 8, 1u << 30, &wave, &err)) {
        CHECK(0, "known layout: %s", err.message);
        goto done;
    }
    oit_packer_set_schedule(wave, OIT_RENDER_SCHEDULE_WAVE);
    oit_view view;
    make_view(&sc, &view);
    const uint32_t order[4] = {0, 1, 2, 3};
    oit_packing t, w;
    if (oit_packer_run(tree, &view, order, 4, &t, &err)) {
        CHECK(0, "known layout, tree: %s", err.message);
        goto done;
    }
    uint32_t tree_count = t.pack_count;
    if (oit_packer_run(wave, &view, order, 4, &w, &err)) {
        CHECK(0, "known layout, wave: %s", err.message);
        goto done;
    }
    CHECK(tree_count == 3, "known layout: the tree's disjoint rule cut %u packs, not 3",
          tree_count);
    int ok = w.pack_count == 2 && w.part_count == 4 && w.pack_first[1] == 2 &&
             w.parts[0] == 0 && w.parts[1] == 2 && w.parts[2] == 1 && w.parts[3] == 3;
    CHECK(ok, "known layout: by level %u packs (%u parts: %u %u %u %u, the second pack from "
          "%u), not [0 2] [1 3]", w.pack_count, w.part_count, w.parts[0], w.parts[1],
          w.parts[2], w.parts[3], w.pack_first[1]);
done:
    oit_packer_destroy(tree);
    oit_packer_destroy(wave);
    oit_partfile_close(pf);
}

int main(void)
{
    char path[600];
    test_tmp_path(path, sizeof path, "test_pack.oitp");
    static scene sc;
    rng r = {1234567u};
    tally t = {0};
    for (int round = 0; round < ROUNDS; round++) {
        make_scene(&r, &sc);
        oit_error err = {0};
        oit_partfile *pf = NULL;
        if (write_scene(path, &sc, &err) || oit_partfile_open(path, NULL, &pf, &err)) {
            CHECK(0, "round %d: %s", round, err.message);
            continue;
        }
        uint64_t budget = rnd(&r, 3) ? 256u * (3 + rnd(&r, 24)) : (uint64_t)1 << 30;
        static const config base[] = {
            {OIT_RENDER_PACK_BUDGET, 0, 0, 0},  {OIT_RENDER_PACK_DISJOINT, 0, 0, 0},
            {OIT_RENDER_PACK_COUNTED, 1, 0, 0}, {OIT_RENDER_PACK_FIRSTK, 1, 0, 0},
            {OIT_RENDER_PACK_COUNTED, 0, 0, 0}, {OIT_RENDER_PACK_BUDGET, 0, 1, 0},
            {OIT_RENDER_PACK_DISJOINT, 0, 1, 0}, {OIT_RENDER_PACK_COUNTED, 0, 1, 0}};
        for (size_t k = 0; k < sizeof base / sizeof *base; k++) {
            config c = base[k];
            c.budget = budget;
            run_config(&t, pf, &sc, &c, round);
        }
        oit_partfile_close(pf);
    }
    known_layout(path);
    remove(path);
    printf("%lu packings, %lu packs, %lu of a wide part, %lu where parts joined a first part "
           "of K layers; disjoint by level: %lu packs where the tree cuts %lu (%lu of %lu at "
           "coarser cells)\n", t.runs, t.packs, t.wide_packs, t.joined_after_first,
           t.level_packs, t.tree_packs, t.coarse, t.level_packings);
    CHECK(t.level_packings > 0 && t.level_packs < t.tree_packs,
          "the levels made no fewer packs than the tree's disjoint rule");
    CHECK(t.wide_packs > 0 && t.joined_after_first > 0,
          "the random scenes miss wide parts or full first parts");
    return test_verdict();
}
