/* The VTK readers (.vtk legacy, .vtp XML PolyData) against files VTK 9.1
 * wrote itself (tests/corpus/vtk, tests/corpus/vtp; made by
 * data_scripts/make_vtk_corpus.py, which also wrote each NAME.expected from
 * VTK's own readers): every triangle's positions and colours, the count and
 * the attribute bits must match exactly, in one chunk and in chunks of 3
 * (the unstructured grids: surface cells, and the boundary faces of a
 * voxel, a pyramid on it, a wedge, a hexahedron and tetrahedra, two of
 * them sharing an inner face, one face covered by a triangle cell).
 * Then each file cut in half, and hand-written malformed files, must fail
 * with the right status and a message naming the file (and, for parse
 * errors, the line or byte offset). Arguments: the two corpus folders. */
#include "oit/mesh.h"
#include "tests/formats/test_tmp_files.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_files.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

/* Compares m with path.expected; returns the number of triangles checked. */
static size_t check_expected(const char *path, const oit_mesh *m, const char *how)
{
    char ex[2200];
    snprintf(ex, sizeof ex, "%s.expected", path);
    FILE *f = fopen(ex, "r");
    CHECK(f != NULL, "%s: cannot open", ex);
    if (!f)
        return 0;
    unsigned long tris = 0, attrs = 0, volume = 0;
    CHECK(fscanf(f, "triangles %lu attributes %lu skipped_volume %lu", &tris, &attrs, &volume) == 3,
          "%s: bad first line", ex);
    CHECK(m->count == tris, "%s (%s): %zu triangles, VTK's %lu", path, how, m->count, tris);
    CHECK(m->info.attributes == attrs, "%s (%s): attributes %u, expected %lu", path, how,
          m->info.attributes, attrs);
    size_t bad = 0;
    for (size_t t = 0; t < tris && t < m->count; t++)
        for (int v = 0; v < 3; v++) {
            float p[3];
            int c[4];
            if (fscanf(f, "%f %f %f %d %d %d %d", &p[0], &p[1], &p[2], &c[0], &c[1], &c[2],
                       &c[3]) != 7) {
                CHECK(0, "%s: short at triangle %zu", ex, t);
                fclose(f);
                return t;
            }
            const oit_vertex *x = &m->tris[t].v[v];
            int ok = x->pos[0] == p[0] && x->pos[1] == p[1] && x->pos[2] == p[2];
            for (int k = 0; k < 4; k++)
                ok &= x->rgba[k] == c[k];
            if (!ok && bad++ < 3)
                CHECK(0, "%s (%s): triangle %zu vertex %d is %g %g %g %d %d %d %d, VTK's "
                      "%g %g %g %d %d %d %d", path, how, t, v, x->pos[0], x->pos[1], x->pos[2],
                      x->rgba[0], x->rgba[1], x->rgba[2], x->rgba[3], p[0], p[1], p[2], c[0],
                      c[1], c[2], c[3]);
        }
    fclose(f);
    return tris;
}

/* Every file of a corpus folder, read whole and in chunks of 3. */
static int test_folder(const char *dir, const char *ext)
{
    DIR *d = opendir(dir);
    CHECK(d != NULL, "cannot open %s", dir);
    if (!d)
        return 0;
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!ends_with(e->d_name, ext))
            continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        oit_read_desc descs[2] = {{0}, {.chunk_triangles = 3}};
        for (int i = 0; i < 2; i++) {
            oit_mesh m;
            oit_error err = {0};
            oit_status st = oit_mesh_load(path, &descs[i], &m, &err);
            CHECK(st == OIT_OK, "%s: %s", path, err.message);
            if (st == OIT_OK) {
                size_t n = check_expected(path, &m, i ? "chunks of 3" : "one chunk");
                if (i == 0)
                    printf("%-40s %zu triangles, attributes %u\n", e->d_name, n,
                           m.info.attributes);
            }
            oit_mesh_free(&m);
        }
        /* the first half of the file: truncated, never a success */
        size_t n = 0;
        uint8_t *b = test_read_file(path, &n);
        char cut[256];
        snprintf(cut, sizeof cut, "half_%s", e->d_name);
        write_bytes(cut, b, n / 2);
        free(b);
        oit_mesh m;
        oit_error err = {0};
        oit_status st = oit_mesh_load(tmp_path(cut), NULL, &m, &err);
        /* a format error, or unsupported where the cut falls in a type name */
        CHECK(st == OIT_ERR_FORMAT || st == OIT_ERR_UNSUPPORTED,
              "%s cut in half: %s, expected a failure (%s)", e->d_name, oit_status_name(st),
              err.message);
        CHECK(strstr(err.message, cut) != NULL, "%s: the message lacks the file name: %s", cut,
              err.message);
        oit_mesh_free(&m);
        files++;
    }
    closedir(d);
    return files;
}

/* text as name must fail with s, its message holding name and `needle`. */
static void expect_error(const char *name, const char *text, oit_status s, const char *needle)
{
    write_text(name, text);
    oit_mesh m;
    oit_error err = {0};
    oit_status got = oit_mesh_load(tmp_path(name), NULL, &m, &err);
    CHECK(got == s, "%s: status %s, expected %s (%s)", name, oit_status_name(got),
          oit_status_name(s), err.message);
    CHECK(strstr(err.message, name) != NULL, "%s: message lacks the file name: %s", name,
          err.message);
    CHECK(strstr(err.message, needle) != NULL, "%s: message lacks '%s': %s", name, needle,
          err.message);
    oit_mesh_free(&m);
}

#define LEG_HEAD "# vtk DataFile Version 4.2\ntitle\nASCII\nDATASET POLYDATA\n"
#define TRI_POINTS "POINTS 3 float\n0 0 0 1 0 0 0 1 0\n"

static void test_legacy_errors(void)
{
    expect_error("e_first_line.vtk", "hello\n", OIT_ERR_FORMAT, "line 1: not a legacy VTK file");
    expect_error("e_dataset.vtk",
                 "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n",
                 OIT_ERR_UNSUPPORTED, "DATASET STRUCTURED_POINTS is not supported");
    expect_error("e_points_only.vtk", LEG_HEAD TRI_POINTS, OIT_ERR_FORMAT,
                 "3 vertices but no faces");
    expect_error("e_index.vtk", LEG_HEAD TRI_POINTS "POLYGONS 1 4\n3 0 1 3\n", OIT_ERR_FORMAT,
                 "line 8: POLYGONS: point index 3 out of range (3 points)");
    expect_error("e_size.vtk", LEG_HEAD TRI_POINTS "POLYGONS 1 5\n3 0 1 2\n", OIT_ERR_FORMAT,
                 "the header says 5");
    expect_error("e_before.vtk", LEG_HEAD "POLYGONS 1 4\n3 0 1 2\n" TRI_POINTS, OIT_ERR_FORMAT,
                 "POLYGONS before POINTS");
    expect_error("e_trunc_points.vtk", LEG_HEAD "POINTS 3 float\n0 0 0 1 0 0\n", OIT_ERR_FORMAT,
                 "file ends in POINTS (truncated)");
    expect_error("e_word.vtk", LEG_HEAD TRI_POINTS "POLYGONS 1 4\n3 0 1 2\nBOGUS 3\n",
                 OIT_ERR_FORMAT, "line 9: unknown keyword 'BOGUS'");
    expect_error("e_cell_data.vtk", LEG_HEAD TRI_POINTS "POLYGONS 1 4\n3 0 1 2\nCELL_DATA 2\n",
                 OIT_ERR_FORMAT, "CELL_DATA 2 for 1 cells");
    expect_error("e_type.vtk", LEG_HEAD "POINTS 3 string\n", OIT_ERR_UNSUPPORTED,
                 "data type 'string' is not supported");
    expect_error("e_no_types.vtk",
                 "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n" TRI_POINTS
                 "CELLS 1 4\n3 0 1 2\n",
                 OIT_ERR_FORMAT, "1 CELLS but no CELL_TYPES");
    expect_error("e_offsets.vtk",
                 "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\n" TRI_POINTS
                 "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 4\n",
                 OIT_ERR_FORMAT, "offsets must start at 0 and grow up to 3");
    /* only cells of a type not read (a quadratic tetrahedron): said as such */
    expect_error("e_quadratic.vtk",
                 "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                 "POINTS 10 float\n0 0 0 1 0 0 0 1 0 0 0 1 .5 0 0 .5 .5 0 0 .5 0 0 0 .5 .5 0 .5 "
                 "0 .5 .5\nCELLS 1 11\n10 0 1 2 3 4 5 6 7 8 9\nCELL_TYPES 1\n24\n",
                 OIT_ERR_FORMAT, "no surface cells and no volume cell with a boundary, only 1 "
                 "cells of unsupported types");
}

/* One triangle's three vertices must have colour r g b a. */
static void expect_colour(const char *name, const oit_mesh *m, size_t t, int r, int g, int b,
                          int a)
{
    if (t >= m->count) {
        CHECK(0, "%s: no triangle %zu", name, t);
        return;
    }
    for (int v = 0; v < 3; v++) {
        const uint8_t *c = m->tris[t].v[v].rgba;
        CHECK(c[0] == r && c[1] == g && c[2] == b && c[3] == a,
              "%s: triangle %zu vertex %d colour %d %d %d %d, expected %d %d %d %d", name, t, v,
              c[0], c[1], c[2], c[3], r, g, b, a);
    }
}

static oit_mesh load_ok(const char *name, const char *text)
{
    write_text(name, text);
    oit_mesh m;
    oit_error err = {0};
    oit_status st = oit_mesh_load(tmp_path(name), NULL, &m, &err);
    CHECK(st == OIT_OK, "%s: %s", name, err.message);
    return m;
}

/* Hand-written legacy files for what VTK's writers emit around colours:
 * SCALARS unsigned_char of 4 components (a colour) beside SCALARS float
 * with a LOOKUP_TABLE (not one), a LOOKUP_TABLE section, METADATA blocks,
 * a FIELD array named like a colour, a 1-component COLOR_SCALARS (grey),
 * lower-case keywords, and COLOR_SCALARS winning over SCALARS whatever the
 * order. */
static void test_legacy_extras(void)
{
    oit_mesh m = load_ok("x_scalars.vtk", LEG_HEAD TRI_POINTS
        "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1\n\n"
        "POLYGONS 1 4\n3 0 1 2\nPOINT_DATA 3\nSCALARS temp float 1\nLOOKUP_TABLE default\n"
        "0.5 0.25 1\nSCALARS rgba unsigned_char 4\nLOOKUP_TABLE default\n"
        "10 20 30 40 10 20 30 40 10 20 30 40\nMETADATA\nCOMPONENT_NAMES\nR\nG\nB\nA\n\n"
        "LOOKUP_TABLE my 2\n0 0 0 1 1 1 1 1\nNORMALS n float\n0 0 1 0 0 1 0 0 1\n");
    expect_colour("x_scalars.vtk", &m, 0, 10, 20, 30, 40);
    CHECK(m.info.attributes == (OIT_ATTR_COLOUR | OIT_ATTR_ALPHA), "x_scalars.vtk: attributes %u",
          m.info.attributes);
    oit_mesh_free(&m);
    m = load_ok("x_field.vtk", LEG_HEAD TRI_POINTS "polygons 1 4\n3 0 1 2\ncell_data 1\n"
        "FIELD FieldData 2\nids 1 1 int\n7\nMETADATA\nINFORMATION 0\n\n"
        "CellColors 3 1 unsigned_char\n200 100 50\n");
    expect_colour("x_field.vtk", &m, 0, 200, 100, 50, 255);
    oit_mesh_free(&m);
    m = load_ok("x_grey.vtk", LEG_HEAD TRI_POINTS "POLYGONS 1 4\n3 0 1 2\nCELL_DATA 1\n"
        "SCALARS rgb unsigned_char 3\nLOOKUP_TABLE default\n1 2 3\n"
        "COLOR_SCALARS grey 1\n0.5\n");
    expect_colour("x_grey.vtk", &m, 0, 128, 128, 128, 255);
    oit_mesh_free(&m);
}

#define VTP_HEAD "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n"
#define VTP_TRI                                                                            \
    "<PolyData><Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n"                         \
    "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"       \
    "0 0 0 1 0 0 0 1 0</DataArray></Points>\n"

static void test_vtp_errors(void)
{
    expect_error("e_not_xml.vtp", "solid x\n", OIT_ERR_FORMAT,
                 "byte offset 0: not an XML VTK file");
    expect_error("e_ugrid.vtp", "<VTKFile type=\"UnstructuredGrid\">\n", OIT_ERR_UNSUPPORTED,
                 "VTKFile type 'UnstructuredGrid' is not supported");
    expect_error("e_lz4.vtp", "<VTKFile type=\"PolyData\" compressor=\"vtkLZ4DataCompressor\">",
                 OIT_ERR_UNSUPPORTED, "compressor 'vtkLZ4DataCompressor' is not supported");
    expect_error("e_open.vtp", VTP_HEAD VTP_TRI, OIT_ERR_FORMAT,
                 "file ends inside <Piece> (truncated)");
    expect_error("e_close.vtp", VTP_HEAD "<PolyData></Piece>", OIT_ERR_FORMAT,
                 "</Piece> does not close the open element");
    expect_error("e_index.vtp",
                 VTP_HEAD VTP_TRI "<Polys><DataArray type=\"Int32\" Name=\"connectivity\" "
                 "format=\"ascii\">0 1 3</DataArray><DataArray type=\"Int32\" Name=\"offsets\" "
                 "format=\"ascii\">3</DataArray></Polys></Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "Polys: point index 3 out of range (3 points)");
    expect_error("e_no_conn.vtp", VTP_HEAD VTP_TRI "</Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "Polys of 1 cells without its connectivity");
    expect_error("e_base64.vtp",
                 VTP_HEAD "<PolyData><Piece NumberOfPoints=\"1\"><Points><DataArray "
                 "type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">DAAAA*AA"
                 "</DataArray></Points></Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "byte 0x2a in base64 data");
    expect_error("e_short.vtp",
                 VTP_HEAD "<PolyData><Piece NumberOfPoints=\"2\"><Points><DataArray "
                 "type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1      "
                 "</DataArray></Points></Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "holds 4 of 6 values");
    /* a declared count is not allocated for before the data could hold it */
    expect_error("e_count.vtp",
                 VTP_HEAD "<PolyData><Piece NumberOfPoints=\"4000000000\"><Points><DataArray "
                 "type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1"
                 "</DataArray></Points></Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "of 7 bytes cannot hold 12000000000 values");
    expect_error("e_no_polys.vtp", VTP_HEAD VTP_TRI "</Piece></PolyData></VTKFile>\n"
                 "<!-- a comment -->", OIT_ERR_FORMAT, "without its connectivity");
    expect_error("e_points_only.vtp",
                 VTP_HEAD "<PolyData><Piece NumberOfPoints=\"3\">"
                 "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
                 "0 0 0 1 0 0 0 1 0</DataArray></Points></Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "3 vertices but no faces");
    expect_error("e_appended.vtp",
                 VTP_HEAD "<PolyData><Piece NumberOfPoints=\"1\"><Points><DataArray "
                 "type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/>"
                 "</Points></Piece></PolyData></VTKFile>\n",
                 OIT_ERR_FORMAT, "appended DataArray but no <AppendedData>");
}

/* Hand-written .vtp of what VTK writers and ParaView add around the data:
 * InformationKey children before an ascii array's values, FieldData outside
 * the Piece, comments, a byte-order mark, an array of strings that is not
 * used, two Pieces (ids per piece, cell colours per piece) and a colour
 * array found by name (no Scalars attribute). */
static void test_vtp_extras(void)
{
    const char *text =
        "\xef\xbb\xbf<?xml version=\"1.0\"?>\n<!-- written by hand -->\n"
        "<VTKFile type='PolyData' version='1.0' byte_order='LittleEndian'>\n"
        "<PolyData><FieldData><DataArray type='Float64' Name='TimeValue' "
        "NumberOfTuples='1' format='ascii'>7</DataArray><DataArray type='String' Name='N' "
        "format='ascii'>65 0</DataArray></FieldData>\n"
        "<Piece NumberOfPoints='3' NumberOfPolys='1'>\n"
        "<Points><DataArray type='Float32' NumberOfComponents='3' format='ascii'>\n"
        "<InformationKey name='L2_NORM_RANGE' location='vtkDataArray' length='2'>"
        "<Value index='0'>99</Value><Value index='1'>98</Value></InformationKey>\n"
        "0 0 0 1 0 0 0 1 0</DataArray></Points>\n"
        "<Polys><DataArray type='Int64' Name='connectivity' format='ascii'>0 1 2</DataArray>"
        "<DataArray type='Int64' Name='offsets' format='ascii'>3</DataArray></Polys>\n"
        "</Piece>\n"
        "<Piece NumberOfPoints='4' NumberOfPolys='1' NumberOfStrips='1'>\n"
        "<CellData><DataArray type='UInt8' Name='Temperature' NumberOfComponents='4' "
        "format='ascii'>1 1 1 1 1 1 1 1</DataArray><DataArray type='UInt8' Name='cellColors' "
        "NumberOfComponents='4' format='ascii'>10 20 30 40 50 60 70 80</DataArray></CellData>\n"
        "<Points><DataArray type='Float64' NumberOfComponents='3' format='ascii'>"
        "2 0 0 3 0 0 2 1 0 3 1 0</DataArray></Points>\n"
        "<Strips><DataArray type='Int32' Name='connectivity' format='ascii'>0 1 2 3</DataArray>"
        "<DataArray type='Int32' Name='offsets' format='ascii'>4</DataArray></Strips>\n"
        "<Polys><DataArray type='Int32' Name='connectivity' format='ascii'>3 2 1</DataArray>"
        "<DataArray type='Int32' Name='offsets' format='ascii'>3</DataArray></Polys>\n"
        "</Piece></PolyData></VTKFile>\n";
    write_text("extras.vtp", text);
    oit_mesh m;
    oit_error err = {0};
    oit_status st = oit_mesh_load(tmp_path("extras.vtp"), NULL, &m, &err);
    CHECK(st == OIT_OK, "extras.vtp: %s", err.message);
    if (st != OIT_OK)
        return;
    /* piece 1: (0,1,2) white; piece 2: poly (3,2,1) = cell 0, then the strip
     * (0,1,2) and flipped (2,1,3) = cell 1 */
    static const float want[4][3][3] = {
        {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
        {{3, 1, 0}, {2, 1, 0}, {3, 0, 0}},
        {{2, 0, 0}, {3, 0, 0}, {2, 1, 0}},
        {{2, 1, 0}, {3, 0, 0}, {3, 1, 0}}};
    static const int rgba[4][4] = {
        {255, 255, 255, 255}, {10, 20, 30, 40}, {50, 60, 70, 80}, {50, 60, 70, 80}};
    CHECK(m.count == 4, "extras.vtp: %zu triangles, 4 expected", m.count);
    for (size_t t = 0; t < m.count && t < 4; t++)
        for (int v = 0; v < 3; v++) {
            const oit_vertex *x = &m.tris[t].v[v];
            CHECK(x->pos[0] == want[t][v][0] && x->pos[1] == want[t][v][1] &&
                  x->pos[2] == want[t][v][2], "extras.vtp: triangle %zu vertex %d at %g %g %g",
                  t, v, x->pos[0], x->pos[1], x->pos[2]);
            CHECK(x->rgba[0] == rgba[t][0] && x->rgba[1] == rgba[t][1] &&
                  x->rgba[2] == rgba[t][2] && x->rgba[3] == rgba[t][3],
                  "extras.vtp: triangle %zu vertex %d colour %d %d %d %d", t, v, x->rgba[0],
                  x->rgba[1], x->rgba[2], x->rgba[3]);
        }
    CHECK(m.info.vertices_in == 7, "extras.vtp: %llu vertices, 7 expected",
          (unsigned long long)m.info.vertices_in);
    oit_mesh_free(&m);
}

/* A budget too small for the held arrays fails as out of memory. */
static void test_budget(const char *dir)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/poly_appended.vtp", dir);
    oit_read_desc desc = {.memory_budget = 5000};
    oit_mesh m;
    oit_error err = {0};
    oit_status st = oit_mesh_load(path, &desc, &m, &err);
    CHECK(st == OIT_ERR_NOMEM, "budget 5000: %s (%s)", oit_status_name(st), err.message);
    oit_mesh_free(&m);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test_vtk CORPUS/vtk CORPUS/vtp\n");
        return 2;
    }
    int n = test_folder(argv[1], ".vtk");
    CHECK(n >= 6, "only %d .vtk files in %s", n, argv[1]);
    n = test_folder(argv[2], ".vtp");
    CHECK(n >= 5, "only %d .vtp files in %s", n, argv[2]);
    test_legacy_errors();
    test_legacy_extras();
    test_vtp_errors();
    test_vtp_extras();
    test_budget(argv[2]);
    return test_verdict();
}
