// STEP and IGES through Open CASCADE (formats/step_adapter.cpp), checked
// against Open CASCADE itself read another way: each file is also read with
// the plain (non-XDE) STEPControl_Reader / IGESControl_Reader, meshed with
// BRepMesh_IncrementalMesh at the deflection our reader reports and the
// same angular deflection, and its faces' Poly_Triangulation counts summed
// over every placed face. Counts must be equal at the default deflection
// and at a coarser one (which must give fewer triangles, so the setting
// reaches the mesher).
//
// tests/corpus/step (data_scripts/occt_samples.cpp) adds what the plain
// reader cannot see: per-face and per-shape colours with alpha, the
// instance placement, winding (the signed volume of closed solids), and
// the from-memory entry; then bad input. Further files given as arguments
// (Debian's occt-misc samples) get the count check.
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "formats/step_internal.h"
#include "oit/mesh.h"
#include "tests/lib/test_check.h"

namespace {

struct Got {
    std::vector<oit_triangle> tris;
    oit_mesh_info info;
    oit_status status;
    std::string message;
};

oit_status keep(void *user, const oit_triangle *t, size_t n, oit_error *)
{
    static_cast<Got *>(user)->tris.insert(static_cast<Got *>(user)->tris.end(), t, t + n);
    return OIT_OK;
}

Got read(const std::string &path, double deflection = 0.0, size_t chunk = 0)
{
    Got g;
    oit_read_desc desc{};
    desc.deflection = deflection;
    desc.chunk_triangles = chunk;
    oit_error err{};
    g.status = oit_mesh_read(path.c_str(), &desc, keep, &g, &g.info, &err);
    g.message = g.status ? err.message : "";
    return g;
}

bool is_iges(const std::string &p)
{
    std::string e = p.substr(p.find_last_of('.') + 1);
    return e == "igs" || e == "iges" || e == "IGS" || e == "IGES";
}

// Open CASCADE's own count: the shape read without XDE, meshed alike.
long long occt_count(const std::string &path, double deflection)
{
    TopoDS_Shape shape;
    if (is_iges(path)) {
        IGESControl_Controller::Init();
        IGESControl_Reader r;
        if (r.ReadFile(path.c_str()) != IFSelect_RetDone)
            return -1;
        r.TransferRoots();
        shape = r.OneShape();
    } else {
        STEPControl_Reader r;
        if (r.ReadFile(path.c_str()) != IFSelect_RetDone)
            return -1;
        r.TransferRoots();
        shape = r.OneShape();
    }
    BRepMesh_IncrementalMesh(shape, deflection, false, 0.5, false);
    long long n = 0;
    for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
        TopLoc_Location loc;
        Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(TopoDS::Face(e.Current()), loc);
        if (!t.IsNull())
            n += t->NbTriangles();
    }
    return n;
}

void check_counts(const std::string &path)
{
    Got g = read(path);
    CHECK(g.status == OIT_OK, "%s: %s", path.c_str(), g.message.c_str());
    if (g.status)
        return;
    double d = g.info.deflection;
    CHECK(d > 0.0, "%s: no deflection reported", path.c_str());
    long long delivered = (long long)(g.info.triangles + g.info.nonfinite_dropped);
    long long want = occt_count(path, d);
    CHECK(delivered == want, "%s: %lld triangles at deflection %g, Open CASCADE's own %lld",
          path.c_str(), delivered, d, want);
    CHECK(g.tris.size() == g.info.triangles, "%s: %zu delivered, info says %llu", path.c_str(),
          g.tris.size(), (unsigned long long)g.info.triangles);
    // The diagonal of the bounds the reader delivered: the default is a
    // thousandth of the model's (Open CASCADE's box may be a little larger).
    double diag2 = 0;
    for (int k = 0; k < 3; k++)
        diag2 += std::pow(double(g.info.bounds_max[k]) - g.info.bounds_min[k], 2);
    CHECK(d >= OIT_DEFAULT_DEFLECTION * std::sqrt(diag2) * 0.999 &&
              d <= OIT_DEFAULT_DEFLECTION * std::sqrt(diag2) * 1.2,
          "%s: default deflection %g, diagonal %g", path.c_str(), d, std::sqrt(diag2));
    Got coarse = read(path, 8 * d);
    long long coarse_n = (long long)(coarse.info.triangles + coarse.info.nonfinite_dropped);
    CHECK(coarse.status == OIT_OK && coarse.info.deflection == 8 * d, "%s: deflection %g: %s",
          path.c_str(), 8 * d, coarse.message.c_str());
    CHECK(coarse_n == occt_count(path, 8 * d), "%s: %lld triangles at deflection %g, Open "
          "CASCADE's own %lld", path.c_str(), coarse_n, 8 * d, occt_count(path, 8 * d));
    printf("%s: %lld triangles at deflection %g (Open CASCADE %lld), %lld at %g\n",
           path.c_str(), delivered, d, want, coarse_n, 8 * d);
}

bool rgba_is(const oit_triangle &t, int r, int g, int b, int a)
{
    for (const oit_vertex &v : t.v)
        if (v.rgba[0] != r || v.rgba[1] != g || v.rgba[2] != b || v.rgba[3] != a)
            return false;
    return true;
}

// Six times the signed volume a closed, outward-wound surface encloses.
double volume(const std::vector<oit_triangle> &tris)
{
    double v = 0;
    for (const oit_triangle &t : tris) {
        const float *a = t.v[0].pos, *b = t.v[1].pos, *c = t.v[2].pos;
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6.0;
}

// parts.step / parts.igs: the plate (grey-blue, its top face yellow) and
// the glass (red; alpha 0.4 in STEP, IGES has no transparency) moved by
// (20,15,4).
void check_parts(const std::string &path, bool transparent)
{
    Got g = read(path);
    CHECK(g.status == OIT_OK, "%s: %s", path.c_str(), g.message.c_str());
    int glass_a = transparent ? 102 : 255; // 0.4 of 255
    size_t plate = 0, top = 0, glass = 0, other = 0, caps_white = 0;
    std::vector<oit_triangle> glass_tris;
    for (const oit_triangle &t : g.tris) {
        if (rgba_is(t, 102, 128, 179, 255))
            plate++;
        else if (rgba_is(t, 255, 255, 0, 255)) {
            top++;
            for (const oit_vertex &v : t.v)
                CHECK(v.pos[2] == 4.0f, "%s: a yellow vertex at z %g, off the top face",
                      path.c_str(), v.pos[2]);
        } else if (rgba_is(t, 255, 0, 0, glass_a) || (!transparent && rgba_is(t, 255, 255, 255, 255))) {
            // Open CASCADE's IGES round trip keeps the glass's colour on its
            // caps only: its side (a surface of revolution in IGES) comes
            // back without one (white)
            if (t.v[0].rgba[1] == 255)
                caps_white++;
            glass++;
            glass_tris.push_back(t);
            for (const oit_vertex &v : t.v)
                CHECK(std::fabs(std::hypot(v.pos[0] - 20.0, v.pos[1] - 15.0)) <= 8.0 + 1e-3 &&
                          v.pos[2] >= 4.0f - 1e-4f && v.pos[2] <= 24.0f + 1e-4f,
                      "%s: a glass vertex (%g %g %g) outside the placed cylinder", path.c_str(),
                      v.pos[0], v.pos[1], v.pos[2]);
        } else
            other++;
    }
    CHECK(plate == 10 && top == 2, "%s: plate %zu triangles (want 10), top face %zu (want 2)",
          path.c_str(), plate, top);
    CHECK(glass > caps_white && other == 0, "%s: %zu glass triangles (%zu white), %zu of no "
          "expected colour", path.c_str(), glass, caps_white, other);
    unsigned want = OIT_ATTR_COLOUR | (transparent ? OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE : 0u);
    CHECK(g.info.attributes == want, "%s: attributes %#x, want %#x", path.c_str(),
          g.info.attributes, want);
    // Winding: the glass, a closed cylinder, encloses up to pi*64*20 outward.
    double vg = volume(glass_tris), cyl = M_PI * 64 * 20;
    CHECK(vg > 0.97 * cyl && vg <= cyl * 1.0001, "%s: glass volume %g, want just under %g",
          path.c_str(), vg, cyl);
    double all = volume(g.tris);
    CHECK(all > 4800 + 0.97 * cyl && all <= 4800 + cyl * 1.0001,
          "%s: volume %g, want the plate's 4800 plus the glass's", path.c_str(), all);
}

void check_plain_box(const std::string &dir)
{
    Got g = read(dir + "/box.step");
    CHECK(g.status == OIT_OK && g.tris.size() == 12, "box.step: %zu triangles (want 12): %s",
          g.tris.size(), g.message.c_str());
    CHECK(g.info.attributes == 0, "box.step: attributes %#x without any colour",
          g.info.attributes);
    CHECK(std::fabs(volume(g.tris) - 6000.0) < 1e-3, "box.step: volume %g, want 6000",
          volume(g.tris));
    Got chunked = read(dir + "/box.step", 0.0, 5);
    CHECK(chunked.tris.size() == 12 &&
              std::memcmp(chunked.tris.data(), g.tris.data(), 12 * sizeof(oit_triangle)) == 0,
          "box.step in chunks of 5: %zu triangles, or others", chunked.tris.size());
}

std::string slurp(const std::string &path)
{
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void check_memory_and_bad(const std::string &dir)
{
    std::string bytes = slurp(dir + "/parts.step");
    Got file = read(dir + "/parts.step");
    Got mem;
    oit_error err{};
    mem.status = oit_read_step_memory(reinterpret_cast<const unsigned char *>(bytes.data()),
                                      bytes.size(), "mem.step", nullptr, keep, &mem, &mem.info,
                                      &err);
    CHECK(mem.status == OIT_OK && mem.tris.size() == file.tris.size() &&
              std::memcmp(mem.tris.data(), file.tris.data(),
                          file.tris.size() * sizeof(oit_triangle)) == 0,
          "parts.step from memory: %zu triangles, from the file %zu (%s)", mem.tris.size(),
          file.tris.size(), mem.status ? err.message : "");
    // Cut mid-DATA: a format error naming the input, nothing delivered.
    Got cut;
    std::string half = bytes.substr(0, bytes.size() / 2);
    cut.status = oit_read_step_memory(reinterpret_cast<const unsigned char *>(half.data()),
                                      half.size(), "cut.step", nullptr, keep, &cut, &cut.info,
                                      &err);
    CHECK(cut.status == OIT_ERR_FORMAT && std::strstr(err.message, "cut.step") && cut.tris.empty(),
          "truncated STEP: status %d, %zu triangles, '%s'", cut.status, cut.tris.size(),
          err.message);
    Got junk;
    const char noise[] = "\x7f\x45\x4c\x46 no STEP at all \x01\x02";
    junk.status = oit_read_step_memory(reinterpret_cast<const unsigned char *>(noise),
                                       sizeof noise - 1, "junk.step", nullptr, keep, &junk,
                                       &junk.info, &err);
    CHECK(junk.status == OIT_ERR_FORMAT && std::strstr(err.message, "junk.step"),
          "junk STEP: status %d, '%s'", junk.status, err.message);
    for (double bad : {-1.0, double(NAN), double(INFINITY)}) {
        Got b = read(dir + "/box.step", bad);
        CHECK(b.status == OIT_ERR_ARGUMENT && b.message.find("box.step") != std::string::npos &&
                  b.message.find("deflection") != std::string::npos,
              "deflection %g: status %d, '%s'", bad, b.status, b.message.c_str());
    }
    // A file that crashes Open CASCADE 7.6 inside its translation (found by
    // fuzz_step): the read runs in a child (read_isolated.h), so the crash is
    // a format error naming the input and the signal, not this process's.
    Got crash = read(dir + "/crashes_occt.step");
    CHECK(crash.status == OIT_ERR_FORMAT &&
              crash.message.find("crashes_occt.step: Open CASCADE crashed reading it") !=
                  std::string::npos &&
              crash.tris.empty(),
          "crashing STEP: status %d, %zu triangles, '%s'", crash.status, crash.tris.size(),
          crash.message.c_str());
    Got missing = read(dir + "/no_such.stp");
    CHECK(missing.status == OIT_ERR_IO && missing.message.find("no_such.stp") != std::string::npos,
          "missing file: status %d, '%s'", missing.status, missing.message.c_str());
}

} // namespace

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_step CORPUS_DIR [MORE.step|.iges ...]\n");
        return 2;
    }
    Message::DefaultMessenger()->ChangePrinters().Clear(); // Open CASCADE's chatter on stdout
    std::string dir = argv[1];
    check_parts(dir + "/parts.step", true);
    check_parts(dir + "/parts.igs", false);
    check_plain_box(dir);
    check_memory_and_bad(dir);
    for (const char *f : {"parts.step", "parts.igs", "box.step"})
        check_counts(dir + "/" + f);
    for (int i = 2; i < argc; i++)
        check_counts(argv[i]);
    return test_verdict();
}
