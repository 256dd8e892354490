/* What the two VTK readers (read_vtk.c: legacy .vtk; read_vtp.c: XML
 * PolyData .vtp) share: VTK's cell types, a cell list, colour arrays and
 * the step that turns cells into triangles (vtk_cells.c).
 *
 * VTK files put the colours after the geometry (legacy: POINT_DATA and
 * CELL_DATA follow the cells; XML: appended data at the end), so neither
 * reader can stream: points, cells and colours are held, each charged to
 * the read's memory budget, and triangles are emitted at the end.
 */
#ifndef OIT_FORMATS_VTK_INTERNAL_H
#define OIT_FORMATS_VTK_INTERNAL_H

#include "formats/readers_internal.h"

/* VTK's cell type numbers (vtkCellType.h) that the readers name. */
enum {
    VTK_CELL_VERTEX = 1, VTK_CELL_POLY_VERTEX = 2, VTK_CELL_LINE = 3, VTK_CELL_POLY_LINE = 4,
    VTK_CELL_TRIANGLE = 5, VTK_CELL_TRIANGLE_STRIP = 6, VTK_CELL_POLYGON = 7,
    VTK_CELL_PIXEL = 8, VTK_CELL_QUAD = 9
};

/* Cells in VTK's id order: cell i has point ids conn[off[i], off[i+1]) and
 * type types[i] (or `type` for all when types is NULL, as in a polydata
 * section). Indices are checked against the point count when stored. */
typedef struct vtk_cells {
    uint64_t *off;
    size_t ncells, off_cap;
    uint32_t *conn;
    size_t nconn, conn_cap;
    uint8_t *types; /* ntypes must equal ncells before emitting */
    size_t ntypes, types_cap;
    int type;
} vtk_cells;

void vtk_cells_free(vtk_cells *cs, oit_rd_budget *b);

/* Colours per point or per cell: rgba[4 * i], 255 where the file has none. */
typedef struct vtk_colours {
    uint8_t *rgba;
    size_t count, cap;
    int components; /* 0: none; 1 grey, 2 grey+alpha, 3 rgb, 4 rgba */
} vtk_colours;

/* Stores component k of tuple i: 8-bit or (unit) 0..1 values. */
static inline void vtk_colour_set(vtk_colours *c, size_t i, int k, int comps, double v,
                                  int unit)
{
    uint8_t u = unit ? oit_rd_unit_to_u8(v) : oit_rd_clamp_u8(v);
    uint8_t *p = c->rgba + 4 * i;
    if (comps <= 2 && k == 0)
        p[0] = p[1] = p[2] = u;
    else if (comps <= 2)
        p[3] = u;
    else
        p[k] = u;
}

/* Makes room for n tuples, all opaque white; sets components. */
oit_status vtk_colours_alloc(vtk_colours *c, oit_rd_budget *b, size_t n, int comps,
                             const char *name, oit_error *err);
void vtk_colours_free(vtk_colours *c, oit_rd_budget *b);

/* Counts of what was not drawn as read, for the note on stderr. */
typedef struct vtk_skipped {
    uint64_t verts_lines; /* vertices, poly-vertices, lines, poly-lines   */
    uint64_t volume;      /* linear volume cells, drawn as their boundary */
    uint64_t boundary;    /* the boundary faces drawn for them            */
    uint64_t other;       /* types not read (quadratic, polyhedron, ...)  */
} vtk_skipped;

/* Applies the point colours to the vertex table (pts->v[i].rgba). */
void vtk_apply_point_colours(oit_rd_vtable *pts, const vtk_colours *pc);

/* Emits the triangles of cells (first_id: the VTK id of its first cell, to
 * index the cell colours cc, which may be empty). Polygons and pixels/quads
 * are fanned, strips alternate their winding as VTK does; linear volume
 * cells give their boundary faces (those no other volume cell of cs shares);
 * a cell colour overrides its points' colours. Surface cells and boundary
 * faces count in info->faces_in. */
oit_status vtk_emit_cells(oit_rd_ctx *c, const oit_rd_vtable *pts, const vtk_cells *cs,
                          uint64_t first_id, const vtk_colours *cc, vtk_skipped *skip);

/* Sets the attribute bits for colours of `components` components. */
void vtk_note_colours(oit_mesh_info *info, int components);

/* The note on stderr for volume and skipped cells, if any; when skipped
 * cells were all there was (no triangle), a format error saying so. */
oit_status vtk_report_skipped(oit_rd_ctx *c, const vtk_skipped *skip);

/* Cell storage, growing as cells arrive (never sized by a declared count):
 * push_off appends the end offset of the next cell, push_id a point id. */
oit_status vtk_cells_push_off(vtk_cells *cs, oit_rd_budget *b, uint64_t off, const char *name,
                              oit_error *err);
oit_status vtk_cells_push_id(vtk_cells *cs, oit_rd_budget *b, uint32_t id, const char *name,
                             oit_error *err);
oit_status vtk_cells_push_type(vtk_cells *cs, oit_rd_budget *b, uint8_t type,
                               const char *name, oit_error *err);

/* The readers' FILE* entries (readers_internal.h). */
oit_rd_file_fn oit_read_vtk_stream;
oit_rd_file_fn oit_read_vtp_stream;

#endif
