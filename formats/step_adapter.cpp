// STEP and IGES reader through Open CASCADE's XDE, behind the C interface
// of oit/mesh.h (step_internal.h).
//
// The file is read into an XCAF document (shapes, assembly structure,
// names, colours, visual materials); every free shape is tessellated with
// BRepMesh_IncrementalMesh at the deflection the caller set (0: 0.1% of
// the model's bounding-box diagonal) and an angular deflection of 0.5 rad
// (Open CASCADE's default), sequentially so that two reads of one file
// yield the same triangles. The assembly is then walked leaf by leaf
// (XCAFPrs_DocumentExplorer composes the locations down the tree and
// inherits styles), and each face's triangulation is emitted with its
// instance's placement, in its orientation (reversed or mirrored faces flip
// winding) and with its colour: the face's own, else its shape's, else the
// nearest assembly's (RWMesh_FaceIterator), a visual material's base colour
// standing in where no colour is set. Colours are converted from Open
// CASCADE's linear RGB to sRGB bytes; alpha is 1 - transparency.
//
// Memory: Open CASCADE holds the whole model and its triangulation, which
// desc->memory_budget cannot bound; the file and the output chunk are
// charged against it. Names and the assembly's structure are not kept
// (oit_mesh has no groups).

#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <Bnd_Box.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESControl_Controller.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Poly_Triangle.hxx>
#include <Quantity_ColorRGBA.hxx>
#include <RWMesh_FaceIterator.hxx>
#include <STEPCAFControl_Controller.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XCAFDoc_VisMaterial.hxx>
#include <XCAFPrs_DocumentExplorer.hxx>

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>
#include <sstream>
#include <string>

#include "formats/adapter_ctx.h"
#include "formats/read_isolated.h"
#include "formats/step_internal.h"

namespace {

using namespace oit_adapter;

constexpr double kAngularDeflection = 0.5; // radians: BRepMesh's default

struct Ctx : Output {
    const char *format; // "STEP" or "IGES", for messages
    double deflection;  // as asked: 0 for the default
    bool any_alpha;   // some face colour is transparent
    bool any_colour;  // some face has a colour
    uint64_t untessellated; // faces BRepMesh gave no triangulation
};

// Open CASCADE reports through its default messenger, to stdout: a tool's
// stdout may be its data (oitprep's statistics), so the reports are dropped. The
// messenger is Open CASCADE's own global, which only this adapter uses.
void quiet_open_cascade()
{
    const Handle(Message_Messenger) &m = Message::DefaultMessenger();
    if (!m.IsNull())
        m->ChangePrinters().Clear();
}

// ---------------------------------------------------------------- output

uint8_t to_byte(double v)
{
    if (!(v > 0.0))
        return 0;
    return v >= 1.0 ? 255 : uint8_t(std::lround(v * 255.0));
}

// The face's colour as sRGB bytes and alpha; white when it has none.
void face_rgba(Ctx &c, const RWMesh_FaceIterator &f, uint8_t rgba[4])
{
    Quantity_ColorRGBA col;
    bool has = f.HasFaceColor();
    if (has)
        col = f.FaceColor();
    else if (!f.FaceStyle().Material().IsNull()) {
        col = f.FaceStyle().Material()->BaseColor();
        has = true;
    }
    if (!has) {
        std::memset(rgba, 255, 4);
        return;
    }
    double r, g, b;
    col.GetRGB().Values(r, g, b, Quantity_TOC_sRGB);
    rgba[0] = to_byte(r);
    rgba[1] = to_byte(g);
    rgba[2] = to_byte(b);
    rgba[3] = to_byte(col.Alpha());
    c.any_colour = true;
    c.any_alpha = c.any_alpha || rgba[3] < 255;
}

void vertex(Ctx &c, const RWMesh_FaceIterator &f, int node, const uint8_t rgba[4], oit_vertex *v)
{
    gp_Pnt p = f.NodeTransformed(node);
    double in[3] = {p.X(), p.Y(), p.Z()};
    place(c, in, v->pos);
    std::memcpy(v->rgba, rgba, 4);
}

oit_status emit_face(Ctx &c, const RWMesh_FaceIterator &f)
{
    uint8_t rgba[4];
    face_rgba(c, f, rgba);
    c.info->vertices_in += uint64_t(f.NbNodes());
    const int lo = f.NodeLower(), hi = f.NodeUpper();
    for (int i = f.ElemLower(); i <= f.ElemUpper(); i++) {
        int n[3];
        f.TriangleOriented(i).Get(n[0], n[1], n[2]);
        oit_triangle t;
        bool ok = true;
        for (int k = 0; k < 3; k++) {
            ok = ok && n[k] >= lo && n[k] <= hi;
            if (ok)
                vertex(c, f, n[k], rgba, &t.v[k]);
        }
        if (!ok)
            return fail(c, OIT_ERR_FORMAT, "a triangle of the tessellation names node %d, "
                        "outside the face's %d..%d", n[0], lo, hi);
        c.info->faces_in++;
        oit_status s = emit(c, t);
        if (s != OIT_OK)
            return s;
    }
    return OIT_OK;
}

// Every leaf of the assembly, each instance placed, every face of it.
oit_status walk(Ctx &c, const Handle(TDocStd_Document) &doc)
{
    for (XCAFPrs_DocumentExplorer ex(doc, XCAFPrs_DocumentExplorerFlags_OnlyLeafNodes); ex.More();
         ex.Next()) {
        const XCAFPrs_DocumentNode &node = ex.Current();
        uint64_t faces = 0, meshed = 0;
        TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(node.RefLabel);
        for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next())
            faces++;
        for (RWMesh_FaceIterator f(node.RefLabel, node.Location, true, node.Style); f.More();
             f.Next()) {
            meshed++;
            if (f.IsEmptyMesh())
                continue;
            oit_status s = emit_face(c, f);
            if (s != OIT_OK)
                return s;
        }
        c.untessellated += faces > meshed ? faces - meshed : 0;
    }
    return OIT_OK;
}

// ------------------------------------------------------------ reading

oit_status check_file(Ctx &c, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return fail(c, OIT_ERR_IO, "cannot open: %s", std::strerror(errno));
    if (!S_ISREG(st.st_mode))
        return fail(c, OIT_ERR_IO, "not a regular file");
    FILE *f = std::fopen(path, "rb");
    if (!f)
        return fail(c, OIT_ERR_IO, "cannot open: %s", std::strerror(errno));
    unsigned char magic[2] = {0, 0};
    size_t got = std::fread(magic, 1, 2, f);
    std::fclose(f);
    if (got == 2 && magic[0] == 0x1f && magic[1] == 0x8b)
        return fail(c, OIT_ERR_UNSUPPORTED, "a gzip-compressed %s file: Open CASCADE reads "
                    "plain files only (gunzip it first)", c.format);
    return charge(c, size_t(st.st_size), "the file");
}

const char *status_words(IFSelect_ReturnStatus s)
{
    switch (s) {
    case IFSelect_RetVoid: return "nothing was read";
    case IFSelect_RetError: return "it could not be opened or parsed";
    case IFSelect_RetFail: return "its data are not valid";
    case IFSelect_RetStop: return "reading was stopped";
    default: return "unknown status";
    }
}

oit_status read_status(Ctx &c, IFSelect_ReturnStatus s)
{
    if (s == IFSelect_RetDone)
        return OIT_OK;
    return fail(c, OIT_ERR_FORMAT, "not a readable %s file: %s (Open CASCADE's status %d)",
                c.format, status_words(s), int(s));
}

// Reads into doc: STEP from the path or, with `in`, from that stream; IGES
// from the path.
oit_status load(Ctx &c, oit_occt_format format, const char *path, std::istream *in,
                Handle(TDocStd_Document) &doc)
{
    if (format == OIT_OCCT_STEP) {
        STEPCAFControl_Controller::Init();
        STEPCAFControl_Reader r;
        r.SetColorMode(true);
        r.SetNameMode(true);
        r.SetLayerMode(false);
        oit_status s = read_status(c, in ? r.ChangeReader().ReadStream(c.name, *in) : r.ReadFile(path));
        if (s == OIT_OK && !r.Transfer(doc))
            s = fail(c, OIT_ERR_FORMAT, "holds nothing Open CASCADE could translate into a "
                     "shape (no geometry?)");
        return s;
    }
    IGESControl_Controller::Init();
    IGESCAFControl_Reader r;
    r.SetColorMode(true);
    r.SetNameMode(true);
    r.SetLayerMode(false);
    oit_status s = read_status(c, r.ReadFile(path));
    if (s == OIT_OK && !r.Transfer(doc))
        s = fail(c, OIT_ERR_FORMAT, "holds nothing Open CASCADE could translate into a "
                 "shape (no geometry?)");
    return s;
}

// The deflection to tessellate with, and every free shape tessellated.
oit_status tessellate(Ctx &c, const Handle(TDocStd_Document) &doc)
{
    Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    TDF_LabelSequence free_shapes;
    tool->GetFreeShapes(free_shapes);
    Bnd_Box box;
    for (const TDF_Label &l : free_shapes)
        BRepBndLib::AddOptimal(XCAFDoc_ShapeTool::GetShape(l), box, false, false);
    if (box.IsVoid())
        return fail(c, OIT_ERR_FORMAT, "holds no geometry (no shape with a bounded extent)");
    if (box.IsOpenXmin() || box.IsOpenXmax() || box.IsOpenYmin() || box.IsOpenYmax() ||
        box.IsOpenZmin() || box.IsOpenZmax())
        return fail(c, OIT_ERR_FORMAT, "holds an unbounded shape, which cannot be tessellated");
    double diagonal = std::sqrt(box.SquareExtent());
    double d = c.deflection > 0.0 ? c.deflection : OIT_DEFAULT_DEFLECTION * diagonal;
    if (!(d > 0.0) || !std::isfinite(d))
        return fail(c, OIT_ERR_FORMAT, "its shapes have no extent (bounding-box diagonal %g): "
                    "nothing to tessellate", diagonal);
    c.info->deflection = d;
    for (const TDF_Label &l : free_shapes) {
        BRepMesh_IncrementalMesh mesher(XCAFDoc_ShapeTool::GetShape(l), d, false,
                                        kAngularDeflection, false);
        if (!mesher.IsDone())
            return fail(c, OIT_ERR_FORMAT, "Open CASCADE could not tessellate it at deflection %g",
                        d);
    }
    return OIT_OK;
}

oit_status read_doc(Ctx &c, oit_occt_format format, const char *path, std::istream *in)
{
    quiet_open_cascade();
    Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
    Handle(TDocStd_Document) doc;
    app->NewDocument("MDTV-XCAF", doc);
    oit_status s = load(c, format, path, in, doc);
    if (s == OIT_OK)
        s = tessellate(c, doc);
    if (s == OIT_OK && (s = reserve_chunk(c)) == OIT_OK)
        s = walk(c, doc);
    if (s == OIT_OK)
        s = flush(c);
    app->Close(doc);
    if (c.any_colour)
        c.info->attributes |= OIT_ATTR_COLOUR;
    if (c.any_alpha)
        c.info->attributes |= OIT_ATTR_ALPHA;
    if (s == OIT_OK && c.untessellated)
        std::fprintf(stderr, "%s: note: %llu faces could not be tessellated and are left out\n",
                     c.name, (unsigned long long)c.untessellated);
    oit_mesh_info_opaque(c.info, nullptr, 0);
    return s;
}

// Exceptions stop at the C boundary; Open CASCADE's carry their own words.
template <class F> oit_status guarded(Ctx &c, F fn)
{
    try {
        return fn();
    } catch (const std::bad_alloc &) {
        return fail(c, OIT_ERR_NOMEM, "out of memory");
    } catch (const Standard_Failure &e) {
        return fail(c, OIT_ERR_FORMAT, "Open CASCADE failed: %s (%s)",
                    e.GetMessageString() && *e.GetMessageString() ? e.GetMessageString()
                                                                  : "no message",
                    e.DynamicType()->Name());
    } catch (const std::exception &e) {
        return fail(c, OIT_ERR_FORMAT, "%s", e.what());
    } catch (...) {
        return fail(c, OIT_ERR_FORMAT, "unexpected failure while reading");
    }
}

oit_status make_ctx(Ctx &c, const char *name, oit_occt_format format, const oit_read_desc *desc,
                    oit_triangle_sink sink, void *user, oit_mesh_info *info, oit_error *err)
{
    start(c, name, desc, sink, user, info, err);
    c.format = format == OIT_OCCT_STEP ? "STEP" : "IGES";
    c.deflection = desc ? desc->deflection : 0.0;
    if (!(c.deflection >= 0.0) || !std::isfinite(c.deflection))
        return fail(c, OIT_ERR_ARGUMENT, "deflection %g: expected a finite number >= 0 "
                    "(0: the default, %g of the bounding-box diagonal)", c.deflection,
                    OIT_DEFAULT_DEFLECTION);
    if (format != OIT_OCCT_STEP && format != OIT_OCCT_IGES)
        return fail(c, OIT_ERR_ARGUMENT, "unknown Open CASCADE format %d", int(format));
    return OIT_OK;
}

// Open CASCADE 7.6 crashes on some malformed STEP files (fuzz_step finds a
// null dereference in StepToTopoDS_TranslateVertex within seconds): the
// translation runs in a child process (read_isolated.h), the context's
// sink, info and error the child's for the read.
struct Job {
    Ctx *c;
    oit_occt_format format;
    const char *path;            // a file, or
    const unsigned char *bytes;  // STEP text in memory
    size_t size;
};

oit_status run_job(void *a, oit_triangle_sink sink, void *sink_user, oit_mesh_info *info,
                   oit_error *err)
{
    Job &j = *static_cast<Job *>(a);
    Ctx &c = *j.c;
    redirect(c, sink, sink_user, info, err);
    oit_status s = guarded(c, [&] {
        if (j.path)
            return read_doc(c, j.format, j.path, nullptr);
        oit_status r = charge(c, j.size, "the bytes");
        if (r != OIT_OK)
            return r;
        std::istringstream in(std::string(reinterpret_cast<const char *>(j.bytes), j.size));
        return read_doc(c, OIT_OCCT_STEP, nullptr, &in);
    });
    return s == OIT_OK ? oit_rd_require_triangles(c.name, c.info, c.err) : s;
}

oit_status isolated(Ctx &c, Job &j)
{
    return oit_read_isolated(c.name, "Open CASCADE", c.chunk_cap, run_job, &j, c.sink, c.user,
                             c.info, c.err);
}

} // namespace

extern "C" oit_status oit_occt_read_file(const char *path, oit_occt_format format,
                                         const oit_read_desc *desc, oit_triangle_sink sink,
                                         void *user, oit_mesh_info *info, oit_error *err)
{
    oit_mesh_info local;
    Ctx c{};
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_%s: no path given",
                             format == OIT_OCCT_IGES ? "iges" : "step");
    oit_status s = make_ctx(c, path, format, desc, sink, user, info ? info : &local, err);
    if (s == OIT_OK)
        s = guarded(c, [&] { return check_file(c, path); });
    if (s != OIT_OK)
        return s;
    Job j{&c, format, path, nullptr, 0};
    return isolated(c, j);
}

extern "C" oit_status oit_read_step_memory(const unsigned char *bytes, size_t size,
                                           const char *name, const oit_read_desc *desc,
                                           oit_triangle_sink sink, void *user,
                                           oit_mesh_info *info, oit_error *err)
{
    oit_mesh_info local;
    Ctx c{};
    oit_status s = make_ctx(c, name, OIT_OCCT_STEP, desc, sink, user, info ? info : &local, err);
    if (s != OIT_OK)
        return s;
    Job j{&c, OIT_OCCT_STEP, nullptr, bytes, size};
    return isolated(c, j);
}
