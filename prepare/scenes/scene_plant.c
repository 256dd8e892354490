/* plant: a procedural power plant of T triangles (within a few triangles).
 *
 * The plant is a grid of blocks; each block is a steel frame of several
 * floors (I-beam columns and beams on a concrete slab) holding grated
 * catwalks with handrails, stairs, tanks, ducts and, filling the rest of its
 * triangle budget, pipe racks and routed pipe runs with elbows. A block holds
 * about TRIS_PER_BLOCK triangles, so a plant grows in area with T (a 12M
 * plant is 120 blocks) while tessellation grows slowly; depth complexity
 * reaches the hundreds across blocks.
 *
 * Clashes: by default objects are kept apart by at least CLEARANCE, as in a
 * designed plant, where clash detection removes every interpenetration
 * before construction. Each object is tried at a few random positions
 * against a voxel occupancy grid of its block (occupancy.h) and skipped
 * when none is clear; only the last top-up objects of a block too full for
 * them are placed regardless. With clashes allowed (oit_scene_args.clashes)
 * nothing is tested: pipes run through each other and through the steel,
 * the stress case for a partitioner, which must cut every crossing apart.
 *
 * Budgeting: every object's exact cost is known before it is emitted (see
 * shapes.h), a block emits objects while they fit its share of T, then tops
 * up with ever cheaper objects (short pipes, pipe supports), so the total
 * lands within 12 triangles per block of T. Objects stream out one by one:
 * memory does not depend on T. */
#include "prepare/scenes/scene.h"

#include <math.h>

#include "prepare/scenes/occupancy.h"
#include "prepare/scenes/rng.h"
#include "prepare/scenes/shapes.h"

enum { FLOORS_MIN = 3, FLOORS_MAX = 5 };
static const float BLOCK_W = 24.0f, BLOCK_GAP = 6.0f, FLOOR_H = 5.0f;
static const double TRIS_PER_BLOCK = 1.0e5;
/* Gap between objects, and the occupancy voxel: objects closer than a voxel
 * or two count as clashing, which only spaces them a little more. */
static const float CLEARANCE = 0.02f, VOXEL = 0.05f;
enum { TRIES = 24, MAX_MISSES = 64 };

typedef struct block {
    oit_emit *e;
    oit_rng rng;
    int seg;            /* ring points of big round objects */
    uint64_t left;      /* triangles left in this block's budget */
    oit_v3 lo;          /* block corner */
    int floors;
    oit_occupancy *occ; /* NULL: clashes allowed */
} block;

/* Boxes covering one object, tested together before it is emitted. */
enum { MAX_COVER = 160 };
typedef struct cover {
    oit_v3 lo[MAX_COVER], hi[MAX_COVER];
    int n;
} cover;

static void cover_add(cover *c, oit_v3 lo, oit_v3 hi)
{
    if (c->n < MAX_COVER) {
        c->lo[c->n] = lo;
        c->hi[c->n] = hi;
        c->n++;
    }
}

/* The box of segment p0..p1 grown by r: covers a cylinder or pipe leg. */
static void cover_segment(cover *c, oit_v3 p0, oit_v3 p1, float r)
{
    cover_add(c, oit_v3_make(fminf(p0.x, p1.x) - r, fminf(p0.y, p1.y) - r, fminf(p0.z, p1.z) - r),
              oit_v3_make(fmaxf(p0.x, p1.x) + r, fmaxf(p0.y, p1.y) + r, fmaxf(p0.z, p1.z) + r));
}

static int cover_clear(const block *b, const cover *c)
{
    for (int i = 0; i < c->n && b->occ; i++)
        if (!oit_occupancy_clear(b->occ, c->lo[i], c->hi[i], CLEARANCE))
            return 0;
    return 1;
}

static void cover_claim(block *b, const cover *c)
{
    for (int i = 0; i < c->n && b->occ; i++)
        oit_occupancy_mark(b->occ, c->lo[i], c->hi[i]);
}

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

/* Emits a cover's boxes as one object (all or nothing), claiming them. */
static int place_boxes(block *b, const cover *c, int kind)
{
    if (!cover_clear(b, c) || !begin_object(b, (uint64_t)c->n * OIT_BOX_TRIS, kind))
        return 0;
    for (int i = 0; i < c->n; i++)
        oit_shape_box(b->e, c->lo[i], c->hi[i]);
    cover_claim(b, c);
    return 1;
}

/* Columns on a 4x4 lattice and, on every floor, beams between them, each
 * clear of the columns by a few centimetres: the frame is clash-free by
 * construction and claims its space first. */
static void frame(block *b)
{
    float w = BLOCK_W, top = FLOOR_H * b->floors, p = 0.35f, gap = 0.03f; /* profile */
    cover slab = {.n = 0};
    cover_add(&slab, at(b, -1, -0.4f, -1), at(b, w + 1, 0, w + 1));
    if (begin_object(b, OIT_BOX_TRIS, C_SLAB)) {
        oit_shape_box(b->e, slab.lo[0], slab.hi[0]);
        cover_claim(b, &slab);
    }
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (begin_object(b, OIT_IBEAM_TRIS, C_STEEL)) {
                float x = i * (w - p) / 3, z = j * (w - p) / 3;
                cover c = {.n = 0};
                cover_add(&c, at(b, x, 0.1f, z), at(b, x + p, top, z + p));
                oit_shape_ibeam(b->e, c.lo[0], c.hi[0], 1, 0);
                cover_claim(b, &c);
            }
    for (int f = 1; f <= b->floors; f++)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 3; j++) {
                float y = f * FLOOR_H - 0.5f, c = i * (w - p) / 3, s0 = j * (w - p) / 3 + p + gap;
                float s1 = (j + 1) * (w - p) / 3 - gap;
                cover cx = {.n = 0}, cz = {.n = 0};
                cover_add(&cx, at(b, s0, y, c), at(b, s1, y + 0.5f, c + p));
                cover_add(&cz, at(b, c, y, s0), at(b, c + p, y + 0.5f, s1));
                if (begin_object(b, OIT_IBEAM_TRIS, C_STEEL)) {
                    oit_shape_ibeam(b->e, cx.lo[0], cx.hi[0], 0, 1);
                    cover_claim(b, &cx);
                }
                if (begin_object(b, OIT_IBEAM_TRIS, C_STEEL)) {
                    oit_shape_ibeam(b->e, cz.lo[0], cz.hi[0], 2, 1);
                    cover_claim(b, &cz);
                }
            }
}

/* A catwalk along x at deck height y, from z0 to z0+width: bearing bars
 * across it between two edge bars, handrails on posts; the parts of the
 * grating stand a few centimetres apart rather than touching. */
static int catwalk(block *b, float y, float z0, float width)
{
    float w = BLOCK_W, pitch = 0.2f, e = 0.06f, g = 0.02f;
    int bars = (int)(w / pitch), posts = (int)(w / 2.0f) + 1;
    cover c = {.n = 0};
    for (int i = 0; i < bars; i++) {
        float x = i * pitch + 0.08f;
        cover_add(&c, at(b, x, y, z0 + e + g), at(b, x + 0.04f, y + 0.05f, z0 + width - e - g));
    }
    for (int s = 0; s < 2; s++) {
        float z = s ? z0 + width - e : z0;
        cover_add(&c, at(b, 0, y - 0.05f, z), at(b, w, y + 0.06f, z + e));
        cover_add(&c, at(b, 0, y + 1.0f, z), at(b, w, y + 1.06f, z + e));
        for (int i = 0; i < posts; i++) {
            float x = fminf(i * 2.0f, w - e);
            cover_add(&c, at(b, x, y + 0.06f + g, z), at(b, x + e, y + 1.0f - g, z + e));
        }
    }
    return place_boxes(b, &c, C_GRATING);
}

/* Stairs from floor f to f+1 along z, at x0: two stringers beside the
 * treads. */
static int stairs(block *b, int f, float x0)
{
    int steps = (int)(FLOOR_H / 0.25f) - 1;
    float y0 = f * FLOOR_H + 0.1f, z0 = 2.0f, run = 0.28f;
    cover c = {.n = 0};
    for (int i = 0; i < steps; i++)
        cover_add(&c, at(b, x0, y0 + i * 0.25f, z0 + i * run),
                  at(b, x0 + 1.0f, y0 + i * 0.25f + 0.05f, z0 + (i + 1) * run));
    for (int s = 0; s < 2; s++) {
        float x = s ? x0 + 1.02f : x0 - 0.1f;
        cover_add(&c, at(b, x, y0, z0), at(b, x + 0.08f, y0 + FLOOR_H - 0.3f, z0 + steps * run));
    }
    return place_boxes(b, &c, C_GRATING);
}

/* A sphere on the ground floor or an upright tank, tried at a few spots. */
static void tank(block *b)
{
    float r = oit_rng_range(&b->rng, 1.5f, 3.5f);
    int sphere = oit_rng_below(&b->rng, 3) == 0;
    float h = oit_rng_range(&b->rng, 3, FLOOR_H * b->floors - 2 * r - 1);
    h = fmaxf(h, 0.5f);
    uint64_t cost = sphere ? oit_shape_sphere_cost(2 * b->seg) : oit_shape_tank_cost(2 * b->seg);
    for (int t = 0; t < TRIES; t++) {
        float x = oit_rng_range(&b->rng, r + 1, BLOCK_W - r - 1);
        float z = oit_rng_range(&b->rng, r + 1, BLOCK_W - r - 1);
        oit_v3 p0 = at(b, x, r + (sphere ? 0.5f : 0.3f), z);
        oit_v3 p1 = sphere ? p0 : at(b, x, r + 0.3f + h, z);
        cover c = {.n = 0};
        cover_segment(&c, p0, p1, r);
        if (!cover_clear(b, &c))
            continue;
        if (!begin_object(b, cost, C_TANK))
            return;
        if (sphere)
            oit_shape_sphere(b->e, p0, r, 2 * b->seg);
        else
            oit_shape_tank(b->e, p0, p1, r, 2 * b->seg);
        cover_claim(b, &c);
        return;
    }
}

/* A duct: rectangular segments along x then z below a floor's beams. */
static void duct(block *b, int f)
{
    for (int t = 0; t < TRIES; t++) {
        float s = oit_rng_range(&b->rng, 0.6f, 1.4f), y = f * FLOOR_H - 0.7f - s;
        float z = oit_rng_range(&b->rng, 1, BLOCK_W - 1 - s), x = oit_rng_range(&b->rng, 4, BLOCK_W - 1 - s);
        cover c = {.n = 0};
        cover_add(&c, at(b, 0.5f, y, z), at(b, x, y + s, z + s));
        cover_add(&c, at(b, x, y, 0.5f), at(b, x + s, y + s, z));
        if (place_boxes(b, &c, C_DUCT) || cover_clear(b, &c))
            return; /* placed, or clear but over budget */
    }
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

/* The boxes covering a pipe run: each leg grown by r, and a cube of
 * half-edge bend + r around each corner, which holds the elbow. */
static void cover_pipe(cover *c, const oit_v3 *p, int n, float r, float bend)
{
    for (int i = 0; i + 1 < n; i++)
        cover_segment(c, p[i], p[i + 1], r);
    for (int i = 1; i + 1 < n; i++)
        cover_segment(c, p[i], p[i], bend + r);
}

/* A routed run at the first of a few routes that is clear; 1 when placed. */
static int routed_pipe(block *b)
{
    float r = pipe_radius(b), bend = 1.5f * r;
    int seg = pipe_seg(b, r), kind = C_PIPE0 + (int)oit_rng_below(&b->rng, PIPE_COLOURS);
    for (int t = 0; t < TRIES / 3; t++) {
        oit_v3 p[OIT_PIPE_MAX_POINTS];
        int n = plan_route(b, r, bend, p);
        cover c = {.n = 0};
        cover_pipe(&c, p, n, r, bend);
        if (n < 2 || !cover_clear(b, &c))
            continue;
        if (!begin_object(b, oit_shape_pipe_cost(n, seg), kind))
            return 0;
        oit_shape_pipe(b->e, p, n, r, bend, seg);
        cover_claim(b, &c);
        return 1;
    }
    return 0;
}

/* A rack: parallel straight pipes across the block at one height, in a
 * colour per pipe; 1 when placed. */
static int rack(block *b)
{
    int along = oit_rng_below(&b->rng, 2) ? 0 : 2, k = 4 + (int)oit_rng_below(&b->rng, 9);
    float r = 0.5f * pipe_radius(b) + 0.05f;
    int seg = pipe_seg(b, r);
    for (int t = 0; t < TRIES; t++) {
        float y = oit_rng_range(&b->rng, 1.5f, FLOOR_H * b->floors - 1.0f);
        float c = oit_rng_range(&b->rng, 1.0f, BLOCK_W - 4.0f);
        oit_v3 a[12], e[12];
        cover all = {.n = 0};
        for (int i = 0; i < k; i++) {
            float cc = c + i * 2.6f * r + r;
            a[i] = along == 0 ? at(b, 0.3f, y + r, cc) : at(b, cc, y + r, 0.3f);
            e[i] = along == 0 ? at(b, BLOCK_W - 0.3f, y + r, cc) : at(b, cc, y + r, BLOCK_W - 0.3f);
            cover_segment(&all, a[i], e[i], r);
        }
        if (!cover_clear(b, &all))
            continue;
        for (int i = 0; i < k; i++)
            if (begin_object(b, oit_shape_cylinder_cost(seg),
                             C_PIPE0 + (int)oit_rng_below(&b->rng, PIPE_COLOURS))) {
                oit_shape_cylinder(b->e, a[i], e[i], r, seg);
                cover one = {.n = 0};
                cover_add(&one, all.lo[i], all.hi[i]);
                cover_claim(b, &one);
            }
        return 1;
    }
    return 0;
}

/* One top-up object of the cover's size at a clear random spot; when the
 * block has none left after a few tries, at the last spot regardless, so
 * that the triangle budget is met. */
static void top_up_one(block *b, int cylinder, int seg)
{
    cover c = {.n = 0};
    for (int t = 0; t < TRIES; t++) {
        float x = oit_rng_range(&b->rng, 1, BLOCK_W - 1), y = oit_rng_range(&b->rng, 0.5f, FLOOR_H * b->floors - 1);
        float z = oit_rng_range(&b->rng, 1, BLOCK_W - 2);
        c.n = 0;
        if (cylinder)
            cover_segment(&c, at(b, x, y, z), at(b, x, y, z + 1.0f), 0.06f);
        else
            cover_add(&c, at(b, x, y, z), at(b, x + 0.15f, y + 0.3f, z + 0.15f));
        if (cover_clear(b, &c))
            break;
    }
    if (cylinder) {
        if (!begin_object(b, oit_shape_cylinder_cost(seg), C_PIPE0 + (int)oit_rng_below(&b->rng, PIPE_COLOURS)))
            return;
        oit_v3 m = oit_v3_scale(oit_v3_add(c.lo[0], c.hi[0]), 0.5f);
        oit_shape_cylinder(b->e, oit_v3_make(m.x, m.y, c.lo[0].z + 0.06f),
                           oit_v3_make(m.x, m.y, c.hi[0].z - 0.06f), 0.06f, seg);
    } else {
        if (!begin_object(b, OIT_BOX_TRIS, C_STEEL))
            return;
        oit_shape_box(b->e, c.lo[0], c.hi[0]);
    }
    cover_claim(b, &c);
}

/* Uses up the last few triangles: short pipes, then small pipe supports. */
static void top_up(block *b)
{
    for (int seg = b->seg; seg >= 3 && b->left >= OIT_BOX_TRIS; seg--)
        while (b->left >= oit_shape_cylinder_cost(seg) + OIT_BOX_TRIS && !b->e->status)
            top_up_one(b, 1, seg);
    while (b->left >= OIT_BOX_TRIS && !b->e->status)
        top_up_one(b, 0, 0);
}

static void fill_block(block *b)
{
    frame(b);
    int ntanks = 1 + (int)oit_rng_below(&b->rng, 3);
    for (int i = 0; i < ntanks; i++)
        tank(b);
    for (int f = 1; f < b->floors; f++) {
        int walks = 1 + (int)oit_rng_below(&b->rng, 3);
        for (int i = 0; i < walks; i++) {
            float width = oit_rng_range(&b->rng, 1.0f, 2.0f);
            for (int t = 0; t < TRIES; t++)
                if (catwalk(b, f * FLOOR_H + 0.12f, oit_rng_range(&b->rng, 0.5f, BLOCK_W - 3.0f), width))
                    break;
        }
        for (int t = 0; t < TRIES; t++)
            if (stairs(b, f - 1, oit_rng_range(&b->rng, 1.0f, BLOCK_W - 2.0f)))
                break;
        duct(b, f);
    }
    /* Pipes until the next one does not fit or the block has no room left
     * for them: racks for a twelfth of them. */
    uint64_t smallest = oit_shape_pipe_cost(2, b->seg);
    int misses = 0;
    while (b->left > 8 * oit_shape_pipe_cost(OIT_PIPE_MAX_POINTS, b->seg) && misses < MAX_MISSES &&
           !b->e->status)
        misses = (oit_rng_below(&b->rng, 12) == 0 ? rack(b) : routed_pipe(b)) ? 0 : misses + 1;
    while (b->left > smallest && misses < MAX_MISSES && !b->e->status)
        misses = routed_pipe(b) ? 0 : misses + 1;
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
    oit_occupancy occ = {0};
    float top = FLOOR_H * FLOORS_MAX + 1.0f;
    if (!a->clashes &&
        oit_occupancy_init(&occ, oit_v3_make(-1, -0.5f, -1), oit_v3_make(BLOCK_W + 1, top, BLOCK_W + 1), VOXEL))
        return oit_error_set(err, OIT_ERR_NOMEM, "plant: no memory for the occupancy grid");
    for (uint64_t i = 0; i < nblocks && !e->status; i++) {
        block b = {.e = e, .rng = oit_rng_make(a->seed, 100 + i), .seg = seg,
                   .occ = a->clashes ? NULL : &occ};
        b.left = t / nblocks + (i + 1 == nblocks ? t % nblocks : 0);
        b.lo = oit_v3_make((float)(i % cols) * (BLOCK_W + BLOCK_GAP), 0,
                           (float)(i / cols) * (BLOCK_W + BLOCK_GAP));
        b.floors = FLOORS_MIN + (int)oit_rng_below(&b.rng, FLOORS_MAX - FLOORS_MIN + 1);
        if (b.occ)
            oit_occupancy_reset(b.occ, oit_v3_add(b.lo, oit_v3_make(-1, -0.5f, -1)));
        fill_block(&b);
    }
    oit_occupancy_free(&occ);
    return oit_emit_flush(e);
}
