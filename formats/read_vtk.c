/* Legacy VTK reader (.vtk), ASCII and BINARY (big-endian).
 *
 * DATASET POLYDATA (POLYGONS and TRIANGLE_STRIPS drawn; VERTICES and LINES
 * read, counted in VTK's cell ids and not drawn) and UNSTRUCTURED_GRID
 * (triangles, quads, polygons, pixels, triangle strips drawn; vertices and
 * lines not drawn; linear volume cells (tetrahedra, voxels, hexahedra,
 * wedges, pyramids) drawn as their boundary faces, vtk_cells.c; higher
 * order cells and polyhedra skipped with a note on stderr). Cells in the
 * classic layout ("POLYGONS n size", each cell "count ids...") and in the
 * layout of file version 5 and later ("POLYGONS nOffsets nConnectivity"
 * then OFFSETS and CONNECTIVITY arrays).
 *
 * Colours: POINT_DATA or CELL_DATA COLOR_SCALARS (1 to 4 components, the
 * 4th alpha; floats 0..1 in ASCII, bytes in BINARY), else SCALARS of
 * unsigned_char with 3 or 4 components (0..255), else a FIELD array of
 * unsigned_char with 3 or 4 components named like a colour ("Colors",
 * "RGBA"); the first of the best kind is used, every other array skipped.
 * A cell colour overrides its points' colours. METADATA blocks are skipped.
 *
 * The colours follow the cells, so points and cells are held (charged to
 * the memory budget, grown as data arrives, never sized by a declared
 * count) and the triangles emitted at the end (vtk_internal.h). Errors name
 * the line in ASCII files and the byte offset in BINARY ones.
 *
 * This file reads the header, dispatches the sections, reads the points
 * and cells and emits; values are read in vtk_legacy_values.c and the
 * attribute sections in vtk_legacy_attributes.c (vtk_legacy_internal.h).
 */
#include "formats/vtk_legacy_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- geometry ---------------------------------------------------------- */

static oit_status leg_points(leg *L)
{
    uint64_t n;
    leg_type t;
    if (L->have_points)
        return leg_fail(L, OIT_ERR_FORMAT, "a second POINTS section");
    if (!leg_count(L, 1, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "POINTS: expected a point count");
    oit_status st = leg_type_word(L, 2, &t);
    if (st == OIT_OK && (t == LT_BIT))
        st = leg_fail(L, OIT_ERR_UNSUPPORTED, "POINTS of type bit");
    if (st == OIT_OK && n > UINT32_MAX)
        st = leg_fail(L, OIT_ERR_UNSUPPORTED, "POINTS: more than 2^32 points");
    for (uint64_t i = 0; i < n && st == OIT_OK; i++) {
        double in[3];
        for (int k = 0; k < 3 && st == OIT_OK; k++)
            st = leg_value(L, t, "POINTS", &in[k]);
        oit_vertex v;
        memset(v.rgba, 255, sizeof v.rgba);
        if (st == OIT_OK) {
            oit_rd_position(L->c, in, v.pos);
            st = oit_rd_vtable_push(&L->pts, &L->c->budget, &v, L->c->name, L->c->err);
        }
    }
    L->have_points = 1;
    L->c->info->vertices_in = L->pts.count;
    return st;
}

/* Classic layout: n cells of "count id...", size values in all. */
static oit_status leg_cells_classic(leg *L, vtk_cells *cs, uint64_t n, uint64_t size,
                                    const char *what)
{
    oit_status st = OIT_OK;
    uint64_t used = 0;
    for (uint64_t i = 0; i < n && st == OIT_OK; i++) {
        double v;
        if ((st = leg_value(L, LT_I32, what, &v)) != OIT_OK)
            break;
        if (!(v >= 0 && v <= (double)size && v == floor(v)) || used + 1 + (uint64_t)v > size)
            return leg_fail(L, OIT_ERR_FORMAT, "%s: cell %" PRIu64 " of %.0f points overruns "
                            "the declared size %" PRIu64, what, i, v, size);
        used += 1 + (uint64_t)v;
        for (uint64_t k = 0; k < (uint64_t)v && st == OIT_OK; k++) {
            double idv;
            uint32_t id = 0;
            st = leg_value(L, LT_I32, what, &idv);
            if (st == OIT_OK)
                st = leg_index(L, idv, what, &id);
            if (st == OIT_OK)
                st = vtk_cells_push_id(cs, &L->c->budget, id, L->c->name, L->c->err);
        }
        if (st == OIT_OK)
            st = vtk_cells_push_off(cs, &L->c->budget, cs->nconn, L->c->name, L->c->err);
    }
    if (st == OIT_OK && used != size)
        return leg_fail(L, OIT_ERR_FORMAT, "%s: cells hold %" PRIu64 " values, the header "
                        "says %" PRIu64, what, used, size);
    return st;
}

/* Version 5 layout: OFFSETS (nofs values from 0) then CONNECTIVITY. */
static oit_status leg_cells_new(leg *L, vtk_cells *cs, uint64_t nofs, uint64_t nconn,
                                const char *what)
{
    leg_type t;
    oit_status st = leg_line(L);
    if (st == OIT_OK && !leg_is(L, 0, "OFFSETS"))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected OFFSETS (file version 5 layout)", what);
    if (st == OIT_OK)
        st = leg_type_word(L, 1, &t);
    uint64_t prev = 0;
    for (uint64_t i = 0; i < nofs && st == OIT_OK; i++) {
        double v;
        if ((st = leg_value(L, t, "OFFSETS", &v)) != OIT_OK)
            break;
        if (!(v >= (double)prev) || v > (double)nconn || (i == 0 && v != 0))
            return leg_fail(L, OIT_ERR_FORMAT, "%s: offset %" PRIu64 " is %.0f: offsets must "
                            "start at 0 and grow up to %" PRIu64, what, i, v, nconn);
        prev = (uint64_t)v;
        if (i > 0)
            st = vtk_cells_push_off(cs, &L->c->budget, prev, L->c->name, L->c->err);
    }
    if (st == OIT_OK && nofs > 0 && prev != nconn)
        return leg_fail(L, OIT_ERR_FORMAT, "%s: the last offset is %" PRIu64 ", not the "
                        "connectivity size %" PRIu64, what, prev, nconn);
    if (st == OIT_OK)
        st = leg_line(L);
    if (st == OIT_OK && !leg_is(L, 0, "CONNECTIVITY"))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected CONNECTIVITY after OFFSETS", what);
    if (st == OIT_OK)
        st = leg_type_word(L, 1, &t);
    for (uint64_t i = 0; i < nconn && st == OIT_OK; i++) {
        double v;
        uint32_t id = 0;
        st = leg_value(L, t, "CONNECTIVITY", &v);
        if (st == OIT_OK)
            st = leg_index(L, v, what, &id);
        if (st == OIT_OK)
            st = vtk_cells_push_id(cs, &L->c->budget, id, L->c->name, L->c->err);
    }
    return st;
}

static oit_status leg_cells(leg *L, vtk_cells *cs, int type)
{
    uint64_t a, b;
    char what[32]; /* the words do not outlive the next read */
    snprintf(what, sizeof what, "%s", L->words[0]);
    if (!L->have_points)
        return leg_fail(L, OIT_ERR_FORMAT, "%s before POINTS", what);
    if (cs->ncells > 0)
        return leg_fail(L, OIT_ERR_FORMAT, "a second %s section", what);
    if (!leg_count(L, 1, &a) || !leg_count(L, 2, &b))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected two counts", what);
    cs->type = type;
    return L->new_cells ? leg_cells_new(L, cs, a, b, what) : leg_cells_classic(L, cs, a, b, what);
}

static oit_status leg_cell_types(leg *L)
{
    uint64_t n;
    vtk_cells *cs = &L->sec[0];
    if (!leg_count(L, 1, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "CELL_TYPES: expected a count");
    if (n != cs->ncells || cs->ntypes > 0)
        return leg_fail(L, OIT_ERR_FORMAT, "CELL_TYPES: %" PRIu64 " types for %zu CELLS", n,
                        cs->ncells);
    oit_status st = OIT_OK;
    for (uint64_t i = 0; i < n && st == OIT_OK; i++) {
        double v;
        st = leg_value(L, LT_I32, "CELL_TYPES", &v);
        if (st == OIT_OK)
            st = vtk_cells_push_type(cs, &L->c->budget, v >= 0 && v < 255 ? (uint8_t)v : 255,
                                     L->c->name, L->c->err);
    }
    return st;
}

/* ---- the file ---------------------------------------------------------- */

static oit_status leg_header(leg *L)
{
    oit_rd_stream *s = &L->c->in;
    char *line;
    int got;
    oit_status st = oit_rd_skip_bom(s);
    if (st == OIT_OK)
        st = oit_rd_line(s, &line, &got);
    if (st != OIT_OK)
        return st;
    int major = 0, minor = 0;
    if (!got || sscanf(line, "# vtk DataFile Version %d.%d", &major, &minor) < 1)
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "not a legacy VTK file (the first line "
                                "should be '# vtk DataFile Version N.N')");
    L->new_cells = major >= 5;
    if ((st = oit_rd_line(s, &line, &got)) != OIT_OK) /* the title */
        return st;
    if (st == OIT_OK)
        st = leg_line(L);
    if (st != OIT_OK)
        return st;
    if (leg_is(L, 0, "BINARY"))
        L->binary = 1;
    else if (!leg_is(L, 0, "ASCII"))
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "expected ASCII or BINARY on line 3");
    if ((st = leg_line(L)) != OIT_OK)
        return st;
    if (!leg_is(L, 0, "DATASET"))
        return oit_rd_fail_line(s, OIT_ERR_FORMAT, "expected DATASET after ASCII/BINARY");
    if (leg_is(L, 1, "UNSTRUCTURED_GRID"))
        L->ugrid = 1;
    else if (!leg_is(L, 1, "POLYDATA"))
        return oit_rd_fail_line(s, OIT_ERR_UNSUPPORTED, "DATASET %.40s is not supported (only "
                                "POLYDATA and UNSTRUCTURED_GRID hold surfaces)",
                                L->nwords > 1 ? L->words[1] : "(none)");
    return OIT_OK;
}

static oit_status leg_section(leg *L)
{
    static const char *const poly[4] = {"VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS"};
    static const int poly_type[4] = {VTK_CELL_POLY_VERTEX, VTK_CELL_POLY_LINE, VTK_CELL_POLYGON,
                                     VTK_CELL_TRIANGLE_STRIP};
    if (leg_is(L, 0, "POINTS"))
        return leg_points(L);
    for (int i = 0; i < 4 && !L->ugrid; i++)
        if (leg_is(L, 0, poly[i]))
            return L->data ? leg_fail(L, OIT_ERR_FORMAT, "%s after the data arrays", poly[i])
                           : leg_cells(L, &L->sec[i], poly_type[i]);
    if (L->ugrid && leg_is(L, 0, "CELLS"))
        return L->data ? leg_fail(L, OIT_ERR_FORMAT, "CELLS after the data arrays")
                       : leg_cells(L, &L->sec[0], 0);
    if (L->ugrid && leg_is(L, 0, "CELL_TYPES"))
        return leg_cell_types(L);
    if (leg_is(L, 0, "POINT_DATA"))
        return leg_data(L, 1);
    if (leg_is(L, 0, "CELL_DATA"))
        return leg_data(L, 2);
    if (leg_is(L, 0, "FIELD"))
        return leg_field(L);
    if (leg_is(L, 0, "METADATA"))
        return leg_skip_metadata(L);
    int done;
    oit_status st = leg_attribute(L, &done);
    if (done)
        return st;
    return leg_fail(L, OIT_ERR_FORMAT, "unknown keyword '%.40s'", L->words[0]);
}

static oit_status leg_emit(leg *L)
{
    if (L->ugrid && L->sec[0].ntypes != L->sec[0].ncells)
        return oit_error_set(L->c->err, OIT_ERR_FORMAT, "%s: %zu CELLS but no CELL_TYPES "
                             "section", L->c->name, L->sec[0].ncells);
    vtk_apply_point_colours(&L->pts, &L->pc);
    vtk_note_colours(L->c->info, L->pc.components);
    vtk_note_colours(L->c->info, L->cc.components);
    vtk_skipped skip = {0};
    uint64_t first = 0;
    oit_status st = OIT_OK;
    for (int i = 0; i < 4 && st == OIT_OK; i++) {
        st = vtk_emit_cells(L->c, &L->pts, &L->sec[i], first, &L->cc, &skip);
        first += L->sec[i].ncells;
    }
    if (st == OIT_OK)
        st = vtk_report_skipped(L->c, &skip);
    return st;
}

static oit_status leg_parse(oit_rd_ctx *c)
{
    leg L;
    memset(&L, 0, sizeof L);
    L.c = c;
    oit_status st = leg_header(&L);
    while (st == OIT_OK) {
        if ((st = leg_line(&L)) != OIT_OK || L.nwords == 0)
            break;
        st = leg_section(&L);
    }
    if (st == OIT_OK)
        st = leg_emit(&L);
    for (int i = 0; i < 4; i++)
        vtk_cells_free(&L.sec[i], &c->budget);
    vtk_colours_free(&L.pc, &c->budget);
    vtk_colours_free(&L.cc, &c->budget);
    oit_rd_release(&c->budget, (void **)&L.pts.v, &L.pts.cap, sizeof *L.pts.v);
    return st;
}

oit_status oit_read_vtk_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    return oit_rd_ctx_run(f, name, desc, sink, user, info, err, leg_parse);
}
