// glTF 2.0 reader (.gltf, .glb, KHR_draco_mesh_compression) behind the C
// interface of oit/mesh.h.
//
// tinygltf parses the JSON and the buffers; the adapter walks the scene's node
// tree, composes each node's transform, resolves every triangle primitive to
// world-space vertices with colours and hands them to the sink in chunks.
// Nothing tinygltf hands back is trusted: every index, accessor range and
// stride is checked against its buffer before a byte is read. Textures are
// ignored (no image is decoded or opened).
//
// Memory: the file and its external buffers are held whole (glTF offers no
// streaming). They are charged against desc->memory_budget: the file three
// times (raw bytes, tinygltf's JSON tree, its buffer copies), external
// buffers twice, plus the arrays of one primitive at a time and one chunk.
//
// This file loads the bytes (file, gzip, tinygltf's parse with the budget's
// file callbacks) and holds the C entries; the scene is walked in
// gltf_scene.cpp, accessors are read in gltf_accessors.cpp and Draco streams
// in gltf_draco.cpp (gltf_adapter_internal.h).

// tinygltf's implementation, compiled here only.
#define TINYGLTF_IMPLEMENTATION
#include "formats/gltf_adapter_internal.h"

#include <sys/stat.h>

#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "formats/gltf_internal.h"

namespace oit_gltf {
namespace {

// ---------------------------------------------------------------- loading

// tinygltf reads external buffers through these, so that they are charged to
// the budget, refused without a folder, and never read from a device.
bool fs_exists(const std::string &path, void *user)
{
    const Ctx &c = *static_cast<const Ctx *>(user);
    struct stat st;
    return c.dir && stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string fs_expand(const std::string &path, void *) { return path; }

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    Ctx &c = *static_cast<Ctx *>(user);
    FILE *f = c.dir ? std::fopen(path.c_str(), "rb") : nullptr;
    struct stat st;
    if (!f || fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        if (f)
            std::fclose(f);
        *err = "cannot open";
        return false;
    }
    size_t size = size_t(st.st_size);
    bool ok = size <= (c.budget_limit - c.budget_used) / 2;
    if (ok) {
        c.budget_used += 2 * size;
        out->resize(size);
        ok = std::fread(out->data(), 1, size, f) == size;
    }
    std::fclose(f);
    *err = ok ? "" : "over the memory budget or short read";
    return ok;
}

bool fs_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    *err = "writing is not supported";
    return false;
}

bool ignore_image(tinygltf::Image *, const int, std::string *, std::string *, int, int,
                  const unsigned char *, int, void *)
{
    return true;
}

std::string first_line(const std::string &s)
{
    size_t end = s.find('\n');
    return s.substr(0, end == std::string::npos ? s.size() : end);
}

bool extension_supported(const std::string &ext)
{
    return ext == kDraco || ext == "KHR_mesh_quantization" || ext.rfind("KHR_materials_", 0) == 0 ||
           ext.rfind("KHR_texture_", 0) == 0 || ext == "EXT_texture_webp";
}

oit_status parse(Ctx &c, const unsigned char *bytes, size_t size, tinygltf::Model *model)
{
    if (size == 0)
        return fail(c, OIT_ERR_FORMAT, "empty file");
    oit_status s = charge(c, 2 * size, "the parsed file");
    if (s != OIT_OK)
        return s;
    std::vector<unsigned char> patched;
    if (patch_draco_json(bytes, size, &patched)) {
        if ((s = charge(c, patched.size(), "the Draco-patched JSON")) != OIT_OK)
            return s;
        bytes = patched.data();
        size = patched.size();
    }
    if (size > UINT_MAX)
        return fail(c, OIT_ERR_UNSUPPORTED, "%zu bytes is over tinygltf's 4 GiB limit", size);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(ignore_image, nullptr);
    loader.SetFsCallbacks(tinygltf::FsCallbacks{fs_exists, fs_expand, fs_read, fs_write, &c});
    std::string err, warn, dir = c.dir ? c.dir : "";
    bool ok = size >= 4 && std::memcmp(bytes, "glTF", 4) == 0
                  ? loader.LoadBinaryFromMemory(model, &err, &warn, bytes, unsigned(size), dir)
                  : loader.LoadASCIIFromString(model, &err, &warn, reinterpret_cast<const char *>(bytes),
                                               unsigned(size), dir);
    if (!ok)
        return fail(c, OIT_ERR_FORMAT, "%s", err.empty() ? "not a glTF file" : first_line(err).c_str());
    for (const std::string &ext : model->extensionsRequired)
        if (!extension_supported(ext))
            return fail(c, OIT_ERR_UNSUPPORTED, "requires glTF extension %s", ext.c_str());
    return OIT_OK;
}

oit_status read_plain(Ctx &c, const unsigned char *bytes, size_t size)
{
    tinygltf::Model model;
    oit_status s = parse(c, bytes, size, &model);
    if (s != OIT_OK)
        return s;
    c.model = &model;
    if ((s = reserve_chunk(c)) != OIT_OK)
        return s;
    s = walk_model(c);
    if (s == OIT_OK)
        s = flush(c);
    oit_mesh_info_opaque(c.info, nullptr, 0); // ALPHA came with the first material
    return s;
}

/* tinygltf parses from memory: gzip bytes are inflated first, within the
 * budget, and the model must yield a triangle like every other format's. */
oit_status read_memory(Ctx &c, const unsigned char *bytes, size_t size)
{
    oit_status s;
    if (oit_gz_magic(bytes, size))
        s = read_gunzipped(c, bytes, size, [&](const unsigned char *plain, size_t n) {
            oit_status r = read_plain(c, plain, n);
            release(c, n);
            return r;
        });
    else
        s = read_plain(c, bytes, size);
    return s == OIT_OK ? oit_rd_require_triangles(c.name, c.info, c.err) : s;
}

oit_status read_file(Ctx &c, const char *path, std::vector<unsigned char> *bytes)
{
    FILE *f;
    size_t size;
    oit_status s = open_regular(c, path, &f, &size);
    if (s != OIT_OK)
        return s;
    if ((s = charge(c, size, "the file")) == OIT_OK) {
        bytes->resize(size);
        if (std::fread(bytes->data(), 1, size, f) != size)
            s = fail(c, OIT_ERR_IO, "short read (%zu bytes expected)", size);
    }
    std::fclose(f);
    return s;
}

oit_status guarded(Ctx &c, oit_status (*fn)(Ctx &, const void *), const void *arg)
{
    try {
        return fn(c, arg);
    } catch (const std::bad_alloc &) {
        return fail(c, OIT_ERR_NOMEM, "out of memory");
    } catch (const std::exception &e) {
        return fail(c, OIT_ERR_FORMAT, "%s", e.what());
    } catch (...) {
        return fail(c, OIT_ERR_FORMAT, "unexpected failure while parsing");
    }
}

Ctx make_ctx(const char *name, const char *dir, const oit_read_desc *desc, oit_triangle_sink sink,
             void *user, oit_mesh_info *info, oit_error *err)
{
    Ctx c{};
    start(c, name, desc, sink, user, info, err);
    c.dir = dir;
    return c;
}

struct MemoryArg {
    const unsigned char *bytes;
    size_t size;
};

} // namespace
} // namespace oit_gltf

// The C entries reach the reader through its namespace.
using namespace oit_gltf;

extern "C" oit_status oit_read_gltf_memory(const unsigned char *bytes, size_t size, const char *name,
                                           const char *dir, const oit_read_desc *desc,
                                           oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                           oit_error *err)
{
    oit_mesh_info local;
    Ctx c = make_ctx(name, dir, desc, sink, user, info ? info : &local, err);
    MemoryArg arg{bytes, size};
    return guarded(
        c,
        [](Ctx &cc, const void *a) {
            const MemoryArg &m = *static_cast<const MemoryArg *>(a);
            return read_memory(cc, m.bytes, m.size);
        },
        &arg);
}

extern "C" oit_status oit_gltf_read_file(const char *path, const oit_read_desc *desc,
                                         oit_triangle_sink sink, void *user, oit_mesh_info *info,
                                         oit_error *err)
{
    std::string dir(path);
    size_t slash = dir.find_last_of('/');
    dir = slash == std::string::npos ? "." : dir.substr(0, slash + 1);
    oit_mesh_info local;
    Ctx c = make_ctx(path, dir.c_str(), desc, sink, user, info ? info : &local, err);
    return guarded(
        c,
        [](Ctx &cc, const void *) {
            std::vector<unsigned char> bytes;
            oit_status s = read_file(cc, cc.name, &bytes);
            return s == OIT_OK ? read_memory(cc, bytes.data(), bytes.size()) : s;
        },
        nullptr);
}
