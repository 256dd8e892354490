/* Packing (pack.h). Per frame O(parts + tiles touched); the tile grid is
 * reset by stamping tiles with the pack number instead of clearing it. */
#include "view/stream/pack.h"

#include "base/minmax.h"
#include "view/render/image/rect.h"
#include "partfile/triangles.h"
#include "view/stream/schedule.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { TILE = 32 };

struct oit_packer {
    const oit_partfile *pf;
    oit_render_pack mode;
    uint32_t K;
    uint64_t budget;
    uint32_t *parts, *pack_first, *layers;
    int (*rects)[4], (*part_rects)[4];
    uint64_t *bytes;
    uint32_t *tile_sum, *tile_stamp;
    int tiles_x, tiles_y;
    uint32_t stamp;
    oit_render_schedule schedule;
    oit_scheduler *scheduler;
    /* the parts that survive culling, in the tree's order */
    uint32_t *kept;
    int (*kept_rects)[4];
    float *kept_near;
    /* the disjoint rule on the wave (pack_levels): each kept part's level,
     * the kept parts sorted by it, and per cell the latest part over it */
    uint32_t *level, *by_level, *level_first;
    uint32_t *cell_last;
    size_t cell_cap;
    uint32_t drawn, packs; /* of the frame being packed */
    int open_empty;        /* wave: the open pack has no part yet */
    int front_first;       /* oit_packer_set_front_first */
};

uint64_t oit_pack_part_bytes(const oit_partfile_part *p)
{
    uint64_t b = oit_part_sourced_bytes(p->index_count / 3);
    return (b + OIT_PACK_ALIGN - 1) / OIT_PACK_ALIGN * OIT_PACK_ALIGN;
}

void oit_packer_destroy(oit_packer *pk)
{
    if (!pk)
        return;
    free(pk->parts);
    free(pk->pack_first);
    free(pk->layers);
    free(pk->rects);
    free(pk->part_rects);
    free(pk->bytes);
    free(pk->tile_sum);
    free(pk->tile_stamp);
    oit_scheduler_destroy(pk->scheduler);
    free(pk->kept);
    free(pk->kept_rects);
    free(pk->kept_near);
    free(pk->level);
    free(pk->by_level);
    free(pk->level_first);
    free(pk->cell_last);
    free(pk);
}

void oit_packer_set_schedule(oit_packer *pk, oit_render_schedule schedule)
{
    pk->schedule = schedule;
}

void oit_packer_set_front_first(oit_packer *pk, int on)
{
    pk->front_first = on;
}

static oit_status check_parts(const oit_partfile *pf, uint32_t K, uint64_t budget, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    for (uint32_t i = 0; i < oit_partfile_part_count(pf); i++) {
        if (parts[i].layer_bound > OIT_PACK_MAX_LAYERS)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: part %u has up to %u layers, "
                                 "more than the widest capture (%u)", oit_partfile_name(pf), i,
                                 parts[i].layer_bound, OIT_PACK_MAX_LAYERS);
        if (oit_pack_part_bytes(&parts[i]) > budget)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: part %u needs %llu bytes, more "
                                 "than the upload budget of %llu", oit_partfile_name(pf), i,
                                 (unsigned long long)oit_pack_part_bytes(&parts[i]),
                                 (unsigned long long)budget);
    }
    return OIT_OK;
}

oit_status oit_packer_create(const oit_partfile *pf, oit_render_pack mode, int K,
                             uint64_t byte_budget, oit_packer **out, oit_error *err)
{
    *out = NULL;
    if (mode == OIT_RENDER_PACK_AUTO)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: the packer needs a resolved pack "
                             "mode, not auto", oit_partfile_name(pf));
    oit_status s = check_parts(pf, (uint32_t)K, byte_budget, err);
    if (s != OIT_OK)
        return s;
    uint32_t n = oit_partfile_part_count(pf);
    oit_packer *pk = calloc(1, sizeof *pk);
    if (pk) {
        pk->parts = calloc((size_t)n + 1, sizeof *pk->parts);
        pk->pack_first = calloc((size_t)n + 2, sizeof *pk->pack_first);
        pk->rects = calloc((size_t)n + 1, sizeof *pk->rects);
        pk->part_rects = calloc((size_t)n + 1, sizeof *pk->part_rects);
        pk->layers = calloc((size_t)n + 1, sizeof *pk->layers);
        pk->bytes = calloc((size_t)n + 1, sizeof *pk->bytes);
        pk->kept = calloc((size_t)n + 1, sizeof *pk->kept);
        pk->kept_rects = calloc((size_t)n + 1, sizeof *pk->kept_rects);
        pk->kept_near = calloc((size_t)n + 1, sizeof *pk->kept_near);
        pk->level = calloc((size_t)n + 1, sizeof *pk->level);
        pk->by_level = calloc((size_t)n + 1, sizeof *pk->by_level);
        pk->level_first = calloc((size_t)n + 2, sizeof *pk->level_first);
    }
    if (!pk || !pk->parts || !pk->pack_first || !pk->rects || !pk->part_rects || !pk->layers ||
        !pk->bytes || !pk->kept || !pk->kept_rects || !pk->kept_near || !pk->level ||
        !pk->by_level || !pk->level_first) {
        oit_packer_destroy(pk);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate packing for %u parts",
                             oit_partfile_name(pf), n);
    }
    pk->pf = pf;
    pk->mode = mode;
    pk->K = (uint32_t)K;
    pk->budget = byte_budget;
    s = oit_scheduler_create(n, &pk->scheduler, err);
    if (s != OIT_OK) {
        oit_packer_destroy(pk);
        return s;
    }
    *out = pk;
    return OIT_OK;
}

static oit_status fit_tiles(oit_packer *pk, const oit_view *v, oit_error *err)
{
    int tx = (v->width + TILE - 1) / TILE, ty = (v->height + TILE - 1) / TILE;
    if (tx == pk->tiles_x && ty == pk->tiles_y)
        return OIT_OK;
    free(pk->tile_sum);
    free(pk->tile_stamp);
    pk->tile_sum = calloc((size_t)tx * ty, sizeof *pk->tile_sum);
    pk->tile_stamp = calloc((size_t)tx * ty, sizeof *pk->tile_stamp);
    pk->tiles_x = pk->tile_sum && pk->tile_stamp ? tx : 0;
    pk->tiles_y = pk->tile_sum && pk->tile_stamp ? ty : 0;
    pk->stamp = 0;
    if (!pk->tiles_x)
        return oit_error_set(err, OIT_ERR_NOMEM, "packing: cannot allocate %dx%d tiles", tx, ty);
    return OIT_OK;
}

/* What projecting a box needs from the view, worked out once a frame: a
 * converted model has 10^5-10^6 parts. */
typedef struct box_projector {
    float m[16];               /* world to eye */
    double fx, fy, w, h;       /* pixels per unit of x/depth, y/depth */
    double znear, zfar;
    /* Off-centre or orthographic: the window (oit_camera_window); ortho
     * projects x and y without dividing by depth. */
    int windowed, ortho;
    double win[4];
} box_projector;

static void projector_init(box_projector *pr, const oit_view *v)
{
    const oit_camera *c = &v->camera;
    oit_view_model_view_matrix(v, pr->m); /* part boxes are in model space */
    double f = 1.0 / tan(0.5 * (c->fovy_deg > 0.0f ? c->fovy_deg : 45.0) * 3.14159265358979 / 180.0);
    pr->w = v->width;
    pr->h = v->height;
    pr->fx = f / (pr->w / pr->h) * 0.5 * pr->w;
    pr->fy = f * 0.5 * pr->h;
    pr->znear = c->znear;
    pr->zfar = c->zfar;
    pr->ortho = c->projection == OIT_PROJ_ORTHOGRAPHIC;
    pr->windowed = pr->ortho || c->window[0] != 0.0f || c->window[1] != 0.0f ||
                   c->window[2] != 0.0f || c->window[3] != 0.0f;
    oit_camera_window(c, pr->w / pr->h, pr->win);
}

/* The screen rectangle of the part's box and the nearest depth of its
 * corners; 0 when the box lies outside the view volume (culled). */
static int project_box(const oit_partfile_part *p, const box_projector *pr, int rect[4],
                       float *near)
{
    const float *m = pr->m;
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    int near_cross = 0, before_near = 0, beyond_far = 0;
    double nearest = HUGE_VAL;
    for (int k = 0; k < 8; k++) {
        double x = k & 1 ? p->bounds_max[0] : p->bounds_min[0];
        double y = k & 2 ? p->bounds_max[1] : p->bounds_min[1];
        double z = k & 4 ? p->bounds_max[2] : p->bounds_min[2];
        double vx = m[0] * x + m[4] * y + m[8] * z + m[12];
        double vy = m[1] * x + m[5] * y + m[9] * z + m[13];
        double depth = -(m[2] * x + m[6] * y + m[10] * z + m[14]);
        nearest = oit_min_d(nearest, depth);
        before_near += depth < pr->znear;
        beyond_far += depth > pr->zfar;
        if (!pr->ortho && depth <= 0.5 * pr->znear) {
            near_cross = 1;
            continue;
        }
        double px, py;
        if (pr->windowed) {
            double sx = pr->ortho ? vx : vx / depth, sy = pr->ortho ? vy : vy / depth;
            px = (sx - pr->win[0]) / (pr->win[1] - pr->win[0]) * pr->w;
            py = (pr->win[3] - sy) / (pr->win[3] - pr->win[2]) * pr->h;
        } else {
            px = pr->fx * vx / depth + 0.5 * pr->w;
            py = 0.5 * pr->h - pr->fy * vy / depth;
        }
        lo[0] = oit_min_d(lo[0], px), hi[0] = oit_max_d(hi[0], px);
        lo[1] = oit_min_d(lo[1], py), hi[1] = oit_max_d(hi[1], py);
    }
    if (before_near == 8 || beyond_far == 8)
        return 0;
    *near = (float)nearest;
    if (near_cross) {
        rect[0] = rect[1] = 0;
        rect[2] = (int)pr->w;
        rect[3] = (int)pr->h;
        return 1;
    }
    /* One pixel of margin covers rounding between this and the rasterizer. */
    rect[0] = (int)fmax(floor(lo[0]) - 1.0, 0.0);
    rect[1] = (int)fmax(floor(lo[1]) - 1.0, 0.0);
    rect[2] = (int)fmin(ceil(hi[0]) + 1.0, pr->w);
    rect[3] = (int)fmin(ceil(hi[1]) + 1.0, pr->h);
    return rect[2] > rect[0] && rect[3] > rect[1];
}

/* Budget rule: adds the part's layers to its tiles if all stay <= cap. */
static int tiles_take(oit_packer *pk, const int r[4], uint32_t layers, uint32_t cap)
{
    int x0 = r[0] / TILE, x1 = (r[2] - 1) / TILE, y0 = r[1] / TILE, y1 = (r[3] - 1) / TILE;
    for (int pass = 0; pass < 2; pass++)
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++) {
                size_t t = (size_t)y * pk->tiles_x + x;
                uint32_t cur = pk->tile_stamp[t] == pk->stamp ? pk->tile_sum[t] : 0;
                if (pass == 0 && cur + layers > cap)
                    return 0;
                if (pass == 1) {
                    pk->tile_stamp[t] = pk->stamp;
                    pk->tile_sum[t] = cur + layers;
                }
            }
    return 1;
}

/* The modes whose capture has no per-pixel limit: packs cut by bytes only. */
static int unbounded(const oit_packer *pk)
{
    return pk->mode == OIT_RENDER_PACK_COUNTED || pk->mode == OIT_RENDER_PACK_FIRSTK;
}

/* Bytes and wide parts: a wide part (layer bound above K) is a pack of its
 * own, except for the captures without a per-pixel limit. */
static int fits(const oit_packer *pk, uint32_t pack, uint32_t layers, uint64_t bytes)
{
    if (pk->bytes[pack] + bytes > pk->budget)
        return 0;
    return unbounded(pk) || (layers <= pk->K && pk->layers[pack] <= pk->K);
}

/* Front first's doubling stops at K * 2^12 layer bounds a tile, a cap no
 * real pack reaches (so later packs are cut by bytes alone), well before
 * K << i could overflow 32 bits. */
#define FRONT_CAP_DOUBLINGS 12u

/* Front first (pack.h): pack i's cap on the layer bounds a tile sums,
 * K * 2^i, so a pixel's front layers take a few packs whatever its depth. */
static uint32_t front_cap(const oit_packer *pk, uint32_t pack)
{
    return pk->K << (pack < FRONT_CAP_DOUBLINGS ? pack : FRONT_CAP_DOUBLINGS);
}

/* The unbounded modes' own tile rule: only front first has one. */
static int tiled(const oit_packer *pk)
{
    return pk->mode == OIT_RENDER_PACK_BUDGET || (unbounded(pk) && pk->front_first);
}

static uint32_t tile_cap(const oit_packer *pk, uint32_t pack)
{
    return pk->mode == OIT_RENDER_PACK_BUDGET ? pk->K : front_cap(pk, pack);
}

static int joins(oit_packer *pk, uint32_t pack, const int r[4], uint32_t layers, uint64_t bytes)
{
    if (!fits(pk, pack, layers, bytes))
        return 0;
    if (tiled(pk))
        return tiles_take(pk, r, layers, tile_cap(pk, pack));
    if (unbounded(pk))
        return 1;
    return !oit_rect_overlaps(pk->rects[pack], r);
}

static void open_pack(oit_packer *pk, uint32_t pack, uint32_t first, uint32_t layers)
{
    pk->pack_first[pack] = first;
    pk->layers[pack] = layers > pk->K ? layers : pk->K;
    pk->bytes[pack] = 0;
    pk->rects[pack][0] = pk->rects[pack][1] = 0x7fffffff;
    pk->rects[pack][2] = pk->rects[pack][3] = -1;
    if (++pk->stamp == 0) { /* wrapped: clear the stale stamps once */
        memset(pk->tile_stamp, 0, (size_t)pk->tiles_x * pk->tiles_y * sizeof *pk->tile_stamp);
        pk->stamp = 1;
    }
}

/* Culls and projects order[0..n) into pk->kept, in order; counts the
 * boxes the section planes remove in out. */
static uint32_t cull(oit_packer *pk, const oit_view *view, const uint32_t *order, uint32_t n,
                     oit_packing *out)
{
    box_projector pr;
    projector_init(&pr, view);
    /* Part boxes are in model space, so the planes go there. */
    double model[16], planes[OIT_CLIP_MAX][4];
    oit_view_model(view, model);
    oit_clip_model(&view->clip, model, planes);
    const oit_partfile_part *parts = oit_partfile_parts(pk->pf);
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; i++) {
        const oit_partfile_part *p = &parts[order[i]];
        if (!project_box(p, &pr, pk->kept_rects[k], &pk->kept_near[k]))
            continue;
        if (oit_clip_box_outside(view->clip.count, (const double(*)[4])planes, p->bounds_min,
                                 p->bounds_max)) {
            out->clipped++;
            out->clipped_bytes += oit_part_sourced_bytes(p->index_count / 3);
            continue;
        }
        pk->kept[k++] = order[i];
    }
    return k;
}

static void place(oit_packer *pk, uint32_t pack, uint32_t id, const int r[4])
{
    oit_rect_grow(pk->rects[pack], r);
    pk->bytes[pack] += oit_pack_part_bytes(&oit_partfile_parts(pk->pf)[id]);
    memcpy(pk->part_rects[pk->drawn], r, sizeof pk->part_rects[pk->drawn]);
    pk->parts[pk->drawn++] = id;
}

/* Tree schedule: a pack takes consecutive parts while they fit. */
static void pack_in_order(oit_packer *pk, uint32_t kept)
{
    const oit_partfile_part *parts = oit_partfile_parts(pk->pf);
    for (uint32_t i = 0; i < kept; i++) {
        const oit_partfile_part *p = &parts[pk->kept[i]];
        const int *r = pk->kept_rects[i];
        if (pk->packs == 0 ||
            !joins(pk, pk->packs - 1, r, p->layer_bound, oit_pack_part_bytes(p))) {
            open_pack(pk, pk->packs++, pk->drawn, p->layer_bound);
            /* A front-first pack's first part counts even above the cap, so
             * nothing joins it in those tiles. */
            if (tiled(pk) && (p->layer_bound <= pk->K || unbounded(pk)))
                tiles_take(pk, r, p->layer_bound, UINT32_MAX);
        }
        place(pk, pk->packs - 1, pk->kept[i], r);
    }
}

/* Wave schedule (schedule.h) of the budget and unbounded rules: packs are
 * filled from the front of the wave. Parts of one pack may lie anywhere on
 * screen, so the rules work per tile. (The disjoint rule takes levels
 * instead, pack_levels.) */
static void wave_open(void *ctx)
{
    ((oit_packer *)ctx)->open_empty = 1;
}

static int wave_join(void *ctx, uint32_t k)
{
    oit_packer *pk = ctx;
    const oit_partfile_part *p = &oit_partfile_parts(pk->pf)[pk->kept[k]];
    const int *r = pk->kept_rects[k];
    uint32_t cost = unbounded(pk) ? 0 : p->layer_bound;
    if (pk->open_empty) {
        open_pack(pk, pk->packs++, pk->drawn, p->layer_bound);
        if (p->layer_bound <= pk->K)
            tiles_take(pk, r, cost, UINT32_MAX);
        pk->open_empty = 0;
    } else {
        uint32_t pack = pk->packs - 1;
        if (!fits(pk, pack, p->layer_bound, oit_pack_part_bytes(p)) ||
            !tiles_take(pk, r, cost, pk->K))
            return 0;
    }
    place(pk, pk->packs - 1, pk->kept[k], r);
    return 1;
}

/* ---- the disjoint rule on the wave: packs by level ----------------------------
 *
 * Wang & Xie (5.1) form "a pack of the unoccluded parts among those
 * remaining": here a part is occluded by every earlier part of the tree's
 * order whose rectangle shares a cell with its own, and level(j) is 1 + the
 * highest level among those (0 when there is none); pack after pack takes a
 * level, cut only by bytes and wide parts. Exact, and byte for byte the
 * image of one part a pack:
 *  - a part's fragments fall inside its rectangle (pack.h), so two parts
 *    that share a pixel share a cell, and the later one in the order has the
 *    higher level: no pixel gets fragments of two parts of one pack, so a
 *    pack's per-pixel sort sees one part's fragments (at most its layer
 *    bound <= K; a wide part is a pack alone, with its own slots), and the
 *    pixels a pack gives nothing keep their state (the resolve skips them);
 *  - where two parts share a pixel the earlier one's level is lower, so
 *    every pixel composites the parts that reach it in the tree's order,
 *    each part's fragments sorted as when it is a pack alone. The order
 *    between parts that share no pixel changes nothing.
 * The fewest packs any rule of disjoint packs keeping those pairs' order
 * can make is the longest chain of parts each sharing a pixel with the next
 * in the order; the levels are exactly that many (at one-pixel cells).
 * Consecutive parts of the guaranteed scheme are neighbours whose
 * rectangles overlap, so the tree's rule (the pack's bounding rectangle)
 * closes a pack at nearly every part: the 1M plant at 512x512, 68,898
 * parts, took 61,790 packs; by level 7,380 (the tile wave: 46,176). */

/* The cells' side: the finest power of two at which the frame's rectangles
 * visit at most LEVEL_VISITS cells a pixel of the screen, in a grid of at
 * most LEVEL_CELLS cells, so that a frame of many wide rectangles (the eye
 * inside the model) stays linear in its pixels. Coarser cells are as exact
 * and make more levels (the 1M plant: 7,380 at 1 pixel, 9,998 at 4, 28,202
 * at 32). */
#define LEVEL_VISITS 16.0
#define LEVEL_CELLS (1u << 22)

static int level_cell(const oit_packer *pk, uint32_t kept, int width, int height)
{
    double area = 0.0;
    for (uint32_t k = 0; k < kept; k++) {
        const int *r = pk->kept_rects[k];
        area += (double)(r[2] - r[0]) * (double)(r[3] - r[1]);
    }
    int c = 1;
    while (c < 64 && (area / ((double)c * c) > LEVEL_VISITS * width * height ||
                      (double)((width + c - 1) / c) * ((height + c - 1) / c) > LEVEL_CELLS))
        c *= 2;
    return c;
}

/* level[k] for kept part k, and the highest level + 1 (0 with no part). */
static uint32_t assign_levels(oit_packer *pk, uint32_t kept, int c, int cx)
{
    uint32_t levels = 0;
    for (uint32_t j = 0; j < kept; j++) {
        const int *r = pk->kept_rects[j];
        uint32_t lv = 0;
        for (int y = r[1] / c; y <= (r[3] - 1) / c; y++) {
            uint32_t *row = pk->cell_last + (size_t)y * cx;
            for (int x = r[0] / c; x <= (r[2] - 1) / c; x++) {
                uint32_t i = row[x];
                if (i != UINT32_MAX && pk->level[i] + 1 > lv)
                    lv = pk->level[i] + 1;
                row[x] = j;
            }
        }
        pk->level[j] = lv;
        levels = lv + 1 > levels ? lv + 1 : levels;
    }
    return levels;
}

static oit_status pack_levels(oit_packer *pk, uint32_t kept, int width, int height,
                              oit_error *err)
{
    int c = level_cell(pk, kept, width, height);
    int cx = (width + c - 1) / c, cy = (height + c - 1) / c;
    size_t cells = (size_t)cx * cy;
    if (cells > pk->cell_cap) {
        uint32_t *l = realloc(pk->cell_last, cells * sizeof *l);
        if (!l)
            return oit_error_set(err, OIT_ERR_NOMEM, "packing: cannot allocate %dx%d cells",
                                 cx, cy);
        pk->cell_last = l;
        pk->cell_cap = cells;
    }
    memset(pk->cell_last, 0xff, cells * sizeof *pk->cell_last); /* UINT32_MAX: no part */
    uint32_t levels = assign_levels(pk, kept, c, cx);
    /* Sorted by level, stably: a level's parts keep the tree's order. */
    memset(pk->level_first, 0, ((size_t)levels + 1) * sizeof *pk->level_first);
    for (uint32_t k = 0; k < kept; k++)
        pk->level_first[pk->level[k] + 1]++;
    for (uint32_t v = 0; v < levels; v++)
        pk->level_first[v + 1] += pk->level_first[v];
    for (uint32_t k = 0; k < kept; k++)
        pk->by_level[pk->level_first[pk->level[k]]++] = k;
    const oit_partfile_part *parts = oit_partfile_parts(pk->pf);
    uint32_t open_level = UINT32_MAX;
    for (uint32_t s = 0; s < kept; s++) {
        uint32_t k = pk->by_level[s];
        const oit_partfile_part *p = &parts[pk->kept[k]];
        if (pk->level[k] != open_level ||
            !fits(pk, pk->packs - 1, p->layer_bound, oit_pack_part_bytes(p))) {
            open_pack(pk, pk->packs++, pk->drawn, p->layer_bound);
            open_level = pk->level[k];
        }
        place(pk, pk->packs - 1, pk->kept[k], pk->kept_rects[k]);
    }
    return OIT_OK;
}

oit_status oit_packer_run(oit_packer *pk, const oit_view *view, const uint32_t *order,
                          uint32_t n, oit_packing *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    oit_status s = fit_tiles(pk, view, err);
    if (s != OIT_OK)
        return s;
    uint32_t kept = cull(pk, view, order, n, out);
    pk->drawn = pk->packs = 0;
    if (pk->schedule == OIT_RENDER_SCHEDULE_WAVE && pk->mode == OIT_RENDER_PACK_DISJOINT) {
        s = pack_levels(pk, kept, view->width, view->height, err);
        if (s != OIT_OK)
            return s;
    } else if (pk->schedule == OIT_RENDER_SCHEDULE_WAVE) {
        oit_schedule_packer sp = {pk, wave_open, wave_join};
        s = oit_schedule_run(pk->scheduler, kept, (const int(*)[4])pk->kept_rects,
                             pk->kept_near, view->width, view->height, &sp, NULL, err);
        if (s != OIT_OK)
            return s;
    } else {
        pack_in_order(pk, kept);
    }
    pk->pack_first[pk->packs] = pk->drawn;
    out->parts = pk->parts;
    out->part_count = pk->drawn;
    out->pack_first = pk->pack_first;
    out->rects = (const int(*)[4])pk->rects;
    out->part_rects = (const int(*)[4])pk->part_rects;
    out->bytes = pk->bytes;
    out->layers = pk->layers;
    out->pack_count = pk->packs;
    out->culled = n - kept - out->clipped;
    return OIT_OK;
}
