/* Buffered emission of indexed, coloured triangles into a PLY writer, and
 * swept surfaces (rings of points joined by quad strips), the building block
 * of every round solid the scenes make.
 *
 * Emission never fails at the call site: the first error sticks in
 * e->status (with e->err filled) and later calls do nothing, so generators
 * stay free of error plumbing and check once at the end.
 *
 * Orientation: every closed solid is wound counter-clockwise seen from
 * outside (outward geometric normals), which the translucent shading needs to
 * tell entering from leaving. A sweep travels along t = u x v, where u and v
 * span each ring; its rings then face outward.
 */
#ifndef OIT_SCENES_EMIT_H
#define OIT_SCENES_EMIT_H

#include <stddef.h>
#include <stdint.h>

#include "formats/ply_writer.h"

#define OIT_PI 3.14159265358979323846

typedef struct oit_v3 {
    float x, y, z;
} oit_v3;

static inline oit_v3 oit_v3_make(float x, float y, float z) { oit_v3 r = {x, y, z}; return r; }
static inline oit_v3 oit_v3_add(oit_v3 a, oit_v3 b) { return oit_v3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline oit_v3 oit_v3_sub(oit_v3 a, oit_v3 b) { return oit_v3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline oit_v3 oit_v3_scale(oit_v3 a, float s) { return oit_v3_make(a.x * s, a.y * s, a.z * s); }
static inline float oit_v3_dot(oit_v3 a, oit_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline oit_v3 oit_v3_cross(oit_v3 a, oit_v3 b)
{
    return oit_v3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
oit_v3 oit_v3_normalize(oit_v3 a);
/* Any unit vector perpendicular to the unit vector a. */
oit_v3 oit_v3_perpendicular(oit_v3 a);
/* a rotated by angle (radians) about the unit axis k (Rodrigues). */
oit_v3 oit_v3_rotate(oit_v3 a, oit_v3 k, float angle);

typedef void (*oit_emit_progress_fn)(void *user, uint64_t triangles);

typedef struct oit_emit {
    oit_ply_writer *writer;
    uint8_t rgba[4]; /* colour of the vertices emitted next */
    float *xyz;      /* buffered vertices: xyz[3*i], rgba[4*i] */
    uint8_t *vrgba;
    size_t nv;
    uint32_t *idx; /* buffered faces, absolute indices */
    size_t nf;
    uint32_t base;      /* absolute index of the first buffered vertex */
    uint64_t triangles; /* emitted so far, buffered included */
    oit_status status;
    oit_error *err;
    oit_emit_progress_fn progress; /* optional, called on every flush */
    void *progress_user;
} oit_emit;

/* The writer must have been opened with vertex_rgba and without face_rgba. */
oit_status oit_emit_init(oit_emit *e, oit_ply_writer *writer, oit_error *err);
/* Hands the buffered data to the writer; returns the sticky status. */
oit_status oit_emit_flush(oit_emit *e);
void oit_emit_free(oit_emit *e);

void oit_emit_color(oit_emit *e, uint8_t r, uint8_t g, uint8_t b, uint8_t a);
/* Returns the vertex's absolute index. */
uint32_t oit_emit_vertex(oit_emit *e, oit_v3 p);
void oit_emit_tri(oit_emit *e, uint32_t a, uint32_t b, uint32_t c);
/* Quad a b c d counter-clockwise as seen from its front. */
void oit_emit_quad(oit_emit *e, uint32_t a, uint32_t b, uint32_t c, uint32_t d);

enum { OIT_SWEEP_MAX_SEG = 128 };

typedef struct oit_sweep {
    oit_emit *e;
    int seg;
    int rings;
    uint32_t first_ring, last_ring;
    int has_start_pole;
    uint32_t start_pole;
    float cs[2 * OIT_SWEEP_MAX_SEG]; /* cos, sin per ring point */
} oit_sweep;

/* seg points per ring, 3..OIT_SWEEP_MAX_SEG. */
void oit_sweep_begin(oit_sweep *s, oit_emit *e, int seg);
/* A single point closing the sweep: before the first ring it starts it (a
 * pole or the centre of a flat cap), after rings it ends it. */
void oit_sweep_pole(oit_sweep *s, oit_v3 p);
/* Ring of points c + ru cos(phi) u + rv sin(phi) v, joined to the previous
 * ring (or start pole). The sweep must travel along u x v. */
void oit_sweep_ring(oit_sweep *s, oit_v3 c, oit_v3 u, oit_v3 v, float ru, float rv);
/* Joins the last ring back to the first (tori, closed bands). */
void oit_sweep_close_loop(oit_sweep *s);

/* Triangles a sweep makes: rings joined in sequence, poles counted 0..2,
 * loop 1 when the last ring joins the first. */
static inline uint64_t oit_sweep_cost(int seg, int rings, int poles, int loop)
{
    return (uint64_t)seg * (2u * (uint64_t)(rings - 1 + loop) + (uint64_t)poles);
}

#endif
