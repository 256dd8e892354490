/* Prints the layout of every structure python/oit/_lib.py mirrors, as the C
 * compiler lays it out: "Struct size N" and "Struct.field offset" lines,
 * and "enum NAME value" lines of the enums it spells, for check_layout.py
 * to hold the ctypes declarations and constants to. A field missed
 * here that ctypes declares fails there by name; one ctypes misses fails
 * by the structure's size. */
#include <stddef.h>
#include <stdio.h>

#include "oit/liboit.h"
#include "oit/mesh.h"
#include "oit/offscreen.h"

#define SIZE(py, c) printf(#py " size %zu\n", sizeof(c))
#define AT(py, c, f) printf(#py "." #f " %zu\n", offsetof(c, f))

static void renderer(void)
{
    SIZE(RenderShading, oit_render_shading);
#define R(f) AT(RenderShading, oit_render_shading, f)
    R(mode); R(alpha); R(default_rgb); R(absorption); R(scene_scale); R(colour_space);
#undef R
    SIZE(RendererDesc, oit_renderer_desc);
#define D(f) AT(RendererDesc, oit_renderer_desc, f)
    D(method); D(ambiguity_px); D(shading); D(see_through); D(epsilon); D(K); D(pack); D(schedule); D(capture);
    D(frames); D(gpu_budget); D(upload_budget); D(cache_budget); D(slot_budget);
    D(store_budget); D(binding_limit); D(reader_threads); D(read_on_draw_thread);
    D(program_cache);
#undef D
    SIZE(RenderMethodInfo, oit_render_method_info);
    AT(RenderMethodInfo, oit_render_method_info, name);
    AT(RenderMethodInfo, oit_render_method_info, flags);
    SIZE(OffscreenDesc, oit_offscreen_desc);
    AT(OffscreenDesc, oit_offscreen_desc, renderer);
}

static void stats(void)
{
    SIZE(DrawStats, oit_draw_stats);
#define S(f) AT(DrawStats, oit_draw_stats, f)
    S(draw); S(ms); S(method); S(device); S(gpu_frame); S(gpu_ms); S(gpu_phase_ms); S(host_waits); S(redraws);
    S(fragments); S(max_layers); S(fragments_saturated); S(overflow_pixels); S(deep_pixels); S(second_pass_pixels);
    S(second_pass_packs); S(parts_drawn); S(parts_culled); S(parts_skipped); S(parts_clipped);
    S(bytes_clipped); S(bytes_uploaded); S(cache_hits); S(cache_bytes); S(draw_calls);
    S(reader_threads); S(resident); S(packs); S(batches); S(predicted_batches); S(capture);
    S(capture_k); S(capture_asked); S(capture_slots); S(capture_slots_k); S(capture_fallback);
    S(order_ms); S(pack_ms); S(auto_first_k); S(front_first); S(choice); S(choice_why);
    S(choice_first_k_ms); S(choice_counted_ms); S(gpu_bytes_peak); S(gpu_mesh_bytes); S(gpu_budget);
    S(ring_budget); S(cache_budget); S(capture_budget); S(store_budget); S(gpu_free_bytes);
    S(budget_source); S(see_through); S(opaque);
#undef S
}

static void scene(void)
{
    SIZE(Error, oit_error);
    AT(Error, oit_error, status);
    AT(Error, oit_error, message);
    SIZE(SceneDesc, oit_scene_desc);
#define C(f) AT(SceneDesc, oit_scene_desc, f)
    C(defer_validation); C(share_count); C(share_index);
#undef C
    SIZE(SceneInfo, oit_scene_info);
#define I(f) AT(SceneInfo, oit_scene_info, f)
    I(triangles); I(parts); I(bounds_min); I(bounds_max); I(K); I(attributes); I(origin);
    I(in_core); I(share_count); I(share_index); I(share_parts); I(share_triangles); I(up_axis);
#undef I
    SIZE(SceneMeshDesc, oit_scene_mesh_desc);
#define M(f) AT(SceneMeshDesc, oit_scene_mesh_desc, f)
    M(positions); M(vertex_count); M(indices); M(index_count); M(colours); M(colour_type);
    M(colour_rate); M(name);
#undef M
}

static void offscreen_view(void)
{
    SIZE(OffscreenView, oit_offscreen_view);
#define V(f) AT(OffscreenView, oit_offscreen_view, f)
    V(width); V(height); V(format); V(use_matrices); V(view); V(projection); V(eye); V(target);
    V(up); V(fovy_deg); V(znear); V(zfar); V(background); V(clip_count); V(clip);
#undef V
}

static void pick_layer(void)
{
    SIZE(PickLayer, oit_pick_layer);
#define P(f) AT(PickLayer, oit_pick_layer, f)
    P(depth); P(point); P(colour); P(alpha); P(transmittance); P(front); P(part);
    P(source_triangle); P(group); P(material);
#undef P
}

/* Every value of the enums _lib.py spells (its ENUMS) and of its
 * module-level constants: "enum NAME value". */
#define E(name) printf("enum " #name " %d\n", (int)(name))
static void enums(void)
{
    printf("enum OIT_PICK_NO_PART %u\n", (unsigned)OIT_PICK_NO_PART); /* past int */
    E(OIT_RENDER_PACK_AUTO); E(OIT_RENDER_PACK_COUNTED); E(OIT_RENDER_PACK_BUDGET);
    E(OIT_RENDER_PACK_DISJOINT); E(OIT_RENDER_PACK_FIRSTK);
    E(OIT_RENDER_CAPTURE_AUTO); E(OIT_RENDER_CAPTURE_ARRAY); E(OIT_RENDER_CAPTURE_STENCIL);
    E(OIT_RENDER_CAPTURE_COMPUTE);
    E(OIT_RENDER_COLOUR_SRGB); E(OIT_RENDER_COLOUR_LINEAR);
    E(OIT_UP_Y); E(OIT_UP_Z); E(OIT_UP_X);
    E(OIT_OK); E(OIT_COLOUR_UINT8); E(OIT_COLOUR_FLOAT); E(OIT_COLOUR_PER_VERTEX);
    E(OIT_COLOUR_PER_TRIANGLE); E(OIT_PIXELS_RGBA8); E(OIT_PIXELS_RGBA32F);
    E(OIT_RENDER_TRANSPARENT); E(OIT_RENDER_TRANSLUCENT); E(OIT_ATTR_COLOUR);
    E(OIT_ATTR_ALPHA);
}
#undef E

int main(void)
{
    renderer();
    stats();
    scene();
    offscreen_view();
    pick_layer();
    enums();
    return 0;
}
