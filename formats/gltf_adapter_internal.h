// The glTF adapter's C++ inside, shared by its four files: gltf_adapter.cpp
// (loading and the C entries), gltf_scene.cpp (the node tree, materials and
// the triangles handed out), gltf_accessors.cpp (accessors resolved to
// vertices) and gltf_draco.cpp (KHR_draco_mesh_compression). Dependencies
// point down that list, draco using accessors; none uses one above it.
// Nothing outside formats/ includes it, nor any C file.
#ifndef OIT_GLTF_ADAPTER_INTERNAL_H
#define OIT_GLTF_ADAPTER_INTERNAL_H

// tinygltf's implementation is compiled once, in gltf_adapter.cpp, which
// defines TINYGLTF_IMPLEMENTATION before it includes this header.
#include "formats/third_party_begin.h"
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
#include "formats/third_party_end.h"

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/adapter_ctx.h"
#include "oit/mesh.h"

namespace oit_gltf {

using namespace oit_adapter;

inline constexpr char kDraco[] = "KHR_draco_mesh_compression";

struct Ctx : Output {
    const char *dir; // NULL: external buffers are refused
    const tinygltf::Model *model;
    bool texture_said; // the unsupported-texture note was printed
};

// Gives bytes charged before back to the budget.
inline void release(Ctx &c, size_t bytes) { c.budget_used -= bytes < c.budget_used ? bytes : c.budget_used; }

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

// ---- gltf_accessors.cpp

// Sizes g for nverts vertices (with colour when color) and nidx indices
// (indexed when nidx > 0), charged to the budget as g.bytes; a count no
// real mesh has is OIT_ERR_FORMAT.
oit_status reserve(Ctx &c, Geometry &g, size_t nverts, size_t nidx, bool color, const char *what);

// Checks that bufferView bv lies inside its buffer; returns its first byte
// and its length.
oit_status buffer_view_bytes(Ctx &c, int bv, const char *what, const unsigned char **bytes,
                             size_t *length);

// Primitive p's POSITION, COLOR_0 and indices resolved into g, every
// accessor checked against its bufferView and buffer before it is read.
oit_status load_accessors(Ctx &c, const tinygltf::Primitive &p, const char *what, Geometry &g);

// ---- gltf_draco.cpp

// A KHR_draco_mesh_compression primitive (ext is its extension object)
// decoded into g: positions, COLOR_0 when the extension names it, faces.
oit_status load_draco(Ctx &c, const tinygltf::Value &ext, const char *what, Geometry &g);

// tinygltf 2.7 insists that a primitive's index accessor has a bufferView,
// but a Draco primitive's accessors legitimately have none (the data is in
// the compressed stream), so such files would be refused. The indices of a
// Draco primitive are never read here (Draco's faces are), so they are
// dropped from the JSON before tinygltf sees it. Returns false, leaving
// *out alone, when nothing needs patching; malformed input is left for
// tinygltf to report.
bool patch_draco_json(const unsigned char *bytes, size_t size, std::vector<unsigned char> *out);

// ---- gltf_scene.cpp

// Every triangle of the model's default scene (without one, of every scene;
// without scenes, of every node that is nobody's child), in world space,
// coloured by its material, through the chunk (flush hands out the last).
oit_status walk_model(Ctx &c);

} // namespace oit_gltf

#endif
