/* Buffered emission and sweeps (contract in emit.h). */
#include "prepare/scenes/emit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Small enough to keep the generator's memory a few MB at any scene size,
 * large enough that writer calls are rare. */
enum { EMIT_VERTS = 1 << 16, EMIT_FACES = 1 << 17 };

oit_v3 oit_v3_normalize(oit_v3 a)
{
    float l = sqrtf(oit_v3_dot(a, a));
    return l > 0 ? oit_v3_scale(a, 1.0f / l) : a;
}

oit_v3 oit_v3_perpendicular(oit_v3 a)
{
    /* Cross with the axis a is least aligned with, for a well-conditioned result. */
    oit_v3 k = fabsf(a.x) < 0.6f ? oit_v3_make(1, 0, 0)
             : fabsf(a.y) < 0.6f ? oit_v3_make(0, 1, 0) : oit_v3_make(0, 0, 1);
    return oit_v3_normalize(oit_v3_cross(a, k));
}

oit_v3 oit_v3_rotate(oit_v3 a, oit_v3 k, float angle)
{
    float c = cosf(angle), s = sinf(angle);
    oit_v3 r = oit_v3_add(oit_v3_scale(a, c), oit_v3_scale(oit_v3_cross(k, a), s));
    return oit_v3_add(r, oit_v3_scale(k, oit_v3_dot(k, a) * (1 - c)));
}

oit_status oit_emit_init(oit_emit *e, oit_ply_writer *writer, oit_error *err)
{
    memset(e, 0, sizeof *e);
    e->writer = writer;
    e->err = err;
    e->xyz = malloc(EMIT_VERTS * 3 * sizeof(float));
    e->vrgba = malloc(EMIT_VERTS * 4);
    e->idx = malloc(EMIT_FACES * 3 * sizeof(uint32_t));
    memset(e->rgba, 255, 4);
    if (!e->xyz || !e->vrgba || !e->idx)
        e->status = oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate emission buffers");
    return e->status;
}

void oit_emit_free(oit_emit *e)
{
    free(e->xyz);
    free(e->vrgba);
    free(e->idx);
    e->xyz = NULL;
    e->vrgba = NULL;
    e->idx = NULL;
}

oit_status oit_emit_flush(oit_emit *e)
{
    if (e->status)
        return e->status;
    /* Vertices first: the writer checks that faces only use written ones. */
    e->status = oit_ply_writer_add_vertices(e->writer, e->xyz, e->vrgba, e->nv, NULL, e->err);
    if (!e->status)
        e->status = oit_ply_writer_add_faces(e->writer, e->idx, NULL, e->nf, e->err);
    e->base += (uint32_t)e->nv;
    e->nv = e->nf = 0;
    if (e->progress)
        e->progress(e->progress_user, e->triangles);
    return e->status;
}

void oit_emit_color(oit_emit *e, uint8_t r, uint8_t g, uint8_t b, uint8_t a)
{
    e->rgba[0] = r, e->rgba[1] = g, e->rgba[2] = b, e->rgba[3] = a;
}

uint32_t oit_emit_vertex(oit_emit *e, oit_v3 p)
{
    if (e->nv == EMIT_VERTS)
        oit_emit_flush(e);
    if (e->status)
        return 0;
    float *x = e->xyz + 3 * e->nv;
    x[0] = p.x, x[1] = p.y, x[2] = p.z;
    memcpy(e->vrgba + 4 * e->nv, e->rgba, 4);
    return e->base + (uint32_t)e->nv++;
}

void oit_emit_tri(oit_emit *e, uint32_t a, uint32_t b, uint32_t c)
{
    if (e->nf == EMIT_FACES)
        oit_emit_flush(e);
    if (e->status)
        return;
    uint32_t *t = e->idx + 3 * e->nf++;
    t[0] = a, t[1] = b, t[2] = c;
    e->triangles++;
}

void oit_emit_quad(oit_emit *e, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    oit_emit_tri(e, a, b, c);
    oit_emit_tri(e, a, c, d);
}

void oit_sweep_begin(oit_sweep *s, oit_emit *e, int seg)
{
    memset(s, 0, sizeof *s);
    s->e = e;
    s->seg = seg < 3 ? 3 : seg > OIT_SWEEP_MAX_SEG ? OIT_SWEEP_MAX_SEG : seg;
    for (int j = 0; j < s->seg; j++) {
        double phi = 2.0 * OIT_PI * j / s->seg;
        s->cs[2 * j] = (float)cos(phi);
        s->cs[2 * j + 1] = (float)sin(phi);
    }
}

/* Ring indices are consecutive (a ring's vertices are emitted together), so
 * point j of a ring starting at r is r + j. */
static uint32_t ring_at(const oit_sweep *s, uint32_t ring, int j)
{
    return ring + (uint32_t)(j % s->seg);
}

static void join_rings(oit_sweep *s, uint32_t a, uint32_t b)
{
    for (int j = 0; j < s->seg; j++)
        oit_emit_quad(s->e, ring_at(s, a, j), ring_at(s, a, j + 1), ring_at(s, b, j + 1),
                      ring_at(s, b, j));
}

void oit_sweep_pole(oit_sweep *s, oit_v3 p)
{
    uint32_t v = oit_emit_vertex(s->e, p);
    if (s->rings == 0) {
        s->has_start_pole = 1;
        s->start_pole = v;
        return;
    }
    for (int j = 0; j < s->seg; j++)
        oit_emit_tri(s->e, ring_at(s, s->last_ring, j), ring_at(s, s->last_ring, j + 1), v);
}

void oit_sweep_ring(oit_sweep *s, oit_v3 c, oit_v3 u, oit_v3 v, float ru, float rv)
{
    oit_v3 su = oit_v3_scale(u, ru), sv = oit_v3_scale(v, rv);
    uint32_t first = 0;
    for (int j = 0; j < s->seg; j++) {
        oit_v3 p = oit_v3_add(c, oit_v3_add(oit_v3_scale(su, s->cs[2 * j]),
                                            oit_v3_scale(sv, s->cs[2 * j + 1])));
        uint32_t id = oit_emit_vertex(s->e, p);
        if (j == 0)
            first = id;
    }
    if (s->rings > 0)
        join_rings(s, s->last_ring, first);
    else if (s->has_start_pole)
        for (int j = 0; j < s->seg; j++)
            oit_emit_tri(s->e, s->start_pole, ring_at(s, first, j + 1), ring_at(s, first, j));
    if (s->rings == 0)
        s->first_ring = first;
    s->last_ring = first;
    s->rings++;
}

void oit_sweep_close_loop(oit_sweep *s)
{
    if (s->rings > 1)
        join_rings(s, s->last_ring, s->first_ring);
}
