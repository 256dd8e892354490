/* Axis-plane clipping (clip.h). */
#include "prepare/partition/clip.h"

#include <math.h>
#include <string.h>

#include "prepare/partition/predicates.h"
#include "base/minmax.h"


/* Lexicographic order on position, then colour: the canonical edge order. */
int oit_vertex_less(const oit_vertex *a, const oit_vertex *b)
{
    for (int k = 0; k < 3; k++)
        if (a->pos[k] != b->pos[k])
            return a->pos[k] < b->pos[k];
    return memcmp(a->rgba, b->rgba, 4) < 0;
}

static float clamp_between(double x, float a, float b)
{
    float lo = a < b ? a : b, hi = a < b ? b : a;
    float f = (float)x;
    return f < lo ? lo : f > hi ? hi : f;
}

/* The point where edge p-q meets pos[axis] = c; p and q lie strictly on
 * opposite sides. */
static oit_vertex edge_point(const oit_vertex *p, const oit_vertex *q, int axis, float c)
{
    const oit_vertex *a = oit_vertex_less(p, q) ? p : q;
    const oit_vertex *b = a == p ? q : p;
    double t = ((double)c - a->pos[axis]) / ((double)b->pos[axis] - a->pos[axis]);
    oit_vertex r;
    for (int k = 0; k < 3; k++)
        r.pos[k] = clamp_between(a->pos[k] + t * ((double)b->pos[k] - a->pos[k]), a->pos[k],
                                 b->pos[k]);
    r.pos[axis] = c;
    for (int k = 0; k < 4; k++)
        r.rgba[k] = (uint8_t)lrint(a->rgba[k] + t * ((double)b->rgba[k] - a->rgba[k]));
    return r;
}

int oit_clip_polygon(const oit_vertex *in, int n, int axis, float c, int keep_below,
                     oit_vertex *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const oit_vertex *p = &in[i], *q = &in[(i + 1) % n];
        float dp = keep_below ? p->pos[axis] - c : c - p->pos[axis];
        float dq = keep_below ? q->pos[axis] - c : c - q->pos[axis];
        if (dp <= 0)
            out[m++] = *p;
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0))
            out[m++] = edge_point(p, q, axis, c);
    }
    return m;
}

static void to_double(const oit_vertex *v, double d[3])
{
    d[0] = v->pos[0];
    d[1] = v->pos[1];
    d[2] = v->pos[2];
}

int oit_triangle_is_degenerate(const oit_triangle *t)
{
    double a[3], b[3], c[3];
    to_double(&t->v[0], a);
    to_double(&t->v[1], b);
    to_double(&t->v[2], c);
    return oit_triangle_degenerate(a, b, c);
}

int oit_polygon_triangulate(const oit_vertex *v, int n, oit_triangle *out)
{
    int m = 0;
    for (int i = 1; i + 1 < n; i++) {
        oit_triangle t = {{v[0], v[i], v[i + 1]}};
        if (!oit_triangle_is_degenerate(&t))
            out[m++] = t;
    }
    return m;
}

static int inside_box(const oit_triangle *t, const float lo[3], const float hi[3])
{
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            if (t->v[i].pos[k] < lo[k] || t->v[i].pos[k] > hi[k])
                return 0;
    return 1;
}

int oit_clip_triangle_box(const oit_triangle *t, const float lo[3], const float hi[3],
                          oit_triangle *out)
{
    if (inside_box(t, lo, hi)) {
        out[0] = *t;
        return 1;
    }
    oit_vertex a[OIT_CLIP_MAX_VERTS], b[OIT_CLIP_MAX_VERTS];
    memcpy(a, t->v, sizeof t->v);
    int n = 3;
    for (int k = 0; k < 3 && n >= 3; k++) {
        n = oit_clip_polygon(a, n, k, lo[k], 0, b);
        if (n >= 3)
            n = oit_clip_polygon(b, n, k, hi[k], 1, a);
    }
    return n >= 3 ? oit_polygon_triangulate(a, n, out) : 0;
}

void oit_clip_triangle_split(const oit_triangle *t, int axis, float c, oit_triangle *below,
                             int *n_below, oit_triangle *above, int *n_above)
{
    float mn = t->v[0].pos[axis], mx = mn;
    for (int i = 1; i < 3; i++) {
        mn = oit_min_f(mn, t->v[i].pos[axis]);
        mx = oit_max_f(mx, t->v[i].pos[axis]);
    }
    *n_below = *n_above = 0;
    if (mx <= c) {
        below[(*n_below)++] = *t;
        return;
    }
    if (mn >= c) {
        above[(*n_above)++] = *t;
        return;
    }
    oit_vertex p[OIT_CLIP_MAX_VERTS];
    int n = oit_clip_polygon(t->v, 3, axis, c, 1, p);
    *n_below = oit_polygon_triangulate(p, n, below);
    n = oit_clip_polygon(t->v, 3, axis, c, 0, p);
    *n_above = oit_polygon_triangulate(p, n, above);
}
