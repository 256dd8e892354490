/* prepare/partition/clip.h: watertight plane splitting of a closed mesh (sides, new
 * vertices on the plane, area kept), and seams that two triangles walking
 * an edge in opposite directions must share bit for bit. */
#include "prepare/partition/clip.h"
#include "tests/prepare/partition/partition_test.h"

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

int main(void)
{
    test_clip();
    test_clip_direction();
    return test_verdict();
}
