/* Writes a part file for the streamer's integration test (test_streamer.sh)
 * with the writer API, as a converter would: a 6x5x4 grid of unit cells,
 * each holding one closed convex box (one piece, 2 layers) or a box with an
 * octahedron nested inside it (two pieces, 4 layers), some cells empty; one
 * cell refined by a 2x2x1 subgrid; one cell holding a slab (normal +z) with
 * a box below, a thin box inside and a box above. Every part lies inside its
 * leaf cell and is listed by that cell only, as partfile/order.h requires; colours
 * and alphas vary per shape; extents are jittered so no two faces are
 * coplanar.
 *
 * usage: test_streamer OUT.oitp [--bad-slab | --understated-bound | --measured |
 *                                --measured-swapped]
 * --bad-slab moves the slab's planes 0.05 up, so the inside box reaches
 * below d0; --understated-bound records the slab's lower box with layer
 * bound 1, though rays meet it twice: files oitprep verify
 * must reject (tests/prepare/convert/test_verify_slab.sh). --measured writes that bound in a
 * file flagged as of measured bounds, which verify must pass, reporting the
 * excess; --measured-swapped also swaps the slab's two parts, so the lower
 * box is drawn as if above: order and slab violations verify must fail even
 * with measured bounds. */
#include <stdio.h>
#include <string.h>

#include "oit/mesh.h"
#include "oit/partfile.h"
#include "partfile/write.h"

enum { NX = 6, NY = 5, NZ = 4, CELLS = NX * NY * NZ, MAXV = 32, MAXI = 64 };

typedef struct shape {
    float pos[MAXV][3];
    uint8_t rgba[MAXV][4];
    uint32_t idx[MAXI * 3];
    uint32_t nv, ni;
    oit_partfile_piece_desc pieces[2];
    uint32_t piece_count;
    uint32_t layer_bound; /* 0: the writer's default */
} shape;

static uint32_t rng_next(uint32_t *r)
{
    *r = *r * 1664525u + 1013904223u;
    return *r >> 8;
}

static float rng_unit(uint32_t *r)
{
    return (float)rng_next(r) / 16777216.0f;
}

static void colour(shape *s, uint32_t first, uint32_t *r)
{
    uint8_t c[4] = {(uint8_t)(40 + rng_next(r) % 200), (uint8_t)(40 + rng_next(r) % 200),
                    (uint8_t)(40 + rng_next(r) % 200), (uint8_t)(60 + rng_next(r) % 120)};
    for (uint32_t v = first; v < s->nv; v++)
        memcpy(s->rgba[v], c, 4);
}

/* An axis-aligned box, counter-clockwise seen from outside. */
static void add_box(shape *s, const float lo[3], const float hi[3], uint32_t *r)
{
    static const uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                          {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                          {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    uint32_t base = s->nv;
    for (uint32_t k = 0; k < 8; k++) {
        s->pos[s->nv][0] = k & 1 ? hi[0] : lo[0];
        s->pos[s->nv][1] = k & 2 ? hi[1] : lo[1];
        s->pos[s->nv][2] = k & 4 ? hi[2] : lo[2];
        s->nv++;
    }
    for (int t = 0; t < 12; t++)
        for (int k = 0; k < 3; k++)
            s->idx[s->ni++] = base + faces[t][k];
    colour(s, base, r);
    s->pieces[s->piece_count++] = (oit_partfile_piece_desc){12, 6};
}

/* An octahedron around c with radii h, outward counter-clockwise. */
static void add_octahedron(shape *s, const float c[3], const float h[3], uint32_t *r)
{
    uint32_t base = s->nv;
    for (int k = 0; k < 6; k++) {
        for (int a = 0; a < 3; a++)
            s->pos[s->nv][a] = c[a];
        s->pos[s->nv][k / 2] += k & 1 ? h[k / 2] : -h[k / 2];
        s->nv++;
    }
    /* vertex 2a+1 is +axis a; each face takes one of +-x, +-y, +-z. */
    for (int f = 0; f < 8; f++) {
        uint32_t x = base + (f & 1), y = base + 2 + ((f >> 1) & 1), z = base + 4 + ((f >> 2) & 1);
        int flip = (f & 1) ^ ((f >> 1) & 1) ^ ((f >> 2) & 1);
        s->idx[s->ni++] = x;
        s->idx[s->ni++] = flip ? y : z;
        s->idx[s->ni++] = flip ? z : y;
    }
    colour(s, base, r);
    s->pieces[s->piece_count++] = (oit_partfile_piece_desc){8, 8};
}

/* A box jittered inside [lo, hi] (10%..30% margins per side). */
static void jitter_box(const float lo[3], const float hi[3], float out_lo[3], float out_hi[3],
                       uint32_t *r)
{
    for (int k = 0; k < 3; k++) {
        float w = hi[k] - lo[k];
        out_lo[k] = lo[k] + w * (0.1f + 0.2f * rng_unit(r));
        out_hi[k] = hi[k] - w * (0.1f + 0.2f * rng_unit(r));
    }
}

/* Triangles written to the file so far (reset per file): each part's
 * source indices are its file positions, reversed within the part, so
 * that they are a permutation of the file's triangles but not their
 * order, and the stream's prim (the source index) and DFB's on the loaded
 * mesh (its position, sorted by source index) agree only if both follow
 * the indices. */
static uint32_t written_triangles;

static int write_shape(oit_partfile_writer *w, const shape *s, uint32_t *index, oit_error *err)
{
    uint32_t src[MAXI], n = s->ni / 3;
    for (uint32_t t = 0; t < n; t++)
        src[t] = written_triangles + (n - 1 - t);
    written_triangles += n;
    oit_partfile_part_desc d = {0};
    d.sources = src;
    d.positions = &s->pos[0][0];
    d.rgba = &s->rgba[0][0];
    d.vertex_count = s->nv;
    d.indices = s->idx;
    d.index_count = s->ni;
    d.pieces = s->pieces;
    d.piece_count = s->piece_count;
    d.layer_bound = s->layer_bound;
    d.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    return oit_partfile_writer_add_part(w, &d, index, err) == OIT_OK ? 0 : -1;
}

/* One box, or a box with an octahedron inside, in the cell [lo, hi]. */
static int cell_part(oit_partfile_writer *w, const float lo[3], const float hi[3], uint32_t *r,
                     uint32_t *index, oit_error *err)
{
    shape s = {0};
    float blo[3], bhi[3];
    jitter_box(lo, hi, blo, bhi, r);
    add_box(&s, blo, bhi, r);
    if (rng_next(r) % 3 == 0) {
        float c[3], h[3];
        for (int k = 0; k < 3; k++) {
            c[k] = 0.5f * (blo[k] + bhi[k]);
            h[k] = (0.3f + 0.15f * rng_unit(r)) * (bhi[k] - blo[k]);
        }
        add_octahedron(&s, c, h, r);
    }
    return write_shape(w, &s, index, err);
}

static const uint32_t SUB_CELL = 2 + NX * (2 + NY * 1), SLAB_CELL = 4 + NX * (1 + NY * 2);

/* Deliberate flaws for oitprep verify's tests. */
enum { FLAW_NONE, FLAW_SLAB, FLAW_BOUND, FLAW_MEASURED, FLAW_MEASURED_SWAPPED };

static int write_scene(const char *path, int flaw, oit_error *err)
{
    int bad_slab = flaw == FLAW_SLAB;
    oit_partfile_writer_desc wd = {0};
    wd.K = 8;
    wd.attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    wd.source_name = "test_streamer grid of convex shapes";
    wd.measured_bounds = flaw == FLAW_MEASURED || flaw == FLAW_MEASURED_SWAPPED;
    oit_partfile_writer *w = NULL;
    written_triangles = 0;
    if (oit_partfile_writer_create(path, &wd, &w, err) != OIT_OK)
        return -1;
    uint32_t r = 2024u, counts[CELLS] = {0}, list[CELLS + 4], used = 0;
    uint32_t sub_counts[4] = {0}, sub_list[4], slab_parts[3];
    for (uint32_t c = 0; c < CELLS; c++) {
        float lo[3] = {(float)(c % NX), (float)(c / NX % NY), (float)(c / (NX * NY))};
        float hi[3] = {lo[0] + 1, lo[1] + 1, lo[2] + 1};
        int ok = 0;
        if (c == SUB_CELL) {
            for (uint32_t q = 0; q < 4 && ok == 0; q++) {
                float slo[3] = {lo[0] + 0.5f * (q & 1), lo[1] + 0.5f * (q >> 1), lo[2]};
                float shi[3] = {slo[0] + 0.5f, slo[1] + 0.5f, hi[2]};
                ok = cell_part(w, slo, shi, &r, &sub_list[q], err);
                sub_counts[q] = 1;
            }
        } else if (c == SLAB_CELL) {
            const float z[4] = {0.05f, 0.4f, 0.6f, 0.95f};
            for (int k = 0; k < 3 && ok == 0; k++) {
                shape s = {0};
                float slo[3] = {lo[0] + 0.1f + 0.03f * k, lo[1] + 0.12f - 0.02f * k, lo[2] + z[k]};
                float shi[3] = {hi[0] - 0.08f - 0.02f * k, hi[1] - 0.1f + 0.01f * k,
                                lo[2] + z[k + 1] - 0.02f};
                add_box(&s, slo, shi, &r);
                if ((flaw == FLAW_BOUND || wd.measured_bounds) && k == 0)
                    s.layer_bound = 1; /* a ray meets the closed box twice */
                ok = write_shape(w, &s, &slab_parts[k], err);
            }
            counts[c] = 3;
            memcpy(list + used, slab_parts, sizeof slab_parts);
            used += 3;
        } else if (rng_next(&r) % 7 != 0) {
            ok = cell_part(w, lo, hi, &r, &list[used], err);
            counts[c] = 1;
            used++;
        }
        if (ok != 0) {
            oit_partfile_writer_abort(w);
            return -1;
        }
    }
    oit_partfile_grid_desc top = {{NX, NY, NZ}, {0, 0, 0}, {1, 1, 1}, OIT_PARTFILE_NONE,
                                  OIT_PARTFILE_NONE, counts, list};
    float slo[3] = {(float)(SUB_CELL % NX), (float)(SUB_CELL / NX % NY), (float)(SUB_CELL / (NX * NY))};
    oit_partfile_grid_desc sub = {{2, 2, 1}, {slo[0], slo[1], slo[2]}, {0.5f, 0.5f, 1.0f}, 0,
                                  SUB_CELL, sub_counts, sub_list};
    float zc = (float)(SLAB_CELL / (NX * NY)) + (bad_slab ? 0.05f : 0.0f);
    int swap = flaw == FLAW_MEASURED_SWAPPED;
    oit_partfile_slab_desc slab = {{0, 0, 1}, zc + 0.4f - 0.01f, zc + 0.6f - 0.01f, 0, SLAB_CELL,
                                   slab_parts[swap ? 2 : 0], slab_parts[swap ? 0 : 2],
                                   &slab_parts[1], 1};
    uint32_t g = 0, sl = 0;
    if (oit_partfile_writer_set_grid(w, &top, err) != OIT_OK ||
        oit_partfile_writer_add_subgrid(w, &sub, &g, err) != OIT_OK ||
        oit_partfile_writer_add_slab(w, &slab, &sl, err) != OIT_OK) {
        oit_partfile_writer_abort(w);
        return -1;
    }
    return oit_partfile_writer_finish(w, NULL, err) == OIT_OK ? 0 : -1;
}

int main(int argc, char **argv)
{
    int flaw = argc == 3 && !strcmp(argv[2], "--bad-slab")           ? FLAW_SLAB
               : argc == 3 && !strcmp(argv[2], "--understated-bound")  ? FLAW_BOUND
               : argc == 3 && !strcmp(argv[2], "--measured")           ? FLAW_MEASURED
               : argc == 3 && !strcmp(argv[2], "--measured-swapped")   ? FLAW_MEASURED_SWAPPED
                                                                       : FLAW_NONE;
    if (argc != 2 && flaw == FLAW_NONE) {
        fprintf(stderr, "usage: test_streamer OUT.oitp [--bad-slab | --understated-bound | "
                        "--measured | --measured-swapped]\n");
        return 2;
    }
    oit_error err = {0};
    if (write_scene(argv[1], flaw, &err) != 0) {
        fprintf(stderr, "test_streamer: %s\n", err.message);
        return 1;
    }
    return 0;
}
