/* Source indices of a converted file against its source mesh: every part
 * triangle's source index names a triangle of the source (as oit_mesh_load
 * delivers it), and each source triangle's area is accounted for by the
 * pieces carrying its index: their areas sum to its own (relative 1e-4),
 * zero for the ones the converter drops (degenerate). A triangle clipped
 * into pieces has new vertices rounded to float (onto a cutting plane, too:
 * prepare/partition/plane_exact.h), which moves its area by up to a few units in
 * the last place of its coordinates times its edges: beyond 1e-4 of the
 * area for small triangles far from the origin and for slivers (and a
 * sliver whose other pieces rounded to nothing may keep one piece). Those
 * are allowed that rounding, max(pieces, 2) x 8 FLT_EPSILON x max
 * |coordinate| x the longest edge, and counted apart; a piece given another triangle's index
 * moves two sums by a whole area. A wrong, shuffled or lost index breaks the sums. Also counts
 * parts whose triangles are not in ascending source order (reported, and
 * failed with --ascending, which the fast scheme guarantees). That the
 * sums can fail is checked on the data itself: the same accounting with
 * every index s read as count - 1 - s (a shuffle) must find mismatches.
 *
 * usage: test_sources SOURCE FILE.oitp [--ascending]
 *        test_sources --write-tie FILE.oitp [TRIANGLES_IN]
 * Exit 0 when every check holds, 1 otherwise, 2 on usage, 3 on bad input.
 *
 * --write-tie writes the part file of tests/view/stream/test_source_prims.sh: the two
 * unit boxes of its tie.ply (box A red, B blue, alpha 100, A's 12 triangles
 * first in the source) as one part that stores B's triangles first, with
 * their source indices (12..23, then A's 0..11): drawn by position, B would
 * win every tie; drawn by source index, A does, as on the source mesh.
 * TRIANGLES_IN (default 24) is what META records as read from the source:
 * far more than the file holds sends oit_partfile_load_mesh down its sort
 * by keys instead of its counting sort. */
#include "oit/mesh.h"
#include "oit/partfile.h"
#include "partfile/write.h"
#include "base/vec.h"
#include "prepare/partition/clip.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static void vertex(const oit_partfile_part_view *v, uint64_t i, float out[3])
{
    memcpy(out, (const char *)v->positions + (size_t)oit_partfile_index(v, i) * v->stride, 12);
}

/* The boxes' vertex i of 8 (as the test's awk writes them) and triangles. */
static const uint32_t BOX_TRIS[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                      2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};

static int write_tie(const char *path, uint64_t triangles_in)
{
    static const uint8_t colour[2][4] = {{230, 40, 40, 100}, {40, 60, 230, 100}};
    float pos[16 * 3];
    uint8_t rgba[16 * 4];
    uint32_t idx[72], src[24];
    /* Vertices 0..7: box B, 8..15: box A; triangles B's first. */
    for (int b = 0; b < 2; b++)
        for (int i = 0; i < 8; i++) {
            float *p = pos + 3 * (8 * b + i);
            p[0] = (float)(i % 2) - 0.5f;
            p[1] = (float)(i / 2 % 2) - 0.5f;
            p[2] = (float)(i / 4) - 0.5f;
            memcpy(rgba + 4 * (8 * b + i), colour[1 - b], 4);
        }
    for (int b = 0; b < 2; b++)
        for (int t = 0; t < 12; t++) {
            for (int c = 0; c < 3; c++)
                idx[36 * b + 3 * t + c] = (uint32_t)(8 * b) + BOX_TRIS[3 * t + c];
            src[12 * b + t] = (uint32_t)(b ? t : 12 + t); /* A: 0..11, B: 12..23 */
        }
    oit_partfile_piece_desc pieces[2] = {{12, 6}, {12, 6}};
    oit_partfile_part_desc d = {.positions = pos, .rgba = rgba, .vertex_count = 16,
                                .indices = idx, .index_count = 72, .sources = src,
                                .pieces = pieces, .piece_count = 2,
                                .attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA};
    uint32_t counts[1] = {1}, parts[1] = {0};
    oit_partfile_grid_desc g = {.dims = {1, 1, 1}, .origin = {-1, -1, -1},
                                .cell_size = {2, 2, 2}, .cell_counts = counts,
                                .cell_parts = parts};
    oit_partfile_writer_desc wd = {.K = 8, .attributes = OIT_ATTR_COLOUR | OIT_ATTR_ALPHA,
                                   .source_name = "tie.ply"};
    oit_partfile_stats st = {triangles_in, triangles_in - 24, 0};
    oit_partfile_writer *w = NULL;
    oit_error err = {0};
    oit_status s = oit_partfile_writer_create(path, &wd, &w, &err);
    if (!s)
        s = oit_partfile_writer_add_part(w, &d, NULL, &err);
    if (!s)
        s = oit_partfile_writer_set_grid(w, &g, &err);
    if (!s)
        s = oit_partfile_writer_finish(w, &st, &err);
    else
        oit_partfile_writer_abort(w);
    if (s)
        fprintf(stderr, "%s\n", err.message);
    return s ? 1 : 0;
}

int main(int argc, char **argv)
{
    if ((argc == 3 || argc == 4) && !strcmp(argv[1], "--write-tie"))
        return write_tie(argv[2], argc == 4 ? strtoull(argv[3], NULL, 10) : 24);
    if (argc < 3 || (argc > 3 && strcmp(argv[3], "--ascending"))) {
        fprintf(stderr, "usage: test_sources SOURCE FILE.oitp [--ascending]\n");
        return 2;
    }
    int want_ascending = argc > 3;
    oit_mesh m;
    oit_error err = {0};
    if (oit_mesh_load(argv[1], NULL, &m, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 3;
    }
    oit_partfile *pf = NULL;
    if (oit_partfile_open(argv[2], NULL, &pf, &err)) {
        fprintf(stderr, "%s\n", err.message);
        oit_mesh_free(&m);
        return 3;
    }
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    double *got = calloc(m.count ? m.count : 1, sizeof *got);
    double *shuffled = calloc(m.count ? m.count : 1, sizeof *shuffled);
    uint32_t *npieces = calloc(m.count ? m.count : 1, sizeof *npieces);
    uint64_t out_of_range = 0, unordered_parts = 0, pieces = 0;
    oit_partfile_buffer buf = {0};
    for (uint32_t p = 0; p < oit_partfile_part_count(pf); p++) {
        oit_partfile_part_view v;
        if (oit_partfile_part_data(pf, p, &buf, &v, &err)) {
            fprintf(stderr, "%s\n", err.message);
            return 3;
        }
        int unordered = 0;
        for (uint64_t t = 0; t < v.index_count / 3; t++) {
            uint32_t s = oit_partfile_source(&v, t);
            if (t && s < oit_partfile_source(&v, t - 1))
                unordered = 1;
            if (s >= m.count) {
                if (!out_of_range++)
                    fprintf(stderr, "part %u triangle %llu: source index %u >= %zu source "
                            "triangles\n", p, (unsigned long long)t, s, m.count);
                continue;
            }
            float a[3], b[3], c[3];
            vertex(&v, 3 * t, a);
            vertex(&v, 3 * t + 1, b);
            vertex(&v, 3 * t + 2, c);
            got[s] += oit_area3fd(a, b, c);
            npieces[s]++;
            shuffled[m.count - 1 - s] += oit_area3fd(a, b, c);
            pieces++;
        }
        unordered_parts += (uint64_t)unordered;
    }
    oit_partfile_buffer_free(&buf);
    uint64_t wrong = 0, missing = 0, caught = 0, rounded = 0;
    double worst = 0;
    for (size_t i = 0; i < m.count; i++) {
        const oit_triangle *t = &m.tris[i];
        double want = oit_area3fd(t->v[0].pos, t->v[1].pos, t->v[2].pos), big = 0, edge = 0;
        for (int k = 0; k < 3; k++) {
            double e2 = 0;
            for (int c = 0; c < 3; c++) {
                double d = (double)t->v[(k + 1) % 3].pos[c] - t->v[k].pos[c];
                e2 += d * d;
                big = fmax(big, fabs(t->v[k].pos[c]));
            }
            edge = fmax(edge, sqrt(e2));
        }
        double allow = (npieces[i] > 2 ? npieces[i] : 2) * 8.0 * FLT_EPSILON * big * edge;
        caught += fabs(shuffled[i] - want) > 1e-4 * want + allow;
        double err_abs = fabs(got[i] - want), rel = want > 0 ? err_abs / want : got[i];
        /* The converter drops degenerate triangles: those carry nothing. */
        if (oit_triangle_is_degenerate(t))
            rel = got[i], allow = 0, err_abs = got[i];
        else
            missing += got[i] == 0;
        if (rel > 1e-4 && err_abs <= 1e-4 * want + allow)
            rounded++;
        else if (rel > 1e-4) {
            if (!wrong++)
                fprintf(stderr, "source triangle %zu: area %.9g, its %u pieces' %.9g\n", i,
                        want, npieces[i], got[i]);
        }
        worst = rel > worst ? rel : worst;
    }
    printf("%s: %llu part triangles over %zu source triangles (triangles_in %llu): %llu "
           "indices out of range, %llu source triangles whose pieces' area differs by more "
           "than 1e-4 (worst %.3g) and %llu more within the rounding of their clipped "
           "vertices, %llu kept ones in no part, %llu of %u parts not in "
           "ascending source order; a shuffled index would show in %llu\n",
           argv[2], (unsigned long long)pieces, m.count, (unsigned long long)sum.triangles_in,
           (unsigned long long)out_of_range, (unsigned long long)wrong, worst,
           (unsigned long long)rounded,
           (unsigned long long)missing, (unsigned long long)unordered_parts,
           oit_partfile_part_count(pf), (unsigned long long)caught);
    int ok = out_of_range == 0 && wrong == 0 && missing == 0 && sum.triangles_in >= m.count &&
             (!want_ascending || unordered_parts == 0) && caught > 0;
    free(got);
    free(shuffled);
    free(npieces);
    oit_partfile_close(pf);
    oit_mesh_free(&m);
    return ok ? 0 : 1;
}
