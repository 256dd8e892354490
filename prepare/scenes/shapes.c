/* Closed solids (contract in shapes.h). */
#include "prepare/scenes/shapes.h"

#include <math.h>

void oit_shape_hexahedron(oit_emit *e, const oit_v3 corner[8])
{
    uint32_t c[8];
    for (int i = 0; i < 8; i++)
        c[i] = oit_emit_vertex(e, corner[i]);
    /* Corner i has bit 0 = x, bit 1 = y, bit 2 = z; each quad is
     * counter-clockwise seen from outside. */
    static const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (int f = 0; f < 6; f++)
        oit_emit_quad(e, c[quads[f][0]], c[quads[f][1]], c[quads[f][2]], c[quads[f][3]]);
}

void oit_shape_box(oit_emit *e, oit_v3 lo, oit_v3 hi)
{
    oit_v3 c[8];
    for (int i = 0; i < 8; i++)
        c[i] = oit_v3_make(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    oit_shape_hexahedron(e, c);
}

static float *axis_ref(oit_v3 *v, int axis)
{
    return axis == 0 ? &v->x : axis == 1 ? &v->y : &v->z;
}

/* The I-profile as one closed prism: a solid of three boxes would have the
 * web's faces lying on the flanges', coincident faces that no transparency
 * method can order and that a partitioner must not split between. */
void oit_shape_ibeam(oit_emit *e, oit_v3 lo, oit_v3 hi, int along, int up)
{
    int w = 3 - along - up;
    float h0 = *axis_ref(&lo, up), h1 = *axis_ref(&hi, up);
    float w0 = *axis_ref(&lo, w), w1 = *axis_ref(&hi, w);
    float tf = 0.15f * (h1 - h0), tw = 0.06f * (w1 - w0), wc = 0.5f * (w0 + w1);
    /* Outline counter-clockwise in (w, up): bottom flange, web, top flange. */
    const float prof[12][2] = {{w0, h0},      {w1, h0},      {w1, h0 + tf}, {wc + tw, h0 + tf},
                               {wc + tw, h1 - tf}, {w1, h1 - tf}, {w1, h1},  {w0, h1},
                               {w0, h1 - tf}, {wc - tw, h1 - tf}, {wc - tw, h0 + tf}, {w0, h0 + tf}};
    /* The web's corners lie on the flanges' inner edges: fanning each
     * flange from its outer corner uses them, so no T-junction appears. */
    static const int cap[10][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 10}, {0, 10, 11}, {10, 3, 4},
                                   {10, 4, 9}, {6, 7, 8}, {6, 8, 9}, {6, 9, 4}, {6, 4, 5}};
    /* (w, up, along) may be a left-handed frame: then every face flips. */
    int flip = up != (w + 1) % 3;
    uint32_t v[2][12];
    for (int end = 0; end < 2; end++)
        for (int i = 0; i < 12; i++) {
            oit_v3 p = end ? hi : lo;
            *axis_ref(&p, w) = prof[i][0];
            *axis_ref(&p, up) = prof[i][1];
            v[end][i] = oit_emit_vertex(e, p);
        }
    for (int t = 0; t < 10; t++) {
        const int *c = cap[t];
        if (flip) {
            oit_emit_tri(e, v[1][c[0]], v[1][c[2]], v[1][c[1]]);
            oit_emit_tri(e, v[0][c[0]], v[0][c[1]], v[0][c[2]]);
        } else {
            oit_emit_tri(e, v[1][c[0]], v[1][c[1]], v[1][c[2]]);
            oit_emit_tri(e, v[0][c[0]], v[0][c[2]], v[0][c[1]]);
        }
    }
    for (int i = 0; i < 12; i++) {
        int j = (i + 1) % 12;
        if (flip)
            oit_emit_quad(e, v[0][i], v[1][i], v[1][j], v[0][j]);
        else
            oit_emit_quad(e, v[0][i], v[0][j], v[1][j], v[1][i]);
    }
}

uint64_t oit_shape_cylinder_cost(int seg)
{
    return oit_sweep_cost(seg, 2, 2, 0);
}

void oit_shape_cylinder(oit_emit *e, oit_v3 p0, oit_v3 p1, float r, int seg)
{
    oit_v3 t = oit_v3_normalize(oit_v3_sub(p1, p0));
    oit_v3 u = oit_v3_perpendicular(t), v = oit_v3_cross(t, u);
    oit_sweep s;
    oit_sweep_begin(&s, e, seg);
    oit_sweep_pole(&s, p0);
    oit_sweep_ring(&s, p0, u, v, r, r);
    oit_sweep_ring(&s, p1, u, v, r, r);
    oit_sweep_pole(&s, p1);
}

static int sphere_stacks(int seg)
{
    return seg / 2 < 2 ? 2 : seg / 2;
}

uint64_t oit_shape_sphere_cost(int seg)
{
    return oit_sweep_cost(seg, sphere_stacks(seg) - 1, 2, 0);
}

void oit_shape_sphere(oit_emit *e, oit_v3 c, float r, int seg)
{
    int stacks = sphere_stacks(seg);
    /* Travel along +y, so the rings are spanned by z and x (z x x = y). */
    oit_v3 y = oit_v3_make(0, 1, 0), u = oit_v3_make(0, 0, 1), v = oit_v3_make(1, 0, 0);
    oit_sweep s;
    oit_sweep_begin(&s, e, seg);
    oit_sweep_pole(&s, oit_v3_sub(c, oit_v3_scale(y, r)));
    for (int k = 1; k < stacks; k++) {
        double th = OIT_PI * k / stacks;
        float rr = r * (float)sin(th);
        oit_sweep_ring(&s, oit_v3_add(c, oit_v3_scale(y, -r * (float)cos(th))), u, v, rr, rr);
    }
    oit_sweep_pole(&s, oit_v3_add(c, oit_v3_scale(y, r)));
}

static int tank_head_rings(int seg)
{
    return seg / 4 < 1 ? 1 : seg / 4;
}

uint64_t oit_shape_tank_cost(int seg)
{
    return oit_sweep_cost(seg, 2 * tank_head_rings(seg), 2, 0);
}

void oit_shape_tank(oit_emit *e, oit_v3 p0, oit_v3 p1, float r, int seg)
{
    int h = tank_head_rings(seg);
    oit_v3 a = oit_v3_normalize(oit_v3_sub(p1, p0));
    oit_v3 u = oit_v3_perpendicular(a), v = oit_v3_cross(a, u);
    oit_sweep s;
    oit_sweep_begin(&s, e, seg);
    oit_sweep_pole(&s, oit_v3_sub(p0, oit_v3_scale(a, r)));
    for (int k = 1; k <= h; k++) { /* bottom head, up to the equator at p0 */
        double th = 0.5 * OIT_PI * k / h;
        float rr = r * (float)sin(th);
        oit_sweep_ring(&s, oit_v3_sub(p0, oit_v3_scale(a, r * (float)cos(th))), u, v, rr, rr);
    }
    for (int k = 0; k < h; k++) { /* top head, from the equator at p1 */
        double th = 0.5 * OIT_PI * k / h;
        float rr = r * (float)cos(th);
        oit_sweep_ring(&s, oit_v3_add(p1, oit_v3_scale(a, r * (float)sin(th))), u, v, rr, rr);
    }
    oit_sweep_pole(&s, oit_v3_add(p1, oit_v3_scale(a, r)));
}

uint64_t oit_shape_torus_cost(int seg_major, int seg_minor)
{
    return oit_sweep_cost(seg_minor, seg_major, 0, 1);
}

void oit_shape_torus(oit_emit *e, oit_v3 c, oit_v3 n, float R, float r, float aspect,
                     int twist_turns, int seg_major, int seg_minor)
{
    oit_v3 a = oit_v3_perpendicular(n), b = oit_v3_cross(n, a); /* a x b = n */
    oit_sweep s;
    oit_sweep_begin(&s, e, seg_minor);
    for (int i = 0; i < seg_major; i++) {
        double th = 2.0 * OIT_PI * i / seg_major, psi = twist_turns * th;
        oit_v3 u0 = oit_v3_add(oit_v3_scale(a, (float)cos(th)), oit_v3_scale(b, (float)sin(th)));
        oit_v3 t = oit_v3_add(oit_v3_scale(a, -(float)sin(th)), oit_v3_scale(b, (float)cos(th)));
        oit_v3 v0 = oit_v3_cross(t, u0);
        float cp = (float)cos(psi), sp = (float)sin(psi);
        oit_v3 u = oit_v3_add(oit_v3_scale(u0, cp), oit_v3_scale(v0, sp));
        oit_v3 v = oit_v3_sub(oit_v3_scale(v0, cp), oit_v3_scale(u0, sp));
        oit_sweep_ring(&s, oit_v3_add(c, oit_v3_scale(u0, R)), u, v, r, r * aspect);
    }
    oit_sweep_close_loop(&s);
}

static int elbow_segments(int seg)
{
    return seg / 4 < 2 ? 2 : seg / 4;
}

uint64_t oit_shape_pipe_cost(int n, int seg)
{
    if (seg > OIT_SWEEP_MAX_SEG)
        seg = OIT_SWEEP_MAX_SEG;
    return oit_sweep_cost(seg, 2 + (n - 2) * (elbow_segments(seg) + 1), 2, 0);
}

/* Rings of one elbow at corner p between directions tin and tout; u is the
 * ring frame carried along the run (parallel transport), updated. */
static void pipe_elbow(oit_sweep *s, oit_v3 p, oit_v3 tin, oit_v3 tout, float r, float bend,
                       oit_v3 *u)
{
    int nb = elbow_segments(s->seg);
    oit_v3 k = oit_v3_normalize(oit_v3_cross(tin, tout));
    oit_v3 o = oit_v3_add(oit_v3_sub(p, oit_v3_scale(tin, bend)), oit_v3_scale(tout, bend));
    oit_v3 uk = *u;
    for (int i = 0; i <= nb; i++) {
        float al = (float)(0.5 * OIT_PI * i / nb);
        oit_v3 c = oit_v3_add(o, oit_v3_add(oit_v3_scale(tout, -bend * cosf(al)),
                                            oit_v3_scale(tin, bend * sinf(al))));
        oit_v3 t = oit_v3_rotate(tin, k, al);
        uk = oit_v3_rotate(*u, k, al);
        uk = oit_v3_normalize(oit_v3_sub(uk, oit_v3_scale(t, oit_v3_dot(t, uk))));
        oit_sweep_ring(s, c, uk, oit_v3_cross(t, uk), r, r);
    }
    *u = uk;
}

void oit_shape_pipe(oit_emit *e, const oit_v3 *p, int n, float r, float bend, int seg)
{
    oit_v3 t = oit_v3_normalize(oit_v3_sub(p[1], p[0]));
    oit_v3 u = oit_v3_perpendicular(t);
    oit_sweep s;
    oit_sweep_begin(&s, e, seg);
    oit_sweep_pole(&s, p[0]);
    oit_sweep_ring(&s, p[0], u, oit_v3_cross(t, u), r, r);
    for (int i = 1; i + 1 < n; i++) {
        oit_v3 tout = oit_v3_normalize(oit_v3_sub(p[i + 1], p[i]));
        pipe_elbow(&s, p[i], t, tout, r, bend, &u);
        t = tout;
    }
    oit_sweep_ring(&s, p[n - 1], u, oit_v3_cross(t, u), r, r);
    oit_sweep_pole(&s, p[n - 1]);
}
