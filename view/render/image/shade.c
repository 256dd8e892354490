/* Shading and compositing as defined in shade.h. Geometry and the running
 * pixel state are kept in double so that the reference is the more accurate
 * side of every comparison; the shaded fragment is stored in float because
 * that is what the GL methods carry. */
#include "view/render/image/shade.h"
#include "base/vec.h"

#include <math.h>
#include <string.h>

/* (p1 - p0) x (p2 - p0) in double, where the float differences are exact
 * and the products keep 53 bits: triangles of one plane get normals
 * parallel to about 1e-16. */
static void cross_normal(const oit_triangle *tri, double n[3])
{
    double e1[3], e2[3];
    oit_sub3fd(tri->v[1].pos, tri->v[0].pos, e1);
    oit_sub3fd(tri->v[2].pos, tri->v[0].pos, e2);
    oit_cross3d(e1, e2, n);
}

/* Linear mode decodes each vertex's colour (and default_rgb) before
 * interpolation, as the GL vertex shader does: shading and the
 * interpolation run in linear light (shade.h, "Colour space"). */
static void interpolate_base(const oit_shading *s, const oit_triangle *tri,
                             const float bary[3], float base_rgb[3], float *base_a)
{
    int lin = s->colour_space == OIT_COLOUR_LINEAR;
    double rgba[4] = {0, 0, 0, 0};
    for (int v = 0; v < 3; v++)
        for (int c = 0; c < 4; c++) {
            double x = tri->v[v].rgba[c];
            if (lin && c < 3)
                x = 255.0 * oit_srgb_decode(x / 255.0);
            rgba[c] += (double)bary[v] * x;
        }
    for (int c = 0; c < 3; c++) {
        float d = lin ? (float)oit_srgb_decode(s->default_rgb[c]) : s->default_rgb[c];
        base_rgb[c] = (oit_shading_attrs(s) & OIT_ATTR_COLOUR) ? (float)(rgba[c] / 255.0) : d;
    }
    *base_a = (oit_shading_attrs(s) & OIT_ATTR_ALPHA) ? (float)(rgba[3] / 255.0) : s->alpha;
    if (oit_triangle_opaque(s, tri))
        *base_a = 1.0f; /* exactly: nothing behind it may show */
}

int oit_triangle_opaque(const oit_shading *s, const oit_triangle *tri)
{
    return s->mode == OIT_SHADING_TRANSPARENT && (oit_shading_attrs(s) & OIT_ATTR_ALPHA) &&
           tri->v[0].rgba[3] == 255 && tri->v[1].rgba[3] == 255 &&
           tri->v[2].rgba[3] == 255;
}

void oit_shade_fragment(const oit_shading *s, const oit_triangle *tri,
                        uint32_t prim, const float bary[3], const float eye[3],
                        double t, oit_shaded_fragment *out)
{
    double n[3], v[3];
    cross_normal(tri, n);
    for (int k = 0; k < 3; k++) {
        double p = 0.0;
        for (int j = 0; j < 3; j++)
            p += (double)bary[j] * tri->v[j].pos[k];
        v[k] = (double)eye[k] - p;
    }
    /* A zero normal or eye vector (left unchanged) shades as edge-on
     * instead of producing NaN. */
    double ndv_signed = 0.0;
    if (oit_normalize3d(n) > 0.0 && oit_normalize3d(v) > 0.0)
        ndv_signed = oit_dot3d(n, v);
    double ndv = fabs(ndv_signed);
    double light = OIT_SHADE_AMBIENT + OIT_SHADE_DIFFUSE * ndv;

    memset(out, 0, sizeof *out);
    out->t = t;
    out->prim = prim;
    out->front = ndv_signed > 0.0;
    float base_a;
    interpolate_base(s, tri, bary, out->base, &base_a);
    if (s->mode == OIT_SHADING_TRANSLUCENT) {
        for (int c = 0; c < 3; c++)
            out->colour[c] = (float)light;
        out->alpha = (float)(OIT_SHADE_F0 + (1.0 - OIT_SHADE_F0) * pow(1.0 - ndv, 5.0));
    } else {
        for (int c = 0; c < 3; c++)
            out->colour[c] = (float)(out->base[c] * light);
        out->alpha = base_a;
    }
}

int oit_depth_plane(const oit_triangle *tri, const float eye[3], float n[3], float *d)
{
    double nn[3], q[3];
    cross_normal(tri, nn);
    oit_sub3fd(tri->v[0].pos, eye, q);
    *d = 0.0f;
    n[0] = n[1] = n[2] = 0.0f;
    if (!(oit_normalize3d(nn) > 0.0) || !isfinite(nn[0] + nn[1] + nn[2]))
        return 0;
    for (int k = 0; k < 3; k++)
        n[k] = (float)nn[k];
    *d = (float)oit_dot3d(nn, q);
    return 1;
}

float oit_depth_quantise(float t)
{
    uint32_t bits;
    memcpy(&bits, &t, sizeof bits);
    bits &= ~((1u << OIT_DEPTH_KEY_DROP_BITS) - 1u);
    memcpy(&t, &bits, sizeof t);
    return t;
}

float oit_depth_key(const float n[3], float d, const float dir[3], float t_interp)
{
    float nd = n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2];
    float t = t_interp;
    if (fabsf(nd) >= OIT_DEPTH_GRAZING) {
        float tp = d / nd;
        if (tp > 0.0f && isfinite(tp))
            t = tp;
    }
    return oit_depth_quantise(t);
}

void oit_pixel_begin(oit_pixel_state *st)
{
    memset(st, 0, sizeof *st);
    for (int c = 0; c < 3; c++)
        st->T[c] = 1.0;
}

/* Beer-Lambert over the distance travelled inside the open medium. */
static void absorb(oit_pixel_state *st, const oit_shading *s, double t)
{
    double per_length = (double)s->absorption / (double)s->scene_scale;
    double d = t - st->t_prev;
    for (int c = 0; c < 3; c++)
        st->T[c] *= exp(-per_length * (1.0 - (double)st->medium[c]) * d);
}

void oit_pixel_add(oit_pixel_state *st, const oit_shading *s,
                   const oit_shaded_fragment *f)
{
    int translucent = s->mode == OIT_SHADING_TRANSLUCENT;
    if (translucent && st->nest > 0)
        absorb(st, s, f->t);
    double a = f->alpha;
    for (int c = 0; c < 3; c++) {
        st->C[c] += st->T[c] * a * f->colour[c];
        st->T[c] *= 1.0 - a;
    }
    if (translucent) {
        if (f->front) {
            st->nest += 1;
            memcpy(st->medium, f->base, sizeof st->medium);
        } else if (st->nest > 0) {
            st->nest -= 1;
        }
        st->t_prev = f->t;
    }
}

void oit_pixel_end(const oit_pixel_state *st, const oit_shading *s, float rgb[3])
{
    for (int c = 0; c < 3; c++) {
        /* A negative background means black (view.h). */
        double bg = s->background[c] > 0.0f ? s->background[c] : 0.0;
        if (s->colour_space == OIT_COLOUR_LINEAR)
            rgb[c] = (float)oit_srgb_encode(st->C[c] + st->T[c] * oit_srgb_decode(bg));
        else
            rgb[c] = (float)(st->C[c] + st->T[c] * bg);
    }
}

double oit_srgb_decode(double c)
{
    if (!(c > 0.0))
        return 0.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

double oit_srgb_encode(double c)
{
    if (!(c > 0.0))
        return 0.0;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

int oit_shaded_fragment_cmp(const void *a, const void *b)
{
    const oit_shaded_fragment *x = a, *y = b;
    if (x->t < y->t) return -1;
    if (x->t > y->t) return 1;
    return (x->prim > y->prim) - (x->prim < y->prim);
}
