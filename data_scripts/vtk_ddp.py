#!/usr/bin/python3
"""Renders a mesh with VTK dual depth peeling (the peer users pick today),
offscreen, with exactly the cameras of an oitstream walk file, and writes one
PNG a walk line plus a stats JSON shaped like oitstream's --stats (frames[].ms,
.view), so that data_scripts/stream_vs_dfb.sh can time it with the same
helpers and compare its images with `oitstream --compare A B --json`.

Usage (VTK's X render window needs a display even offscreen):
  xvfb-run -a -s "-screen 0 1280x1024x24" /usr/bin/python3 data_scripts/vtk_ddp.py \\
      MESH --walk WALK.txt --size 1024x1024 --peels 1000 --out DIR/ [--stats S.json]

MESH: .ply and .stl go to VTK's own readers; .off, .obj(+.mtl) and
uncompressed .gltf/.glb are converted here to a binary PLY (vertices
de-indexed, one colour a vertex), mirroring formats/read_off.c,
formats/read_obj.c (fan triangulation, MTL Kd/d/Tr, white for faces without
Kd in a coloured file) and formats/gltf_scene.cpp (node transforms,
baseColorFactor x COLOR_0 encoded sRGB, alphaMode; VTK's own glTF importer
would shade PBR), because no tool of the project writes a mesh as it reads
it; --keep-ply PATH keeps it, so that `oitstream PATH --method dfb` can check
that it renders as MESH does. Draco-compressed glTF is refused (exit 3).

The walk: one camera a line in oitstream's --view syntax,
ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy[,znear,zfar] in file coordinates (what
oitstream --stats prints as "view"); each line is rendered once, in order,
and timed (Render() plus WaitForCompletion(): the GPU work included, as
oitstream's ms); a walk that repeats each view gives warm frames to time.

Matching oitstream's conventions (view/render/image/view.h, view/render/image/shade.h):
  camera    vtkCamera position/focal point/view up from the line, view angle
            = fovy (VTK's is vertical too), clipping range = znear,zfar
            (checked after each render: VTK must not have reset it);
  image     PNG written top row first, as oitstream's; background white;
  shading   colour = base * (0.3 + 0.7 |n.v|): flat interpolation with no
            normals (VTK derives the face normal per fragment and turns it
            towards the eye), ambient 0.3, diffuse 0.7, specular 0, one
            positional white light at the eye (cone 180: no spot, no
            attenuation), so the light vector is v = eye - p per fragment;
            vertex colours (direct 8-bit scalars) feed both ambient and
            diffuse (VTK 9 always does so); base colour
            0.85,0.55,0.2 and alpha 0.35 (--alpha) for meshes without them;
            a per-vertex alpha multiplies an opacity of 1;
  peeling   vtkDualDepthPeelingPass in a vtkRenderStepsPass (what
            SetUseDepthPeeling picks on a GL 3.2+ driver), occlusion ratio 0,
            --peels N (VTK 9.1's 0 = 'no limit' stops after one peel: use
            1000 for exact), multisampling off (llvmpipe paints white with
            it), alpha bit planes on.
What differs, printed into the stats as "differences": VTK's peel blenders
(front and back accumulators) are RGBA8 textures, so every peel rounds the
running colour to 8 bits (oitstream composites in float): a few 1/255 on
shallow models, more where tens of layers stack (the 1M plant: ~4% of pixels
off by > 1/255 even at 1000 peels); it orders by window depth (RG32F), not by
the eye distance t with the triangle index breaking ties, so equal-depth
fragments may composite in another order; the face normal comes from
screen-space derivatives of the view-space position (float) instead of the
triangle's edges.
Exit codes: 0 ok, 1 render failure, 2 usage, 3 bad input.
"""
import argparse
import json
import math
import os
import struct
import sys
import tempfile
import time

DEFAULT_RGB = (0.85, 0.55, 0.2)
DIFFERENCES = [
    "VTK's dual peeling accumulates front and back colours in RGBA8 textures: "
    "each peel rounds to 8 bits, oitstream composites in float",
    "VTK orders fragments by window depth (RG32F) per peel, oitstream by eye "
    "distance t with the triangle index breaking ties: equal-depth fragments "
    "may composite in another order",
    "VTK's face normal comes from screen-space derivatives of the view-space "
    "position (float), oitstream's from the triangle's edges",
    "timing: VTK's Render() + WaitForCompletion() from Python; oitstream's ms is "
    "measured in C around the frame",
]


def fail(code, msg):
    print("vtk_ddp: " + msg, file=sys.stderr)
    sys.exit(code)


def unit_to_u8(v):
    """formats/readers_internal.h oit_rd_unit_to_u8."""
    if not v > 0.0:
        return 0
    if v >= 1.0:
        return 255
    return int(v * 255.0 + 0.5)


def clamp_u8(v):
    if not v > 0.0:
        return 0
    if v >= 255.0:
        return 255
    return int(v + 0.5)


def write_ply(path, tris, colours, alpha):
    """Binary PLY: 3 vertices a triangle (de-indexed), rgb(a) per vertex when
    colours is not None. tris: list of (p0, p1, p2); colours: list of three
    rgba tuples a triangle."""
    n = len(tris)
    with open(path, "wb") as f:
        head = ["ply", "format binary_little_endian 1.0",
                "comment written by data_scripts/vtk_ddp.py",
                "element vertex %d" % (3 * n),
                "property float x", "property float y", "property float z"]
        if colours is not None:
            head += ["property uchar red", "property uchar green", "property uchar blue"]
            if alpha:
                head.append("property uchar alpha")
        head += ["element face %d" % n, "property list uchar int vertex_indices",
                 "end_header"]
        f.write(("\n".join(head) + "\n").encode())
        vfmt = struct.Struct("<3f4B" if alpha else "<3f3B") if colours is not None \
            else struct.Struct("<3f")
        out = bytearray()
        for i, t in enumerate(tris):
            for k in range(3):
                if colours is None:
                    out += vfmt.pack(*t[k])
                elif alpha:
                    out += vfmt.pack(*t[k], *colours[i][k])
                else:
                    out += vfmt.pack(*t[k], *colours[i][k][:3])
            if len(out) > (1 << 22):
                f.write(out)
                out = bytearray()
        f.write(out)
        face = struct.Struct("<B3i")
        out = bytearray()
        for i in range(n):
            out += face.pack(3, 3 * i, 3 * i + 1, 3 * i + 2)
            if len(out) > (1 << 22):
                f.write(out)
                out = bytearray()
        f.write(out)


def content_lines(path, comment="#"):
    with open(path, "r", errors="replace") as f:
        for line in f:
            i = line.find(comment)
            if i >= 0:
                line = line[:i]
            line = line.strip()
            if line:
                yield line


def finite(p):
    return all(math.isfinite(c) for c in p)


def read_off(path):
    """The subset of formats/read_off.c the fetched meshes use: OFF/NOFF
    (normals skipped), per-face or per-vertex colours refused loudly rather
    than guessed."""
    it = content_lines(path)
    first = next(it).split()
    kw = first[0].upper()
    if kw.endswith("OFF"):
        flags = kw[:-3]
        flags = flags[2:] if flags.startswith("ST") else flags
        if flags.replace("C", "").replace("N", ""):
            fail(3, "%s: OFF variant %s is not converted by vtk_ddp.py" % (path, kw))
        counts = first[1:] or next(it).split()
    elif kw.isdigit():
        flags, counts = "", first
    else:
        fail(3, "%s: not an OFF file" % path)
    if "C" in flags:
        fail(3, "%s: coloured OFF (%s) is not converted by vtk_ddp.py" % (path, kw))
    normals = "N" in flags
    nv, nf = int(counts[0]), int(counts[1])
    verts = []
    for _ in range(nv):
        w = next(it).split()
        if len(w) not in (3, 6) or (len(w) == 6 and not normals):
            fail(3, "%s: vertex line with colours or texture coordinates is not "
                 "converted by vtk_ddp.py: %r" % (path, " ".join(w)))
        verts.append(tuple(float(x) for x in w[:3]))
    tris = []
    for _ in range(nf):
        w = next(it).split()
        n = int(w[0])
        if len(w) > n + 1:
            fail(3, "%s: face colours are not converted by vtk_ddp.py" % path)
        idx = [int(x) for x in w[1:n + 1]]
        for k in range(2, n):
            t = (verts[idx[0]], verts[idx[k - 1]], verts[idx[k]])
            if all(finite(p) for p in t):
                tris.append(t)
    return tris, None, False


def read_mtl(path):
    mats, cur = {}, None
    try:
        lines = list(content_lines(path))
    except OSError:
        return mats  # the reader skips a library it cannot open
    for line in lines:
        w = line.split()
        if w[0] == "newmtl":
            cur = {"kd": None, "a": None, "has_d": False}
            mats[line.split(None, 1)[1].strip()] = cur
        elif cur is None:
            continue
        elif w[0] == "Kd":
            v = [float(x) for x in w[1:4]]
            if len(v) == 1:
                v = v * 3
            cur["kd"] = tuple(unit_to_u8(x) for x in v)
        elif w[0] == "d" or (w[0] == "Tr" and not cur["has_d"]):
            x = float(w[1])
            cur["a"] = unit_to_u8(x if w[0] == "d" else 1.0 - x)
            cur["has_d"] = cur["has_d"] or w[0] == "d"
    return mats


def read_obj(path):
    """formats/read_obj.c: v [rgb], f (fan), usemtl/mtllib (Kd, d, Tr)."""
    folder = os.path.dirname(os.path.abspath(path))
    verts, vcol = [], []
    mats, cur = {}, None
    vertex_colours = False
    has_colour = has_alpha = False
    tris, cols = [], []
    text = open(path, "r", errors="replace").read().replace("\\\r\n", " ").replace("\\\n", " ")
    for line in text.splitlines():
        i = line.find("#")
        if i >= 0:
            line = line[:i]
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append(tuple(float(x) for x in w[1:4]))
            if len(w) >= 7:
                vcol.append(tuple(unit_to_u8(float(x)) for x in w[4:7]) + (255,))
                vertex_colours = has_colour = True
            else:
                vcol.append((255, 255, 255, 255))
        elif w[0] == "f":
            refs = []
            for r in w[1:]:
                k = int(r.split("/")[0])
                k = k - 1 if k > 0 else len(verts) + k
                c = list(vcol[k])
                if cur is not None and cur["kd"] is not None and not vertex_colours:
                    c[:3] = cur["kd"]
                if cur is not None and cur["a"] is not None:
                    c[3] = cur["a"]
                refs.append((verts[k], tuple(c)))
            if cur is not None and len(refs) >= 3:
                has_colour |= cur["kd"] is not None
                has_alpha |= cur["a"] is not None
            for k in range(2, len(refs)):
                t = (refs[0], refs[k - 1], refs[k])
                if all(finite(p) for p, _ in t):
                    tris.append(tuple(p for p, _ in t))
                    cols.append(tuple(c for _, c in t))
        elif w[0] == "usemtl":
            cur = mats.get(line.split(None, 1)[1].strip())
        elif w[0] == "mtllib":
            for name in line.split(None, 1)[1].split():
                mats.update(read_mtl(os.path.join(folder, name.replace("\\", "/"))))
    return tris, (cols if has_colour or has_alpha else None), has_alpha


GLTF_COMP = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
GLTF_NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def srgb_u8(linear):
    """formats/gltf_scene.cpp srgb_u8."""
    v = 12.92 * linear if linear <= 0.0031308 else 1.055 * math.pow(linear, 1.0 / 2.4) - 0.055
    return 0 if not v > 0.0 else 255 if v >= 1.0 else int(v * 255.0 + 0.5)


def mat_mul(a, b):  # column-major 4x4
    r = [0.0] * 16
    for col in range(4):
        for row in range(4):
            r[col * 4 + row] = sum(a[k * 4 + row] * b[col * 4 + k] for k in range(4))
    return r


def node_matrix(n):
    if "matrix" in n:
        return [float(x) for x in n["matrix"]]
    t = n.get("translation", [0, 0, 0])
    x, y, z, w = n.get("rotation", [0, 0, 0, 1])
    sc = n.get("scale", [1, 1, 1])
    r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]
    m = [0.0] * 16
    for col in range(3):
        for row in range(3):
            m[col * 4 + row] = r[col * 3 + row] * sc[col]
    for row in range(3):
        m[12 + row] = t[row]
    m[15] = 1.0
    return m


def read_gltf(path):
    """formats/gltf_adapter.cpp for uncompressed glTF/GLB: the default scene's
    node tree (matrix or TRS), triangle lists/strips/fans, COLOR_0 times
    baseColorFactor, sRGB-encoded, alpha by alphaMode; mirroring transforms
    flip the winding. Draco, sparse and quantized accessors are refused."""
    raw = open(path, "rb").read()
    bins = []
    if raw[:4] == b"glTF":
        jlen, jtype = struct.unpack_from("<II", raw, 12)
        if jtype != 0x4E4F534A:
            fail(3, "%s: first GLB chunk is not JSON" % path)
        doc = json.loads(raw[20:20 + jlen])
        off = 20 + jlen
        if off + 8 <= len(raw):
            blen, btype = struct.unpack_from("<II", raw, off)
            if btype == 0x004E4942:
                bins.append(raw[off + 8:off + 8 + blen])
    else:
        doc = json.loads(raw)
    folder = os.path.dirname(os.path.abspath(path))
    buffers = []
    for i, b in enumerate(doc.get("buffers", [])):
        uri = b.get("uri")
        if uri is None:
            buffers.append(bins[0] if bins else b"")
        elif uri.startswith("data:"):
            import base64
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            from urllib.parse import unquote
            buffers.append(open(os.path.join(folder, unquote(uri)), "rb").read())

    def accessor(index):
        a = doc["accessors"][index]
        if "sparse" in a:
            fail(3, "%s: sparse accessor %d is not converted by vtk_ddp.py" % (path, index))
        ct, nc, count = a["componentType"], GLTF_NCOMP[a["type"]], a["count"]
        fmt = GLTF_COMP[ct]
        csize = struct.calcsize(fmt)
        bv = doc["bufferViews"][a["bufferView"]]
        data = buffers[bv["buffer"]]
        base = bv.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = bv.get("byteStride") or csize * nc
        st = struct.Struct("<%d%s" % (nc, fmt))
        out = [st.unpack_from(data, base + i * stride) for i in range(count)]
        return out, ct, a.get("normalized", False)

    materials = doc.get("materials", [])
    tris, cols = [], []
    has_colour = has_alpha = False
    scenes = doc.get("scenes", [])
    if "scene" in doc:
        roots = [list(scenes[doc["scene"]]["nodes"])]
    elif scenes:
        roots = [list(sc.get("nodes", [])) for sc in scenes]
    else:
        child = {c for n in doc.get("nodes", []) for c in n.get("children", [])}
        roots = [[i for i in range(len(doc.get("nodes", []))) if i not in child]]
    ident = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]
    for root in roots:
        stack = [(r, ident) for r in reversed(root)]
        while stack:
            node, parent = stack.pop()
            n = doc["nodes"][node]
            world = mat_mul(parent, node_matrix(n))
            if "mesh" in n:
                m = world
                det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + \
                    m[8] * (m[1] * m[6] - m[5] * m[2])
                flip = det < 0.0
                for prim in doc["meshes"][n["mesh"]]["primitives"]:
                    mode = prim.get("mode", 4)
                    if mode not in (4, 5, 6):
                        continue
                    if "KHR_draco_mesh_compression" in prim.get("extensions", {}):
                        fail(3, "%s: Draco-compressed glTF is not converted by vtk_ddp.py" % path)
                    base, amode, cutoff = [1.0, 1.0, 1.0, 1.0], "OPAQUE", 0.5
                    if prim.get("material", -1) >= 0:
                        mat = materials[prim["material"]]
                        base = list(mat.get("pbrMetallicRoughness", {}).get(
                            "baseColorFactor", [1.0, 1.0, 1.0, 1.0]))
                        amode = mat.get("alphaMode", "OPAQUE")
                        cutoff = mat.get("alphaCutoff", 0.5)
                        has_colour = True
                        has_alpha |= amode != "OPAQUE"
                    pos, ct, _ = accessor(prim["attributes"]["POSITION"])
                    if ct != 5126:
                        fail(3, "%s: quantized POSITION is not converted by vtk_ddp.py" % path)
                    vc = None
                    if "COLOR_0" in prim["attributes"]:
                        vc, cct, _ = accessor(prim["attributes"]["COLOR_0"])
                        scale = {5126: 1.0, 5121: 255.0, 5123: 65535.0}[cct]
                        vc = [tuple(x / scale for x in c) + ((1.0,) if len(c) == 3 else ())
                              for c in vc]
                        has_colour = True
                    verts, vcols = [], []
                    for i, p in enumerate(pos):
                        p = [float(struct.unpack("<f", struct.pack("<f", x))[0]) for x in p]
                        q = tuple(m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] +
                                  m[12 + row] for row in range(3))
                        verts.append(q)
                        c = [base[k] * (vc[i][k] if vc else 1.0) for k in range(4)]
                        a = c[3] if amode == "BLEND" else float(c[3] >= cutoff) \
                            if amode == "MASK" else 1.0
                        vcols.append(tuple(srgb_u8(x) for x in c[:3]) + (unit_to_u8(a),))
                    if "indices" in prim:
                        idx = [t[0] for t in accessor(prim["indices"])[0]]
                    else:
                        idx = list(range(len(pos)))
                    nidx = len(idx)
                    ntri = nidx // 3 if mode == 4 else max(nidx - 2, 0)
                    for t in range(ntri):
                        if mode == 4:
                            k = [3 * t, 3 * t + 1, 3 * t + 2]
                        elif mode == 5:
                            k = [t + (t & 1), t + 1 - (t & 1), t + 2]
                        else:
                            k = [0, t + 1, t + 2]
                        if flip:
                            k = [k[0], k[2], k[1]]
                        tri = tuple(verts[idx[j]] for j in k)
                        if all(finite(p) for p in tri):
                            tris.append(tri)
                            cols.append(tuple(vcols[idx[j]] for j in k))
            for c in reversed(n.get("children", [])):
                stack.append((c, world))
    return tris, (cols if has_colour or has_alpha else None), has_alpha


def parse_view(line):
    v = [float(x) for x in line.split(",")]
    if len(v) not in (10, 12):
        raise ValueError("expected ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy[,znear,zfar]")
    return v


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--walk", required=True, help="oitstream walk file (one --view a line)")
    ap.add_argument("--size", default="1024x1024")
    ap.add_argument("--peels", type=int, default=1000,
                    help="SetMaximumNumberOfPeels (default 1000; VTK's default is 4)")
    ap.add_argument("--out", required=True, help="folder: frame_000.png, ... one a walk line")
    ap.add_argument("--stats", help="JSON like oitstream --stats")
    ap.add_argument("--alpha", type=float, default=0.35)
    ap.add_argument("--keep-ply", help="keep the PLY converted from .off/.obj here")
    a = ap.parse_args()

    try:
        w, h = (int(x) for x in a.size.lower().split("x"))
        assert w > 0 and h > 0
    except Exception:
        fail(2, "--size %r: expected WxH" % a.size)
    if a.peels < 0:
        fail(2, "--peels must be >= 0")
    try:
        views = [(l.strip(), parse_view(l.strip())) for l in open(a.walk) if l.strip()]
    except (OSError, ValueError) as e:
        fail(3, "%s: %s" % (a.walk, e))
    if not views:
        fail(3, "%s: no views" % a.walk)
    if not os.path.isfile(a.mesh):
        fail(3, "%s: no such file" % a.mesh)

    import vtkmodules.all as vtk
    vtk.vtkObject.GlobalWarningDisplayOff()

    ext = os.path.splitext(a.mesh)[1].lower()
    conversion = None
    tmpdir = None
    path = a.mesh
    if ext in (".off", ".obj", ".gltf", ".glb"):
        t0 = time.perf_counter()
        tris, cols, alpha = {".off": read_off, ".obj": read_obj}.get(ext, read_gltf)(a.mesh)
        if a.keep_ply:
            path = a.keep_ply
        else:
            tmpdir = tempfile.mkdtemp(prefix="vtk_ddp.")
            path = os.path.join(tmpdir, "mesh.ply")
        write_ply(path, tris, cols, alpha)
        conversion = {"from": ext[1:], "to": "ply", "by": "data_scripts/vtk_ddp.py",
                      "triangles": len(tris), "colour": cols is not None, "alpha": alpha,
                      "seconds": round(time.perf_counter() - t0, 3)}
        ext = ".ply"
    if ext == ".ply":
        reader = vtk.vtkPLYReader()
    elif ext == ".stl":
        reader = vtk.vtkSTLReader()
        reader.MergingOff()
    else:
        fail(3, "%s: unknown mesh format %r" % (a.mesh, ext))
    reader.SetFileName(path)
    reader.Update()
    tri = vtk.vtkTriangleFilter()  # polygons of a PLY fan-triangulated as the readers do
    tri.SetInputConnection(reader.GetOutputPort())
    tri.PassVertsOff()
    tri.PassLinesOff()
    tri.Update()
    poly = vtk.vtkPolyData()
    poly.DeepCopy(tri.GetOutput())
    if tmpdir:
        os.remove(path)
        os.rmdir(tmpdir)
    ntris = poly.GetNumberOfPolys()
    if ntris == 0:
        fail(3, "%s: no triangles read" % a.mesh)
    pd = poly.GetPointData()
    pd.SetNormals(None)  # flat shading from the face, as oitstream's
    pd.SetTCoords(None)
    scal = pd.GetScalars()
    if scal is None:
        for name in ("RGBA", "RGB"):
            if pd.GetArray(name) is not None:
                pd.SetActiveScalars(name)
                scal = pd.GetScalars()
                break
    has_colour = scal is not None and scal.GetDataType() == vtk.VTK_UNSIGNED_CHAR \
        and scal.GetNumberOfComponents() in (3, 4)
    has_alpha = has_colour and scal.GetNumberOfComponents() == 4
    if scal is not None and not has_colour:
        fail(3, "%s: point scalars that are not 8-bit RGB(A) colours" % a.mesh)
    if poly.GetCellData().GetScalars() is not None:
        fail(3, "%s: face colours are not rendered by vtk_ddp.py" % a.mesh)

    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(poly)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetInterpolationToFlat()
    prop.LightingOn()
    prop.SetAmbient(0.3)
    prop.SetDiffuse(0.7)
    prop.SetSpecular(0.0)
    prop.BackfaceCullingOff()
    prop.FrontfaceCullingOff()
    if has_colour:
        mapper.ScalarVisibilityOn()
        mapper.SetColorModeToDirectScalars()
        mapper.SetScalarModeToUsePointData()
        prop.SetColor(1.0, 1.0, 1.0)
        prop.SetOpacity(1.0 if has_alpha else a.alpha)
    else:
        mapper.ScalarVisibilityOff()
        prop.SetColor(*DEFAULT_RGB)  # ambient and diffuse colour
        prop.SetOpacity(a.alpha)
    actor.ForceTranslucentOn()

    ren = vtk.vtkRenderer()
    ren.SetBackground(1.0, 1.0, 1.0)
    ren.AddActor(actor)
    ren.AutomaticLightCreationOff()
    ren.RemoveAllLights()
    ren.TwoSidedLightingOn()
    light = vtk.vtkLight()
    light.SetLightTypeToSceneLight()
    light.PositionalOn()
    light.SetConeAngle(180.0)
    light.SetAttenuationValues(1.0, 0.0, 0.0)
    light.SetColor(1.0, 1.0, 1.0)
    light.SetIntensity(1.0)
    ren.AddLight(light)

    steps = vtk.vtkRenderStepsPass()
    ddp = vtk.vtkDualDepthPeelingPass()
    ddp.SetTranslucentPass(steps.GetTranslucentPass())
    ddp.SetMaximumNumberOfPeels(a.peels)
    ddp.SetOcclusionRatio(0.0)
    steps.SetTranslucentPass(ddp)
    ren.SetPass(steps)

    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    win.SetAlphaBitPlanes(1)
    win.SetSize(w, h)
    win.AddRenderer(ren)

    cam = ren.GetActiveCamera()
    cam.ParallelProjectionOff()
    cam.UseHorizontalViewAngleOff()
    os.makedirs(a.out, exist_ok=True)
    frames = []
    renderer_name = None
    for i, (text, v) in enumerate(views):
        cam.SetPosition(v[0], v[1], v[2])
        cam.SetFocalPoint(v[3], v[4], v[5])
        cam.SetViewUp(v[6], v[7], v[8])
        cam.SetViewAngle(v[9])
        if len(v) == 12:
            cam.SetClippingRange(v[10], v[11])
        else:
            ren.ResetCameraClippingRange()
        light.SetPosition(v[0], v[1], v[2])
        light.SetFocalPoint(v[3], v[4], v[5])
        t0 = time.perf_counter()
        win.Render()
        win.WaitForCompletion()
        ms = (time.perf_counter() - t0) * 1000.0
        if len(v) == 12:
            near, far = cam.GetClippingRange()
            if abs(near - v[10]) > 1e-6 * v[11] or abs(far - v[11]) > 1e-6 * v[11]:
                fail(1, "view %d: VTK changed the clipping range to %g,%g" % (i, near, far))
        if renderer_name is None:
            caps = win.ReportCapabilities() or ""
            for line in caps.splitlines():
                if "renderer string" in line:
                    renderer_name = line.split(":", 1)[1].strip()
            if not win.SupportsOpenGL():
                fail(1, "no OpenGL context")
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(win)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.ShouldRerenderOff()
        grab.Update()
        png = vtk.vtkPNGWriter()
        name = os.path.join(a.out, "frame_%03d.png" % i)
        png.SetFileName(name)
        png.SetInputConnection(grab.GetOutputPort())
        png.Write()
        if not os.path.isfile(name) or os.path.getsize(name) == 0:
            fail(1, "%s: not written" % name)
        frames.append({"method": "vtk-ddp", "view": text, "ms": round(ms, 3)})
        print("vtk_ddp: view %d: %.1f ms" % (i, ms), file=sys.stderr)

    if a.stats:
        stats = {"model": a.mesh, "triangles": ntris, "renderer": renderer_name or "?",
                 "vtk": vtk.vtkVersion.GetVTKVersion(), "width": w, "height": h,
                 "peels": a.peels, "occlusion_ratio": 0.0, "multisamples": 0,
                 "pass": "vtkDualDepthPeelingPass", "colour": has_colour,
                 "alpha": a.alpha if not has_alpha else "per vertex",
                 "conversion": conversion, "differences": DIFFERENCES, "frames": frames}
        with open(a.stats, "w") as f:
            json.dump(stats, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
