/* The layers at one pixel (pick.h). */
#include "view/render/pick/pick.h"

#include "partfile/triangles.h"
#include "view/render/image/shade.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

oit_status oit_pick_ray_make(const oit_view *view, int x, int y, oit_pick_ray *out,
                             oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (x < 0 || y < 0 || x >= view->width || y >= view->height)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "pick: pixel %d,%d lies outside the %dx%d view", x, y, view->width,
                             view->height);
    out->has_model = oit_view_model(view, out->model);
    oit_status s = oit_ray_basis_make(view, "pick", &out->basis, err);
    if (s != OIT_OK)
        return s;
    out->view = view;
    out->x = x;
    out->y = y;
    oit_ray_basis_pixel(&out->basis, x + 0.5, y + 0.5, view->width, view->height, out->org,
                        out->dir);
    return OIT_OK;
}

static void sub3(const float a[3], const float b[3], double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = (double)a[k] - b[k];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* tri as the GL methods see it: through the model matrix, in float. */
static const oit_triangle *placed(const oit_pick_ray *r, const oit_triangle *tri,
                                  oit_triangle *buf)
{
    if (!r->has_model)
        return tri;
    const double *m = r->model;
    *buf = *tri;
    for (int v = 0; v < 3; v++) {
        const float *p = tri->v[v].pos;
        for (int k = 0; k < 3; k++)
            buf->v[v].pos[k] = (float)(m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k]);
    }
    return buf;
}

/* Möller and Trumbore's test in double, edges included (a centre exactly
 * on an edge is on the ambiguity mask, where either answer is allowed). */
static int ray_meets(const oit_pick_ray *r, const oit_triangle *given, oit_pick_hit *hit)
{
    oit_triangle buf;
    const oit_triangle *tri = placed(r, given, &buf);
    double e1[3], e2[3], pv[3], tv[3], qv[3];
    sub3(tri->v[1].pos, tri->v[0].pos, e1);
    sub3(tri->v[2].pos, tri->v[0].pos, e2);
    cross3(r->dir, e2, pv);
    double det = dot3(e1, pv);
    if (det == 0.0 || !isfinite(det))
        return 0;
    double inv = 1.0 / det;
    for (int k = 0; k < 3; k++)
        tv[k] = r->org[k] - tri->v[0].pos[k];
    double u = dot3(tv, pv) * inv;
    if (!(u >= 0.0 && u <= 1.0))
        return 0;
    cross3(tv, e1, qv);
    double v = dot3(r->dir, qv) * inv;
    if (!(v >= 0.0 && u + v <= 1.0))
        return 0;
    double t = dot3(e2, qv) * inv;
    if (!(t > 0.0))
        return 0;
    hit->tri = *tri;
    hit->t = (float)t;
    hit->u = (float)u;
    hit->v = (float)v;
    return 1;
}

oit_status oit_pick_mesh(const oit_pick_ray *ray, const oit_mesh *mesh, const uint32_t *source,
                         oit_pick_hits *hits, oit_error *err)
{
    for (size_t i = 0; i < mesh->count; i++) {
        oit_pick_hit h;
        if (!ray_meets(ray, &mesh->tris[i], &h))
            continue;
        h.source = source ? source[i] : i;
        h.part = OIT_PICK_NO_PART;
        oit_status s = oit_pick_hits_add(hits, &h, err);
        if (s != OIT_OK)
            return s;
    }
    return OIT_OK;
}

/* A part's box through the model matrix: the box of its corners'
 * images. */
static void placed_box(const oit_pick_ray *r, const float lo[3], const float hi[3], float out_lo[3],
                       float out_hi[3])
{
    for (int k = 0; k < 3; k++) {
        out_lo[k] = INFINITY;
        out_hi[k] = -INFINITY;
    }
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
        for (int k = 0; k < 3; k++) {
            const double *m = r->model;
            float q = (float)(m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k]);
            out_lo[k] = q < out_lo[k] ? q : out_lo[k];
            out_hi[k] = q > out_hi[k] ? q : out_hi[k];
        }
    }
}

/* The slab test against a part's bounds (through the model matrix),
 * widened by a millionth of their size so that rounding never skips a part
 * the ray grazes. */
static int ray_crosses_box(const oit_pick_ray *r, const float in_lo[3], const float in_hi[3])
{
    float plo[3], phi[3];
    const float *lo = in_lo, *hi = in_hi;
    if (r->has_model) {
        placed_box(r, in_lo, in_hi, plo, phi);
        lo = plo;
        hi = phi;
    }
    double t0 = 0.0, t1 = INFINITY;
    for (int k = 0; k < 3; k++) {
        double pad = 1e-6 * ((double)hi[k] - lo[k]) + 1e-30;
        double a = lo[k] - pad, b = hi[k] + pad;
        if (r->dir[k] == 0.0) {
            if (r->org[k] < a || r->org[k] > b)
                return 0;
            continue;
        }
        double ta = (a - r->org[k]) / r->dir[k], tb = (b - r->org[k]) / r->dir[k];
        if (ta > tb) {
            double s = ta;
            ta = tb;
            tb = s;
        }
        t0 = ta > t0 ? ta : t0;
        t1 = tb < t1 ? tb : t1;
        if (t0 > t1)
            return 0;
    }
    return 1;
}

/* The hits of one part, decoded (and validated on its first use) into
 * *blob, grown as needed. */
static oit_status pick_part(const oit_pick_ray *ray, oit_partfile *pf, uint32_t part,
                            oit_partfile_buffer *buf, void **blob, size_t *blob_cap,
                            oit_pick_hits *hits, oit_error *err)
{
    const oit_partfile_part *p = &oit_partfile_parts(pf)[part];
    uint64_t tris = p->index_count / 3, bytes = oit_part_sourced_bytes(tris);
    if (bytes > *blob_cap) {
        void *nb = realloc(*blob, bytes);
        if (!nb)
            return oit_error_set(err, OIT_ERR_NOMEM, "pick: cannot hold part %u (%llu bytes)",
                                 part, (unsigned long long)bytes);
        *blob = nb;
        *blob_cap = bytes;
    }
    oit_status s = oit_part_expand_sourced(pf, part, buf, *blob, err);
    const oit_triangle *t = *blob;
    const uint32_t *src = (const uint32_t *)(t + tris);
    for (uint64_t i = 0; s == OIT_OK && i < tris; i++) {
        oit_pick_hit h;
        if (!ray_meets(ray, &t[i], &h))
            continue;
        h.source = src[i];
        h.part = part;
        s = oit_pick_hits_add(hits, &h, err);
    }
    return s;
}

oit_status oit_pick_partfile(const oit_pick_ray *ray, oit_partfile *pf, oit_pick_hits *hits,
                             oit_error *err)
{
    oit_partfile_buffer buf = {0};
    void *blob = NULL;
    size_t blob_cap = 0;
    oit_status s = OIT_OK;
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    for (uint32_t i = 0; s == OIT_OK && i < oit_partfile_part_count(pf); i++)
        if (ray_crosses_box(ray, parts[i].bounds_min, parts[i].bounds_max))
            s = pick_part(ray, pf, i, &buf, &blob, &blob_cap, hits, err);
    free(blob);
    oit_partfile_buffer_free(&buf);
    return s;
}

static int by_source_t(const void *a, const void *b)
{
    const oit_pick_hit *x = a, *y = b;
    if (x->source != y->source)
        return x->source < y->source ? -1 : 1;
    return (x->t > y->t) - (x->t < y->t);
}

/* The tie rule: (key, source) ascending, a strict weak order. */
static int by_key_source(const void *a, const void *b)
{
    const oit_pick_hit *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->source > y->source) - (x->source < y->source);
}

/* Keys the hits and drops those outside the depth range or cut away, and
 * all but the nearest hit of each source triangle; returns how many stay. */
static size_t key_and_keep(const oit_pick_ray *ray, oit_pick_hit *h, size_t n)
{
    oit_ray_keying k;
    oit_ray_pixel px;
    oit_ray_keying_init(ray->view, &k);
    oit_ray_pixel_at(&k, ray->x, ray->y, &px);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (oit_ray_depth_kept(&ray->basis, h[i].t, ray->dir) &&
            oit_ray_key_hit(&k, &px, &h[i].tri, h[i].t, &h[i].key))
            h[m++] = h[i];
    if (m > 1)
        qsort(h, m, sizeof *h, by_source_t);
    size_t u = 0;
    for (size_t i = 0; i < m; i++)
        if (u == 0 || h[i].source != h[u - 1].source)
            h[u++] = h[i];
    return u;
}

static void layer_of(const oit_pick_ray *ray, const oit_shaded_fragment *f,
                     const oit_pixel_state *before, const oit_shading *s,
                     const oit_pick_hit *h, oit_pick_layer *out)
{
    /* The transmittance in front of the fragment, after the medium it
     * crosses (translucent) but before its own alpha: the state's after a
     * copy of it with alpha 0 is added to a copy of the state. */
    oit_pixel_state st = *before;
    oit_shaded_fragment clear = *f;
    clear.alpha = 0.0f;
    oit_pixel_add(&st, s, &clear);
    memset(out, 0, sizeof *out);
    out->depth = f->t;
    for (int k = 0; k < 3; k++)
        out->point[k] = ray->org[k] + (double)h->t * ray->dir[k];
    for (int c = 0; c < 3; c++) {
        out->colour[c] = f->colour[c];
        out->transmittance[c] = (float)st.T[c];
    }
    out->alpha = f->alpha;
    out->front = f->front;
    out->part = h->part;
    out->source_triangle = h->source;
}

size_t oit_pick_compose(const oit_pick_ray *ray, oit_pick_hits *hits, oit_pick_layer *layers,
                        size_t capacity)
{
    oit_shading s = ray->view->shading;
    oit_shading_resolve_defaults(&s);
    size_t n = key_and_keep(ray, hits->h, hits->n);
    hits->n = n;
    if (n > 1)
        qsort(hits->h, n, sizeof *hits->h, by_key_source);
    /* Shading looks back along the ray: from the eye, or (orthographic) from
     * the ray's origin on the near plane. */
    float from[3];
    for (int k = 0; k < 3; k++)
        from[k] = ray->basis.ortho ? (float)ray->org[k] : ray->view->camera.eye[k];
    oit_pixel_state st;
    oit_pixel_begin(&st);
    /* only the layers asked for are shaded: those behind change none of them */
    for (size_t i = 0; i < n && i < capacity; i++) {
        const oit_pick_hit *h = &hits->h[i];
        float bary[3] = {1.0f - h->u - h->v, h->u, h->v};
        oit_shaded_fragment f;
        oit_shade_fragment(&s, &h->tri, (uint32_t)h->source, bary, from, h->key, &f);
        layer_of(ray, &f, &st, &s, h, &layers[i]);
        oit_pixel_add(&st, &s, &f);
    }
    return n;
}
