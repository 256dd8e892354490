// glTF 2.0 reader (.gltf, .glb, KHR_draco_mesh_compression) behind the C
// interface of oit/mesh.h.
//
// tinygltf parses the JSON and the buffers; this file walks the scene's node
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

#if defined(__clang__)
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Weverything"
#elif defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#endif
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <draco/compression/decode.h>
#if defined(__clang__)
#pragma clang diagnostic pop
#elif defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <sys/stat.h>

#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "formats/gltf_internal.h"
#include "formats/gzip_input.h"
#include "oit/mesh.h"

namespace {

constexpr size_t kDefaultChunk = 65536;
constexpr size_t kDefaultBudget = size_t(2) << 30;
const char kDraco[] = "KHR_draco_mesh_compression";

// Everything one read needs; errors are formatted as "<name>: <what>".
struct Ctx {
    const char *name;
    const char *dir; // NULL: external buffers are refused
    size_t budget_limit;
    size_t budget_used;
    oit_triangle_sink sink;
    void *user;
    oit_mesh_info *info;
    oit_error *err;
    bool origin_set; // info->origin picked from the first vertex
    std::vector<oit_triangle> chunk;
    size_t chunk_cap;
    const tinygltf::Model *model;
    bool texture_said; // the unsupported-texture note was printed
};

oit_status fail(Ctx &c, oit_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

oit_status fail(Ctx &c, oit_status s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    oit_error_setv(c.err, s, fmt, ap);
    va_end(ap);
    oit_error_prefix(c.err, c.name);
    return s;
}

oit_status charge(Ctx &c, size_t bytes, const char *what)
{
    if (bytes > c.budget_limit - c.budget_used)
        return fail(c, OIT_ERR_NOMEM, "%s needs %zu bytes, over the memory budget of %zu (%zu in use)",
                    what, bytes, c.budget_limit, c.budget_used);
    c.budget_used += bytes;
    return OIT_OK;
}

void release(Ctx &c, size_t bytes) { c.budget_used -= bytes < c.budget_used ? bytes : c.budget_used; }

// ---------------------------------------------------------------- output

oit_status flush(Ctx &c)
{
    if (c.chunk.empty())
        return OIT_OK;
    oit_mesh_info_add(c.info, c.chunk.data(), c.chunk.size());
    // ALPHA may come later (a primitive with a material after one without):
    // oit_mesh_info_opaque at the end clears OPAQUE if it never does
    for (const oit_triangle &t : c.chunk)
        if (t.v[0].rgba[3] == 255 && t.v[1].rgba[3] == 255 && t.v[2].rgba[3] == 255) {
            c.info->attributes |= OIT_ATTR_OPAQUE;
            break;
        }
    oit_status s = c.sink(c.user, c.chunk.data(), c.chunk.size(), c.err);
    c.chunk.clear();
    return s;
}

oit_status emit(Ctx &c, const oit_triangle &t)
{
    c.info->faces_in++;
    if (!oit_triangle_is_finite(&t)) {
        c.info->nonfinite_dropped++;
        return OIT_OK;
    }
    c.chunk.push_back(t);
    return c.chunk.size() == c.chunk_cap ? flush(c) : OIT_OK;
}

// ------------------------------------------------------------- accessors

size_t component_size(int type)
{
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0; // INT and DOUBLE are not valid in glTF 2.0 accessors
    }
}

int component_count(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0; // matrices carry no geometry we read
    }
}

// A checked window on an accessor's elements. base == nullptr stands for an
// accessor without bufferView, whose elements are all zero (glTF 2.0 5.1.1).
struct View {
    const unsigned char *base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int comp_type = 0;
    int ncomp = 0;
    bool normalized = false;

    double get(size_t i, int k) const
    {
        if (!base)
            return 0.0;
        const unsigned char *p = base + i * stride + size_t(k) * component_size(comp_type);
        switch (comp_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::fmax(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::fmax(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        }
    }
};

// Checks that bufferView bv lies inside its buffer; returns its first byte.
oit_status buffer_view_bytes(Ctx &c, int bv, const char *what, const unsigned char **bytes,
                             size_t *length)
{
    const tinygltf::Model &m = *c.model;
    if (bv < 0 || size_t(bv) >= m.bufferViews.size())
        return fail(c, OIT_ERR_FORMAT, "%s: bufferView %d does not exist (%zu bufferViews)", what, bv,
                    m.bufferViews.size());
    const tinygltf::BufferView &v = m.bufferViews[size_t(bv)];
    if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size())
        return fail(c, OIT_ERR_FORMAT, "bufferView %d: buffer %d does not exist (%zu buffers)", bv,
                    v.buffer, m.buffers.size());
    size_t size = m.buffers[size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
        return fail(c, OIT_ERR_FORMAT,
                    "bufferView %d: bytes %zu..+%zu lie outside buffer %d of %zu bytes", bv,
                    v.byteOffset, v.byteLength, v.buffer, size);
    *bytes = m.buffers[size_t(v.buffer)].data.data() + v.byteOffset;
    *length = v.byteLength;
    return OIT_OK;
}

oit_status make_view(Ctx &c, int index, const char *what, View *out)
{
    const tinygltf::Model &m = *c.model;
    if (index < 0 || size_t(index) >= m.accessors.size())
        return fail(c, OIT_ERR_FORMAT, "%s: accessor %d does not exist (%zu accessors)", what, index,
                    m.accessors.size());
    const tinygltf::Accessor &a = m.accessors[size_t(index)];
    if (a.sparse.isSparse)
        return fail(c, OIT_ERR_UNSUPPORTED, "%s: accessor %d is sparse", what, index);
    size_t csize = component_size(a.componentType);
    int ncomp = component_count(a.type);
    if (!csize || !ncomp)
        return fail(c, OIT_ERR_FORMAT, "%s: accessor %d has component type %d, type %d", what, index,
                    a.componentType, a.type);
    *out = View{};
    out->count = a.count;
    out->comp_type = a.componentType;
    out->ncomp = ncomp;
    out->normalized = a.normalized;
    if (a.bufferView < 0)
        return OIT_OK;
    const unsigned char *bytes;
    size_t length;
    oit_status s = buffer_view_bytes(c, a.bufferView, what, &bytes, &length);
    if (s != OIT_OK)
        return s;
    size_t elem = csize * size_t(ncomp);
    size_t stride = m.bufferViews[size_t(a.bufferView)].byteStride;
    if (stride == 0)
        stride = elem;
    if (stride < elem)
        return fail(c, OIT_ERR_FORMAT, "%s: accessor %d: byteStride %zu is below its element size %zu",
                    what, index, stride, elem);
    if (a.count > 0 &&
        (a.byteOffset > length || elem > length - a.byteOffset ||
         a.count - 1 > (length - a.byteOffset - elem) / stride))
        return fail(c, OIT_ERR_FORMAT,
                    "%s: accessor %d: %zu elements of %zu bytes (stride %zu) from offset %zu "
                    "overrun bufferView %d of %zu bytes",
                    what, index, a.count, elem, stride, a.byteOffset, a.bufferView, length);
    out->base = bytes + a.byteOffset;
    out->stride = stride;
    return OIT_OK;
}

// ------------------------------------------------------------ primitives

// One primitive resolved to model space: positions, linear RGBA (when the
// file has COLOR_0) and the index list (empty when not indexed).
struct Geometry {
    std::vector<float> xyz;
    std::vector<float> rgba;
    std::vector<uint32_t> idx;
    bool indexed = false;
    size_t nverts = 0;
    size_t bytes = 0; // charged to the budget
};

oit_status reserve(Ctx &c, Geometry &g, size_t nverts, size_t nidx, bool color, const char *what)
{
    const size_t max = SIZE_MAX / 64;
    if (nverts > max || nidx > max)
        return fail(c, OIT_ERR_FORMAT, "%s: %zu vertices, %zu indices is not a real mesh", what, nverts,
                    nidx);
    size_t bytes = nverts * (3 + (color ? 4 : 0)) * sizeof(float) + nidx * sizeof(uint32_t) +
                   nverts * sizeof(oit_vertex);
    oit_status s = charge(c, bytes, what);
    if (s != OIT_OK)
        return s;
    g.bytes = bytes;
    g.nverts = nverts;
    g.xyz.resize(nverts * 3);
    if (color)
        g.rgba.resize(nverts * 4);
    g.idx.resize(nidx);
    g.indexed = nidx > 0;
    return OIT_OK;
}

oit_status color_view(Ctx &c, const View &v, const char *what)
{
    bool type_ok = v.comp_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                   ((v.comp_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                     v.comp_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) && v.normalized);
    if ((v.ncomp != 3 && v.ncomp != 4) || !type_ok)
        return fail(c, OIT_ERR_FORMAT, "%s: COLOR_0 must be a vec3/vec4 of float or normalized "
                    "unsigned byte/short (got %d components of type %d)", what, v.ncomp, v.comp_type);
    return OIT_OK;
}

oit_status load_accessors(Ctx &c, const tinygltf::Primitive &p, const char *what, Geometry &g)
{
    auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end())
        return fail(c, OIT_ERR_FORMAT, "%s: no POSITION attribute", what);
    View vp, vc, vi;
    oit_status s = make_view(c, pos->second, what, &vp);
    if (s == OIT_OK && vp.ncomp != 3)
        s = fail(c, OIT_ERR_FORMAT, "%s: POSITION is not a vec3", what);
    auto col = p.attributes.find("COLOR_0");
    bool has_color = col != p.attributes.end();
    if (s == OIT_OK && has_color && (s = make_view(c, col->second, what, &vc)) == OIT_OK)
        s = color_view(c, vc, what);
    if (s == OIT_OK && has_color && vc.count < vp.count)
        s = fail(c, OIT_ERR_FORMAT, "%s: COLOR_0 has %zu elements for %zu positions", what, vc.count,
                 vp.count);
    bool indexed = p.indices >= 0;
    if (s == OIT_OK && indexed && (s = make_view(c, p.indices, what, &vi)) == OIT_OK &&
        (vi.ncomp != 1 || vi.comp_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
         vi.comp_type == TINYGLTF_COMPONENT_TYPE_BYTE || vi.comp_type == TINYGLTF_COMPONENT_TYPE_SHORT))
        s = fail(c, OIT_ERR_FORMAT, "%s: indices must be scalar unsigned byte/short/int", what);
    if (s == OIT_OK)
        s = reserve(c, g, vp.count, indexed ? vi.count : 0, has_color, what);
    if (s != OIT_OK)
        return s;
    g.indexed = indexed;
    for (size_t i = 0; i < vp.count; i++)
        for (int k = 0; k < 3; k++)
            g.xyz[3 * i + size_t(k)] = float(vp.get(i, k));
    for (size_t i = 0; has_color && i < vp.count; i++)
        for (int k = 0; k < 4; k++)
            g.rgba[4 * i + size_t(k)] = k < vc.ncomp ? float(vc.get(i, k)) : 1.0f;
    for (size_t i = 0; i < g.idx.size(); i++)
        g.idx[i] = uint32_t(vi.get(i, 0));
    return OIT_OK;
}

// ------------------------------------------------------------------ Draco

int draco_attribute_id(const tinygltf::Value &ext, const char *semantic)
{
    const tinygltf::Value &attrs = ext.Get("attributes");
    if (!attrs.IsObject() || !attrs.Has(semantic) || !attrs.Get(semantic).IsNumber())
        return -1;
    double id = attrs.Get(semantic).GetNumberAsDouble();
    return id >= 0 && id <= INT_MAX ? int(id) : -1;
}

// Reads n components of point p as floats, normalizing integer data that
// Draco did not flag as normalized (colours are 0..1 in glTF).
void draco_value(const draco::PointAttribute &a, uint32_t p, int n, float *out)
{
    a.ConvertValue<float>(a.mapped_index(draco::PointIndex(p)), int8_t(n), out);
    if (a.normalized())
        return;
    float scale = a.data_type() == draco::DT_UINT8    ? 255.0f
                  : a.data_type() == draco::DT_UINT16 ? 65535.0f
                                                      : 1.0f;
    for (int k = 0; k < n && scale != 1.0f; k++)
        out[k] /= scale;
}

oit_status decode_draco(Ctx &c, const tinygltf::Value &ext, const char *what,
                        std::unique_ptr<draco::Mesh> *mesh)
{
    const tinygltf::Value &bv = ext.Get("bufferView");
    double d = bv.IsNumber() ? bv.GetNumberAsDouble() : -1.0;
    if (!(d >= 0 && d <= INT_MAX))
        return fail(c, OIT_ERR_FORMAT, "%s: %s has no valid bufferView", what, kDraco);
    const int view = int(d);
    const unsigned char *bytes;
    size_t length;
    oit_status s = buffer_view_bytes(c, view, what, &bytes, &length);
    if (s != OIT_OK)
        return s;
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char *>(bytes), length);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok())
        return fail(c, OIT_ERR_FORMAT, "%s: bad Draco data in bufferView %d: %s", what, view,
                    decoded.status().error_msg());
    *mesh = std::move(decoded).value();
    return OIT_OK;
}

oit_status load_draco(Ctx &c, const tinygltf::Value &ext, const char *what, Geometry &g)
{
    std::unique_ptr<draco::Mesh> mesh;
    oit_status s = decode_draco(c, ext, what, &mesh);
    if (s != OIT_OK)
        return s;
    int pos_id = draco_attribute_id(ext, "POSITION");
    const draco::PointAttribute *pos = pos_id < 0 ? nullptr : mesh->GetAttributeByUniqueId(uint32_t(pos_id));
    if (!pos || pos->num_components() < 3)
        return fail(c, OIT_ERR_FORMAT, "%s: Draco POSITION attribute %d is missing or not a vec3", what,
                    pos_id);
    int col_id = draco_attribute_id(ext, "COLOR_0");
    const draco::PointAttribute *col = col_id < 0 ? nullptr : mesh->GetAttributeByUniqueId(uint32_t(col_id));
    if (col_id >= 0 && (!col || col->num_components() < 3 || col->num_components() > 4))
        return fail(c, OIT_ERR_FORMAT, "%s: Draco COLOR_0 attribute %d is missing or not vec3/vec4",
                    what, col_id);
    size_t nfaces = mesh->num_faces();
    s = reserve(c, g, mesh->num_points(), nfaces * 3, col != nullptr, what);
    if (s != OIT_OK)
        return s;
    for (uint32_t p = 0; p < mesh->num_points(); p++) {
        draco_value(*pos, p, 3, &g.xyz[3 * size_t(p)]);
        float *rgba = col ? &g.rgba[4 * size_t(p)] : nullptr;
        if (rgba) {
            rgba[3] = 1.0f;
            draco_value(*col, p, col->num_components(), rgba);
        }
    }
    for (size_t f = 0; f < nfaces; f++) {
        const draco::Mesh::Face &face = mesh->face(draco::FaceIndex(uint32_t(f)));
        for (int k = 0; k < 3; k++)
            g.idx[3 * f + size_t(k)] = face[size_t(k)].value();
    }
    return OIT_OK;
}

// ---------------------------------------------------------------- colours

uint8_t srgb_u8(double linear)
{
    double v = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return v > 0.0 ? (v >= 1.0 ? 255 : uint8_t(v * 255.0 + 0.5)) : 0;
}

uint8_t unit_u8(double v) { return v > 0.0 ? (v >= 1.0 ? 255 : uint8_t(v * 255.0 + 0.5)) : 0; }

// glTF colours are linear and vertex colours multiply baseColorFactor; the
// triangles carry sRGB-encoded rgb and straight alpha (oit/mesh.h).
struct Shade {
    double base[4] = {1, 1, 1, 1};
    enum { OPAQUE, MASK, BLEND } mode = OPAQUE;
    double cutoff = 0.5;
};

oit_status material_shade(Ctx &c, int material, const char *what, Shade *sh)
{
    if (material < 0)
        return OIT_OK;
    if (size_t(material) >= c.model->materials.size())
        return fail(c, OIT_ERR_FORMAT, "%s: material %d does not exist (%zu materials)", what, material,
                    c.model->materials.size());
    const tinygltf::Material &m = c.model->materials[size_t(material)];
    const std::vector<double> &f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4)
        return fail(c, OIT_ERR_FORMAT, "material %d: baseColorFactor has %zu components, not 4", material,
                    f.size());
    for (int k = 0; k < 4; k++)
        sh->base[k] = f[size_t(k)];
    sh->mode = m.alphaMode == "BLEND" ? Shade::BLEND : m.alphaMode == "MASK" ? Shade::MASK : Shade::OPAQUE;
    sh->cutoff = m.alphaCutoff;
    // Every material gives alpha, OPAQUE's being 1: its triangles are
    // opaque (render/image/shade.h); a file without materials takes the default.
    c.info->attributes |= OIT_ATTR_COLOUR | OIT_ATTR_ALPHA;
    if (m.pbrMetallicRoughness.baseColorTexture.index >= 0 && !c.texture_said) {
        c.texture_said = true; // once per file
        std::fprintf(stderr, "%s: baseColorTexture textures are not supported; using "
                             "baseColorFactor\n", c.name ? c.name : "glTF");
    }
    return OIT_OK;
}

void shade_vertex(const Shade &sh, const float *rgba, uint8_t out[4])
{
    double col[4];
    for (int k = 0; k < 4; k++)
        col[k] = sh.base[k] * (rgba ? rgba[k] : 1.0);
    for (int k = 0; k < 3; k++)
        out[k] = srgb_u8(col[k]);
    double a = sh.mode == Shade::BLEND ? col[3] : sh.mode == Shade::MASK ? (col[3] >= sh.cutoff) : 1.0;
    out[3] = unit_u8(a);
}

// --------------------------------------------------------------- emitting

struct Mat4 {
    double m[16]; // column-major, as glTF stores it

    static Mat4 identity()
    {
        Mat4 r{};
        r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
        return r;
    }
    Mat4 operator*(const Mat4 &b) const
    {
        Mat4 r{};
        for (int col = 0; col < 4; col++)
            for (int row = 0; row < 4; row++)
                for (int k = 0; k < 4; k++)
                    r.m[col * 4 + row] += m[k * 4 + row] * b.m[col * 4 + k];
        return r;
    }
    void apply(const float *p, double *out) const
    {
        for (int row = 0; row < 3; row++)
            out[row] = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row];
    }
    // A mirroring transform turns counter-clockwise faces clockwise.
    bool mirrors() const
    {
        double det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
                     m[8] * (m[1] * m[6] - m[5] * m[2]);
        return det < 0.0;
    }
};

// Triangle t of a list, strip or fan, as corner numbers into the index list.
void corners(int mode, size_t t, size_t out[3])
{
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        out[0] = 3 * t, out[1] = 3 * t + 1, out[2] = 3 * t + 2;
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other strip triangle is flipped to keep one winding.
        out[0] = t + (t & 1), out[1] = t + 1 - (t & 1), out[2] = t + 2;
    } else {
        out[0] = 0, out[1] = t + 1, out[2] = t + 2;
    }
}

oit_status emit_geometry(Ctx &c, const Geometry &g, const Shade &sh, int mode, const Mat4 &world,
                         const char *what)
{
    size_t n = g.indexed ? g.idx.size() : g.nverts;
    for (size_t i = 0; g.indexed && i < n; i++)
        if (g.idx[i] >= g.nverts)
            return fail(c, OIT_ERR_FORMAT, "%s: index %u at position %zu is out of range (%zu vertices)",
                        what, g.idx[i], i, g.nverts);
    std::vector<oit_vertex> verts(g.nverts);
    for (size_t i = 0; i < g.nverts; i++) {
        double p[3];
        world.apply(&g.xyz[3 * i], p);
        if (!c.origin_set) {
            oit_mesh_origin_pick(p, c.info->origin);
            c.origin_set = true;
        }
        oit_mesh_position(c.info->origin, p, verts[i].pos);
        shade_vertex(sh, g.rgba.empty() ? nullptr : &g.rgba[4 * i], verts[i].rgba);
    }
    c.info->vertices_in += g.nverts;
    size_t ntri = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : n >= 3 ? n - 2 : 0;
    bool flip = world.mirrors();
    for (size_t t = 0; t < ntri; t++) {
        size_t k[3];
        corners(mode, t, k);
        oit_triangle tri;
        for (int v = 0; v < 3; v++) {
            size_t corner = k[flip && v ? 3 - v : v];
            tri.v[v] = verts[g.indexed ? g.idx[corner] : corner];
        }
        oit_status s = emit(c, tri);
        if (s != OIT_OK)
            return s;
    }
    return OIT_OK;
}

oit_status emit_primitive(Ctx &c, int mesh, size_t prim, const Mat4 &world)
{
    const tinygltf::Primitive &p = c.model->meshes[size_t(mesh)].primitives[prim];
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return OIT_OK; // points and lines have no surface to render
    char what[64];
    std::snprintf(what, sizeof what, "mesh %d primitive %zu", mesh, prim);
    Shade sh;
    oit_status s = material_shade(c, p.material, what, &sh);
    if (s != OIT_OK)
        return s;
    Geometry g;
    auto draco = p.extensions.find(kDraco);
    if (draco != p.extensions.end())
        s = load_draco(c, draco->second, what, g);
    else
        s = load_accessors(c, p, what, g);
    if (s == OIT_OK) {
        if (!g.rgba.empty())
            c.info->attributes |= OIT_ATTR_COLOUR;
        s = emit_geometry(c, g, sh, p.mode, world, what);
    }
    release(c, g.bytes);
    return s;
}

// ------------------------------------------------------------------ nodes

oit_status node_matrix(Ctx &c, int index, Mat4 *out)
{
    const tinygltf::Node &n = c.model->nodes[size_t(index)];
    if (n.matrix.size() == 16) {
        for (int k = 0; k < 16; k++)
            out->m[k] = n.matrix[size_t(k)];
        return OIT_OK;
    }
    if (!n.matrix.empty() || (!n.translation.empty() && n.translation.size() != 3) ||
        (!n.rotation.empty() && n.rotation.size() != 4) || (!n.scale.empty() && n.scale.size() != 3))
        return fail(c, OIT_ERR_FORMAT, "node %d: matrix, translation, rotation or scale has the wrong "
                    "number of components", index);
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    for (size_t k = 0; k < n.translation.size(); k++) t[k] = n.translation[k];
    for (size_t k = 0; k < n.rotation.size(); k++) q[k] = n.rotation[k];
    for (size_t k = 0; k < n.scale.size(); k++) s[k] = n.scale[k];
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                         2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                         2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
    *out = Mat4::identity();
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++)
            out->m[col * 4 + row] = r[col * 3 + row] * s[col];
    for (int row = 0; row < 3; row++)
        out->m[12 + row] = t[row];
    return OIT_OK;
}

oit_status emit_mesh(Ctx &c, int mesh, const Mat4 &world)
{
    if (size_t(mesh) >= c.model->meshes.size())
        return fail(c, OIT_ERR_FORMAT, "mesh %d does not exist (%zu meshes)", mesh, c.model->meshes.size());
    for (size_t p = 0; p < c.model->meshes[size_t(mesh)].primitives.size(); p++) {
        oit_status s = emit_primitive(c, mesh, p, world);
        if (s != OIT_OK)
            return s;
    }
    return OIT_OK;
}

// Depth-first over one scene with an explicit stack, so a deep chain of
// nodes cannot overflow the C stack. glTF nodes form trees; a node met twice
// (a cycle or a shared child) is an error, which also bounds the work.
oit_status walk_scene(Ctx &c, const std::vector<int> &roots)
{
    const size_t nnodes = c.model->nodes.size();
    std::vector<char> seen(nnodes, 0);
    std::vector<std::pair<int, Mat4>> stack;
    for (size_t i = roots.size(); i-- > 0;)
        stack.emplace_back(roots[i], Mat4::identity());
    while (!stack.empty()) {
        auto [node, parent] = stack.back();
        stack.pop_back();
        if (node < 0 || size_t(node) >= nnodes)
            return fail(c, OIT_ERR_FORMAT, "node %d does not exist (%zu nodes)", node, nnodes);
        if (seen[size_t(node)]++)
            return fail(c, OIT_ERR_FORMAT, "node %d is reached twice: nodes must form trees", node);
        Mat4 local = Mat4::identity();
        oit_status s = node_matrix(c, node, &local);
        Mat4 world = parent * local;
        const tinygltf::Node &n = c.model->nodes[size_t(node)];
        if (s == OIT_OK && n.mesh >= 0)
            s = emit_mesh(c, n.mesh, world);
        if (s != OIT_OK)
            return s;
        for (size_t i = n.children.size(); i-- > 0;)
            stack.emplace_back(n.children[i], world);
    }
    return OIT_OK;
}

// The default scene; without one, every scene; without scenes, every node
// that is nobody's child.
oit_status walk_model(Ctx &c)
{
    const tinygltf::Model &m = *c.model;
    if (m.defaultScene >= 0 && size_t(m.defaultScene) < m.scenes.size())
        return walk_scene(c, m.scenes[size_t(m.defaultScene)].nodes);
    if (m.defaultScene >= 0)
        return fail(c, OIT_ERR_FORMAT, "default scene %d does not exist (%zu scenes)", m.defaultScene,
                    m.scenes.size());
    for (const tinygltf::Scene &scene : m.scenes) {
        oit_status s = walk_scene(c, scene.nodes);
        if (s != OIT_OK)
            return s;
    }
    if (!m.scenes.empty())
        return OIT_OK;
    std::vector<char> is_child(m.nodes.size(), 0);
    for (const tinygltf::Node &n : m.nodes)
        for (int child : n.children)
            if (child >= 0 && size_t(child) < m.nodes.size())
                is_child[size_t(child)] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < m.nodes.size(); i++)
        if (!is_child[i])
            roots.push_back(int(i));
    return walk_scene(c, roots);
}

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

// tinygltf 2.7 insists that a primitive's index accessor has a bufferView,
// but a Draco primitive's accessors legitimately have none (the data is in
// the compressed stream), so such files would be refused. The indices of a
// Draco primitive are never read here (Draco's faces are), so they are
// dropped from the JSON before tinygltf sees it. Returns false, leaving
// *out alone, when nothing needs patching; malformed input is left for
// tinygltf to report.
uint32_t le32(const unsigned char *p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

void put_le32(unsigned char *p, size_t v)
{
    for (int k = 0; k < 4; k++)
        p[k] = (unsigned char)(v >> (8 * k));
}

bool drop_draco_indices(nlohmann::json &j)
{
    bool changed = false;
    auto meshes = j.find("meshes");
    if (meshes == j.end() || !meshes->is_array())
        return false;
    for (auto &mesh : *meshes) {
        auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
        if (prims == mesh.end() || !prims->is_array())
            continue;
        for (auto &p : *prims) {
            auto ext = p.is_object() ? p.find("extensions") : p.end();
            if (ext != p.end() && ext->is_object() && ext->contains(kDraco) && p.erase("indices"))
                changed = true;
        }
    }
    return changed;
}

bool patch_draco_json(const unsigned char *bytes, size_t size, std::vector<unsigned char> *out)
{
    bool glb = size >= 20 && std::memcmp(bytes, "glTF", 4) == 0;
    size_t begin = glb ? 20 : 0, end = size;
    if (glb) {
        size_t json_len = le32(bytes + 12);
        if (le32(bytes + 16) != 0x4E4F534Au || json_len > size - 20)
            return false;
        end = 20 + json_len;
    }
    const char *text = reinterpret_cast<const char *>(bytes);
    if (std::string_view(text + begin, end - begin).find(kDraco) == std::string_view::npos)
        return false;
    nlohmann::json j = nlohmann::json::parse(text + begin, text + end, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !drop_draco_indices(j))
        return false;
    std::string patched = j.dump();
    if (!glb) {
        out->assign(patched.begin(), patched.end());
        return true;
    }
    patched.resize((patched.size() + 3) & ~size_t(3), ' ');
    out->assign(bytes, bytes + 12);
    out->resize(20);
    put_le32(out->data() + 12, patched.size());
    put_le32(out->data() + 16, 0x4E4F534Au);
    out->insert(out->end(), patched.begin(), patched.end());
    out->insert(out->end(), bytes + end, bytes + size);
    put_le32(out->data() + 8, out->size());
    return true;
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
    if (c.chunk_cap > SIZE_MAX / sizeof(oit_triangle))
        return fail(c, OIT_ERR_NOMEM, "a chunk of %zu triangles is too large", c.chunk_cap);
    s = charge(c, c.chunk_cap * sizeof(oit_triangle), "the output chunk");
    if (s != OIT_OK)
        return s;
    c.chunk.reserve(c.chunk_cap);
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
    if (oit_gz_magic(bytes, size)) {
        unsigned char *plain = nullptr;
        size_t n = 0;
        s = oit_gunzip(bytes, size, c.budget_limit - c.budget_used, c.name, &plain, &n, c.err);
        if (s == OIT_OK && (s = charge(c, n, "the inflated gzip data")) == OIT_OK) {
            s = read_plain(c, plain, n);
            release(c, n);
        }
        std::free(plain);
    } else {
        s = read_plain(c, bytes, size);
    }
    return s == OIT_OK ? oit_rd_require_triangles(c.name, c.info, c.err) : s;
}

oit_status read_file(Ctx &c, const char *path, std::vector<unsigned char> *bytes)
{
    FILE *f = std::fopen(path, "rb");
    struct stat st;
    if (!f)
        return fail(c, OIT_ERR_IO, "cannot open: %s", std::strerror(errno));
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        std::fclose(f);
        return fail(c, OIT_ERR_IO, "not a regular file");
    }
    size_t size = size_t(st.st_size);
    oit_status s = charge(c, size, "the file");
    if (s == OIT_OK) {
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
    c.name = name;
    c.dir = dir;
    c.budget_limit = desc && desc->memory_budget ? desc->memory_budget : kDefaultBudget;
    c.chunk_cap = desc && desc->chunk_triangles ? desc->chunk_triangles : kDefaultChunk;
    c.sink = sink;
    c.user = user;
    c.info = info;
    c.err = err;
    oit_mesh_info_init(info);
    return c;
}

struct MemoryArg {
    const unsigned char *bytes;
    size_t size;
};

} // namespace

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
