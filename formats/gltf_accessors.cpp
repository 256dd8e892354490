// glTF accessors resolved to a primitive's vertices (gltf_adapter_internal.h):
// every index, range and stride checked against its bufferView and buffer
// before a byte is read. Apart as the one place that reads a buffer's bytes
// by accessor; the Draco path (gltf_draco.cpp) reads its own stream.
#include "formats/gltf_adapter_internal.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace oit_gltf {
namespace {

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

} // namespace

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

} // namespace oit_gltf
