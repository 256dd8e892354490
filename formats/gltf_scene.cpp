// The glTF scene turned into triangles (gltf_adapter_internal.h): the node
// tree walked with each node's transform, every triangle primitive resolved
// (gltf_accessors.cpp, gltf_draco.cpp), coloured by its material and handed
// to the sink in chunks. Apart from loading (gltf_adapter.cpp): this is what
// a model means, not how its bytes arrive.
#include "formats/gltf_adapter_internal.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

namespace oit_gltf {
namespace {

// ---------------------------------------------------------------- colours

uint8_t srgb_u8(double linear)
{
    return unit_u8(linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055);
}

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
    // opaque (view/render/image/shade.h); a file without materials takes the default.
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
        place(c, p, verts[i].pos);
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
        c.info->faces_in++;
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

} // namespace

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

} // namespace oit_gltf
