/* What the prepare/partition/ tests share (one program a module,
 * tests/partition/CMakeLists.txt): closed meshes built from triangles
 * (cube, torus, sphere, a stack of sheets, a box bar in any frame), triangle areas, and the source
 * indices the kd builds are given and checked against. Static inline: each
 * test uses some of them. */
#ifndef OIT_TESTS_PARTITION_TEST_H
#define OIT_TESTS_PARTITION_TEST_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/mesh.h"
#include "prepare/partition/clip.h"
#include "prepare/partition/kd.h"
#include "base/vec.h"
#include "tests/lib/test_check.h"

static const double PI = 3.14159265358979323846;

typedef struct tri_list {
    oit_triangle *t;
    size_t n, cap;
} tri_list;

static inline void push(tri_list *l, const oit_triangle *t)
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

static inline oit_vertex vtx(float x, float y, float z)
{
    oit_vertex v = {{x, y, z}, {200, 100, 50, 128}};
    return v;
}

static inline void push3(tri_list *l, oit_vertex a, oit_vertex b, oit_vertex c)
{
    oit_triangle t = {{a, b, c}};
    push(l, &t);
}

/* Cube [lo, hi]^3, 12 triangles, outward counter-clockwise. */
static inline void make_cube(tri_list *l, float lo, float hi)
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
static inline void push_grid(tri_list *l, const oit_vertex *g, int nu, int nv, int wrap_u)
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

static inline void make_torus(tri_list *l, int nu, int nv)
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
static inline void make_sphere(tri_list *l, int rings, int segs)
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

static inline double tri_area(const oit_triangle *t)
{
    return oit_area3fd(t->v[0].pos, t->v[1].pos, t->v[2].pos);
}

/* n parallel unit squares at z = 0.05 i: every line near the z axis
 * crosses all of them. */
static inline void make_stack(tri_list *l, int n)
{
    for (int i = 0; i < n; i++) {
        float z = 0.05f * (float)i;
        push3(l, vtx(0, 0, z), vtx(1, 0, z), vtx(1, 1, z));
        push3(l, vtx(0, 0, z), vtx(1, 1, z), vtx(0, 1, z));
    }
}

/* Source indices given to the builds: 2 i + 1, so that an index that is
 * really a position (or a lost one, 0) shows. */
static inline uint32_t *odd_sources(size_t n)
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
static inline void check_sources(const char *name, const tri_list *l, const oit_kd_result *r)
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

/* A closed box bar: centre c, half-extents h along the right-handed frame
 * (u, v, u x v). */
static inline void make_bar(tri_list *l, const double c[3], const double u[3], const double v[3],
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

#endif
