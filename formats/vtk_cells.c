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

static int vtk_is_volume(int type)
{
    /* linear and quadratic/higher-order 3D cells, polyhedron */
    return (type >= 10 && type <= 16) || type == 24 || type == 25 || type == 26 ||
           type == 27 || type == 29 || type == 32 || type == 33 || type == 42 ||
           (type >= 71 && type <= 74) || type == 78 || type == 79 || type == 81 ||
           type == 82;
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

static oit_status vtk_cell(oit_rd_ctx *c, const oit_rd_vtable *pts, int type,
                           const uint32_t *p, size_t n, const uint8_t *rgba, vtk_skipped *skip)
{
    oit_status st = OIT_OK;
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
        if (vtk_is_volume(type))
            skip->volume++;
        else
            skip->other++;
        return OIT_OK;
    }
    skip->other++; /* a pixel of other than 4 points */
    return OIT_OK;
}

oit_status vtk_emit_cells(oit_rd_ctx *c, const oit_rd_vtable *pts, const vtk_cells *cs,
                          uint64_t first_id, const vtk_colours *cc, vtk_skipped *skip)
{
    oit_status st = OIT_OK;
    for (size_t i = 0; i < cs->ncells && st == OIT_OK; i++) {
        uint64_t id = first_id + i;
        const uint8_t *rgba = cc->components && id < cc->count ? cc->rgba + 4 * id : NULL;
        int type = cs->types ? cs->types[i] : cs->type;
        size_t n = (size_t)(cs->off[i + 1] - cs->off[i]);
        /* cells of no point leave conn unallocated: no pointer into it */
        st = vtk_cell(c, pts, type, n ? cs->conn + cs->off[i] : NULL, n, rgba, skip);
    }
    return st;
}

oit_status vtk_report_skipped(oit_rd_ctx *c, const vtk_skipped *skip)
{
    if (c->info->triangles + c->out.count == 0 && (skip->volume || skip->other))
        return oit_error_set(c->err, OIT_ERR_FORMAT, "%s: no surface cells, only %" PRIu64
                             " volume cells (tetrahedra, hexahedra, ...) and %" PRIu64 " of "
                             "unsupported types: nothing to draw (volume cells are not turned "
                             "into their boundary)", c->name, skip->volume, skip->other);
    if (skip->volume)
        fprintf(stderr, "%s: %" PRIu64 " volume cells (tetrahedra, hexahedra, ...) skipped: "
                "only surface cells are drawn\n", c->name, skip->volume);
    if (skip->other)
        fprintf(stderr, "%s: %" PRIu64 " cells of unsupported types (quadratic or higher "
                "order, ...) skipped\n", c->name, skip->other);
    return OIT_OK;
}
