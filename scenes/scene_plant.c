/* plant: a procedural power plant of T triangles (within a few triangles).
 *
 * The plant is a grid of blocks; each block is a steel frame of several
 * floors (I-beam columns and beams on a concrete slab) holding grated
 * catwalks with handrails, stairs, tanks, ducts and, filling the rest of its
 * triangle budget, pipe racks and routed pipe runs with elbows. Tessellation
 * grows slowly with T and the block count linearly, so big plants are both
 * finer and larger; pipes dominate, giving depth complexity in the hundreds
 * across blocks at 12M triangles.
 *
 * Budgeting: every object's exact cost is known before it is emitted (see
 * shapes.h), a block emits objects while they fit its share of T, then tops
 * up with ever cheaper objects (short pipes, pipe supports), so the total
 * lands within 12 triangles per block of T. Objects stream out one by one:
 * memory does not depend on T. */
#include "scenes/scene.h"

#include <math.h>

#include "scenes/rng.h"
#include "scenes/shapes.h"

enum { FLOORS_MIN = 3, FLOORS_MAX = 5 };
static const float BLOCK_W = 24.0f, BLOCK_GAP = 6.0f, FLOOR_H = 5.0f;
static const double TRIS_PER_BLOCK = 1.0e6;

typedef struct block {
    oit_emit *e;
    oit_rng rng;
    int seg;         /* ring points of big round objects */
    uint64_t left;   /* triangles left in this block's budget */
    oit_v3 lo, hi;   /* block volume */
    int floors;
} block;

/* Industrial palette: rgb, per kind of object. */
enum { C_STEEL, C_GRATING, C_TANK, C_DUCT, C_SLAB, C_PIPE0 };
static const uint8_t PALETTE[][3] = {
    {80, 95, 110},   /* structural steel, primer blue-grey */
    {230, 185, 30},  /* safety yellow catwalks and stairs */
    {215, 215, 220}, /* tank white */
    {165, 170, 175}, /* galvanised duct */
    {150, 145, 135}, /* concrete */
    {40, 135, 70},   /* pipes: process green, */
    {190, 40, 30},   /* fire red, */
    {40, 90, 185},   /* water blue, */
    {235, 120, 25},  /* orange, */
    {120, 80, 50},   /* brown, */
    {120, 120, 125}, /* grey, */
    {110, 60, 140},  /* violet */
};
enum { PIPE_COLOURS = 7 };

uint64_t oit_scene_plant_estimate(const oit_scene_args *a)
{
    return a->triangles;
}

static int plant_seg(uint64_t t)
{
    double s = 8.0 * pow((double)t / 1e4, 0.1);
    int seg = 4 * (int)lround(s / 4);
    return seg < 8 ? 8 : seg > 24 ? 24 : seg;
}

/* Starts an object of `cost` triangles in colour `kind` when it fits. */
static int begin_object(block *b, uint64_t cost, int kind)
{
    if (cost > b->left || b->e->status)
        return 0;
    b->left -= cost;
    const uint8_t *c = PALETTE[kind];
    int j = (int)oit_rng_below(&b->rng, 21) - 10; /* per-object shade */
    uint8_t rgb[3];
    for (int k = 0; k < 3; k++) {
        int v = c[k] + j;
        rgb[k] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
    }
    oit_emit_color(b->e, rgb[0], rgb[1], rgb[2], (uint8_t)oit_rng_range(&b->rng, 51, 154));
    return 1;
}

static oit_v3 at(const block *b, float x, float y, float z)
{
    return oit_v3_make(b->lo.x + x, b->lo.y + y, b->lo.z + z);
}

static void frame(block *b)
{
    float w = BLOCK_W, top = FLOOR_H * b->floors, p = 0.35f; /* profile */
    if (begin_object(b, OIT_BOX_TRIS, C_SLAB))
        oit_shape_box(b->e, at(b, -1, -0.4f, -1), at(b, w + 1, 0, w + 1));
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (begin_object(b, OIT_IBEAM_TRIS, C_STEEL)) {
                float x = i * (w - p) / 3, z = j * (w - p) / 3;
                oit_shape_ibeam(b->e, at(b, x, 0, z), at(b, x + p, top, z + p), 1, 0);
            }
    for (int f = 1; f <= b->floors; f++)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 3; j++) {
                float y = f * FLOOR_H - 0.5f, c = i * (w - p) / 3, s0 = j * (w - p) / 3 + p;
                float s1 = (j + 1) * (w - p) / 3;
                if (begin_object(b, OIT_IBEAM_TRIS, C_STEEL))
                    oit_shape_ibeam(b->e, at(b, s0, y, c), at(b, s1, y + 0.5f, c + p), 0, 1);
                if (begin_object(b, OIT_IBEAM_TRIS, C_STEEL))
                    oit_shape_ibeam(b->e, at(b, c, y, s0), at(b, c + p, y + 0.5f, s1), 2, 1);
            }
}

/* A catwalk along x at height y, from z0 to z0+width: bearing bars across
 * it, two edge bars, handrails on posts. */
static void catwalk(block *b, float y, float z0, float width)
{
    float w = BLOCK_W, pitch = 0.2f;
    int bars = (int)(w / pitch);
    int posts = (int)(w / 2.0f) + 1;
    uint64_t cost = (uint64_t)(bars + 4 + 2 * posts) * OIT_BOX_TRIS;
    if (!begin_object(b, cost, C_GRATING))
        return;
    for (int i = 0; i < bars; i++) {
        float x = i * pitch + 0.08f;
        oit_shape_box(b->e, at(b, x, y, z0), at(b, x + 0.04f, y + 0.05f, z0 + width));
    }
    for (int s = 0; s < 2; s++) {
        float z = s ? z0 + width - 0.06f : z0;
        oit_shape_box(b->e, at(b, 0, y - 0.05f, z), at(b, w, y + 0.06f, z + 0.06f));
        oit_shape_box(b->e, at(b, 0, y + 1.0f, z), at(b, w, y + 1.06f, z + 0.06f));
        for (int i = 0; i < posts; i++) {
            float x = fminf(i * 2.0f, w - 0.06f);
            oit_shape_box(b->e, at(b, x, y + 0.06f, z), at(b, x + 0.06f, y + 1.0f, z + 0.06f));
        }
    }
}

/* Stairs from floor f to f+1 along z, at x0: two stringers and the treads. */
static void stairs(block *b, int f, float x0)
{
    int steps = (int)(FLOOR_H / 0.25f);
    uint64_t cost = (uint64_t)(steps + 2) * OIT_BOX_TRIS;
    if (!begin_object(b, cost, C_GRATING))
        return;
    float y0 = f * FLOOR_H, z0 = 2.0f, run = 0.28f;
    for (int i = 0; i < steps; i++)
        oit_shape_box(b->e, at(b, x0, y0 + i * 0.25f, z0 + i * run),
                      at(b, x0 + 1.0f, y0 + i * 0.25f + 0.05f, z0 + (i + 1) * run));
    for (int s = 0; s < 2; s++) {
        float x = s ? x0 + 1.0f : x0 - 0.08f;
        oit_shape_box(b->e, at(b, x, y0, z0), at(b, x + 0.08f, y0 + FLOOR_H, z0 + steps * run));
    }
}

static void tanks(block *b)
{
    int n = 1 + (int)oit_rng_below(&b->rng, 3);
    for (int i = 0; i < n; i++) {
        float r = oit_rng_range(&b->rng, 1.5f, 3.5f);
        float x = oit_rng_range(&b->rng, r + 1, BLOCK_W - r - 1);
        float z = oit_rng_range(&b->rng, r + 1, BLOCK_W - r - 1);
        if (oit_rng_below(&b->rng, 3) == 0) { /* a sphere on the ground floor */
            if (begin_object(b, oit_shape_sphere_cost(2 * b->seg), C_TANK))
                oit_shape_sphere(b->e, at(b, x, r + 0.5f, z), r, 2 * b->seg);
        } else {
            float h = oit_rng_range(&b->rng, 3, FLOOR_H * b->floors - 2 * r - 1);
            if (begin_object(b, oit_shape_tank_cost(2 * b->seg), C_TANK))
                oit_shape_tank(b->e, at(b, x, r + 0.3f, z), at(b, x, r + 0.3f + fmaxf(h, 0.5f), z),
                               r, 2 * b->seg);
        }
    }
}

/* A duct: rectangular segments along x then z below a floor's beams. */
static void duct(block *b, int f)
{
    if (!begin_object(b, 2 * OIT_BOX_TRIS, C_DUCT))
        return;
    float s = oit_rng_range(&b->rng, 0.6f, 1.4f), y = f * FLOOR_H - 0.7f - s;
    float z = oit_rng_range(&b->rng, 1, BLOCK_W - 1 - s), x = oit_rng_range(&b->rng, 4, BLOCK_W - 1 - s);
    oit_shape_box(b->e, at(b, 0.5f, y, z), at(b, x, y + s, z + s));
    oit_shape_box(b->e, at(b, x, y, 0.5f), at(b, x + s, y + s, z));
}

/* Pipe radius: many small, few large, as in real plants. */
static float pipe_radius(block *b)
{
    static const float r[] = {0.04f, 0.06f, 0.08f, 0.1f, 0.1f, 0.15f, 0.2f, 0.3f, 0.4f};
    return r[oit_rng_below(&b->rng, sizeof r / sizeof r[0])];
}

static int pipe_seg(const block *b, float r)
{
    return r >= 0.15f ? b->seg : b->seg / 2 < 6 ? 6 : b->seg / 2;
}

static float coord(oit_v3 p, int axis)
{
    return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
}

/* Routed run: up to OIT_PIPE_MAX_POINTS points, legs along alternating axes,
 * each long enough for an elbow at both ends, inside the block. */
static int plan_route(block *b, float r, float bend, oit_v3 *p)
{
    float margin = r + 0.2f, hi[3] = {BLOCK_W - margin, FLOOR_H * b->floors - margin, BLOCK_W - margin};
    float minleg = 2 * bend + 0.3f;
    p[0] = oit_v3_make(oit_rng_range(&b->rng, margin, hi[0]), oit_rng_range(&b->rng, margin, hi[1]),
                       oit_rng_range(&b->rng, margin, hi[2]));
    int want = 2 + (int)oit_rng_below(&b->rng, OIT_PIPE_MAX_POINTS - 3), n = 1, prev = -1;
    while (n < want) {
        int axis = (int)oit_rng_below(&b->rng, 3);
        if (axis == prev)
            axis = (axis + 1 + (int)oit_rng_below(&b->rng, 2)) % 3;
        float c = coord(p[n - 1], axis), len = oit_rng_range(&b->rng, minleg, 10.0f);
        float room_up = hi[axis] - c, room_down = c - margin;
        float dir = room_up >= room_down ? 1.0f : -1.0f;
        if (oit_rng_below(&b->rng, 2) && fminf(room_up, room_down) >= minleg)
            dir = -dir;
        len = fminf(len, dir > 0 ? room_up : room_down);
        if (len < minleg)
            break;
        oit_v3 d = oit_v3_make(axis == 0 ? dir * len : 0, axis == 1 ? dir * len : 0,
                               axis == 2 ? dir * len : 0);
        p[n] = oit_v3_add(p[n - 1], d);
        n++;
        prev = axis;
    }
    for (int i = 0; i < n; i++)
        p[i] = oit_v3_add(p[i], b->lo);
    return n;
}

static void routed_pipe(block *b)
{
    float r = pipe_radius(b), bend = 1.5f * r;
    oit_v3 p[OIT_PIPE_MAX_POINTS];
    int n = plan_route(b, r, bend, p), seg = pipe_seg(b, r);
    if (n >= 2 && begin_object(b, oit_shape_pipe_cost(n, seg), C_PIPE0 + (int)oit_rng_below(&b->rng, PIPE_COLOURS)))
        oit_shape_pipe(b->e, p, n, r, bend, seg);
}

/* A rack: parallel straight pipes across the block at one height, on a
 * support beam, in a shared colour per pipe. */
static void rack(block *b)
{
    int along = oit_rng_below(&b->rng, 2) ? 0 : 2, k = 4 + (int)oit_rng_below(&b->rng, 9);
    float y = oit_rng_range(&b->rng, 1.5f, FLOOR_H * b->floors - 1.0f);
    float c = oit_rng_range(&b->rng, 1.0f, BLOCK_W - 4.0f), r = 0.5f * pipe_radius(b) + 0.05f;
    int seg = pipe_seg(b, r);
    for (int i = 0; i < k; i++) {
        float cc = c + i * 2.6f * r + r;
        oit_v3 a = along == 0 ? at(b, 0.3f, y + r, cc) : at(b, cc, y + r, 0.3f);
        oit_v3 e = along == 0 ? at(b, BLOCK_W - 0.3f, y + r, cc) : at(b, cc, y + r, BLOCK_W - 0.3f);
        if (begin_object(b, oit_shape_cylinder_cost(seg), C_PIPE0 + (int)oit_rng_below(&b->rng, PIPE_COLOURS)))
            oit_shape_cylinder(b->e, a, e, r, seg);
    }
}

/* Uses up the last few triangles: short pipes, then small pipe supports. */
static void top_up(block *b)
{
    for (int seg = b->seg; seg >= 3 && b->left >= OIT_BOX_TRIS; seg--) {
        while (b->left >= oit_shape_cylinder_cost(seg) + OIT_BOX_TRIS && !b->e->status) {
            float x = oit_rng_range(&b->rng, 1, BLOCK_W - 1), y = oit_rng_range(&b->rng, 0.5f, FLOOR_H * b->floors - 1);
            float z = oit_rng_range(&b->rng, 1, BLOCK_W - 2);
            if (begin_object(b, oit_shape_cylinder_cost(seg), C_PIPE0 + (int)oit_rng_below(&b->rng, PIPE_COLOURS)))
                oit_shape_cylinder(b->e, at(b, x, y, z), at(b, x, y, z + 1.0f), 0.06f, seg);
        }
    }
    while (b->left >= OIT_BOX_TRIS && !b->e->status) {
        float x = oit_rng_range(&b->rng, 1, BLOCK_W - 1), y = oit_rng_range(&b->rng, 0.5f, FLOOR_H * b->floors - 1);
        float z = oit_rng_range(&b->rng, 1, BLOCK_W - 1);
        if (begin_object(b, OIT_BOX_TRIS, C_STEEL))
            oit_shape_box(b->e, at(b, x, y, z), at(b, x + 0.15f, y + 0.3f, z + 0.15f));
    }
}

static void fill_block(block *b)
{
    frame(b);
    for (int f = 1; f < b->floors; f++) {
        int walks = 1 + (int)oit_rng_below(&b->rng, 3);
        for (int i = 0; i < walks; i++)
            catwalk(b, f * FLOOR_H + 0.02f, oit_rng_range(&b->rng, 0.5f, BLOCK_W - 3.0f),
                    oit_rng_range(&b->rng, 1.0f, 2.0f));
        stairs(b, f - 1, oit_rng_range(&b->rng, 1.0f, BLOCK_W - 2.0f));
        duct(b, f);
    }
    tanks(b);
    /* Pipes until the next one does not fit: racks for a third of them. */
    uint64_t smallest = oit_shape_pipe_cost(2, b->seg);
    while (b->left > 8 * oit_shape_pipe_cost(OIT_PIPE_MAX_POINTS, b->seg) && !b->e->status) {
        if (oit_rng_below(&b->rng, 12) == 0)
            rack(b);
        else
            routed_pipe(b);
    }
    while (b->left > smallest && !b->e->status)
        routed_pipe(b);
    top_up(b);
}

oit_status oit_scene_plant(oit_emit *e, const oit_scene_args *a, oit_error *err)
{
    uint64_t t = a->triangles;
    uint64_t nblocks = (uint64_t)llround((double)t / TRIS_PER_BLOCK);
    if (nblocks < 1)
        nblocks = 1;
    uint64_t cols = (uint64_t)ceil(sqrt((double)nblocks));
    int seg = plant_seg(t);
    for (uint64_t i = 0; i < nblocks && !e->status; i++) {
        block b = {.e = e, .rng = oit_rng_make(a->seed, 100 + i), .seg = seg};
        b.left = t / nblocks + (i + 1 == nblocks ? t % nblocks : 0);
        b.lo = oit_v3_make((float)(i % cols) * (BLOCK_W + BLOCK_GAP), 0,
                           (float)(i / cols) * (BLOCK_W + BLOCK_GAP));
        b.floors = FLOORS_MIN + (int)oit_rng_below(&b.rng, FLOORS_MAX - FLOORS_MIN + 1);
        fill_block(&b);
    }
    return oit_emit_flush(e);
}
