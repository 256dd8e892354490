/* VTK cells to triangles, shared by the legacy and XML readers
 * (vtk_internal.h). Triangulation follows VTK's own triangle filter in its
 * counts: a polygon of n points gives n - 2 triangles (fanned from its first
 * point, so a concave polygon's triangles can differ from VTK's ear cut, not
 * their number), a strip of n points n - 2 triangles with every second one
 * flipped (vtkTriangleStrip::DecomposeStrip), a pixel (points in x-then-y
 * order) 0,1,3 and 0,3,2, a quad 0,1,2 and 0,2,3. */
#include "formats/vtk_internal.h"

#include <inttypes.h>
#include <stdlib.h>

void vtk_cells_free(vtk_cells *cs, oit_rd_budget *b)
{
    oit_rd_release(b, (void **)&cs->off, &cs->off_cap, sizeof *cs->off);
    oit_rd_release(b, (void **)&cs->conn, &cs->conn_cap, sizeof *cs->conn);
    oit_rd_release(b, (void **)&cs->types, &cs->types_cap, sizeof *cs->types);
    cs->ncells = cs->nconn = cs->ntypes = 0;
}

oit_status vtk_cells_push_off(vtk_cells *cs, oit_rd_budget *b, uint64_t end, const char *name,
                              oit_error *err)
{
    if (cs->off_cap < cs->ncells + 2) { /* off[0] = 0, then each cell's end */
        oit_status st = oit_rd_grow(b, (void **)&cs->off, &cs->off_cap, sizeof *cs->off,
                                    cs->ncells + 2, name, "cell offsets", err);
        if (st != OIT_OK)
            return st;
    }
    cs->off[0] = 0;
    cs->off[++cs->ncells] = end;
    return OIT_OK;
}

oit_status vtk_cells_push_id(vtk_cells *cs, oit_rd_budget *b, uint32_t id, const char *name,
                             oit_error *err)
{
    if (cs->nconn == cs->conn_cap) {
        oit_status st = oit_rd_grow(b, (void **)&cs->conn, &cs->conn_cap, sizeof *cs->conn,
                                    cs->nconn + 1, name, "cell connectivity", err);
        if (st != OIT_OK)
            return st;
    }
    cs->conn[cs->nconn++] = id;
    return OIT_OK;
}

oit_status vtk_cells_push_type(vtk_cells *cs, oit_rd_budget *b, uint8_t type, const char *name,
                               oit_error *err)
{
    if (cs->ntypes == cs->types_cap) {
        oit_status st = oit_rd_grow(b, (void **)&cs->types, &cs->types_cap, sizeof *cs->types,
                                    cs->ntypes + 1, name, "cell types", err);
        if (st != OIT_OK)
            return st;
    }
    cs->types[cs->ntypes++] = type;
    return OIT_OK;
}

oit_status vtk_colours_alloc(vtk_colours *c, oit_rd_budget *b, size_t n, int comps,
                             const char *name, oit_error *err)
{
    oit_status st = oit_rd_grow(b, (void **)&c->rgba, &c->cap, 4, n, name, "colour array", err);
    if (st != OIT_OK)
        return st;
    if (n > 0)
        memset(c->rgba, 255, 4 * n);
    c->count = n;
    c->components = comps;
    return OIT_OK;
}

void vtk_colours_free(vtk_colours *c, oit_rd_budget *b)
{
    oit_rd_release(b, (void **)&c->rgba, &c->cap, 4);
    c->count = 0;
    c->components = 0;
}

void vtk_apply_point_colours(oit_rd_vtable *pts, const vtk_colours *pc)
{
    if (pc->components == 0)
        return;
    for (size_t i = 0; i < pts->count && i < pc->count; i++)
        memcpy(pts->v[i].rgba, pc->rgba + 4 * i, 4);
}

void vtk_note_colours(oit_mesh_info *info, int components)
{
    if (components >= 1)
        info->attributes |= OIT_ATTR_COLOUR;
    if (components == 2 || components == 4)
        info->attributes |= OIT_ATTR_ALPHA;
}

/* ---- volume cells: their boundary faces -------------------------------
 * A face of a linear volume cell (tetrahedron, voxel, hexahedron, wedge,
 * pyramid) that no other volume cell of the file shares is on the boundary
 * and drawn, in the cell's colour, oriented as VTK orients it (outward);
 * shared faces are interior and dropped, and a face that a triangle, quad
 * or pixel cell of the same points covers is drawn once, as that cell, as
 * vtkGeometryFilter does. Faces
 * are told apart by their sorted point ids in a hash table charged to the
 * budget. Higher-order and polyhedron cells are skipped. */

typedef struct vtk_vol_shape {
    int type, npts, nfaces;
    signed char faces[6][4]; /* -1 ends a triangle; quads in cyclic order */
} vtk_vol_shape;

static const vtk_vol_shape vtk_shapes[] = {
    {10, 4, 4, {{0, 1, 3, -1}, {1, 2, 3, -1}, {2, 0, 3, -1}, {0, 2, 1, -1}}},
    {11, 8, 6, {{2, 0, 4, 6}, {1, 3, 7, 5}, {0, 1, 5, 4}, {3, 2, 6, 7}, {1, 0, 2, 3},
                {4, 5, 7, 6}}},
    {12, 8, 6, {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1},
                {4, 5, 6, 7}}},
    {13, 6, 5, {{0, 1, 2, -1}, {3, 5, 4, -1}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}}},
    {14, 5, 5, {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}}},
};

static const vtk_vol_shape *vtk_shape(int type, size_t n)
{
    for (size_t i = 0; i < sizeof vtk_shapes / sizeof vtk_shapes[0]; i++)
        if (vtk_shapes[i].type == type)
            return (size_t)vtk_shapes[i].npts == n ? &vtk_shapes[i] : NULL;
    return NULL;
}

typedef struct vtk_face_key {
    uint32_t id[4]; /* sorted; UINT32_MAX pads a triangle */
    uint32_t count; /* 0: empty slot */
} vtk_face_key;

typedef struct vtk_faces {
    vtk_face_key *slot;
    size_t cap, used;
} vtk_faces;

static void vtk_face_of(const vtk_vol_shape *sh, int f, const uint32_t *p, vtk_face_key *k)
{
    int n = sh->faces[f][3] < 0 ? 3 : 4;
    k->count = 0;
    for (int i = 0; i < 4; i++)
        k->id[i] = i < n ? p[sh->faces[f][i]] : UINT32_MAX;
    for (int i = 1; i < 4; i++) /* insertion sort of four */
        for (int j = i; j > 0 && k->id[j - 1] > k->id[j]; j--) {
            uint32_t t = k->id[j];
            k->id[j] = k->id[j - 1];
            k->id[j - 1] = t;
        }
}

static size_t vtk_face_slot(const vtk_faces *t, const vtk_face_key *k)
{
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 4; i++)
        h = (h ^ k->id[i]) * 1099511628211ull;
    size_t i = (size_t)(h ^ h >> 29) & (t->cap - 1);
    while (t->slot[i].count && memcmp(t->slot[i].id, k->id, sizeof k->id) != 0)
        i = (i + 1) & (t->cap - 1);
    return i;
}

/* A surface cell of 3 or 4 points also counts in the face table (when cs
 * has volume cells): a volume face it covers is drawn once, as the surface
 * cell, as vtkGeometryFilter does. */
static const vtk_vol_shape vtk_surface_shape[2] = {{0, 3, 1, {{0, 1, 2, -1}}},
                                                   {0, 4, 1, {{0, 1, 2, 3}}}};

static int vtk_surface_face(int type, size_t n)
{
    return (n == 3 || n == 4) && (type == VTK_CELL_TRIANGLE || type == VTK_CELL_QUAD ||
                                  type == VTK_CELL_PIXEL || type == VTK_CELL_POLYGON);
}

/* Counts every face of the volume cells of cs (and the surface cells that
 * may cover one); t stays empty when there is no volume cell. */
static oit_status vtk_faces_count(oit_rd_ctx *c, const vtk_cells *cs, vtk_faces *t)
{
    size_t faces = 0, surface = 0;
    for (size_t i = 0; cs->types && i < cs->ncells; i++) {
        size_t n = (size_t)(cs->off[i + 1] - cs->off[i]);
        const vtk_vol_shape *sh = vtk_shape(cs->types[i], n);
        faces += sh ? (size_t)sh->nfaces : 0;
        surface += vtk_surface_face(cs->types[i], n);
    }
    if (!faces)
        return OIT_OK;
    faces += surface;
    size_t cap = 16;
    while (cap < faces / 3 * 4 + 16) /* a load of at most 3/4 */
        cap *= 2;
    oit_status st = oit_rd_grow(&c->budget, (void **)&t->slot, &t->cap, sizeof *t->slot, cap,
                                c->name, "volume face table", c->err);
    if (st != OIT_OK)
        return st;
    t->cap = cap; /* a power of two: oit_rd_grow may have given more */
    memset(t->slot, 0, cap * sizeof *t->slot);
    for (size_t i = 0; i < cs->ncells; i++) {
        const uint32_t *p = cs->conn + cs->off[i];
        size_t n = (size_t)(cs->off[i + 1] - cs->off[i]);
        const vtk_vol_shape *sh = vtk_shape(cs->types[i], n);
        int nf = sh ? sh->nfaces : vtk_surface_face(cs->types[i], n) ? 1 : 0;
        for (int f = 0; f < nf; f++) {
            vtk_face_key k;
            if (sh)
                vtk_face_of(sh, f, p, &k);
            else
                vtk_face_of(&vtk_surface_shape[n - 3], 0, p, &k);
            vtk_face_key *e = &t->slot[vtk_face_slot(t, &k)];
            if (e->count == 0)
                *e = k, t->used++;
            e->count++;
        }
    }
    return OIT_OK;
}

/* The point ids of one triangle after colour override, emitted. */
static oit_status vtk_tri(oit_rd_ctx *c, const oit_rd_vtable *pts, uint32_t a, uint32_t b,
                          uint32_t d, const uint8_t *rgba)
{
    oit_vertex v[3] = {pts->v[a], pts->v[b], pts->v[d]};
    if (rgba)
        for (int j = 0; j < 3; j++)
            memcpy(v[j].rgba, rgba, 4);
    return oit_rd_emit(&c->out, &v[0], &v[1], &v[2]);
}

/* The boundary faces of one volume cell (shape sh, points p). */
static oit_status vtk_volume(oit_rd_ctx *c, const oit_rd_vtable *pts, const vtk_vol_shape *sh,
                             const uint32_t *p, const vtk_faces *t, const uint8_t *rgba,
                             vtk_skipped *skip)
{
    oit_status st = OIT_OK;
    skip->volume++;
    for (int f = 0; f < sh->nfaces && st == OIT_OK; f++) {
        vtk_face_key k;
        vtk_face_of(sh, f, p, &k);
        if (t->slot[vtk_face_slot(t, &k)].count != 1)
            continue; /* shared: inside the volume */
        const signed char *q = sh->faces[f];
        c->info->faces_in++;
        skip->boundary++;
        st = vtk_tri(c, pts, p[q[0]], p[q[1]], p[q[2]], rgba);
        if (st == OIT_OK && q[3] >= 0)
            st = vtk_tri(c, pts, p[q[0]], p[q[2]], p[q[3]], rgba);
    }
    return st;
}

static oit_status vtk_cell(oit_rd_ctx *c, const oit_rd_vtable *pts, int type,
                           const uint32_t *p, size_t n, const uint8_t *rgba,
                           const vtk_faces *faces, vtk_skipped *skip)
{
    oit_status st = OIT_OK;
    const vtk_vol_shape *sh = faces->cap ? vtk_shape(type, n) : NULL;
    if (sh)
        return vtk_volume(c, pts, sh, p, faces, rgba, skip);
    switch (type) {
    case VTK_CELL_VERTEX: case VTK_CELL_POLY_VERTEX: case VTK_CELL_LINE: case VTK_CELL_POLY_LINE:
        skip->verts_lines++;
        return OIT_OK;
    case VTK_CELL_PIXEL:
        if (n != 4)
            break;
        c->info->faces_in++;
        st = vtk_tri(c, pts, p[0], p[1], p[3], rgba);
        return st == OIT_OK ? vtk_tri(c, pts, p[0], p[3], p[2], rgba) : st;
    case VTK_CELL_TRIANGLE_STRIP:
        c->info->faces_in++;
        for (size_t i = 0; i + 2 < n && st == OIT_OK; i++)
            st = i % 2 ? vtk_tri(c, pts, p[i + 1], p[i], p[i + 2], rgba)
                       : vtk_tri(c, pts, p[i], p[i + 1], p[i + 2], rgba);
        return st;
    case VTK_CELL_TRIANGLE: case VTK_CELL_POLYGON: case VTK_CELL_QUAD:
        c->info->faces_in++;
        for (size_t i = 2; i < n && st == OIT_OK; i++)
            st = vtk_tri(c, pts, p[0], p[i - 1], p[i], rgba);
        return st;
    default:
        skip->other++; /* higher order, polyhedra, volume cells of odd sizes */
        return OIT_OK;
    }
    skip->other++; /* a pixel of other than 4 points */
    return OIT_OK;
}

oit_status vtk_emit_cells(oit_rd_ctx *c, const oit_rd_vtable *pts, const vtk_cells *cs,
                          uint64_t first_id, const vtk_colours *cc, vtk_skipped *skip)
{
    vtk_faces faces = {0};
    oit_status st = vtk_faces_count(c, cs, &faces);
    for (size_t i = 0; i < cs->ncells && st == OIT_OK; i++) {
        uint64_t id = first_id + i;
        const uint8_t *rgba = cc->components && id < cc->count ? cc->rgba + 4 * id : NULL;
        int type = cs->types ? cs->types[i] : cs->type;
        size_t n = (size_t)(cs->off[i + 1] - cs->off[i]);
        /* cells of no point leave conn unallocated: no pointer into it */
        st = vtk_cell(c, pts, type, n ? cs->conn + cs->off[i] : NULL, n, rgba, &faces, skip);
    }
    oit_rd_release(&c->budget, (void **)&faces.slot, &faces.cap, sizeof *faces.slot);
    return st;
}

oit_status vtk_report_skipped(oit_rd_ctx *c, const vtk_skipped *skip)
{
    if (c->info->triangles + c->out.count == 0 && skip->other)
        return oit_error_set(c->err, OIT_ERR_FORMAT, "%s: no surface cells and no volume cell "
                             "with a boundary, only %" PRIu64 " cells of unsupported types "
                             "(higher order, polyhedra): nothing to draw", c->name, skip->other);
    if (skip->verts_lines)
        fprintf(stderr, "%s: %" PRIu64 " vertex and line cells not drawn\n", c->name,
                skip->verts_lines);
    if (skip->volume)
        fprintf(stderr, "%s: %" PRIu64 " volume cells drawn as their %" PRIu64 " boundary faces\n",
                c->name, skip->volume, skip->boundary);
    if (skip->other)
        fprintf(stderr, "%s: %" PRIu64 " cells of unsupported types (quadratic or higher "
                "order, polyhedra, ...) skipped\n", c->name, skip->other);
    return OIT_OK;
}
