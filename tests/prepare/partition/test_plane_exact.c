/* prepare/partition/plane_exact.h: exact sides where double rounding loses the
 * sign; seam vertices on the plane to the last bit, inside the box, the
 * same from either end of the edge; split halves on their sides, area
 * kept. */
#include "prepare/partition/plane_exact.h"
#include "tests/prepare/partition/partition_test.h"

static uint32_t lcg_next(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static float lcg_coord(uint32_t *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)lcg_next(s) / (float)(1u << 24);
}

/* Exact sides where double rounding loses the sign; seam vertices on the
 * plane to the last bit, inside the box, the same from either end of the
 * edge and near the true edge point; split halves on their sides with the
 * area kept. */
static void test_plane_exact(void)
{
    const float big = 1152921504606846976.0f; /* 2^60 */
    const float n1[3] = {1, 1, 1}, p1[3] = {big, 1, -big};
    double naive = (double)p1[0] + p1[1] + p1[2];
    CHECK(oit_plane_side_exact(n1, 0, p1) == 1 && naive == 0,
          "2^60 + 1 - 2^60: exact side %d (want 1), plain double %g (the case needs 0)",
          oit_plane_side_exact(n1, 0, p1), naive);
    CHECK(oit_plane_side_exact(n1, 1, p1) == 0 && oit_plane_side_exact(n1, 2, p1) == -1,
          "2^60 + 1 - 2^60 against d = 1 and 2");

    const float lo[3] = {-3, -2, 0.5f}, hi[3] = {5, 4, 1000};
    int dirs[][3] = {{1, 0, 0}, {1, 1, 0}, {1, -2, 1}, {2, 1, -1}, {1, 2, 2}, {0, 1, -2}};
    uint32_t seed = 12345;
    int seams = 0, worst_grains = 0;
    double area_in = 0, area_out = 0;
    for (int k = 0; k < (int)(sizeof dirs / sizeof dirs[0]); k++) {
        oit_plane_exact pl;
        oit_plane_exact_init(&pl, dirs[k], lo, hi);
        for (int i = 0; i < 400; i++) {
            oit_triangle t;
            for (int v = 0; v < 3; v++)
                t.v[v] = vtx(lcg_coord(&seed, lo[0], hi[0]), lcg_coord(&seed, lo[1], hi[1]),
                             lcg_coord(&seed, lo[2], i % 2 ? 2.0f : hi[2]));
            double x[3], mn = INFINITY, mx = -INFINITY;
            for (int v = 0; v < 3; v++) {
                x[v] = dirs[k][0] * (double)t.v[v].pos[0] + dirs[k][1] * (double)t.v[v].pos[1] +
                       dirs[k][2] * (double)t.v[v].pos[2];
                mn = fmin(mn, x[v]);
                mx = fmax(mx, x[v]);
            }
            pl.d = floor(0.5 * (mn + mx) / pl.grain) * pl.grain;
            for (int v = 0; v < 3; v++) {
                int w = (v + 1) % 3, sv = oit_plane_exact_side(&pl, t.v[v].pos),
                    sw = oit_plane_exact_side(&pl, t.v[w].pos);
                if (sv * sw >= 0)
                    continue;
                oit_vertex a, b;
                CHECK(oit_plane_exact_seam(&pl, &t.v[v], &t.v[w], lo, hi, &a) &&
                          oit_plane_exact_seam(&pl, &t.v[w], &t.v[v], lo, hi, &b),
                      "dir %d: no seam vertex", k);
                CHECK(memcmp(a.pos, b.pos, sizeof a.pos) == 0, "dir %d: the seam depends on "
                      "the edge's direction", k);
                CHECK(oit_plane_exact_side(&pl, a.pos) == 0, "dir %d: seam vertex off the plane",
                      k);
                double tt = (pl.d - x[v]) / (x[w] - x[v]), off = 0;
                for (int c = 0; c < 3; c++) {
                    double e = t.v[v].pos[c] + tt * ((double)t.v[w].pos[c] - t.v[v].pos[c]);
                    CHECK(a.pos[c] >= lo[c] && a.pos[c] <= hi[c], "dir %d: seam leaves the box",
                          k);
                    off = fmax(off, fabs(a.pos[c] - e));
                }
                int grains = (int)ceil(off / pl.grain);
                worst_grains = grains > worst_grains ? grains : worst_grains;
                seams++;
            }
            oit_triangle below[2], above[2];
            int nb, na;
            CHECK(oit_plane_exact_split(&pl, &t, lo, hi, below, &nb, above, &na),
                  "dir %d: split failed", k);
            double area = 0;
            for (int h = 0; h < nb + na; h++) {
                const oit_triangle *q = h < nb ? &below[h] : &above[h - nb];
                area += tri_area(q);
                for (int v = 0; v < 3; v++) {
                    int side = oit_plane_exact_side(&pl, q->v[v].pos);
                    CHECK(h < nb ? side <= 0 : side >= 0, "dir %d: a split vertex on the wrong "
                          "side", k);
                }
            }
            area_in += tri_area(&t);
            area_out += area;
        }
    }
    double area_err = fabs(area_out - area_in) / area_in;
    printf("exact planes: %d seam vertices on their planes, at most %d grains from the edge "
           "point; split area error %.2g\n", seams, worst_grains, area_err);
    CHECK(seams > 1000, "only %d seams tested", seams);
    CHECK(worst_grains <= 4, "a seam vertex %d grains from its edge point", worst_grains);
    CHECK(area_err < 1e-5, "split area off by %.3g", area_err);
}

int main(void)
{
    test_plane_exact();
    return test_verdict();
}
