/* partfile/order.h: view culling of subgrids that stick out of their parent
 * cells, as a property over random files and random views.
 *
 * A subgrid covers its parent cell and may reach beyond it on any side
 * (docs/part-file.md: a two-cell subgrid puts its one boundary anywhere), and
 * the parts in its cells need only lie in those cells; so a part can lie
 * wholly outside the cell that stands for it in the grid above, two levels
 * up even further. Each round writes a random file: a top grid of 1-3 cells
 * an axis, cells refined (to depth 3) by subgrids of 1-2 cells an axis that
 * stick out of the region their parent cell stands for by up to 1.5 times
 * its size on random sides, and a
 * small triangle part somewhere in most leaf cells. Views look at a random
 * part (most often one that lies outside its top cell, or two levels down
 * outside its first subgrid) from random directions and distances, or from
 * beyond it back at its top cell with the far plane just behind it, narrow
 * or wide, perspective and orthographic.
 * Asserted for every view, against the unculled order:
 *   - the culled order keeps the full order's relative order;
 *   - every part it leaves out lies wholly outside one frustum plane (all 8
 *     corners of its box);
 * the same for a chain of three one-cell subgrids along each axis, either
 * way, whose overhangs add up: the part at its far end, seen from beyond with
 * the far plane just behind it, must be kept;
 * and over the run: views kept parts whose top cell lies wholly outside a
 * plane ("rescued"), and parts two subgrids down whose first subgrid's box
 * lies wholly outside a plane ("rescued two levels down"), so a cull by the
 * parent boxes alone, or by one level of overhang, fails the test. */
#include "oit/partfile.h"
#include "partfile/write.h"
#include "partfile/order.h"
#include "view/render/image/view.h"
#include "tests/lib/test_rng.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_files.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_GRIDS = 48, MAX_CELLS = 27, MAX_PARTS = 400, ROUNDS = 24, VIEWS = 60 };

static float unit(rng *r)
{
    return (float)rnd(r, 1u << 24) / (float)(1u << 24);
}

typedef struct grid {
    uint32_t dims[3];
    float origin[3], size[3];
    uint32_t parent, parent_cell, depth;
    /* What the grid stands for, as the reader checks it: its parent cell
     * within the parent's region (the top grid: its box). */
    double rlo[3], rhi[3];
    int32_t child[MAX_CELLS]; /* subgrid refining the cell, or -1 */
    int32_t part[MAX_CELLS];  /* the leaf cell's part, or -1 */
    uint32_t counts[MAX_CELLS], list[MAX_CELLS];
} grid;

typedef struct scene {
    grid g[MAX_GRIDS];
    uint32_t ng;
    float tri[MAX_PARTS][9];
    float lo[MAX_PARTS][3], hi[MAX_PARTS][3];
    uint32_t grid_of[MAX_PARTS]; /* the leaf's grid */
    uint32_t np;
} scene;

static void cell_box(const grid *g, uint32_t c, double lo[3], double hi[3])
{
    uint32_t i[3] = {c % g->dims[0], c / g->dims[0] % g->dims[1], c / g->dims[0] / g->dims[1]};
    for (int k = 0; k < 3; k++) {
        lo[k] = (double)g->origin[k] + (double)i[k] * g->size[k];
        hi[k] = lo[k] + g->size[k];
    }
}

static void grid_box(const grid *g, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = g->origin[k];
        hi[k] = (double)g->origin[k] + (double)g->dims[k] * g->size[k];
    }
}

static uint32_t cells_of(const grid *g)
{
    return g->dims[0] * g->dims[1] * g->dims[2];
}

/* A subgrid over the region [lo, hi] of 1-2 cells an axis, reaching out by
 * up to 1.5 times the region on each side that draws an overhang. */
static void make_subgrid(rng *r, grid *s, const double lo[3], const double hi[3])
{
    for (int k = 0; k < 3; k++) {
        s->rlo[k] = lo[k];
        s->rhi[k] = hi[k];
        double w = hi[k] - lo[k];
        double out_lo = rnd(r, 5) < 2 ? 0.0 : 1.5 * w * unit(r);
        double out_hi = rnd(r, 5) < 2 ? 0.0 : 1.5 * w * unit(r);
        s->dims[k] = 1 + rnd(r, 2);
        s->origin[k] = (float)(lo[k] - out_lo);
        /* a float cell size that rounds up: the subgrid still covers hi */
        s->size[k] = nextafterf((float)((hi[k] + out_hi - s->origin[k]) / s->dims[k]), INFINITY);
    }
}

/* A triangle spanning a random sub-box (10-60% a side) of the cell, inset
 * by a thousandth so that its float corners stay inside the cell. */
static void make_part(rng *r, scene *sc, uint32_t gi, const double lo[3], const double hi[3])
{
    uint32_t p = sc->np++;
    double blo[3], bhi[3];
    for (int k = 0; k < 3; k++) {
        double w = (hi[k] - lo[k]) * 0.998, f = 0.1 + 0.5 * unit(r);
        blo[k] = lo[k] + 0.001 * (hi[k] - lo[k]) + (1.0 - f) * w * unit(r);
        bhi[k] = blo[k] + f * w;
    }
    /* (lo lo lo), (hi * *), (* hi hi): the triangle's box is the sub-box */
    double v[3][3] = {{blo[0], blo[1], blo[2]},
                      {bhi[0], blo[1] + unit(r) * (bhi[1] - blo[1]), blo[2] + unit(r) * (bhi[2] - blo[2])},
                      {blo[0] + unit(r) * (bhi[0] - blo[0]), bhi[1], bhi[2]}};
    for (int i = 0; i < 9; i++)
        sc->tri[p][i] = (float)v[i / 3][i % 3];
    for (int k = 0; k < 3; k++) {
        sc->lo[p][k] = fminf(sc->tri[p][k], fminf(sc->tri[p][3 + k], sc->tri[p][6 + k]));
        sc->hi[p][k] = fmaxf(sc->tri[p][k], fmaxf(sc->tri[p][3 + k], sc->tri[p][6 + k]));
    }
    sc->grid_of[p] = gi;
}

static void make_scene(rng *r, scene *sc)
{
    memset(sc, 0, sizeof *sc);
    grid *top = &sc->g[0];
    for (int k = 0; k < 3; k++) {
        top->dims[k] = 1 + rnd(r, 3);
        top->origin[k] = (float)rnd(r, 20) - 10.0f;
        top->size[k] = 0.5f + 1.5f * unit(r);
    }
    top->parent = top->parent_cell = OIT_PARTFILE_NONE;
    grid_box(top, top->rlo, top->rhi);
    sc->ng = 1;
    for (uint32_t gi = 0; gi < sc->ng; gi++) {
        grid *g = &sc->g[gi];
        for (uint32_t c = 0; c < cells_of(g); c++) {
            double lo[3], hi[3], rlo[3], rhi[3];
            cell_box(g, c, lo, hi);
            /* a cell wholly in its grid's overhang stands for no region: the
             * reader refuses a subgrid there, so it stays a leaf */
            int region = 1;
            for (int k = 0; k < 3; k++) {
                rlo[k] = fmax(lo[k], g->rlo[k]);
                rhi[k] = fmin(hi[k], g->rhi[k]);
                region &= rlo[k] < rhi[k];
            }
            g->child[c] = g->part[c] = -1;
            if (region && g->depth < 3 && sc->ng < MAX_GRIDS && rnd(r, 100) < 45) {
                grid *s = &sc->g[sc->ng];
                make_subgrid(r, s, rlo, rhi);
                s->parent = gi;
                s->parent_cell = c;
                s->depth = g->depth + 1;
                g->child[c] = (int32_t)sc->ng++;
            } else if (sc->np < MAX_PARTS && rnd(r, 100) < 85) {
                g->part[c] = (int32_t)sc->np;
                make_part(r, sc, gi, lo, hi);
            }
        }
    }
}

static oit_status write_scene(const char *path, scene *sc, oit_error *err)
{
    oit_partfile_writer *w = NULL;
    oit_status s = oit_partfile_writer_create(path, NULL, &w, err);
    if (s)
        return s;
    static const uint32_t idx[3] = {0, 1, 2};
    for (uint32_t p = 0; !s && p < sc->np; p++) {
        uint32_t src = p, index = 0;
        oit_partfile_piece_desc piece = {1, 1};
        oit_partfile_part_desc d = {.positions = sc->tri[p], .vertex_count = 3, .indices = idx,
                                    .index_count = 3, .sources = &src, .pieces = &piece,
                                    .piece_count = 1};
        s = oit_partfile_writer_add_part(w, &d, &index, err);
    }
    for (uint32_t gi = 0; !s && gi < sc->ng; gi++) {
        grid *g = &sc->g[gi];
        uint32_t n = 0;
        for (uint32_t c = 0; c < cells_of(g); c++) {
            g->counts[c] = g->part[c] >= 0;
            if (g->part[c] >= 0)
                g->list[n++] = (uint32_t)g->part[c];
        }
        oit_partfile_grid_desc d = {{g->dims[0], g->dims[1], g->dims[2]},
                                    {g->origin[0], g->origin[1], g->origin[2]},
                                    {g->size[0], g->size[1], g->size[2]},
                                    g->parent, g->parent_cell, g->counts, g->list};
        uint32_t index = 0;
        s = gi ? oit_partfile_writer_add_subgrid(w, &d, &index, err)
               : oit_partfile_writer_set_grid(w, &d, err);
        if (!s && index != gi)
            s = oit_error_set(err, OIT_ERR_ARGUMENT, "subgrid %u written as %u", gi, index);
    }
    if (s) {
        oit_partfile_writer_abort(w);
        return s;
    }
    return oit_partfile_writer_finish(w, NULL, err);
}

/* ---- the oracle ---------------------------------------------------------------- */

/* 1 when every corner of [lo, hi] lies outside one of the planes. */
static int box_outside(const float (*planes)[4], const double lo[3], const double hi[3])
{
    for (int q = 0; q < 6; q++) {
        int all = 1;
        for (int c = 0; c < 8 && all; c++) {
            double x = c & 1 ? hi[0] : lo[0], y = c & 2 ? hi[1] : lo[1], z = c & 4 ? hi[2] : lo[2];
            all = planes[q][0] * x + planes[q][1] * y + planes[q][2] * z + planes[q][3] < 0;
        }
        if (all)
            return 1;
    }
    return 0;
}

static int part_outside(const scene *sc, const float (*planes)[4], uint32_t p)
{
    double lo[3] = {sc->lo[p][0], sc->lo[p][1], sc->lo[p][2]};
    double hi[3] = {sc->hi[p][0], sc->hi[p][1], sc->hi[p][2]};
    return box_outside(planes, lo, hi);
}

/* The grids on the path from the top to part p's leaf: path[0] = 0. */
static uint32_t path_of(const scene *sc, uint32_t p, uint32_t path[4])
{
    uint32_t n = 0, chain[8];
    for (uint32_t g = sc->grid_of[p]; g != OIT_PARTFILE_NONE && n < 8; g = sc->g[g].parent)
        chain[n++] = g;
    for (uint32_t i = 0; i < n && i < 4; i++)
        path[i] = chain[n - 1 - i];
    return n;
}

/* The top cell that stands for part p. */
static void top_cell_box(const scene *sc, uint32_t p, double lo[3], double hi[3])
{
    uint32_t path[4], n = path_of(sc, p, path);
    grid_box(&sc->g[0], lo, hi);
    if (n == 1) {
        for (uint32_t c = 0; c < cells_of(&sc->g[0]); c++)
            if (sc->g[0].part[c] == (int32_t)p)
                cell_box(&sc->g[0], c, lo, hi);
        return;
    }
    cell_box(&sc->g[0], sc->g[path[1]].parent_cell, lo, hi);
}

typedef struct tally {
    unsigned long views, culled, rescued, rescued_deep, bad;
} tally;

static void check_view(tally *t, oit_order *o, const scene *sc, const oit_camera *cam, int ortho,
                       const float dir[3])
{
    float planes[6][4];
    oit_camera_frustum(cam, 1.3f, planes);
    const float(*pl)[4] = (const float(*)[4])planes;
    uint32_t full[MAX_PARTS], kept[MAX_PARTS], nf = 0, nk = 0;
    oit_error err = {0};
    oit_status s = ortho ? oit_order_compute_parallel(o, dir, NULL, full, &nf, &err)
                         : oit_order_compute(o, cam->eye, full, &nf, &err);
    if (!s)
        s = ortho ? oit_order_compute_parallel(o, dir, pl, kept, &nk, &err)
                  : oit_order_compute_culled(o, cam->eye, pl, kept, &nk, &err);
    CHECK(s == OIT_OK && nf == sc->np, "order: %s (%u of %u parts)", err.message, nf, sc->np);
    if (s)
        return;
    uint32_t j = 0;
    for (uint32_t k = 0; k < nf; k++) {
        uint32_t p = full[k];
        if (j < nk && kept[j] == p) {
            j++;
            if (part_outside(sc, pl, p))
                continue;
            double lo[3], hi[3];
            top_cell_box(sc, p, lo, hi);
            t->rescued += box_outside(pl, lo, hi);
            uint32_t path[4];
            if (path_of(sc, p, path) >= 3) {
                grid_box(&sc->g[path[1]], lo, hi);
                t->rescued_deep += box_outside(pl, lo, hi);
            }
            continue;
        }
        t->culled++;
        if (!part_outside(sc, pl, p)) {
            t->bad++;
            CHECK(0, "%s view from (%g %g %g) to (%g %g %g) fov %g: part %u (grid %u, box "
                  "(%g %g %g)..(%g %g %g)) left out, though no plane has it outside",
                  ortho ? "orthographic" : "perspective", cam->eye[0], cam->eye[1], cam->eye[2],
                  cam->target[0], cam->target[1], cam->target[2], cam->fovy_deg, p,
                  sc->grid_of[p], sc->lo[p][0], sc->lo[p][1], sc->lo[p][2], sc->hi[p][0],
                  sc->hi[p][1], sc->hi[p][2]);
        }
    }
    CHECK(j == nk, "a kept part is out of the full order's order (%u of %u matched)", j, nk);
    t->views++;
}

/* 1 when part p pokes out of [lo, hi]. */
static int pokes_out(const scene *sc, uint32_t p, const double lo[3], const double hi[3])
{
    for (int k = 0; k < 3; k++)
        if (sc->lo[p][k] < lo[k] || sc->hi[p][k] > hi[k])
            return 1;
    return 0;
}

/* Most often a part that lies outside its top cell, or (every other view)
 * two subgrids down outside its first subgrid's box, when there is one. */
static uint32_t pick_target(rng *r, const scene *sc, int deep)
{
    uint32_t start = rnd(r, sc->np);
    for (uint32_t i = 0; rnd(r, 8) && i < sc->np; i++) {
        uint32_t p = (start + i) % sc->np, path[4];
        double lo[3], hi[3];
        if (deep && path_of(sc, p, path) < 3)
            continue;
        if (deep)
            grid_box(&sc->g[path[1]], lo, hi);
        else
            top_cell_box(sc, p, lo, hi);
        if (pokes_out(sc, p, lo, hi))
            return p;
    }
    return start;
}

static void check_views(tally *t, rng *r, oit_order *o, const scene *sc)
{
    for (int v = 0; v < VIEWS; v++) {
        uint32_t p = pick_target(r, sc, v % 2);
        float target[3], dir[3];
        double len = 0, lo[3], hi[3];
        /* every other view looks from beyond the part back at its top cell,
         * the far plane just behind the part: the cell is out of view */
        int back = v % 4 < 2;
        top_cell_box(sc, p, lo, hi);
        for (int k = 0; k < 3; k++) {
            target[k] = (sc->tri[p][k] + sc->tri[p][3 + k] + sc->tri[p][6 + k]) / 3.0f;
            dir[k] = 2.0f * unit(r) - 1.0f;
            if (back)
                dir[k] = (float)(0.5 * (lo[k] + hi[k]) - target[k]) + 0.3f * dir[k];
            len += (double)dir[k] * dir[k];
        }
        if (len < 1e-4)
            dir[2] = 1.0f, len = 1.0;
        float dist = 0.5f + 12.0f * unit(r);
        oit_camera cam;
        memset(&cam, 0, sizeof cam);
        for (int k = 0; k < 3; k++) {
            dir[k] = (float)(dir[k] / sqrt(len));
            cam.target[k] = target[k];
            cam.eye[k] = target[k] - dist * dir[k];
        }
        int vertical = fabsf(dir[1]) > 0.9f;
        cam.up[vertical ? 0 : 1] = 1.0f;
        cam.fovy_deg = 2.0f + 40.0f * unit(r);
        cam.znear = 0.05f;
        cam.zfar = dist + (back ? 0.05f + 0.5f * unit(r) : 0.5f + 10.0f * unit(r));
        int ortho = v % 3 == 2;
        if (ortho) {
            cam.projection = OIT_PROJ_ORTHOGRAPHIC;
            cam.ortho_height = 0.2f + 2.0f * unit(r);
            cam.znear = -1.0f;
        }
        check_view(t, o, sc, &cam, ortho, dir);
    }
}

/* A chain of three one-cell subgrids over the unit cell, each reaching
 * further out along axis a (side +1 or -1) than the one before: 0.5 beyond
 * the top cell, 1.0 beyond the first subgrid's cell, 1.5 beyond the
 * second's, so their overhangs add up to 3; the one part lies at the far
 * end, between 2.8 and 2.95 out. The views look back at it from 0.5 beyond
 * its middle, the far plane at 0.65: the top cell grown by less than the
 * sum is out of view, the part is not. */
static void chain_scene(scene *sc, int a, int side)
{
    memset(sc, 0, sizeof *sc);
    static const double reach[4] = {0.0, 0.5, 1.5, 3.0};
    for (uint32_t g = 0; g < 4; g++) {
        grid *gr = &sc->g[g];
        for (int k = 0; k < 3; k++) {
            gr->dims[k] = 1;
            gr->rlo[k] = 0.0, gr->rhi[k] = 1.0;
            gr->origin[k] = 0.0f;
            gr->size[k] = 1.0f;
        }
        gr->origin[a] = side > 0 ? 0.0f : (float)-reach[g];
        gr->size[a] = (float)(1.0 + reach[g]);
        gr->parent = g ? g - 1 : OIT_PARTFILE_NONE;
        gr->parent_cell = g ? 0 : OIT_PARTFILE_NONE;
        gr->depth = g;
        gr->child[0] = g < 3 ? (int32_t)g + 1 : -1;
        gr->part[0] = g < 3 ? -1 : 0;
    }
    sc->ng = 4;
    sc->np = 1;
    sc->grid_of[0] = 3;
    double lo[3] = {0.4, 0.4, 0.4}, hi[3] = {0.6, 0.6, 0.6};
    lo[a] = side > 0 ? 3.8 : -2.95;
    hi[a] = side > 0 ? 3.95 : -2.8;
    double v[3][3] = {{lo[0], lo[1], lo[2]}, {hi[0], lo[1], hi[2]}, {lo[0], hi[1], hi[2]}};
    for (int i = 0; i < 9; i++)
        sc->tri[0][i] = (float)v[i / 3][i % 3];
    for (int k = 0; k < 3; k++) {
        sc->lo[0][k] = (float)lo[k];
        sc->hi[0][k] = (float)hi[k];
    }
}

static void check_chains(tally *t, const char *path)
{
    static scene sc;
    for (int a = 0; a < 3; a++)
        for (int side = -1; side <= 1; side += 2) {
            chain_scene(&sc, a, side);
            oit_error err = {0};
            oit_partfile *pf = NULL;
            oit_order *o = NULL;
            if (write_scene(path, &sc, &err) || oit_partfile_open(path, NULL, &pf, &err) ||
                oit_order_create(pf, &o, &err)) {
                CHECK(0, "chain along %d (%+d): %s", a, side, err.message);
                oit_partfile_close(pf);
                continue;
            }
            for (int ortho = 0; ortho < 2; ortho++) {
                oit_camera cam;
                memset(&cam, 0, sizeof cam);
                float dir[3] = {0, 0, 0};
                dir[a] = (float)-side;
                for (int k = 0; k < 3; k++)
                    cam.target[k] = cam.eye[k] = 0.5f;
                cam.target[a] = side > 0 ? 3.9f : -2.9f;
                cam.eye[a] = cam.target[a] + 0.5f * (float)side;
                cam.up[a == 1 ? 0 : 1] = 1.0f;
                cam.fovy_deg = 30.0f;
                cam.znear = 0.05f;
                cam.zfar = 0.65f;
                if (ortho) {
                    cam.projection = OIT_PROJ_ORTHOGRAPHIC;
                    cam.ortho_height = 1.0f;
                }
                unsigned long before = t->bad;
                check_view(t, o, &sc, &cam, ortho, dir);
                CHECK(t->bad == before, "chain along axis %d (%+d): the part three overhangs "
                      "out was culled", a, side);
            }
            oit_order_destroy(o);
            oit_partfile_close(pf);
        }
}

int main(void)
{
    char path[600];
    test_tmp_path(path, sizeof path, "order_cull.oitp");
    static scene sc;
    rng r = {7201u};
    tally t = {0};
    unsigned long grids = 0, parts = 0;
    for (int round = 0; round < ROUNDS; round++) {
        make_scene(&r, &sc);
        if (sc.np == 0)
            continue;
        oit_error err = {0};
        oit_partfile *pf = NULL;
        oit_order *o = NULL;
        if (write_scene(path, &sc, &err) || oit_partfile_open(path, NULL, &pf, &err) ||
            oit_order_create(pf, &o, &err)) {
            CHECK(0, "round %d: %s", round, err.message);
            oit_partfile_close(pf);
            continue;
        }
        grids += sc.ng;
        parts += sc.np;
        check_views(&t, &r, o, &sc);
        oit_order_destroy(o);
        oit_partfile_close(pf);
    }
    check_chains(&t, path);
    remove(path);
    printf("%d files (%lu grids, %lu parts), %lu views: %lu parts culled, %lu wrongly; kept "
           "parts outside their top cell's view: %lu, outside their first subgrid's: %lu\n",
           ROUNDS, grids, parts, t.views, t.culled, t.bad, t.rescued, t.rescued_deep);
    CHECK(t.culled > 0, "no view culled a part: the views miss the point");
    CHECK(t.rescued > 0 && t.rescued_deep > 0,
          "no view needed the overhang of a subgrid (%lu) or of a nested one (%lu)", t.rescued,
          t.rescued_deep);
    return test_verdict();
}
