// glTF's KHR_draco_mesh_compression (gltf_adapter_internal.h): a primitive's
// Draco stream decoded into its vertices, and the JSON patch that lets
// tinygltf load such a file at all. Apart as the only file that includes
// Draco.
#include "formats/gltf_adapter_internal.h"

#include "formats/third_party_begin.h"
#include <draco/compression/decode.h>
// drop_draco_indices edits the JSON with tinygltf's own nlohmann::json,
// included as tinygltf's implementation includes it.
#ifdef __GNUC__
#pragma GCC visibility push(hidden)
#endif
#include <nlohmann/json.hpp>
#ifdef __GNUC__
#pragma GCC visibility pop
#endif
#include "formats/third_party_end.h"

#include <climits>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace oit_gltf {
namespace {

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

} // namespace

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

// tinygltf 2.7 insists that a primitive's index accessor has a bufferView,
// but a Draco primitive's accessors legitimately have none (the data is in
// the compressed stream), so such files would be refused. The indices of a
// Draco primitive are never read here (Draco's faces are), so they are
// dropped from the JSON before tinygltf sees it. Returns false, leaving
// *out alone, when nothing needs patching; malformed input is left for
// tinygltf to report.
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

} // namespace oit_gltf
