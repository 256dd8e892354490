// Every mesh format assimp imports (FBX, Collada, 3DS, 3MF, IFC, ...) behind
// the C interface of oit/mesh.h (assimp_internal.h says who calls it).
//
// assimp parses and triangulates (aiProcess_Triangulate, its ear clipping
// for concave polygons) and validates its scene (aiProcess_ValidateDataStructure);
// this file walks the node tree, composes each node's transform in double,
// resolves every triangle to world-space vertices with colours and hands
// them to the sink in chunks. Indices are checked again here: a scene is
// trusted no more than a file.
//
// Colours, straight 8-bit as the other readers give them (oit/mesh.h): rgb
// is the material's diffuse colour, or the mesh's first vertex-colour set
// where it has one; alpha is the material's opacity (AI_MATKEY_OPACITY, or
// 1 - AI_MATKEY_TRANSPARENCYFACTOR where only that is set), times the vertex
// colour's alpha. A material assimp made up (AI_DEFAULT_MATERIAL_NAME: the
// file had none) gives no colour, so the renderer's default applies.

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "formats/adapter_ctx.h"
#include "formats/assimp_internal.h"
#include "formats/read_isolated.h"
#include "oit/mesh.h"

namespace {

using namespace oit_adapter;

constexpr unsigned kImportFlags = aiProcess_Triangulate | aiProcess_ValidateDataStructure;

struct Ctx : Output {
    uint64_t skipped; // point and line primitives
};

// ---------------------------------------------------------------- colours

struct Shade {
    double rgb[3] = {1, 1, 1};
    double alpha = 1;
    bool colour = false, has_alpha = false;
};

Shade material_shade(const aiMaterial *m)
{
    Shade sh;
    aiString name;
    if (!m || (m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS &&
               std::strcmp(name.C_Str(), AI_DEFAULT_MATERIAL_NAME) == 0))
        return sh;
    aiColor4D d;
    if (m->Get(AI_MATKEY_COLOR_DIFFUSE, d) == AI_SUCCESS) {
        sh.rgb[0] = d.r, sh.rgb[1] = d.g, sh.rgb[2] = d.b;
        sh.colour = true;
    }
    float f;
    if (m->Get(AI_MATKEY_OPACITY, f) == AI_SUCCESS) {
        sh.alpha = f;
        sh.has_alpha = true;
    } else if (m->Get(AI_MATKEY_TRANSPARENCYFACTOR, f) == AI_SUCCESS) {
        sh.alpha = 1.0 - double(f);
        sh.has_alpha = true;
    }
    return sh;
}

// --------------------------------------------------------------- emitting

struct Mat4 {
    double m[4][4]; // row-major, as aiMatrix4x4: p' = M p for column vectors

    static Mat4 from(const aiMatrix4x4 &a)
    {
        const ai_real *r[4] = {&a.a1, &a.b1, &a.c1, &a.d1};
        Mat4 o;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                o.m[i][j] = double(r[i][j]);
        return o;
    }
    Mat4 operator*(const Mat4 &b) const
    {
        Mat4 o;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                double s = 0;
                for (int k = 0; k < 4; k++)
                    s += m[i][k] * b.m[k][j];
                o.m[i][j] = s;
            }
        return o;
    }
    void apply(const aiVector3D &v, double out[3]) const
    {
        double in[3] = {double(v.x), double(v.y), double(v.z)}, w = m[3][3];
        for (int i = 0; i < 3; i++)
            w += m[3][i] * in[i];
        for (int i = 0; i < 3; i++) {
            double s = m[i][3];
            for (int k = 0; k < 3; k++)
                s += m[i][k] * in[k];
            out[i] = w == 1.0 ? s : s / w;
        }
    }
};

void vertex(Ctx &c, const aiMesh *mesh, const Shade &sh, const Mat4 &world, unsigned i, oit_vertex *out)
{
    double p[3];
    world.apply(mesh->mVertices[i], p);
    place(c, p, out->pos);
    double rgb[3] = {sh.rgb[0], sh.rgb[1], sh.rgb[2]}, a = sh.alpha;
    if (mesh->mColors[0]) {
        const aiColor4D &vc = mesh->mColors[0][i];
        rgb[0] = vc.r, rgb[1] = vc.g, rgb[2] = vc.b;
        a *= vc.a;
    }
    for (int k = 0; k < 3; k++)
        out->rgba[k] = unit_u8(rgb[k]);
    out->rgba[3] = unit_u8(a);
}

oit_status emit_mesh(Ctx &c, const aiScene *scene, unsigned index, const Mat4 &world)
{
    if (index >= scene->mNumMeshes || !scene->mMeshes[index])
        return fail(c, OIT_ERR_FORMAT, "a node refers to mesh %u of %u", index, scene->mNumMeshes);
    const aiMesh *mesh = scene->mMeshes[index];
    if (mesh->mNumFaces && (!mesh->mVertices || !mesh->mFaces))
        return fail(c, OIT_ERR_FORMAT, "mesh %u has faces but no vertex array", index);
    const aiMaterial *mat = mesh->mMaterialIndex < scene->mNumMaterials
                                ? scene->mMaterials[mesh->mMaterialIndex] : nullptr;
    Shade sh = material_shade(mat);
    bool vc = mesh->mColors[0] != nullptr;
    c.info->attributes |= (sh.colour || vc ? OIT_ATTR_COLOUR : 0) |
                          (sh.has_alpha || vc ? OIT_ATTR_ALPHA : 0);
    c.info->vertices_in += mesh->mNumVertices;
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        const aiFace &face = mesh->mFaces[f];
        c.info->faces_in++;
        if (face.mNumIndices < 3 || !face.mIndices) {
            c.skipped++;
            continue;
        }
        for (unsigned k = 0; k < face.mNumIndices; k++)
            if (face.mIndices[k] >= mesh->mNumVertices)
                return fail(c, OIT_ERR_FORMAT, "mesh %u face %u: vertex %u of %u", index, f,
                            face.mIndices[k], mesh->mNumVertices);
        // a polygon left whole (aiProcess_Triangulate gives none) as a fan
        oit_triangle t;
        vertex(c, mesh, sh, world, face.mIndices[0], &t.v[0]);
        for (unsigned k = 2; k < face.mNumIndices; k++) {
            vertex(c, mesh, sh, world, face.mIndices[k - 1], &t.v[1]);
            vertex(c, mesh, sh, world, face.mIndices[k], &t.v[2]);
            oit_status s = emit(c, t);
            if (s != OIT_OK)
                return s;
        }
    }
    return OIT_OK;
}

// Every node instance of every mesh, depth first with an explicit stack: a
// deep hierarchy from a hostile file cannot exhaust the call stack.
oit_status walk(Ctx &c, const aiScene *scene)
{
    struct Item {
        const aiNode *node;
        Mat4 parent;
    };
    Mat4 id{};
    for (int i = 0; i < 4; i++)
        id.m[i][i] = 1;
    std::vector<Item> stack;
    if (scene->mRootNode)
        stack.push_back({scene->mRootNode, id});
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        Mat4 world = it.parent * Mat4::from(it.node->mTransformation);
        for (unsigned i = 0; i < it.node->mNumMeshes; i++) {
            oit_status s = emit_mesh(c, scene, it.node->mMeshes[i], world);
            if (s != OIT_OK)
                return s;
        }
        for (unsigned i = it.node->mNumChildren; i-- > 0;)
            if (it.node->mChildren && it.node->mChildren[i])
                stack.push_back({it.node->mChildren[i], world});
    }
    return OIT_OK;
}

// The bytes assimp's scene holds for its geometry, charged to the budget.
size_t scene_bytes(const aiScene *scene)
{
    size_t n = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        const aiMesh *m = scene->mMeshes[i];
        if (!m)
            continue;
        n += size_t(m->mNumVertices) * (sizeof(aiVector3D) * 2 + (m->mColors[0] ? sizeof(aiColor4D) : 0));
        n += size_t(m->mNumFaces) * (sizeof(aiFace) + 3 * sizeof(unsigned));
    }
    return n;
}

oit_status import_failed(Ctx &c, Assimp::Importer &imp)
{
    const char *why = imp.GetErrorString();
    return fail(c, OIT_ERR_FORMAT, "assimp cannot read it: %s", why && *why ? why : "no reason given");
}

// The scene as imported, with no step run yet: one without meshes (an IFC
// of spaces alone, a file of cameras) is said to be so, then validation
// (which runs first) and triangulation.
oit_status emit_scene(Ctx &c, Assimp::Importer &imp, const aiScene *scene)
{
    if (!scene)
        return import_failed(c, imp);
    if (scene->mNumMeshes == 0)
        return fail(c, OIT_ERR_FORMAT, "no geometry: assimp found no mesh in it");
    if (!(scene = imp.ApplyPostProcessing(kImportFlags)))
        return import_failed(c, imp);
    oit_status s = charge(c, scene_bytes(scene), "assimp's scene");
    if (s != OIT_OK || (s = reserve_chunk(c)) != OIT_OK)
        return s;
    s = walk(c, scene);
    if (s == OIT_OK)
        s = flush(c);
    oit_mesh_info_opaque(c.info, nullptr, 0);
    if (s == OIT_OK && c.skipped)
        std::fprintf(stderr, "%s: %llu point and line primitives skipped (only triangles are drawn)\n",
                     c.name, (unsigned long long)c.skipped);
    return s == OIT_OK ? oit_rd_require_triangles(c.name, c.info, c.err) : s;
}

void configure(Assimp::Importer &imp)
{
    // a file with bones and no geometry must not draw assimp's stand-in skeleton
    imp.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
}

// Bytes in memory (gzip inflated first, within the budget).
oit_status read_memory(Ctx &c, const unsigned char *bytes, size_t size, const char *hint)
{
    if (oit_gz_magic(bytes, size))
        return read_gunzipped(c, bytes, size, [&](const unsigned char *plain, size_t n) {
            return read_memory(c, plain, n, hint);
        });
    if (size == 0)
        return fail(c, OIT_ERR_FORMAT, "the file is empty");
    Assimp::Importer imp;
    configure(imp);
    return emit_scene(c, imp, imp.ReadFileFromMemory(bytes, size, 0, hint ? hint : ""));
}

// The format's extension, a trailing ".gz" set aside (as read_mesh.c does).
std::string format_ext(const char *path)
{
    std::string base(path);
    size_t slash = base.find_last_of('/');
    if (slash != std::string::npos)
        base.erase(0, slash + 1);
    if (base.size() > 3 && (base.compare(base.size() - 3, 3, ".gz") == 0 ||
                            base.compare(base.size() - 3, 3, ".GZ") == 0))
        base.resize(base.size() - 3);
    size_t dot = base.find_last_of('.');
    return dot == std::string::npos ? std::string() : base.substr(dot + 1);
}

// assimp's extensions but ours ("*.3d;*.3ds;..." to ".3d .3ds ..."): what
// the message of an unknown extension adds to our readers' list.
std::string supported_list(Assimp::Importer &imp)
{
    static const char *const ours[] = {"ply", "obj", "off", "stl", "gltf", "glb",
                                       "vtk", "vtp", "step", "stp", "iges", "igs"};
    std::string list, out;
    imp.GetExtensionList(list);
    for (size_t at = 0; at < list.size();) {
        size_t end = list.find(';', at);
        if (end == std::string::npos)
            end = list.size();
        std::string ext = list.substr(at, end - at);
        at = end + 1;
        if (ext.compare(0, 2, "*.") == 0)
            ext.erase(0, 2);
        bool taken = ext.empty();
        for (const char *o : ours)
            taken = taken || ext == o;
        if (!taken)
            out += (out.empty() ? "." : " .") + ext;
    }
    return out;
}

oit_status read_path(Ctx &c, const char *path)
{
    std::string ext = format_ext(path);
    Assimp::Importer imp;
    if (ext.empty() || !imp.IsExtensionSupported(("." + ext).c_str()))
        return fail(c, OIT_ERR_UNSUPPORTED, "unknown mesh format '.%s' (expected .ply .obj .off .stl "
                    ".gltf .glb .vtk .vtp .step .stp .iges .igs, or through assimp %s)", ext.c_str(), supported_list(imp).c_str());
    FILE *f;
    size_t size;
    oit_status s = open_regular(c, path, &f, &size);
    if (s != OIT_OK)
        return s;
    unsigned char magic[2];
    bool gz = std::fread(magic, 1, 2, f) == 2 && oit_gz_magic(magic, 2);
    s = charge(c, size, "the file");
    if (s == OIT_OK && gz) { // assimp reads no gzip: inflate, then read from memory
        std::vector<unsigned char> bytes(size);
        std::rewind(f);
        s = std::fread(bytes.data(), 1, size, f) == size
                ? read_memory(c, bytes.data(), size, ext.c_str())
                : fail(c, OIT_ERR_IO, "short read (%zu bytes expected)", size);
    }
    std::fclose(f);
    if (s != OIT_OK || gz)
        return s;
    if (size == 0)
        return fail(c, OIT_ERR_FORMAT, "the file is empty");
    // from the path, so that files beside it (textures, Collada's and
    // X3D's references) are found as assimp's importers look for them
    configure(imp);
    return emit_scene(c, imp, imp.ReadFile(path, 0));
}

template <typename Fn> oit_status guarded(Ctx &c, Fn fn)
{
    try {
        return fn();
    } catch (const std::bad_alloc &) {
        return fail(c, OIT_ERR_NOMEM, "out of memory");
    } catch (const std::exception &e) {
        return fail(c, OIT_ERR_FORMAT, "assimp cannot read it: %s", e.what());
    } catch (...) {
        return fail(c, OIT_ERR_FORMAT, "assimp cannot read it: unexpected failure while importing");
    }
}

// ------------------------------------------------------------- isolation
//
// assimp 5.2 crashes on some malformed files (the fuzz targets find SEGVs
// inside libassimp within seconds, in its FBX, 3MF and IFC importers), and
// no check of ours can run before its parser: the import runs in a child
// process (read_isolated.h), the context's sink, info and error the
// child's for the read.

struct Job {
    Ctx *c;
    oit_status (*fn)(Ctx &, const void *);
    const void *arg;
};

oit_status run_job(void *a, oit_triangle_sink sink, void *sink_user, oit_mesh_info *info,
                   oit_error *err)
{
    Job &j = *static_cast<Job *>(a);
    redirect(*j.c, sink, sink_user, info, err);
    return j.fn(*j.c, j.arg);
}

oit_status isolated(Ctx &c, oit_status (*fn)(Ctx &, const void *), const void *arg)
{
    Job j{&c, fn, arg};
    return oit_read_isolated(c.name, "assimp", c.chunk_cap, run_job, &j, c.sink, c.user, c.info,
                             c.err);
}

} // namespace

extern "C" oit_status oit_read_assimp_memory(const unsigned char *bytes, size_t size, const char *name,
                                             const char *hint, const oit_read_desc *desc,
                                             oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                             oit_error *err)
{
    oit_mesh_info local;
    Ctx c{};
    start(c, name ? name : "(memory)", desc, sink, user, info ? info : &local, err);
    struct Arg {
        const unsigned char *bytes;
        size_t size;
        const char *hint;
    } arg{bytes, size, hint};
    return isolated(
        c,
        [](Ctx &cc, const void *a) {
            const Arg &m = *static_cast<const Arg *>(a);
            return guarded(cc, [&] { return read_memory(cc, m.bytes, m.size, m.hint); });
        },
        &arg);
}

extern "C" oit_status oit_assimp_read_file(const char *path, const oit_read_desc *desc,
                                           oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                           oit_error *err)
{
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_read_assimp: no path given");
    oit_mesh_info local;
    Ctx c{};
    start(c, path, desc, sink, user, info ? info : &local, err);
    return isolated(
        c, [](Ctx &cc, const void *) { return guarded(cc, [&] { return read_path(cc, cc.name); }); },
        nullptr);
}
