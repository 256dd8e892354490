// What the C++ adapters (gltf_adapter.cpp, assimp_adapter.cpp,
// step_adapter.cpp) keep of one read the same way: the file's name for
// messages, the memory budget, and the chunk of triangles handed to the
// sink. Each adapter's context derives from Output. A header of inline
// functions: the adapters are separate plugins (liboit-gltf.so,
// liboit-assimp.so, liboit-occt.so), and each compiles its own copy.
#ifndef OIT_FORMATS_ADAPTER_CTX_H
#define OIT_FORMATS_ADAPTER_CTX_H

#include <sys/stat.h>

#include <cerrno>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "formats/gzip_input.h"
#include "oit/mesh.h"

// read_common.c's check that a read delivered a triangle (readers_internal.h,
// which is C).
extern "C" oit_status oit_rd_require_triangles(const char *name, const oit_mesh_info *info,
                                               oit_error *err);

namespace oit_adapter {

constexpr size_t kDefaultChunk = 65536;
constexpr size_t kDefaultBudget = size_t(2) << 30;

// Errors are formatted as "<name>: <what>".
struct Output {
    const char *name;
    size_t budget_limit;
    size_t budget_used;
    oit_triangle_sink sink;
    void *user;
    oit_mesh_info *info;
    oit_error *err;
    bool origin_set; // info->origin picked from the first vertex
    std::vector<oit_triangle> chunk;
    size_t chunk_cap;
};

// The read's output and budget as desc asks (0: the defaults), info cleared.
inline void start(Output &o, const char *name, const oit_read_desc *desc, oit_triangle_sink sink,
                  void *user, oit_mesh_info *info, oit_error *err)
{
    o.name = name;
    o.budget_limit = desc && desc->memory_budget ? desc->memory_budget : kDefaultBudget;
    o.chunk_cap = desc && desc->chunk_triangles ? desc->chunk_triangles : kDefaultChunk;
    o.sink = sink;
    o.user = user;
    o.info = info;
    o.err = err;
    oit_mesh_info_init(info);
}

// In the child of an isolated read (read_isolated.h) the sink, info and
// error are the child's.
inline void redirect(Output &o, oit_triangle_sink sink, void *user, oit_mesh_info *info,
                     oit_error *err)
{
    o.sink = sink;
    o.user = user;
    o.info = info;
    o.err = err;
}

// The error s with the message (printf's fmt) prefixed by the file's name.
inline oit_status fail(Output &o, oit_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

inline oit_status fail(Output &o, oit_status s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    oit_error_setv(o.err, s, fmt, ap);
    va_end(ap);
    oit_error_prefix(o.err, o.name);
    return s;
}

// Charges bytes to the read's memory budget; OIT_ERR_NOMEM naming what when
// it would go over.
inline oit_status charge(Output &o, size_t bytes, const char *what)
{
    if (bytes > o.budget_limit - o.budget_used)
        return fail(o, OIT_ERR_NOMEM, "%s needs %zu bytes, over the memory budget of %zu (%zu in use)",
                    what, bytes, o.budget_limit, o.budget_used);
    o.budget_used += bytes;
    return OIT_OK;
}

// The output chunk, charged to the budget before the first triangle.
inline oit_status reserve_chunk(Output &o)
{
    if (o.chunk_cap > SIZE_MAX / sizeof(oit_triangle))
        return fail(o, OIT_ERR_NOMEM, "a chunk of %zu triangles is too large", o.chunk_cap);
    oit_status s = charge(o, o.chunk_cap * sizeof(oit_triangle), "the output chunk");
    if (s == OIT_OK)
        o.chunk.reserve(o.chunk_cap);
    return s;
}

// A world-space point as a vertex position, relative to the origin that
// the first point picks (oit/mesh.h).
inline void place(Output &o, const double p[3], float pos[3])
{
    if (!o.origin_set) {
        oit_mesh_origin_pick(p, o.info->origin);
        o.origin_set = true;
    }
    oit_mesh_position(o.info->origin, p, pos);
}

// Hands the triangles gathered so far to the sink (none: OIT_OK), counting
// them into o.info.
inline oit_status flush(Output &o)
{
    if (o.chunk.empty())
        return OIT_OK;
    oit_mesh_info_add(o.info, o.chunk.data(), o.chunk.size());
    // ALPHA may be known only later (a later mesh, material or face): the
    // oit_mesh_info_opaque at the end of the read clears OPAQUE if it never is
    for (const oit_triangle &t : o.chunk)
        if (t.v[0].rgba[3] == 255 && t.v[1].rgba[3] == 255 && t.v[2].rgba[3] == 255) {
            o.info->attributes |= OIT_ATTR_OPAQUE;
            break;
        }
    oit_status s = o.sink(o.user, o.chunk.data(), o.chunk.size(), o.err);
    o.chunk.clear();
    return s;
}

// Adds t to the chunk, handing the chunk out when full; a triangle with a
// non-finite coordinate is dropped and counted. The caller counts faces_in
// (a polygon of the file may give several triangles).
inline oit_status emit(Output &o, const oit_triangle &t)
{
    if (!oit_triangle_is_finite(&t)) {
        o.info->nonfinite_dropped++;
        return OIT_OK;
    }
    o.chunk.push_back(t);
    return o.chunk.size() == o.chunk_cap ? flush(o) : OIT_OK;
}

// A colour component in 0..1 as a byte, rounded.
inline uint8_t unit_u8(double v) { return v > 0.0 ? (v >= 1.0 ? 255 : uint8_t(v * 255.0 + 0.5)) : 0; }

// path opened for binary reading, and its size; anything but a regular
// file (a folder, a device) is refused.
inline oit_status open_regular(Output &o, const char *path, FILE **f, size_t *size)
{
    *size = 0;
    *f = std::fopen(path, "rb");
    struct stat st;
    if (!*f)
        return fail(o, OIT_ERR_IO, "cannot open: %s", std::strerror(errno));
    if (fstat(fileno(*f), &st) != 0 || !S_ISREG(st.st_mode)) {
        std::fclose(*f);
        *f = nullptr;
        return fail(o, OIT_ERR_IO, "not a regular file");
    }
    *size = size_t(st.st_size);
    return OIT_OK;
}

// gzip bytes (oit_gz_magic) inflated within the budget, the inflated size
// charged, then read by fn(plain, n): the libraries the adapters wrap read
// no gzip.
template <class Fn> oit_status read_gunzipped(Output &o, const unsigned char *bytes, size_t size, Fn fn)
{
    unsigned char *plain = nullptr;
    size_t n = 0;
    oit_status s = oit_gunzip(bytes, size, o.budget_limit - o.budget_used, o.name, &plain, &n, o.err);
    if (s == OIT_OK && (s = charge(o, n, "the inflated gzip data")) == OIT_OK)
        s = fn(static_cast<const unsigned char *>(plain), n);
    std::free(plain);
    return s;
}

} // namespace oit_adapter

#endif
