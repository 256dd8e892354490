/* partition/ kernels: exact orient3d where the double filter cannot decide,
 * watertight plane splitting of a closed mesh, and greedy convex clustering
 * on shapes whose piece counts are known; seams that two triangles walking
 * an edge in opposite directions must share bit for bit; a planar fan whose
 * last triangle overlaps its first. */
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "partition/clip.h"
#include "partition/convex.h"
#include "partition/kd.h"
#include "partition/kd_cut.h"
#include "partition/kd_fast.h"
#include "partition/layers_measured.h"
#include "partition/plane_exact.h"
#include "partition/kd_split.h"
#include "partition/predicates.h"
#include "base/sort.h"
#include "base/vec.h"
#include "tests/lib/test_check.h"

/* ---------------------------------------------------------------- predicates */

static const double PI = 3.14159265358979323846;

static int sign_i64(int64_t v) { return (v > 0) - (v < 0); }

/* For a = e_x, b = e_y, c = e_z, det[b-a; c-a; d-a] = dx + dy + dz - 1. With
 * every coordinate a multiple of 2^-55 below 1, the sum is exact in int64. */
static int plane_sign_exact(const double d[3])
{
    int64_t s = -((int64_t)1 << 55);
    for (int k = 0; k < 3; k++)
        s += (int64_t)ldexp(d[k], 55);
    return sign_i64(s);
}

static int naive_orient3d(const double a[3], const double b[3], const double c[3],
                          const double d[3])
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = d[k] - a[k];
    }
    double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                 u[2] * (v[0] * w[1] - v[1] * w[0]);
    return (det > 0) - (det < 0);
}

static void test_predicates(void)
{
    const double o[3] = {0, 0, 0}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    const double below[3] = {0.25, 0.25, -0.5}, on[3] = {3, -7, 0};
    CHECK(oit_orient3d(o, ex, ey, ez) == 1, "unit tetrahedron must be +1");
    CHECK(oit_orient3d(o, ey, ex, ez) == -1, "swapped tetrahedron must be -1");
    CHECK(oit_orient3d(o, ex, ey, below) == -1, "point below z=0 must be -1");
    CHECK(oit_orient3d(o, ex, ey, on) == 0, "point in z=0 must be 0");

    /* d = (x, y, 1 - x - y rounded, then nudged by -1..+1 ulp): within 1e-16
     * of the plane x+y+z=1, where the double determinant's error bound
     * (~1e-15) exceeds its value. */
    int counts[3] = {0, 0, 0}, naive_wrong = 0, cases = 0;
    for (int i = 0; i < 40; i++)
        for (int j = 0; j < 40; j++)
            for (int nudge = -1; nudge <= 1; nudge++) {
                double d[3];
                d[0] = 0.125 + i * (0.1 / 40.0);
                d[1] = 0.125 + j * (0.1 / 41.0);
                d[2] = 1.0 - d[0] - d[1];
                if (nudge)
                    d[2] = nextafter(d[2], nudge > 0 ? 2.0 : 0.0);
                int want = plane_sign_exact(d);
                int got = oit_orient3d(ex, ey, ez, d);
                CHECK(got == want, "orient3d(e_x,e_y,e_z,(%.17g,%.17g,%.17g)) = %d, exact %d",
                      d[0], d[1], d[2], got, want);
                CHECK(oit_orient3d_exact(ex, ey, ez, d) == want, "exact fallback disagrees");
                counts[want + 1]++;
                naive_wrong += naive_orient3d(ex, ey, ez, d) != want;
                cases++;
            }
    printf("predicates: %d near-coplanar cases: %d negative, %d zero, %d positive; "
           "naive double determinant wrong on %d\n",
           cases, counts[0], counts[1], counts[2], naive_wrong);
    CHECK(counts[0] > 0 && counts[1] > 0 && counts[2] > 0, "cases must cover all three signs");
    CHECK(naive_wrong > 0, "cases must include some the plain double determinant gets wrong");

    const double p[3] = {0.1, 0.2, 0.3}, q[3] = {0.2, 0.4, 0.6}, r[3] = {0.4, 0.8, 1.2};
    const double r2[3] = {0.4, 0.8, nextafter(1.2, 2.0)};
    /* 0.1*2, 0.2*2, ... are exact doublings, so p, q, r are exactly collinear. */
    CHECK(oit_triangle_degenerate(p, q, r) == 1, "exactly collinear points");
    CHECK(oit_triangle_degenerate(p, q, r2) == 0, "collinear up to one ulp is not degenerate");
}

/* ---------------------------------------------------------------- meshes */

typedef struct tri_list {
    oit_triangle *t;
    size_t n, cap;
} tri_list;

static void push(tri_list *l, const oit_triangle *t)
{
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 64;
        l->t = realloc(l->t, l->cap * sizeof *l->t);
        if (!l->t) {
            fprintf(stderr, "out of memory\n");
            exit(1);
        }
    }
    l->t[l->n++] = *t;
}

static oit_vertex vtx(float x, float y, float z)
{
    oit_vertex v = {{x, y, z}, {200, 100, 50, 128}};
    return v;
}

static void push3(tri_list *l, oit_vertex a, oit_vertex b, oit_vertex c)
{
    oit_triangle t = {{a, b, c}};
    push(l, &t);
}

/* Cube [lo, hi]^3, 12 triangles, outward counter-clockwise. */
static void make_cube(tri_list *l, float lo, float hi)
{
    static const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    oit_vertex c[8];
    for (int i = 0; i < 8; i++)
        c[i] = vtx(i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo);
    for (int f = 0; f < 6; f++) {
        const int *q = quads[f];
        push3(l, c[q[0]], c[q[1]], c[q[2]]);
        push3(l, c[q[0]], c[q[2]], c[q[3]]);
    }
}

/* A closed surface from a periodic grid of vertices: g[i * nv + j]. */
static void push_grid(tri_list *l, const oit_vertex *g, int nu, int nv, int wrap_u)
{
    for (int i = 0; i + (wrap_u ? 0 : 1) < nu; i++)
        for (int j = 0; j < nv; j++) {
            int i1 = (i + 1) % nu, j1 = (j + 1) % nv;
            oit_vertex a = g[i * nv + j], b = g[i1 * nv + j], c = g[i1 * nv + j1],
                       d = g[i * nv + j1];
            if (!oit_triangle_is_degenerate(&(oit_triangle){{a, b, c}}))
                push3(l, a, b, c);
            if (!oit_triangle_is_degenerate(&(oit_triangle){{a, c, d}}))
                push3(l, a, c, d);
        }
}

static void make_torus(tri_list *l, int nu, int nv)
{
    oit_vertex *g = malloc((size_t)nu * nv * sizeof *g);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2 * PI * i / nu, v = 2 * PI * j / nv, r = 1.0 + 0.35 * cos(v);
            g[i * nv + j] = vtx((float)(r * cos(u)), (float)(r * sin(u)), (float)(0.35 * sin(v)));
        }
    push_grid(l, g, nu, nv, 1);
    free(g);
}

/* UV sphere off the origin; each pole is one vertex repeated along its ring,
 * whose collapsed triangles push_grid drops, so the surface stays closed. */
static void make_sphere(tri_list *l, int rings, int segs)
{
    oit_vertex *g = malloc((size_t)(rings + 1) * segs * sizeof *g);
    for (int i = 0; i <= rings; i++)
        for (int j = 0; j < segs; j++) {
            double th = PI * i / rings, ph = 2 * PI * j / segs;
            double s = (i == 0 || i == rings) ? 0.0 : sin(th);
            g[i * segs + j] = vtx((float)(0.1 + s * cos(ph)), (float)(0.2 + s * sin(ph)),
                                  (float)(0.3 + cos(th)));
        }
    push_grid(l, g, rings + 1, segs, 0);
    free(g);
}

static double tri_area(const oit_triangle *t)
{
    return oit_area3fd(t->v[0].pos, t->v[1].pos, t->v[2].pos);
}

/* ---------------------------------------------------------------- clip */

typedef struct edge_key {
    float p[6];
} edge_key;

static int edge_cmp(const void *a, const void *b) { return memcmp(a, b, sizeof(edge_key)); }

/* Closed and consistently oriented means every directed edge (bit-exact
 * endpoints) has its reverse: a cut point computed differently from the two
 * triangles sharing an edge leaves both halves unmatched. */
static size_t unmatched_edges(const tri_list *l)
{
    size_t n = 3 * l->n, bad = 0;
    edge_key *e = calloc(n ? n : 1, sizeof *e);
    for (size_t i = 0; i < l->n; i++)
        for (int k = 0; k < 3; k++) {
            memcpy(e[3 * i + k].p, l->t[i].v[k].pos, 12);
            memcpy(e[3 * i + k].p + 3, l->t[i].v[(k + 1) % 3].pos, 12);
        }
    qsort(e, n, sizeof *e, edge_cmp);
    for (size_t i = 0; i < n; i++) {
        edge_key r;
        memcpy(r.p, e[i].p + 3, 12);
        memcpy(r.p + 3, e[i].p, 12);
        bad += bsearch(&r, e, n, sizeof *e, edge_cmp) == NULL;
    }
    free(e);
    return bad;
}

static int is_input_vertex(const oit_triangle *t, const oit_vertex *v)
{
    for (int i = 0; i < 3; i++)
        if (memcmp(t->v[i].pos, v->pos, 12) == 0)
            return 1;
    return 0;
}

/* Splits mesh at pos[axis] = c; checks sides, new vertices, area and
 * watertightness; returns the relative area error. */
static double check_split(const char *name, const tri_list *mesh, int axis, float c)
{
    tri_list below = {0}, above = {0}, both = {0};
    double area_in = 0, area_out = 0;
    size_t new_vertices = 0, off_plane = 0, wrong_side = 0;
    for (size_t i = 0; i < mesh->n; i++) {
        oit_triangle b[2], a[2];
        int nb, na;
        oit_clip_triangle_split(&mesh->t[i], axis, c, b, &nb, a, &na);
        area_in += tri_area(&mesh->t[i]);
        for (int s = 0; s < 2; s++) {
            const oit_triangle *out = s ? a : b;
            for (int j = 0; j < (s ? na : nb); j++) {
                area_out += tri_area(&out[j]);
                push(s ? &above : &below, &out[j]);
                push(&both, &out[j]);
                for (int k = 0; k < 3; k++) {
                    float x = out[j].v[k].pos[axis];
                    wrong_side += s ? x < c : x > c;
                    if (!is_input_vertex(&mesh->t[i], &out[j].v[k])) {
                        new_vertices++;
                        off_plane += x != c;
                    }
                }
            }
        }
    }
    double rel = fabs(area_out - area_in) / area_in;
    size_t bad = unmatched_edges(&both);
    printf("clip %s: %zu triangles -> %zu below + %zu above, %zu new vertex uses, "
           "area rel. error %.3g, unmatched edges %zu\n",
           name, mesh->n, below.n, above.n, new_vertices, rel, bad);
    CHECK(below.n > 0 && above.n > 0, "%s: the plane must cut the mesh", name);
    CHECK(new_vertices > 0, "%s: the cut must create vertices", name);
    CHECK(off_plane == 0, "%s: %zu new vertices off the plane", name, off_plane);
    CHECK(wrong_side == 0, "%s: %zu vertices on the wrong side", name, wrong_side);
    CHECK(bad == 0, "%s: %zu directed edges without their reverse (not watertight)", name, bad);
    CHECK(unmatched_edges(mesh) == 0, "%s: input mesh must be closed", name);
    free(below.t);
    free(above.t);
    free(both.t);
    return rel;
}

static void test_clip(void)
{
    tri_list cube = {0}, sphere = {0};
    make_cube(&cube, -1.0f, 1.0f);
    /* Dyadic cut: every cut point is exact in float, so area is preserved to
     * rounding of the area sums only. */
    double rel = check_split("cube z=0.25", &cube, 2, 0.25f);
    CHECK(rel < 1e-12, "cube area changed by %.3g relative", rel);

    /* Generic cut: cut points round to float, moving the boundary by half an
     * ulp, so area is preserved to float precision, not better. */
    make_sphere(&sphere, 9, 13);
    rel = check_split("sphere x=0.1234", &sphere, 0, 0.1234f);
    CHECK(rel < 1e-6, "sphere area changed by %.3g relative", rel);
    rel = check_split("sphere z=0.7071", &sphere, 2, 0.7071f);
    CHECK(rel < 1e-6, "sphere area changed by %.3g relative", rel);
    free(cube.t);
    free(sphere.t);
}

/* The point of p-q at pos[axis] = c computed from p's end, as a clipper that
 * ignores the canonical order would (float result, double arithmetic). */
static void naive_edge_point(const oit_vertex *p, const oit_vertex *q, int axis, float c,
                             float out[3])
{
    double t = ((double)c - p->pos[axis]) / ((double)q->pos[axis] - p->pos[axis]);
    for (int k = 0; k < 3; k++)
        out[k] = (float)(p->pos[k] + t * ((double)q->pos[k] - p->pos[k]));
    out[axis] = c;
}

/* The vertex on the plane nearest to near (the seam vertex of one edge). */
static const float *seam_vertex(const oit_vertex *v, int n, int axis, float c, const float near[3])
{
    const float *best = NULL;
    double bd = INFINITY;
    for (int i = 0; i < n; i++) {
        double d = fabs(v[i].pos[0] - near[0]) + fabs(v[i].pos[1] - near[1]) +
                   fabs(v[i].pos[2] - near[2]);
        if (v[i].pos[axis] == c && d < bd) {
            bd = d;
            best = v[i].pos;
        }
    }
    return best;
}

/* Edges whose two directions give seam points that differ in the last bit:
 * the two triangles sharing such an edge, walking it in opposite
 * directions, must still get the same seam vertex bit for bit. */
static void test_clip_direction(void)
{
    uint32_t seed = 2024, found = 0, tried = 0, cracked = 0;
    for (; found < 64 && tried < 100000; tried++) {
        float r[6];
        for (int k = 0; k < 6; k++) {
            seed = seed * 1664525u + 1013904223u;
            r[k] = (float)(seed >> 8) / 16777216.0f * 2.0f - 1.0f;
        }
        /* The edge's y and z cross near zero at the plane, where the
         * rounding of p + t (q - p) is largest against the result's ulp. */
        const float c = 0.0123f;
        float px = -fabsf(r[0]) - 0.01f, qx = fabsf(r[3]) + 0.01f;
        double t = ((double)c - px) / ((double)qx - px);
        float dy = (float)(r[1] + t * (r[4] - r[1])) - 1e-6f * r[2];
        float dz = (float)(r[2] + t * (r[5] - r[2])) - 1e-6f * r[1];
        oit_vertex p = vtx(px, r[1] - dy, r[2] - dz), q = vtx(qx, r[4] - dy, r[5] - dz);
        float fwd[3], back[3];
        naive_edge_point(&p, &q, 0, c, fwd);
        naive_edge_point(&q, &p, 0, c, back);
        if (memcmp(fwd, back, sizeof fwd) == 0)
            continue;
        found++;
        /* Two triangles on either side of the edge, p->q in one, q->p in
         * the other. */
        oit_vertex a[3] = {p, q, vtx(0.0f, 5.0f, 0.0f)}, b[3] = {q, p, vtx(0.0f, -5.0f, 0.0f)};
        oit_vertex ca[4], cb[4];
        int na = oit_clip_polygon(a, 3, 0, c, 1, ca), nb = oit_clip_polygon(b, 3, 0, c, 1, cb);
        const float *sa = seam_vertex(ca, na, 0, c, fwd), *sb = seam_vertex(cb, nb, 0, c, fwd);
        cracked += !sa || !sb || memcmp(sa, sb, 3 * sizeof *sa) != 0;
    }
    printf("clip direction: %u of %u random edges round differently from each end; "
           "%u seams differ between the two triangles\n", found, tried, cracked);
    CHECK(found == 64, "only %u direction-sensitive edges in %u tries", found, tried);
    CHECK(cracked == 0, "%u of %u shared edges got different seam vertices from their two "
          "triangles (a crack)", cracked, found);
}

/* ---------------------------------------------------------------- convex */

/* Clusters l; checks every triangle has a piece and every piece passes the
 * brute-force check; returns the piece count (0 on failure). */
static uint32_t cluster(const char *name, const tri_list *l)
{
    oit_convex_result r;
    oit_error err = {0};
    if (oit_convex_cluster(l->t, l->n, NULL, &r, &err) != OIT_OK) {
        CHECK(0, "%s: oit_convex_cluster failed: %s", name, err.message);
        return 0;
    }
    uint32_t *idx = malloc((l->n ? l->n : 1) * sizeof *idx);
    size_t non_convex = 0, assigned = 0, max_size = 0;
    for (uint32_t p = 0; p < r.piece_count; p++) {
        size_t m = 0;
        for (size_t i = 0; i < l->n; i++)
            if (r.piece_of[i] == p)
                idx[m++] = (uint32_t)i;
        assigned += m;
        max_size = m > max_size ? m : max_size;
        CHECK(m > 0, "%s: piece %u is empty", name, p);
        non_convex += !oit_convex_check(l->t, idx, m);
    }
    printf("convex %s: %zu triangles -> %u pieces (largest %zu)\n", name, l->n, r.piece_count,
           max_size);
    CHECK(assigned == l->n, "%s: %zu of %zu triangles in a piece", name, assigned, l->n);
    CHECK(non_convex == 0, "%s: %zu pieces fail oit_convex_check", name, non_convex);
    uint32_t count = r.piece_count;
    oit_convex_result_free(&r);
    free(idx);
    return count;
}

static int whole_is_convex(const tri_list *l)
{
    uint32_t *idx = malloc(l->n * sizeof *idx);
    for (size_t i = 0; i < l->n; i++)
        idx[i] = (uint32_t)i;
    int ok = oit_convex_check(l->t, idx, l->n);
    free(idx);
    return ok;
}

static void test_convex(void)
{
    tri_list cube = {0}, torus = {0}, opp = {0}, overlap = {0}, adjacent = {0}, fan = {0};
    make_cube(&cube, -0.5f, 1.5f);
    CHECK(whole_is_convex(&cube), "the cube must pass oit_convex_check");
    uint32_t n = cluster("cube", &cube);
    CHECK(n == 1, "closed cube: %u pieces, want 1", n);

    make_torus(&torus, 12, 8);
    CHECK(!whole_is_convex(&torus), "the torus must fail oit_convex_check");
    n = cluster("torus 12x8", &torus);
    CHECK(n > 1 && n < torus.n, "torus: %u pieces, want several (2..%zu)", n, torus.n - 1);

    oit_vertex a = vtx(0, 0, 0), b = vtx(1, 0, 0), c = vtx(0, 1, 0), d = vtx(1, 1, 0);
    push3(&opp, a, b, c);
    push3(&opp, a, c, b);
    n = cluster("coincident opposite-facing", &opp);
    CHECK(n == 2, "coincident opposite-facing triangles: %u pieces, want 2", n);

    push3(&overlap, a, b, c);
    push3(&overlap, vtx(0.25f, 0.25f, 0), vtx(1.25f, 0.25f, 0), vtx(0.25f, 1.25f, 0));
    n = cluster("overlapping coplanar", &overlap);
    CHECK(n == 2, "overlapping coplanar same-facing triangles: %u pieces, want 2", n);

    /* An edge-connected fan of eight 50-degree triangles round one centre,
     * 400 degrees in all: the last overlaps the first but shares no edge
     * with it, and the breadth-first growth reaches it through the chain,
     * so only a check against every triangle on the plane (not just the
     * newest, its neighbour) keeps it out of the first piece. */
    for (int i = 0; i < 8; i++) {
        double a0 = (50.0 * i) * PI / 180.0, a1 = (50.0 * (i + 1)) * PI / 180.0;
        push3(&fan, vtx(0, 0, 0), vtx((float)cos(a0), (float)sin(a0), 0),
              vtx((float)cos(a1), (float)sin(a1), 0));
    }
    n = cluster("overlapping planar fan", &fan);
    CHECK(n == 2, "a planar fan whose last triangle overlaps its first: %u pieces, want 2", n);

    push3(&adjacent, a, b, c);
    push3(&adjacent, b, d, c);
    n = cluster("adjacent coplanar", &adjacent);
    CHECK(n == 1, "adjacent coplanar same-facing triangles: %u pieces, want 1", n);

    free(cube.t);
    free(torus.t);
    free(opp.t);
    free(overlap.t);
    free(adjacent.t);
    free(fan.t);
}

/* ---------------------------------------------------------------- kd */

/* Ten separate pieces along x: the chosen plane must cut none of them, leave
 * ceil(20/8) = 3 parts' worth, and be exactly a subgrid boundary. */
static void test_kd_split(void)
{
    oit_kd_piece_box b[10];
    for (int i = 0; i < 10; i++)
        b[i] = (oit_kd_piece_box){{(float)i, 0, 0}, {(float)i + 0.5f, 1, 1}, 2, 0, 0};
    float lo[3] = {0, 0, 0}, hi[3] = {16, 16, 16}, pos = 0, origin[3], cell[3];
    int axis = -1;
    CHECK(oit_kd_choose_split(b, 10, lo, hi, 8, &axis, &pos), "no split for 10 pieces");
    CHECK(axis == 0, "split on axis %d, want x", axis);
    uint32_t below = 0, above = 0;
    for (int i = 0; i < 10; i++) {
        CHECK(!(b[i].lo[0] < pos && b[i].hi[0] > pos), "split at %g cuts piece %d", pos, i);
        below += b[i].hi[0] <= pos ? 2 : 0;
        above += b[i].lo[0] >= pos ? 2 : 0;
    }
    CHECK((below + 7) / 8 + (above + 7) / 8 == 3, "split at %g leaves %u | %u layers", pos,
          below, above);
    CHECK(oit_kd_split_cells(lo, hi, 0, pos, origin, cell) && origin[0] + cell[0] == pos &&
              origin[0] <= lo[0] && origin[0] + 2 * cell[0] >= hi[0],
          "split at %g is not one subgrid boundary", pos);
    printf("kd split: 10 pieces -> x = %g, %u | %u layers, none cut\n", pos, below, above);
}

/* Every dyadic plane of [0, 16] falls inside some piece; only a plane at a
 * piece's own end or start (5.5 or 5.6) separates them without a cut. */
static void test_kd_split_events(void)
{
    static const float x[5][2] = {{0.5f, 5.5f}, {5.6f, 8.5f}, {8.6f, 11.5f}, {11.6f, 15.5f},
                                  {1.5f, 4.5f}};
    oit_kd_piece_box b[5];
    for (int i = 0; i < 5; i++)
        b[i] = (oit_kd_piece_box){{x[i][0], 0, 0}, {x[i][1], 1, 1}, 2, 0, 0};
    float lo[3] = {0, 0, 0}, hi[3] = {16, 16, 16}, pos = 0, origin[3], cell[3];
    int axis = -1;
    CHECK(oit_kd_choose_split(b, 5, lo, hi, 8, &axis, &pos) == 1, "no split for 5 pieces");
    CHECK(axis == 0 && pos >= 5.5f && pos <= 5.6f, "split on axis %d at %g, want x in "
          "[5.5, 5.6]", axis, pos);
    for (int i = 0; i < 5; i++)
        CHECK(!(b[i].lo[0] < pos && b[i].hi[0] > pos), "split at %g cuts piece %d", pos, i);
    CHECK(oit_kd_split_cells(lo, hi, 0, pos, origin, cell) && origin[0] + cell[0] == pos,
          "split at %.9g is not one subgrid boundary", pos);
    printf("kd split at piece bounds: x = %.9g, cell origin %.9g size %.9g, none cut\n", pos,
           origin[0], cell[0]);
}

/* Two pieces with faces in the plane x = 6 (a box standing on a slab): the
 * best plane by count and balance is x = 6, but there the two parts would
 * tie on coincident faces, so it must not be chosen; without the faces it
 * is (the check can fail). */
static void test_kd_split_touching(void)
{
    static const float x[5][2] = {{1, 6}, {6, 11}, {1, 6}, {6, 11}, {12, 15}};
    oit_kd_piece_box b[5];
    float lo[3] = {0, 0, 0}, hi[3] = {16, 16, 16}, pos[2] = {0, 0};
    int axis[2] = {-1, -1};
    for (int faces = 0; faces < 2; faces++) {
        for (int i = 0; i < 5; i++)
            b[i] = (oit_kd_piece_box){{x[i][0], 0, 0}, {x[i][1], 1, 1}, 2, 0, 0};
        b[0].face_hi = (uint8_t)faces;
        b[1].face_lo = (uint8_t)faces;
        CHECK(oit_kd_choose_split(b, 5, lo, hi, 8, &axis[faces], &pos[faces]) == 1,
              "no split for 5 pieces");
    }
    CHECK(axis[0] == 0 && pos[0] == 6.0f, "without faces: split on axis %d at %g, want x = 6",
          axis[0], pos[0]);
    CHECK(!(axis[1] == 0 && pos[1] == 6.0f), "split between coincident faces at x = 6");
    for (int i = 0; i < 5; i++)
        CHECK(!(axis[1] == 0 && b[i].lo[0] < pos[1] && b[i].hi[0] > pos[1]),
              "split at %g cuts piece %d", pos[1], i);
    printf("kd split with faces touching at x = 6: axis %d at %g instead\n", axis[1], pos[1]);
}

/* Source indices given to the builds: 2 i + 1, so that an index that is
 * really a position (or a lost one, 0) shows. */
static uint32_t *odd_sources(size_t n)
{
    uint32_t *src = malloc((n ? n : 1) * sizeof *src);
    for (size_t i = 0; i < n; i++)
        src[i] = (uint32_t)(2 * i + 1);
    return src;
}

/* Every output triangle carries a source index of the input (2 i + 1), the
 * pieces carrying one cover its triangle's area exactly (relative 1e-4:
 * clipping only adds rounding), and within a piece the indices ascend (the
 * input's order is kept). A wrong or shuffled index breaks the areas. */
static void check_sources(const char *name, const tri_list *l, const oit_kd_result *r)
{
    double *area = calloc(l->n ? l->n : 1, sizeof *area);
    size_t bad = 0, unordered = 0;
    for (size_t i = 0; i < r->tri_count; i++) {
        uint32_t s = r->src[i];
        if (s % 2 == 0 || (s - 1) / 2 >= l->n) {
            bad++;
            continue;
        }
        area[(s - 1) / 2] += tri_area(&r->tris[i]);
    }
    size_t wrong = 0;
    for (size_t i = 0; i < l->n; i++) {
        double a = tri_area(&l->t[i]);
        if (fabs(area[i] - a) > 1e-4 * a + 1e-12)
            wrong++;
    }
    for (size_t p = 0; p < r->part_count; p++) {
        size_t at = r->parts[p].tri_first;
        for (uint32_t k = 0; k < r->parts[p].piece_count; k++) {
            size_t n = r->pieces[r->parts[p].piece_first + k].triangle_count;
            for (size_t j = at + 1; j < at + n; j++)
                unordered += r->src[j] < r->src[j - 1];
            at += n;
        }
    }
    CHECK(bad == 0 && wrong == 0 && unordered == 0,
          "%s: %zu source indices out of range, %zu of %zu source triangles whose pieces' "
          "area differs, %zu descending steps within pieces", name, bad, wrong, l->n,
          unordered);
    free(area);
}

static oit_status kd_of(const tri_list *l, uint32_t K, oit_kd_result *r, oit_error *err)
{
    float lo[3] = {-4, -4, -4}, hi[3] = {4, 4, 4};
    oit_convex_result cr;
    if (oit_convex_cluster(l->t, l->n, NULL, &cr, err))
        return OIT_ERR_NOMEM;
    oit_kd_params kp = {K, 0, 0, OIT_KD_SLABS_ALL};
    uint32_t *src = odd_sources(l->n);
    oit_status s = oit_kd_build(lo, hi, l->t, src, l->n, cr.piece_of, cr.plane_of,
                                cr.piece_count, &kp, r, err);
    oit_convex_result_free(&cr);
    free(src);
    if (s == OIT_OK)
        check_sources("kd", l, r);
    return s;
}

/* Every part within K (or wide), its bound the sum of 1 or 2 per piece,
 * inside its leaf's box, and no area lost or gained. */
static void check_kd(const char *name, const tri_list *l, const oit_kd_result *r, uint32_t K)
{
    double area_in = 0, area_out = 0;
    for (size_t i = 0; i < l->n; i++)
        area_in += tri_area(&l->t[i]);
    for (size_t i = 0; i < r->tri_count; i++)
        area_out += tri_area(&r->tris[i]);
    CHECK(fabs(area_out - area_in) <= 1e-5 * area_in, "%s: area %.9g in, %.9g out", name,
          area_in, area_out);
    uint32_t wide = 0;
    for (size_t p = 0; p < r->part_count; p++) {
        const oit_kd_part *pt = &r->parts[p];
        uint32_t sum = 0;
        for (uint32_t q = 0; q < pt->piece_count; q++)
            sum += r->pieces[pt->piece_first + q].plane_count > 1 ? 2 : 1;
        CHECK(pt->layer_bound == sum, "%s: part %zu bound %u, pieces say %u", name, p,
              pt->layer_bound, sum);
        wide += pt->layer_bound > K;
    }
    CHECK(wide == r->wide_parts, "%s: %u wide parts, result says %u", name, wide, r->wide_parts);
    for (size_t n = 0; n < r->node_count; n++) {
        const oit_kd_node *nd = &r->nodes[n];
        if (nd->axis >= 0 || nd->part < 0)
            continue;
        const oit_kd_part *pt = &r->parts[nd->part];
        for (size_t i = pt->tri_first; i < pt->tri_first + pt->tri_count; i++)
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++) {
                    float x = r->tris[i].v[v].pos[k];
                    CHECK(x >= nd->lo[k] && x <= nd->hi[k], "%s: part %d leaves its box",
                          name, nd->part);
                }
    }
    for (size_t i = 0; i < r->slab_count; i++) {
        const oit_kd_slab_leaf *sl = &r->slabs[i];
        const float *n = sl->planes.normal;
        CHECK(sl->planes.d0 <= sl->planes.d1, "%s: slab %zu planes %g > %g", name, i,
              sl->planes.d0, sl->planes.d1);
        for (int h = 0; h < 2; h++) {
            const oit_kd_part *pt = &r->parts[h ? sl->part_above : sl->part_below];
            CHECK(pt->layer_bound <= K, "%s: slab %zu: a part of %u layers", name, i,
                  pt->layer_bound);
            for (size_t t = pt->tri_first; t < pt->tri_first + pt->tri_count; t++)
                for (int v = 0; v < 3; v++) {
                    const float *q = r->tris[t].v[v].pos;
                    double x = (double)n[0] * q[0] + (double)n[1] * q[1] + (double)n[2] * q[2];
                    CHECK(h ? oit_plane_side_exact(n, sl->planes.d1, q) >= 0
                            : oit_plane_side_exact(n, sl->planes.d0, q) <= 0,
                          "%s: slab %zu: a vertex at %.9g is on the wrong side of %g..%g", name,
                          i, x, sl->planes.d0, sl->planes.d1);
                }
        }
    }
    printf("kd %s: %zu triangles -> %zu, %zu parts (%u wide, %zu slabs), depth %u\n", name,
           l->n, r->tri_count, r->part_count, wide, r->slab_count, r->depth);
}

/* A closed box bar: centre c, half-extents h along the right-handed frame
 * (u, v, u x v). */
static void make_bar(tri_list *l, const double c[3], const double u[3], const double v[3],
                     const double h[3])
{
    static const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    double w[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    oit_vertex k[8];
    for (int i = 0; i < 8; i++) {
        double a = i & 1 ? h[0] : -h[0], b = i & 2 ? h[1] : -h[1], e = i & 4 ? h[2] : -h[2];
        k[i] = vtx((float)(c[0] + a * u[0] + b * v[0] + e * w[0]),
                   (float)(c[1] + a * u[1] + b * v[1] + e * w[1]),
                   (float)(c[2] + a * u[2] + b * v[2] + e * w[2]));
    }
    for (int f = 0; f < 6; f++) {
        const int *q = quads[f];
        push3(l, k[q[0]], k[q[1]], k[q[2]]);
        push3(l, k[q[0]], k[q[2]], k[q[3]]);
    }
}

/* Two parallel diagonal bars side by side: every axis plane through their
 * common box cuts one, a diagonal plane separates them, so at K = 2 the
 * node becomes a slab leaf and nothing is clipped. Two crossing bars have
 * no separating plane: they are clipped, as before. */
static void test_kd_slab(void)
{
    const double r2 = sqrt(0.5), u[3] = {r2, r2, 0}, v[3] = {-r2, r2, 0}, h[3] = {2, 0.15, 0.5};
    tri_list side = {0}, cross = {0};
    for (int i = 0; i < 2; i++)
        make_bar(&side, (const double[3]){v[0] * (i ? 0.4 : -0.4), v[1] * (i ? 0.4 : -0.4), 0.1},
                 u, v, h);
    make_bar(&cross, (const double[3]){0, 0, 0.1}, u, v, h);
    make_bar(&cross, (const double[3]){0, 0, 0.1}, v, (const double[3]){-r2, -r2, 0}, h);
    oit_kd_result r;
    oit_error err = {0};
    CHECK(kd_of(&side, 2, &r, &err) == OIT_OK, "side by side: %s", err.message);
    check_kd("side by side", &side, &r, 2);
    CHECK(r.slab_count == 1 && r.part_count == 2 && r.tri_count == side.n && r.split_added == 0,
          "side by side: %zu slabs, %zu parts, %zu of %zu triangles, want 1 slab, 2 parts and "
          "nothing clipped", r.slab_count, r.part_count, r.tri_count, side.n);
    if (r.slab_count) {
        const float *n = r.slabs[0].planes.normal;
        CHECK(fabs(fabs(n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) - 1) < 1e-3,
              "side by side: slab normal (%g %g %g), want +-(%g %g 0)", n[0], n[1], n[2], v[0],
              v[1]);
    }
    oit_kd_result_free(&r);
    CHECK(kd_of(&cross, 2, &r, &err) == OIT_OK, "crossing: %s", err.message);
    check_kd("crossing", &cross, &r, 2);
    CHECK(r.slab_count == 0 && r.split_added > 0, "crossing: %zu slabs, %llu triangles added; "
          "crossing bars have no separating plane", r.slab_count,
          (unsigned long long)r.split_added);
    oit_kd_result_free(&r);
    free(side.t);
    free(cross.t);
}


/* ------------------------------------------------------ cutting planes */

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

/* ------------------------------------------------------------- sorting */

typedef struct keyed {
    uint32_t key, order;
} keyed;
#define KEYED_LESS(x, y) ((x)->key < (y)->key)
OIT_SORT_DEFINE(sort_keyed, keyed, KEYED_LESS)

/* Sorted and stable at every size around the insertion threshold and far
 * above it, with many equal keys. */
static void test_sort(void)
{
    uint32_t seed = 7;
    const size_t sizes[] = {0, 1, 2, 23, 24, 25, 48, 49, 1000, 4097};
    keyed *a = malloc(4097 * sizeof *a);
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        size_t n = sizes[s];
        for (size_t i = 0; i < n; i++)
            a[i] = (keyed){lcg_next(&seed) % 17, (uint32_t)i};
        sort_keyed(a, n);
        for (size_t i = 1; i < n; i++)
            CHECK(a[i - 1].key < a[i].key ||
                      (a[i - 1].key == a[i].key && a[i - 1].order < a[i].order),
                  "sort of %zu: element %zu out of order or unstable", n, i);
    }
    free(a);
}

/* A quad of the plane z = h in the frame u = (1,1,0)/sqrt2, v = (-1,1,0)/sqrt2. */
static void push_uv_quad(tri_list *l, double u0, double u1, double v0, double v1, float h)
{
    const double r = sqrt(0.5);
    oit_vertex c[4];
    for (int i = 0; i < 4; i++) {
        double u = i & 1 ? u1 : u0, v = i & 2 ? v1 : v0;
        c[i] = vtx((float)(r * (u - v)), (float)(r * (u + v)), h);
    }
    push3(l, c[0], c[1], c[3]);
    push3(l, c[0], c[3], c[2]);
}

/* Three long pieces side by side along a diagonal, weights 2 (K = 4),
 * each of the last two with a triangle reaching back across the gap before
 * it: every axis plane, and every plane tilted out of the diagonal, crosses
 * long triangles, the plane of normal (1,-1,0) in the first gap crosses
 * only one (in the second gap, the third piece would count below too). */
static void test_kd_cut(void)
{
    tri_list l = {0};
    uint32_t slot[16];
    const double r = sqrt(0.5);
    push_uv_quad(&l, -3, 3, -1, -0.1, 0);
    push_uv_quad(&l, -3, 3, -1, -0.1, 2);
    size_t zero = l.n, first = 0;
    for (int piece = 1; piece <= 2; piece++) {
        double v0 = piece == 1 ? 0.1 : 1.2, v1 = piece == 1 ? 1 : 2, back = v0 - 0.5;
        push_uv_quad(&l, -3, 3, v0, v1, 0);
        push_uv_quad(&l, -3, 3, v0, v1, 2);
        push3(&l, vtx((float)(r * -back), (float)(r * back), 0),
              vtx((float)(r * -back), (float)(r * back), 2),
              vtx((float)(r * -(v0 + 0.4)), (float)(r * (v0 + 0.4)), 1));
        if (piece == 1)
            first = l.n;
    }
    for (size_t i = 0; i < l.n; i++)
        slot[i] = i < zero ? 0 : i < first ? 1 : 2;
    const uint32_t weight[3] = {2, 2, 2};
    const float lo[3] = {-4, -4, -1}, hi[3] = {4, 4, 3};
    oit_kd_cut cut;
    int found = oit_kd_find_cut(l.t, l.n, slot, weight, 3, 4, lo, hi, UINT32_MAX, &cut);
    const int *n = cut.plane.n;
    double v = cut.plane.d / sqrt(2.0);
    printf("kd cut: found %d, normal (%d %d %d), d %g (v = %g), %u crossed\n", found, n[0], n[1],
           n[2], cut.plane.d, v, cut.cut);
    CHECK(found == 1 && cut.cut == 1 && n[0] == 1 && n[1] == -1 && n[2] == 0,
          "want the plane of normal (1,-1,0) crossing 1 triangle");
    CHECK(found == 1 && -v > -0.1 && -v < 0.1, "plane at v = %g, want inside the gap (-0.1, 0.1)",
          -v);
    CHECK(oit_kd_find_cut(l.t, l.n, slot, weight, 3, 4, lo, hi, 0, &cut) == 0,
          "max_cut 0: a plane crossing nothing does not exist");
    CHECK(oit_kd_find_cut(l.t, l.n, slot, weight, 3, 2, lo, hi, UINT32_MAX, &cut) == 0,
          "K = 2: a half of 2 pieces cannot be within 2 layers");
    free(l.t);
}

static void test_kd(void)
{
    tri_list torus = {0}, saddle = {0};
    make_torus(&torus, 24, 12);
    /* 16 sectors around one vertex, alternately up and down: 8 two-plane
     * pieces meet there (16 layers), so it ends as one wide part. */
    oit_vertex c = vtx(0.31f, 0.17f, 0.05f);
    for (int i = 0; i < 16; i++) {
        double a0 = 2 * PI * i / 16, a1 = 2 * PI * (i + 1) / 16;
        push3(&saddle, c, vtx(0.31f + (float)cos(a0), 0.17f + (float)sin(a0), i % 2 ? -0.55f : 0.65f),
              vtx(0.31f + (float)cos(a1), 0.17f + (float)sin(a1), i % 2 ? 0.65f : -0.55f));
    }
    oit_kd_result r;
    oit_error err = {0};
    CHECK(kd_of(&torus, 8, &r, &err) == OIT_OK, "torus: %s", err.message);
    check_kd("torus", &torus, &r, 8);
    CHECK(r.wide_parts == 0, "torus: %u wide parts, it has no vertex of > 8 layers",
          r.wide_parts);
    oit_kd_result_free(&r);
    CHECK(kd_of(&saddle, 8, &r, &err) == OIT_OK, "saddle: %s", err.message);
    check_kd("saddle", &saddle, &r, 8);
    CHECK(r.wide_parts == 1, "saddle: %u wide parts, want 1 (the centre)", r.wide_parts);
    oit_kd_result_free(&r);
    free(torus.t);
    free(saddle.t);
}

/* ------------------------------------------- the fast scheme (kd_fast.h) */

/* n parallel unit squares at z = 0.05 i: every line near the z axis
 * crosses all of them. */
static void make_stack(tri_list *l, int n)
{
    for (int i = 0; i < n; i++) {
        float z = 0.05f * (float)i;
        push3(l, vtx(0, 0, z), vtx(1, 0, z), vtx(1, 1, z));
        push3(l, vtx(0, 0, z), vtx(1, 1, z), vtx(0, 1, z));
    }
}

static uint32_t measured(const tri_list *l)
{
    uint32_t layers = 0;
    oit_error err = {0};
    CHECK(oit_layers_measure(l->t, l->n, &layers, &err) == OIT_OK, "measure: %s", err.message);
    return layers;
}

static void test_layers_measured(void)
{
    tri_list cube = {0}, sphere = {0}, torus = {0}, stack = {0};
    make_cube(&cube, 0, 1);
    make_sphere(&sphere, 16, 24);
    make_torus(&torus, 48, 24);
    make_stack(&stack, 20);
    /* A closed convex surface: two crossings; a torus: four along its axis
     * plane; the stack: one a sheet. */
    CHECK(measured(&cube) == 2, "cube: %u layers, want 2", measured(&cube));
    CHECK(measured(&sphere) == 2, "sphere: %u layers, want 2", measured(&sphere));
    CHECK(measured(&torus) == 4, "torus: %u layers, want 4", measured(&torus));
    CHECK(measured(&stack) == 20, "stack of 20: %u layers", measured(&stack));
    CHECK(oit_layers_measure(NULL, 0, &(uint32_t){0}, NULL) == OIT_OK, "empty part");
    free(cube.t);
    free(sphere.t);
    free(torus.t);
    free(stack.t);
}

/* Every part within T triangles and inside its leaf's box, bounds equal to
 * the measured count, few triangles added. */
static void check_fast(const char *name, const tri_list *l, uint32_t T, const oit_kd_result *r)
{
    size_t tris = 0;
    for (size_t i = 0; i < r->node_count; i++) {
        const oit_kd_node *nd = &r->nodes[i];
        if (nd->axis >= 0 || nd->part < 0)
            continue;
        const oit_kd_part *p = &r->parts[nd->part];
        tris += p->tri_count;
        CHECK(p->tri_count <= T || p->layer_bound > OIT_PARTFILE_MAX_LAYERS / 2,
              "%s: part of %zu triangles > %u", name, p->tri_count, T);
        uint32_t want = 0;
        oit_layers_measure(r->tris + p->tri_first, p->tri_count, &want, NULL);
        CHECK(p->layer_bound == (want < OIT_PARTFILE_MAX_LAYERS ? want : OIT_PARTFILE_MAX_LAYERS),
              "%s: part bound %u, measured %u", name, p->layer_bound, want);
        for (size_t t = p->tri_first; t < p->tri_first + p->tri_count; t++)
            for (int v = 0; v < 3; v++)
                for (int a = 0; a < 3; a++) {
                    float x = r->tris[t].v[v].pos[a];
                    CHECK(x >= nd->lo[a] && x <= nd->hi[a], "%s: vertex outside its leaf",
                          name);
                }
    }
    CHECK(tris == r->tri_count, "%s: leaves hold %zu of %zu triangles", name, tris, r->tri_count);
    CHECK(r->tri_count <= l->n + l->n / 5, "%s: %zu -> %zu triangles", name, l->n, r->tri_count);
    CHECK(r->slab_count == 0 && r->piece_count == r->part_count, "%s: slabs or pieces", name);
}

static void test_kd_fast(void)
{
    tri_list torus = {0}, stack = {0};
    make_torus(&torus, 64, 32);
    make_stack(&stack, 100);
    float lo[3] = {-2, -2, -2}, hi[3] = {2, 2, 2};
    oit_kd_fast_params p = {500, 8, 0, 0};
    oit_kd_result r;
    oit_error err = {0};
    uint32_t *src = odd_sources(torus.n);
    CHECK(oit_kd_build_fast(lo, hi, torus.t, src, torus.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    free(src);
    check_sources("kd fast torus", &torus, &r);
    CHECK(r.part_count >= torus.n / 500 && r.part_count <= torus.n / 50,
          "torus of %zu: %zu parts at T = 500", torus.n, r.part_count);
    printf("kd fast torus: %zu triangles -> %zu, %zu parts at T = 500, most measured %u\n",
           torus.n, r.tri_count, r.part_count, r.max_measured);
    check_fast("torus", &torus, 500, &r);
    oit_kd_result_free(&r);
    /* 100 sheets in one node of 200 triangles: above the file's 64 layers,
     * so it is split further (along z) until every part is within it. */
    float slo[3] = {0, 0, 0}, shi[3] = {8, 8, 8};
    p.part_triangles = 100000;
    src = odd_sources(stack.n);
    CHECK(oit_kd_build_fast(slo, shi, stack.t, src, stack.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    free(src);
    check_sources("kd fast stack", &stack, &r);
    CHECK(r.part_count >= 2 && r.clamped_parts == 0 && r.max_measured <= 64 &&
              r.tri_count == stack.n,
          "stack of 100: %zu parts, %u clamped, max %u, %zu triangles", r.part_count,
          r.clamped_parts, r.max_measured, r.tri_count);
    printf("kd fast stack of 100 sheets: %zu parts, most measured %u\n", r.part_count,
           r.max_measured);
    check_fast("stack", &stack, 100000, &r);
    oit_kd_result_free(&r);
    p.part_triangles = 0;
    CHECK(oit_kd_build_fast(lo, hi, torus.t, NULL, torus.n, &p, &r, &err) == OIT_ERR_ARGUMENT,
          "parts of 0 triangles must be refused");
    free(torus.t);
    free(stack.t);
}

/* The tree of a fast build, checked against its input alone: the root is the
 * given box; every split lies strictly inside its node and halves it into
 * its two children (one level deeper); every leaf names its own part or
 * none, and the parts tile the output triangles; each part lies in its
 * leaf's closed box with its measured layer count (1..64); every output
 * triangle carries an input source; and every input triangle that no split
 * plane on its way down crosses comes out exactly once, bit for bit, in the
 * leaf it falls in (a triangle in a plane goes below). Returns the number of
 * input triangles that some plane clipped. */
static size_t check_fast_tree(const char *name, const tri_list *l, const float lo[3],
                              const float hi[3], const oit_kd_result *r)
{
    size_t bad_node = 0, bad_part = 0, bad_tri = 0, lost = 0, doubled = 0, clipped = 0;
    CHECK(r->node_count >= 1 && !memcmp(r->nodes[0].lo, lo, 12) && !memcmp(r->nodes[0].hi, hi, 12),
          "%s: the root is not the cell's box", name);
    unsigned char *part_seen = calloc(r->part_count + 1, 1);
    for (size_t i = 0; i < r->node_count; i++) {
        const oit_kd_node *nd = &r->nodes[i];
        if (nd->axis >= 0) {
            int a = nd->axis;
            const oit_kd_node *c = &r->nodes[nd->child];
            int ok = a < 3 && nd->child + 1u < r->node_count && nd->child > i &&
                     nd->lo[a] < nd->split && nd->split < nd->hi[a];
            for (int h = 0; ok && h < 2; h++)
                for (int k = 0; k < 3; k++) {
                    float want_lo = h && k == a ? nd->split : nd->lo[k];
                    float want_hi = !h && k == a ? nd->split : nd->hi[k];
                    ok &= c[h].lo[k] == want_lo && c[h].hi[k] == want_hi &&
                          c[h].depth == nd->depth + 1;
                }
            bad_node += !ok;
            continue;
        }
        if (nd->part < 0)
            continue;
        if ((size_t)nd->part >= r->part_count || part_seen[nd->part]++) {
            bad_part++;
            continue;
        }
        const oit_kd_part *p = &r->parts[nd->part];
        uint32_t layers = 0;
        oit_layers_measure(r->tris + p->tri_first, p->tri_count, &layers, NULL);
        layers = layers < OIT_PARTFILE_MAX_LAYERS ? layers : OIT_PARTFILE_MAX_LAYERS;
        bad_part += p->tri_count == 0 || p->layer_bound != layers || p->layer_bound < 1;
        for (size_t t = p->tri_first; t < p->tri_first + p->tri_count && t < r->tri_count; t++)
            for (int v = 0; v < 3; v++)
                for (int k = 0; k < 3; k++) {
                    float x = r->tris[t].v[v].pos[k];
                    bad_tri += !(x >= nd->lo[k] && x <= nd->hi[k]);
                }
    }
    size_t covered = 0;
    for (size_t p = 0; p < r->part_count; p++) {
        bad_part += !part_seen[p] || r->parts[p].tri_first != covered;
        covered += r->parts[p].tri_count;
    }
    bad_part += covered != r->tri_count;
    for (size_t i = 0; i < r->tri_count; i++)
        bad_tri += r->src[i] % 2 == 0 || (r->src[i] - 1) / 2 >= l->n;
    /* Each input triangle down the tree to its leaf, unless a plane crosses it. */
    for (size_t i = 0; i < l->n && !bad_node; i++) {
        const oit_triangle *t = &l->t[i];
        size_t n = 0;
        int cut = 0;
        while (r->nodes[n].axis >= 0 && !cut) {
            const oit_kd_node *nd = &r->nodes[n];
            float a = t->v[0].pos[nd->axis], b = t->v[1].pos[nd->axis], c = t->v[2].pos[nd->axis];
            float tmin = fminf(a, fminf(b, c)), tmax = fmaxf(a, fmaxf(b, c));
            if (tmax <= nd->split)
                n = nd->child;
            else if (tmin >= nd->split)
                n = nd->child + 1;
            else
                cut = 1;
        }
        clipped += cut;
        if (cut)
            continue;
        int32_t part = r->nodes[n].part;
        size_t copies = 0, same = 0;
        for (size_t j = 0; j < r->tri_count; j++)
            if (r->src[j] == 2 * i + 1) {
                copies++;
                same += part >= 0 && j >= r->parts[part].tri_first &&
                        j < r->parts[part].tri_first + r->parts[part].tri_count &&
                        !memcmp(r->tris[j].v, t->v, sizeof t->v);
            }
        lost += same == 0;
        doubled += copies > 1;
    }
    CHECK(bad_node == 0 && bad_part == 0 && bad_tri == 0,
          "%s: %zu bad splits, %zu bad parts (leaf, cover, layer bound), %zu triangles outside "
          "their leaf or of no source", name, bad_node, bad_part, bad_tri);
    CHECK(lost == 0 && doubled == 0,
          "%s: of %zu triangles no plane cuts, %zu lost or changed, %zu stored twice", name,
          l->n - clipped, lost, doubled);
    free(part_seen);
    return clipped;
}

/* A coordinate k ulps above x. */
static float ulps(float x, int k)
{
    while (k-- > 0)
        x = nextafterf(x, INFINITY);
    return x;
}

/* n triangles with corners on the float grid of [base, base + w ulps] on
 * every axis, none degenerate. */
static void make_ulp_cluster(tri_list *l, const float base[3], int w, int n, uint32_t seed)
{
    for (int i = 0; i < n; i++) {
        float c[3][3];
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                seed = seed * 1664525u + 1013904223u;
                c[v][k] = ulps(base[k], (int)((seed >> 16) % (uint32_t)(w + 1)));
            }
        oit_triangle t = {{vtx(c[0][0], c[0][1], c[0][2]), vtx(c[1][0], c[1][1], c[1][2]),
                           vtx(c[2][0], c[2][1], c[2][2])}};
        if (tri_area(&t) > 0)
            push(l, &t);
        else
            i--;
    }
}

/* Nodes no plane can split: a few ulps wide. The build must end (the test's
 * timeout), keep a valid tree, lose and duplicate nothing, and make such a
 * node one part however many triangles it holds. */
static void test_kd_fast_ulps(void)
{
    oit_kd_fast_params p = {4, 8, 0, 0};
    oit_kd_result r;
    oit_error err = {0};
    /* 1 ulp a side: no float lies strictly inside, so the cell is one part
     * of all its triangles, in input order. */
    const float base[3] = {1.0f, -3.0f, 1024.0f};
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = base[k];
        hi[k] = ulps(base[k], 1);
    }
    tri_list one = {0};
    make_ulp_cluster(&one, base, 1, 40, 7);
    uint32_t *src = odd_sources(one.n);
    CHECK(oit_kd_build_fast(lo, hi, one.t, src, one.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    CHECK(r.node_count == 1 && r.part_count == 1 && r.tri_count == one.n &&
              r.nodes[0].part == 0 && !memcmp(r.tris, one.t, one.n * sizeof *one.t) &&
              !memcmp(r.src, src, one.n * sizeof *src),
          "1-ulp cell of %zu triangles: %zu nodes, %zu parts, %zu triangles: want the cell as "
          "one part, its triangles as given", one.n, r.node_count, r.part_count, r.tri_count);
    check_fast_tree("1-ulp cell", &one, lo, hi, &r);
    oit_kd_result_free(&r);
    free(src);
    /* 2 and 3 ulps a side: a plane or two, then unsplittable nodes. */
    for (int w = 2; w <= 3; w++) {
        tri_list l = {0};
        for (int k = 0; k < 3; k++)
            hi[k] = ulps(base[k], w);
        make_ulp_cluster(&l, base, w, 60, 11u * (uint32_t)w);
        src = odd_sources(l.n);
        char name[48];
        snprintf(name, sizeof name, "%d-ulp cell", w);
        CHECK(oit_kd_build_fast(lo, hi, l.t, src, l.n, &p, &r, &err) == OIT_OK, "%s: %s", name,
              err.message);
        check_fast_tree(name, &l, lo, hi, &r);
        CHECK(r.node_count > 1 && r.node_count < 200, "%s: %zu nodes", name, r.node_count);
        oit_kd_result_free(&r);
        free(src);
        free(l.t);
    }
    /* A cell of ordinary size whose triangles gather in a 2-ulp cluster
     * beside a torus: the build descends to the cluster and stops there. */
    tri_list mix = {0};
    make_torus(&mix, 24, 12);
    const float spot[3] = {0.7f, 0.3f, 0.2f};
    make_ulp_cluster(&mix, spot, 2, 50, 5);
    const float clo[3] = {-2, -2, -2}, chi[3] = {2, 2, 2};
    src = odd_sources(mix.n);
    p.part_triangles = 16;
    CHECK(oit_kd_build_fast(clo, chi, mix.t, src, mix.n, &p, &r, &err) == OIT_OK, "%s",
          err.message);
    size_t clipped = check_fast_tree("torus and a 2-ulp cluster", &mix, clo, chi, &r);
    printf("kd fast, ulp-wide nodes: 1-ulp cell one part of %zu; torus and a cluster of 50: "
           "%zu parts, depth %u, %zu triangles clipped\n", one.n, r.part_count, r.depth,
           clipped);
    CHECK(r.depth < 48, "torus and a 2-ulp cluster: depth %u, the cap", r.depth);
    oit_kd_result_free(&r);
    free(src);
    free(mix.t);
    free(one.t);
}

int main(void)
{
    test_predicates();
    test_clip();
    test_clip_direction();
    test_convex();
    test_kd_split();
    test_kd_split_events();
    test_kd_split_touching();
    test_kd();
    test_kd_slab();
    test_sort();
    test_plane_exact();
    test_kd_cut();
    test_layers_measured();
    test_kd_fast();
    test_kd_fast_ulps();
    return test_verdict();
}
