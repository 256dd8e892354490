/* VTK XML PolyData reader (.vtp).
 *
 * <VTKFile type="PolyData"> with any number of Pieces; DataArrays in the
 * ascii, binary (base64) and appended (raw or base64) formats, either byte
 * order, header_type UInt32 or UInt64, uncompressed or compressed with
 * vtkZLibDataCompressor (zlib, loaded as for gzip input: zlib_load.h).
 * Points, Polys and Strips are drawn; Verts and Lines are counted in VTK's
 * cell ids (verts, lines, polys, strips) and not drawn. Colours: the
 * PointData or CellData array named by its Scalars attribute when it is
 * UInt8 with 3 or 4 components (the 4th alpha), else the first such array
 * named like a colour ("Colors", "RGBA"); every other array is skipped and
 * never decoded. A cell colour overrides its points' colours.
 *
 * Appended data comes after every element that refers to it, so the whole
 * file is held (charged to the memory budget, with the arrays that are
 * decoded); a small tokenizer walks the elements, attributes and text it
 * needs, and nothing beyond it (no DTD, no entities in what is read).
 * Errors name the file and the byte offset of the element or data at fault.
 *
 * This file turns each piece into points, cells and colours and emits
 * them; the file is walked in vtp_xml.c and its arrays decoded in
 * vtp_decode.c (vtp_internal.h).
 */
#include "formats/vtp_internal.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* ---- a piece ----------------------------------------------------------- */

static int vtp_colourish(const vtp_array *a)
{
    static const char *const names[] = {"color", "colour", "rgb"};
    for (size_t i = 0; i < 3; i++)
        for (size_t p = 0; p < a->name_len; p++) {
            size_t k = 0;
            while (names[i][k] && p + k < a->name_len && (a->name[p + k] | 0x20) == names[i][k])
                k++;
            if (!names[i][k])
                return 1;
        }
    return 0;
}

static const vtp_array *vtp_find(const vtp *V, const vtp_piece *p, int role, int sec)
{
    for (size_t i = p->first; i < p->first + p->count; i++)
        if (V->arrays[i].role == role && (role == ROLE_POINTS || V->arrays[i].sec == sec))
            return &V->arrays[i];
    return NULL;
}

static const vtp_array *vtp_colour_array(const vtp *V, const vtp_piece *p, int k)
{
    int role = k ? ROLE_CDATA : ROLE_PDATA;
    const vtp_array *best = NULL;
    for (size_t i = p->first; i < p->first + p->count; i++) {
        const vtp_array *a = &V->arrays[i];
        if (a->role != role || a->type != VT_U8 || (a->comps != 3 && a->comps != 4))
            continue;
        if (p->scalars[k] && a->name && a->name_len == p->scalars_len[k] &&
            memcmp(a->name, p->scalars[k], a->name_len) == 0)
            return a;
        if (!best && vtp_colourish(a))
            best = a;
    }
    return best;
}

static oit_status vtp_colours(vtp *V, const vtp_array *a, size_t n, vtk_colours *col)
{
    if (!a)
        return OIT_OK;
    unsigned char *own = NULL;
    size_t own_cap = 0;
    vtp_view v;
    oit_status st = vtp_decode(V, a, n * (size_t)a->comps, &v, &own, &own_cap);
    if (st == OIT_OK)
        st = vtk_colours_alloc(col, &V->c->budget, n, a->comps, V->c->name, V->c->err);
    for (size_t i = 0; i < n && st == OIT_OK; i++)
        for (int k = 0; k < a->comps; k++)
            vtk_colour_set(col, i, k, a->comps, vtp_get(&v, i * (size_t)a->comps + (size_t)k), 0);
    oit_rd_release(&V->c->budget, (void **)&own, &own_cap, 1);
    return st;
}

static oit_status vtp_section(vtp *V, const vtp_piece *p, int sec, size_t npts, vtk_cells *cs)
{
    static const char *const names[SEC_N] = {"Verts", "Lines", "Polys", "Strips"};
    static const int types[SEC_N] = {VTK_CELL_POLY_VERTEX, VTK_CELL_POLY_LINE, VTK_CELL_POLYGON,
                                     VTK_CELL_TRIANGLE_STRIP};
    size_t n = (size_t)p->ncells[sec];
    cs->type = types[sec];
    if (n == 0)
        return OIT_OK;
    const vtp_array *ca = vtp_find(V, p, ROLE_CONN, sec), *oa = vtp_find(V, p, ROLE_OFFS, sec);
    if (!ca || !oa)
        return vtp_fail(V, p->at, OIT_ERR_FORMAT, "%s of %zu cells without its connectivity "
                        "and offsets arrays", names[sec], n);
    unsigned char *co = NULL, *oo = NULL;
    size_t cc = 0, oc = 0;
    vtp_view ov, cv;
    oit_status st = vtp_decode(V, oa, n, &ov, &oo, &oc);
    double last = st == OIT_OK ? vtp_get(&ov, n - 1) : 0;
    if (st == OIT_OK && !(last >= 0 && last < 1e15))
        st = vtp_fail(V, oa->at, OIT_ERR_FORMAT, "%s: bad last offset %g", names[sec], last);
    if (st == OIT_OK)
        st = vtp_decode(V, ca, (size_t)last, &cv, &co, &cc);
    double prev = 0;
    for (size_t i = 0; i < n && st == OIT_OK; i++) {
        double end = vtp_get(&ov, i);
        if (!(end >= prev) || end > last || end != floor(end))
            st = vtp_fail(V, oa->at, OIT_ERR_FORMAT, "%s: offset %zu is %g: offsets must grow",
                          names[sec], i, end);
        for (size_t k = (size_t)prev; st == OIT_OK && k < (size_t)end; k++) {
            double id = vtp_get(&cv, k);
            if (!(id >= 0) || id >= (double)npts || id != floor(id))
                st = vtp_fail(V, ca->at, OIT_ERR_FORMAT, "%s: point index %g out of range "
                              "(%zu points)", names[sec], id, npts);
            else
                st = vtk_cells_push_id(cs, &V->c->budget, (uint32_t)id, V->c->name, V->c->err);
        }
        if (st == OIT_OK)
            st = vtk_cells_push_off(cs, &V->c->budget, cs->nconn, V->c->name, V->c->err);
        prev = end;
    }
    oit_rd_release(&V->c->budget, (void **)&oo, &oc, 1);
    oit_rd_release(&V->c->budget, (void **)&co, &cc, 1);
    return st;
}

static oit_status vtp_points(vtp *V, const vtp_piece *p, oit_rd_vtable *pts)
{
    size_t n = (size_t)p->npoints;
    if (n == 0)
        return OIT_OK;
    if (p->npoints > UINT32_MAX)
        return vtp_fail(V, p->at, OIT_ERR_UNSUPPORTED, "more than 2^32 points in a piece");
    const vtp_array *a = vtp_find(V, p, ROLE_POINTS, 0);
    if (!a)
        return vtp_fail(V, p->at, OIT_ERR_FORMAT, "Piece of %zu points without <Points>", n);
    if (a->comps != 3)
        return vtp_fail(V, a->at, OIT_ERR_FORMAT, "Points with %d components, 3 expected",
                        a->comps);
    unsigned char *own = NULL;
    size_t own_cap = 0;
    vtp_view v;
    oit_status st = vtp_decode(V, a, 3 * n, &v, &own, &own_cap);
    for (size_t i = 0; i < n && st == OIT_OK; i++) {
        double in[3] = {vtp_get(&v, 3 * i), vtp_get(&v, 3 * i + 1), vtp_get(&v, 3 * i + 2)};
        oit_vertex vx;
        memset(vx.rgba, 255, sizeof vx.rgba);
        oit_rd_position(V->c, in, vx.pos);
        st = oit_rd_vtable_push(pts, &V->c->budget, &vx, V->c->name, V->c->err);
    }
    oit_rd_release(&V->c->budget, (void **)&own, &own_cap, 1);
    return st;
}

static oit_status vtp_piece_emit(vtp *V, const vtp_piece *p, vtk_skipped *skip)
{
    oit_rd_vtable pts = {0};
    vtk_cells cs[SEC_N];
    vtk_colours pc = {0}, cc = {0};
    memset(cs, 0, sizeof cs);
    uint64_t ncells = 0;
    for (int s = 0; s < SEC_N; s++)
        ncells += p->ncells[s];
    oit_status st = vtp_points(V, p, &pts);
    for (int s = 0; s < SEC_N && st == OIT_OK; s++)
        st = vtp_section(V, p, s, pts.count, &cs[s]);
    if (st == OIT_OK)
        st = vtp_colours(V, vtp_colour_array(V, p, 0), pts.count, &pc);
    if (st == OIT_OK)
        st = vtp_colours(V, vtp_colour_array(V, p, 1), (size_t)ncells, &cc);
    if (st == OIT_OK) {
        V->c->info->vertices_in += pts.count;
        vtk_apply_point_colours(&pts, &pc);
        vtk_note_colours(V->c->info, pc.components);
        vtk_note_colours(V->c->info, cc.components);
    }
    uint64_t first = 0;
    for (int s = 0; s < SEC_N && st == OIT_OK; s++) {
        st = vtk_emit_cells(V->c, &pts, &cs[s], first, &cc, skip);
        first += cs[s].ncells;
    }
    for (int s = 0; s < SEC_N; s++)
        vtk_cells_free(&cs[s], &V->c->budget);
    vtk_colours_free(&pc, &V->c->budget);
    vtk_colours_free(&cc, &V->c->budget);
    oit_rd_release(&V->c->budget, (void **)&pts.v, &pts.cap, sizeof *pts.v);
    return st;
}

static oit_status vtp_parse(oit_rd_ctx *c)
{
    vtp V;
    memset(&V, 0, sizeof V);
    V.c = c;
    vtk_skipped skip = {0};
    oit_status st = vtp_slurp(&V);
    if (st == OIT_OK)
        st = vtp_walk_file(&V);
    for (size_t i = 0; i < V.npieces && st == OIT_OK; i++)
        st = vtp_piece_emit(&V, &V.pieces[i], &skip);
    if (st == OIT_OK)
        st = vtk_report_skipped(c, &skip);
    oit_zlib_close(&V.z);
    oit_rd_release(&c->budget, (void **)&V.dec, &V.dec_cap, 1);
    oit_rd_release(&c->budget, (void **)&V.arrays, &V.arrays_cap, sizeof *V.arrays);
    oit_rd_release(&c->budget, (void **)&V.pieces, &V.pieces_cap, sizeof *V.pieces);
    oit_rd_release(&c->budget, (void **)&V.buf, &V.cap, 1);
    return st;
}

oit_status oit_read_vtp_stream(FILE *f, const char *name, const char *dir,
                               const oit_read_desc *desc, oit_triangle_sink sink, void *user,
                               oit_mesh_info *info, oit_error *err)
{
    return oit_rd_ctx_run(f, name, desc, sink, user, info, err, vtp_parse);
}
