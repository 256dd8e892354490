#!/usr/bin/python3
"""Writes the VTK test files of tests/corpus/vtk (legacy .vtk) and
tests/corpus/vtp (XML PolyData) with VTK itself, and beside each the
triangles our readers must deliver (NAME.expected), derived from VTK's own
readers, so that the tests need no VTK at run time.

Run once by hand (Debian: apt-get install python3-vtk9), from the repository
root:  /usr/bin/python3 data_scripts/make_vtk_corpus.py
It prints each file with its triangle count; the count is also checked
against vtkTriangleFilter's (surface cells only).

NAME.expected: a first line "triangles N attributes A skipped_volume V",
then one line per triangle: three vertices of "x y z r g b a" (positions as
VTK's reader returns them, printed exactly as float32 with %.9g).
Triangulation is the readers' documented one (formats/vtk_cells.c): fans
from a cell's first point (polygons, quads, triangles), strips with every
second triangle flipped, pixels 0,1,3 and 0,3,2; a cell colour overrides
its points' colours; a linear volume cell gives the faces (VTK's, as VTK
orients them) that no other volume cell shares and no triangle/quad/pixel
cell covers, quads fanned, a voxel's
pixel faces split as pixels. vtkGeometryFilter + vtkTriangleFilter give the
same counts (checked here); the ear cut places a polygon's diagonals
elsewhere, which is why the positions are not taken from them.
"""
import os
import sys

import vtk
from vtk.util.numpy_support import vtk_to_numpy  # noqa: F401 (python3-vtk9 ships numpy)

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
LEG = os.path.join(ROOT, "tests", "corpus", "vtk")
XML = os.path.join(ROOT, "tests", "corpus", "vtp")

# Coordinates on a 1/8 grid: exact in float32 and in any decimal VTK prints.
PTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0.25), (2, 1, 0.5), (3, 0, 0),
       (4, 0, 0.125), (4.5, 1, 0.125), (4, 2, 0.25), (3, 1.5, 0.375),
       (0, 3, 1), (1, 3, 1.5), (2, 3, 1), (3, 3, 1.5), (4, 3, 1), (5, 3, 1.5),
       (-1.5, -2.25, 0.75)]


# More points for the unstructured grid's volume cells: a voxel (17-24), a
# pyramid on its top (21, 22, 24, 23, 25), a wedge (26-31) and two
# tetrahedra sharing a face (32-36), whose shared face is inside.
EXTRA = [(0, 0, 2), (1, 0, 2), (0, 1, 2), (1, 1, 2), (0, 0, 3), (1, 0, 3), (0, 1, 3), (1, 1, 3),
         (0.5, 0.5, 4), (3, 0, 2), (4, 0, 2), (3, 1, 2), (3, 0, 3), (4, 0, 3), (3, 1, 3),
         (6, 0, 0), (7, 0, 0), (6, 1, 0), (6, 0, 1), (6.5, 0.5, -1)]


def colours(name, n, comps, seed):
    a = vtk.vtkUnsignedCharArray()
    a.SetName(name)
    a.SetNumberOfComponents(comps)
    for i in range(n):
        a.InsertNextTuple([(seed + 37 * i + 71 * k) % 256 for k in range(comps)])
    return a


def polydata(point_comps, cell_comps):
    pd = vtk.vtkPolyData()
    p = vtk.vtkPoints()
    for x in PTS:
        p.InsertNextPoint(x)
    pd.SetPoints(p)
    polys = vtk.vtkCellArray()
    for c in [(0, 1, 2), (1, 5, 4, 3), (5, 6, 7, 8, 9)]:
        polys.InsertNextCell(len(c), c)
    strips = vtk.vtkCellArray()
    strips.InsertNextCell(6, (10, 11, 12, 13, 14, 15))
    verts = vtk.vtkCellArray()
    verts.InsertNextCell(1, (16,))
    lines = vtk.vtkCellArray()
    lines.InsertNextCell(2, (16, 0))
    pd.SetPolys(polys)
    pd.SetStrips(strips)
    pd.SetVerts(verts)
    pd.SetLines(lines)
    if point_comps:
        pd.GetPointData().SetScalars(colours("Colors", pd.GetNumberOfPoints(), point_comps, 11))
    if cell_comps:
        pd.GetCellData().SetScalars(colours("RGBA", pd.GetNumberOfCells(), cell_comps, 200))
    # an array that is not a colour, to be skipped
    f = vtk.vtkFloatArray()
    f.SetName("Temperature")
    for i in range(pd.GetNumberOfPoints()):
        f.InsertNextValue(i * 0.5)
    pd.GetPointData().AddArray(f)
    return pd


def ugrid(cell_comps):
    g = vtk.vtkUnstructuredGrid()
    p = vtk.vtkPoints()
    for x in PTS + EXTRA:
        p.InsertNextPoint(x)
    g.SetPoints(p)
    cells = [(vtk.VTK_TRIANGLE, (0, 1, 2)), (vtk.VTK_QUAD, (1, 5, 4, 3)),
             (vtk.VTK_TETRA, (0, 1, 2, 16)), (vtk.VTK_POLYGON, (5, 6, 7, 8, 9)),
             (vtk.VTK_PIXEL, (10, 11, 2, 3)), (vtk.VTK_VERTEX, (16,)),
             (vtk.VTK_TRIANGLE_STRIP, (14, 15, 9, 8, 7)), (vtk.VTK_LINE, (16, 5)),
             (vtk.VTK_HEXAHEDRON, (0, 1, 3, 2, 10, 11, 13, 12)),
             (vtk.VTK_VOXEL, (17, 18, 19, 20, 21, 22, 23, 24)),
             (vtk.VTK_PYRAMID, (21, 22, 24, 23, 25)),
             (vtk.VTK_WEDGE, (26, 27, 28, 29, 30, 31)),
             (vtk.VTK_TETRA, (32, 33, 34, 35)), (vtk.VTK_TETRA, (32, 34, 33, 36))]
    for t, ids in cells:
        g.InsertNextCell(t, len(ids), ids)
    if cell_comps:
        g.GetCellData().SetScalars(colours("Colors", g.GetNumberOfCells(), cell_comps, 5))
    return g


def colour_array(data):
    s = data.GetScalars()
    if s is not None and s.GetDataType() == vtk.VTK_UNSIGNED_CHAR:
        return s
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        if a is not None and a.GetDataType() == vtk.VTK_UNSIGNED_CHAR and \
                a.GetNumberOfComponents() in (3, 4):
            return a
    return None


def rgba(arr, i):
    if arr is None:
        return [255, 255, 255, 255]
    t = [int(round(v)) for v in arr.GetTuple(i)]
    n = len(t)
    if n == 1:
        return [t[0], t[0], t[0], 255]
    if n == 2:
        return [t[0], t[0], t[0], t[1]]
    if n == 3:
        return t + [255]
    return t


def comps_bits(arr):
    if arr is None:
        return 0
    n = arr.GetNumberOfComponents()
    return 1 | (2 if n in (2, 4) else 0)



def expected(data):
    """Triangles (VTK's reader's points and colours, our triangulation)."""
    pts = data.GetPoints()
    pc = colour_array(data.GetPointData())
    cc = colour_array(data.GetCellData())
    tris, volume = [], 0
    shared = {}
    for cid in range(data.GetNumberOfCells()):
        cell = data.GetCell(cid)
        if data.GetCellType(cid) in (vtk.VTK_TRIANGLE, vtk.VTK_QUAD, vtk.VTK_PIXEL,
                                     vtk.VTK_POLYGON) and cell.GetNumberOfPoints() in (3, 4):
            key = tuple(sorted(cell.GetPointId(j) for j in range(cell.GetNumberOfPoints())))
            shared[key] = shared.get(key, 0) + 1  # a surface cell covers a volume face
        if cell.GetCellDimension() == 3:
            for k in range(cell.GetNumberOfFaces()):
                f = cell.GetFace(k)
                key = tuple(sorted(f.GetPointId(j) for j in range(f.GetNumberOfPoints())))
                shared[key] = shared.get(key, 0) + 1
    for cid in range(data.GetNumberOfCells()):
        cell = data.GetCell(cid)
        t = data.GetCellType(cid)
        ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
        if t in (vtk.VTK_TRIANGLE, vtk.VTK_QUAD, vtk.VTK_POLYGON):
            idx = [(ids[0], ids[k - 1], ids[k]) for k in range(2, len(ids))]
        elif t == vtk.VTK_PIXEL:
            idx = [(ids[0], ids[1], ids[3]), (ids[0], ids[3], ids[2])]
        elif t == vtk.VTK_TRIANGLE_STRIP:
            idx = [(ids[k + 1], ids[k], ids[k + 2]) if k % 2 else (ids[k], ids[k + 1], ids[k + 2])
                   for k in range(len(ids) - 2)]
        elif cell.GetCellDimension() == 3:
            # the faces no other volume cell shares, as VTK orients them
            volume += 1
            idx = []
            for k in range(cell.GetNumberOfFaces()):
                f = cell.GetFace(k)
                fi = [f.GetPointId(j) for j in range(f.GetNumberOfPoints())]
                if shared[tuple(sorted(fi))] != 1:
                    continue
                if len(fi) == 3:
                    idx.append(tuple(fi))
                elif f.GetCellType() == vtk.VTK_PIXEL:
                    idx += [(fi[0], fi[1], fi[3]), (fi[0], fi[3], fi[2])]
                else:
                    idx += [(fi[0], fi[1], fi[2]), (fi[0], fi[2], fi[3])]
        else:
            continue
        for tri in idx:
            tris.append([(pts.GetPoint(i), rgba(cc, cid) if cc is not None else rgba(pc, i))
                         for i in tri])
    attrs = comps_bits(pc) | comps_bits(cc)
    if attrs & 2 and any(all(v[1][3] == 255 for v in t) for t in tris):
        attrs |= 4
    return tris, attrs, volume


def vtk_count(data):
    """vtkTriangleFilter's triangles of the surface cells (a check)."""
    if isinstance(data, vtk.vtkUnstructuredGrid):
        geo = vtk.vtkGeometryFilter()  # 2D cells, and 3D cells' boundary faces
        geo.SetInputData(data)
        geo.Update()
        data = geo.GetOutput()
    tf = vtk.vtkTriangleFilter()
    tf.SetInputData(data)
    tf.PassVertsOff()
    tf.PassLinesOff()
    tf.Update()
    return tf.GetOutput().GetNumberOfCells()


def write_expected(path, data):
    tris, attrs, volume = expected(data)
    count = vtk_count(data)
    if count != len(tris):
        sys.exit("%s: vtkTriangleFilter gives %d triangles, the rules %d" % (path, count, len(tris)))
    with open(path + ".expected", "w") as f:
        f.write("triangles %d attributes %d skipped_volume %d\n" % (len(tris), attrs, volume))
        for t in tris:
            f.write("  ".join("%.9g %.9g %.9g %d %d %d %d" % (tuple(p) + tuple(c)) for p, c in t))
            f.write("\n")
    print("%-28s %3d triangles  attributes %d  %d volume cells  %5d bytes"
          % (os.path.relpath(path, ROOT), len(tris), attrs, volume, os.path.getsize(path)))


def read_back(path):
    if path.endswith(".vtp"):
        r = vtk.vtkXMLPolyDataReader()
    else:
        r = vtk.vtkGenericDataObjectReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def legacy(name, data, binary, version42):
    path = os.path.join(LEG, name)
    w = vtk.vtkPolyDataWriter() if isinstance(data, vtk.vtkPolyData) else \
        vtk.vtkUnstructuredGridWriter()
    w.SetInputData(data)
    w.SetFileName(path)
    if binary:
        w.SetFileTypeToBinary()
    if version42:
        w.SetFileVersion(42)
    if not w.Write():
        sys.exit("cannot write " + path)
    write_expected(path, read_back(path))


def xml(name, data, setup):
    path = os.path.join(XML, name)
    w = vtk.vtkXMLPolyDataWriter()
    w.SetInputData(data)
    w.SetFileName(path)
    setup(w)
    if not w.Write():
        sys.exit("cannot write " + path)
    write_expected(path, read_back(path))


def main():
    os.makedirs(LEG, exist_ok=True)
    os.makedirs(XML, exist_ok=True)
    print("VTK", vtk.vtkVersion.GetVTKVersion())
    legacy("poly_ascii_42.vtk", polydata(3, 0), False, True)
    legacy("poly_binary_42.vtk", polydata(3, 4), True, True)
    legacy("poly_ascii_51.vtk", polydata(4, 0), False, False)
    legacy("poly_binary_51.vtk", polydata(0, 4), True, False)
    legacy("ugrid_ascii_51.vtk", ugrid(4), False, False)
    legacy("ugrid_binary_42.vtk", ugrid(3), True, True)

    def ascii(w):
        w.SetDataModeToAscii()

    def binary32(w):
        w.SetDataModeToBinary()
        w.SetCompressorTypeToNone()
        w.SetHeaderTypeToUInt32()

    def binary_zlib(w):
        w.SetDataModeToBinary()
        w.SetCompressorTypeToZLib()
        w.SetHeaderTypeToUInt64()

    def appended_b64(w):  # VTK's default: appended, base64, zlib
        w.SetDataModeToAppended()
        w.SetCompressorTypeToZLib()
        w.SetBlockSize(64)  # several compressed blocks per array

    def appended_raw_be(w):
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()
        w.SetCompressorTypeToNone()
        w.SetByteOrderToBigEndian()

    xml("poly_ascii.vtp", polydata(3, 0), ascii)
    xml("poly_binary.vtp", polydata(4, 0), binary32)
    xml("poly_binary_zlib.vtp", polydata(0, 4), binary_zlib)
    xml("poly_appended.vtp", polydata(3, 4), appended_b64)
    xml("poly_raw_be.vtp", polydata(4, 3), appended_raw_be)


if __name__ == "__main__":
    main()
