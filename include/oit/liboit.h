/* liboit: exact order-independent transparency of a converted part file or
 * of an in-core mesh, drawn into the caller's own GL framebuffer with the
 * caller's matrices.
 *
 *   oit_scene_open     opens a part file, or loads a mesh file (no GL needed)
 *   oit_scene_create_mesh  an in-core scene from the caller's arrays
 *   oit_renderer_create a renderer running one method (oit_render_methods)
 *   oit_renderer_draw  composites the scene over the caller's framebuffer
 *                      (needs the caller's current GL 4.5 core context)
 *   oit_renderer_draw_image  the same frame resolved into memory over a
 *                      background, bit for bit the tools' images
 *   oit_renderer_draw_pixels  that, with per-pixel counts or ambiguity
 *
 * Both kinds of scene go through the same handle and the same draw: a part
 * file is streamed (parts read, uploaded and captured pack by pack); an
 * in-core scene is uploaded whole at its first draw and drawn with DFB, the
 * in-core exact method (every fragment of the frame stored and sorted per
 * pixel). The images agree within the
 * tolerance of stream against DFB; the Result paragraph holds for both.
 * oit/offscreen.h renders a scene without a caller's context (scripts).
 *
 * Conventions. Handles are opaque; every create has one matching destroy or
 * close, which accepts NULL. Descriptors may be NULL and zero fields mean the
 * documented default. Every fallible call returns an oit_status and, on
 * failure, fills err (when non-NULL) with one line naming the input.
 *
 * Threads: no global state. A scene may be shared by renderers of one thread;
 * a renderer belongs to the GL context that was current at its first GL
 * draw and must be used and destroyed on a thread where that context is
 * current (a renderer that never drew with GL, anywhere). A
 * renderer starts reader threads of its own at its first draw (the cores
 * there are, less one, at least 1; see read_on_draw_thread), which touch
 * only the scene's file and memory the renderer mapped, never GL; they are
 * idle between oit_renderer_draw calls and joined by
 * oit_renderer_destroy.
 *
 * Result: the frame is composited OVER the target's existing content with
 * premultiplied colour C and per-channel transmittance T of the scene's
 * fragments composited front to back:
 *     dst.rgb = C + T * dst.rgb,   dst.a = (1 - t) + t * dst.a, t = mean(T)
 * through dual-source blending (GL_ONE, GL_SRC1_COLOR), so whatever the
 * caller drew before (a sky, opaque geometry without depth interaction) shows
 * through; where no fragment falls the target is left as it was. With
 * oit_frame.depth_texture, transparent fragments at or behind the caller's
 * opaque depth are dropped first, so C and T are those of the fragments
 * strictly in front of it: the target shows what the scene with the opaque
 * geometry included would, within the tolerance of the depth comparison
 * (oit_frame.depth_texture). Without it, transparent surfaces cover
 * everything drawn before, whatever its depth.
 * Colour space. OIT_RENDER_COLOUR_SRGB (default): compositing happens on the
 * sRGB-encoded values, C is written as computed (no sRGB conversion by
 * liboit; GL_FRAMEBUFFER_SRGB is left as the caller set it, and should be
 * off, or the target UNORM, for the encoded values to blend as such).
 * OIT_RENDER_COLOUR_LINEAR: C and T are linear light, and liboit enables
 * GL_FRAMEBUFFER_SRGB for its blend (restoring the caller's setting): on an
 * sRGB target (GL_SRGB8_ALPHA8, or an sRGB-capable default framebuffer) GL
 * decodes dst, blends in linear light and stores the sRGB encoding; on a
 * float or UNORM target the stored values are linear light, for the caller
 * to encode (oit/offscreen.h does so). So for 8-bit sRGB output give liboit
 * an sRGB target; its existing content is then read as sRGB-encoded.
 *
 * GL state: oit_renderer_draw saves and restores the draw framebuffer
 * binding, viewport, current program, vertex array, draw-indirect buffer
 * binding, blend enable / function / equation, depth, stencil, cull,
 * scissor and GL_FRAMEBUFFER_SRGB enables, colour and depth write masks,
 * and (with a depth texture) the active texture unit and the 2D texture and
 * sampler bound to texture unit 7, which it binds during the capture; and
 * the 2D texture bound to texture unit 6, which it binds while a scene
 * with opaque triangles (alpha 255 where the scene has alpha: glTF OPAQUE
 * materials, MTL d 1) is captured. It does NOT restore indexed shader-storage buffer bindings 0..9, the texture
 * bound to unit 0, or the framebuffer default-size parameters of its own
 * objects; callers that rely on those must rebind them.
 */
#ifndef OIT_LIBOIT_H
#define OIT_LIBOIT_H

#include "oit/export.h"

#include <stddef.h>
#include <stdint.h>

#include "draw_stats.h"
#include "frame.h"
#include "pick.h"
#include "mesh.h"
#include "render_modes.h"
#include "status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_scene oit_scene;
typedef struct oit_renderer oit_renderer;

/* ---- scene ------------------------------------------------------------- */

typedef struct oit_scene_desc {
    /* 0 (default): every part's data is checked at open. 1: only the
     * management sections; each part is checked when first drawn. */
    int defer_validation;
    /* Sort-last rendering over several processes (MPI ranks, each with
     * its own GL), a part file only. share_count 0 or 1 (default): the
     * whole file. 2..4096: the scene is share share_index (< share_count)
     * of the file: one whole subtree of its management tree, the shares
     * balanced by triangles, so that every view orders them. A renderer
     * then draws only that share's parts, and its C and T are the share's:
     * read them as premultiplied colour and 1 - T (a float target cleared
     * to 0, or oit/offscreen.h's OIT_PIXELS_PREMUL32F) and composite the
     * processes' images with the over operator (IceT's
     * ICET_COMPOSITE_MODE_BLEND) in the order oit_scene_share_order gives.
     * Exact for OIT_RENDER_TRANSPARENT; OIT_RENDER_TRANSLUCENT is refused
     * at draw (OIT_ERR_UNSUPPORTED): its absorbing medium and per-channel
     * T cross share boundaries. Bad numbers fail at open with
     * OIT_ERR_ARGUMENT, as does share_count > 1 for a mesh file. */
    uint32_t share_count, share_index;
} oit_scene_desc;

typedef struct oit_scene_info {
    uint64_t triangles;
    uint64_t parts;
    float bounds_min[3];
    float bounds_max[3];
    uint32_t K;          /* layers per part the file was converted for */
    uint32_t attributes; /* OIT_ATTR_* stored per vertex               */
    /* Positions (and bounds) are relative to this point of the source's
     * coordinates, non-zero for georeferenced models (oit_mesh_info).
     * Build the view matrix relative to it too: subtract it from the eye in
     * double, so that float matrices stay precise far from zero. */
    double origin[3];
    /* 1: an in-core scene (a mesh file or the caller's arrays), drawn with
     * DFB; parts and K are then 0. 0: a part file, streamed. */
    uint32_t in_core;
    /* oit_scene_desc's share, resolved: share_count 1 and share_index 0
     * for a whole scene; the parts and triangles the scene's share draws
     * (triangles and parts above are the whole file's). */
    uint32_t share_count, share_index;
    uint64_t share_parts, share_triangles;
    /* The up axis (an oit_up_axis, oit/offscreen.h) the file's format says
     * or its bounds suggest: y for glTF, z for STEP and IGES, else z for a
     * model flat in z (its z extent under half its x and y extents), else
     * y; a part file by its source's name. The offscreen API's default
     * view turns about it when oit_offscreen_view.up is 0. */
    uint32_t up_axis;
} oit_scene_info;

/* path: a part file (its content starts with the part-file magic, or its
 * name ends in .oitp) is opened and streamed; any other name is read as a
 * mesh by extension (.ply .obj .off .stl .gltf .glb .vtk .vtp, case-insensitive, a
 * trailing .gz allowed: oit_mesh_read) and held in core, as
 * oit_scene_create_mesh holds arrays. desc applies to part files only.
 * A missing or unreadable file fails with OIT_ERR_IO, a malformed one with
 * OIT_ERR_FORMAT, an unknown extension with OIT_ERR_UNSUPPORTED; the
 * message names path. */
OIT_API oit_status oit_scene_open(const char *path, const oit_scene_desc *desc, oit_scene **out,
                                  oit_error *err);

/* Colour arrays of oit_scene_mesh_desc. */
typedef enum oit_colour_type {
    OIT_COLOUR_UINT8 = 0, /* 4 uint8_t a colour, 0..255                    */
    OIT_COLOUR_FLOAT = 1  /* 4 floats a colour, 0..1 (clamped; NaN is 0),
                             rounded to 8 bits as the mesh readers do     */
} oit_colour_type;

typedef enum oit_colour_rate {
    OIT_COLOUR_PER_VERTEX = 0,  /* one colour a vertex: vertex_count colours */
    OIT_COLOUR_PER_TRIANGLE = 1 /* one colour a triangle, for its 3 corners  */
} oit_colour_rate;

/* An in-core mesh from the caller's arrays; zero fields mean the default.
 * Colours are RGBA, sRGB-encoded with straight alpha, as the mesh readers
 * deliver them (oit/mesh.h): a scene with colours has OIT_ATTR_COLOUR |
 * OIT_ATTR_ALPHA, one without takes the renderer's default colour and
 * alpha (oit_render_shading). */
typedef struct oit_scene_mesh_desc {
    const float *positions; /* x, y, z a vertex: 3 * vertex_count floats, finite */
    uint64_t vertex_count;  /* >= 3                                            */
    /* Triangle list, 3 a triangle, each < vertex_count; index_count a
     * multiple of 3. NULL: a soup, vertices 3i, 3i+1, 3i+2 form triangle i
     * (vertex_count a multiple of 3; index_count must be 0). */
    const uint32_t *indices;
    uint64_t index_count;
    const void *colours;       /* NULL: none; else see colour_type, colour_rate */
    oit_colour_type colour_type;
    oit_colour_rate colour_rate;
    const char *name;          /* the scene in messages; default "mesh"       */
} oit_scene_mesh_desc;

/* Copies the arrays (the caller may free them on return) into an in-core
 * scene, drawn with DFB. Bad arrays fail with OIT_ERR_ARGUMENT naming the
 * field and the element ("oit_scene_mesh_desc.indices[7] = 12: not below
 * vertex_count 9"); OIT_ERR_NOMEM when the copy does not fit. No GL needed. */
OIT_API oit_status oit_scene_create_mesh(const oit_scene_mesh_desc *desc, oit_scene **out,
                                         oit_error *err);
/* An in-core scene over the caller's mesh (oit/mesh.h: oit_mesh_load's or
 * a generator's), not copied, as Embree shares a caller's buffers: the
 * mesh must stay as it is until the scene is freed (oit_scene_close, and
 * the last renderer holding it letting it go). name: the scene in
 * messages; NULL: "mesh". No GL needed. */
OIT_API oit_status oit_scene_borrow_mesh(const oit_mesh *mesh, const char *name, oit_scene **out,
                                         oit_error *err);
OIT_API oit_status oit_scene_get_info(const oit_scene *scene, oit_scene_info *info, oit_error *err);
/* Lifetime: a renderer holds the last scene it drew (the scene and the GPU
 * state it built for it) until it draws another scene, releases it
 * (oit_renderer_release_scene) or is destroyed. So a scene may be closed
 * whenever no draw of it is under way, whoever drew it: the handle is then
 * the caller's no more, and the scene's memory (its triangles or its open
 * part file) is freed when the last renderer holding it lets it go; a scene
 * opened later is never mistaken for it. Release it first to free that
 * memory at once. */
OIT_API void oit_scene_close(oit_scene *scene);

/* ---- renderer ---------------------------------------------------------- */

typedef enum oit_render_shading_mode {
    OIT_RENDER_TRANSPARENT = 0, /* per-vertex or default colour and alpha     */
    OIT_RENDER_TRANSLUCENT = 1  /* Fresnel surfaces over an absorbing medium  */
} oit_render_shading_mode;

/* Where compositing happens (oit/mesh.h and Result above). Colours
 * (vertex colours, default_rgb) are 8-bit sRGB-encoded, straight alpha. */
typedef enum oit_render_colour_space {
    OIT_RENDER_COLOUR_SRGB = 0,  /* on the encoded values, as the OIT papers and
                                    most viewers do (default)                    */
    OIT_RENDER_COLOUR_LINEAR = 1 /* colours decoded with the exact sRGB EOTF,
                                    composited in linear light (Result)          */
} oit_render_colour_space;

/* The shading; zero means default. There is no background: the caller's
 * framebuffer is the background. */
typedef struct oit_render_shading {
    oit_render_shading_mode mode;
    float alpha;          /* for files without alpha; default 0.35          */
    float default_rgb[3]; /* for files without colour; default .85,.55,.2   */
    float absorption;     /* translucent; default 4                         */
    float scene_scale;    /* translucent; default: the scene's diagonal     */
    oit_render_colour_space colour_space; /* default OIT_RENDER_COLOUR_SRGB */
} oit_render_shading;

/* Zero fields mean the documented default. Grouped by concept: the image,
 * then (part files only) how packs are cut and captured, the GPU memory,
 * the host threads and the program cache. An in-core scene is drawn with
 * DFB, which stores every fragment of the frame: only the image's fields
 * and binding_limit apply to it (its image is the exact one, whatever
 * epsilon). */
typedef struct oit_renderer_desc {
    /* ---- the method ---- */
    /* NULL (default): a part file is streamed ("stream"), an in-core scene
     * drawn by DFB ("dfb"). Else a name oit_render_methods lists: "stream"
     * for part files; for in-core scenes the exact "dfb", "array",
     * "stencil" and "compute" (the capture's fills drawing the mesh as one
     * batch of K slots a pixel), "reference" (Embree's ray tracer on the
     * CPU, no GL, loaded from liboit-reference.so beside liboit) and the
     * baselines the papers compare with ("unsorted", "wboit", "pll", "dp",
     * "ppll4", "b3d", "ddp", "guarded", "f2b"). An unknown name fails at
     * create (OIT_ERR_ARGUMENT), one that does not draw the scene's kind at
     * draw (OIT_ERR_UNSUPPORTED). Only stream and dfb blend into a
     * framebuffer (oit_renderer_draw); every method draws images
     * (oit_renderer_draw_pixels). The string need not outlive create. */
    const char *method;
    /* The reference's ambiguity radius in pixels (oit_pixels_desc.ambiguous);
     * 0: 1/64. */
    float ambiguity_px;

    /* ---- the image ---- */
    oit_render_shading shading;
    /* 0 (default): a scene's own alpha, and its opaque triangles (alpha
     * 255 at all three corners where the scene has alpha: glTF OPAQUE and
     * MASK materials, MTL d 1) hide what is behind them. 1: see-through:
     * every triangle takes shading.alpha (the scene's colours are kept),
     * so nothing is opaque and what opaque triangles hid is stored and
     * composited too. Other values: OIT_ERR_ARGUMENT. */
    int see_through;
    /* Early termination; 0 (default): exact. In [0, 1): fragments behind
     * pixels whose transmittance fell below epsilon in every channel are
     * dropped, and parts whose whole footprint did are neither uploaded nor
     * drawn (oit_draw_stats.parts_skipped); the image then differs from the
     * exact one by at most epsilon per channel (in the compositing space:
     * in linear light for OIT_RENDER_COLOUR_LINEAR, where the encoding can
     * magnify it near black). The other methods flagged
     * OIT_RENDER_METHOD_EPSILON read it as their threshold: f2b's alpha
     * and guarded's contribution (0: their defaults, 0.02 and 0.0025;
     * OIT_RENDER_EPSILON_ZERO: a threshold of exactly 0), the reference's
     * saturation, below which it counts fragments as saturated
     * (oit_draw_stats.fragments_saturated; no pixel changes). */
    float epsilon;

    /* ---- a part file's packs and their capture ---- */
    uint32_t K; /* capture layers 2..16; 0: the scene's K (in-core methods: 16) */
    oit_render_pack pack;
    /* The order packs are cut in: OIT_RENDER_SCHEDULE_TREE (0) the
     * management tree's, WAVE the wavefront; the image is the same. */
    oit_render_schedule schedule;
    /* How the K-slot fills are made: for the K-slot packs (BUDGET,
     * DISJOINT) and the first pass of FIRSTK packs (AUTO too).
     * OIT_RENDER_CAPTURE_AUTO (0): the stencil-routed A-buffer where its
     * start-up self-test passes on this GL driver, else array slots;
     * STENCIL: that or OIT_ERR_GL (the driver's limit) at the first draw,
     * with the self-test's reason; ARRAY: slots through an atomic counter;
     * COMPUTE: no K-slot fill at all, every pack binned, rasterized, sorted
     * and composited in compute shaders (AUTO packs then are COUNTED's;
     * BUDGET and DISJOINT packs are cut by their rule; FIRSTK, whose first
     * pass is a K-slot fill, is OIT_ERR_ARGUMENT). The image is the same;
     * oit_draw_stats says what ran and why. */
    oit_render_capture capture;
    /* The frames the caller expects to draw with the renderer: 1, a
     * one-image run, where OIT_RENDER_PACK_AUTO starts with counted packs,
     * stored exactly as DFB stores a frame, instead of first-K ones, whose
     * K-slot store (up to slot_budget) only later frames amortize; 0
     * (default): many. A hint: any number of frames may be drawn, the
     * image is the same. */
    uint32_t frames;

    /* ---- GPU memory (bytes) ---- */
    /* The upload ring, the cache and the capture together; 0: half the
     * free memory the driver reports (GL_NVX_gpu_memory_info,
     * GL_ATI_meminfo), or, where it reports none, no total (the budgets
     * below alone). The budgets below stay inside it: given ones that add
     * up to more fail the first draw. The chosen split is in
     * oit_draw_stats. */
    uint64_t gpu_budget;
    /* The upload ring, >= 64 KiB; 0: 64 MiB. A scene within it and
     * cache_budget is read once into a ring of its size and kept there,
     * with no cache buffer beside it. */
    uint64_t upload_budget;
    /* Keeps parts drawn in one frame resident for the next ones, drawn
     * without reading or uploading them again (oit_draw_stats.cache_hits),
     * >= 64 KiB; 0: 256 MiB (never more than the scene's parts take);
     * OIT_RENDER_CACHE_OFF: no cache. The cache and the upload ring grow
     * with what the frames draw up to their budgets rather than start
     * there. */
    uint64_t cache_budget;
    /* The capture's slots a pack; 0: 64 MiB of first-K slots for counted
     * and first-K packs, 32 MiB of K slots for the others. */
    uint64_t slot_budget;
    /* The counted and first-K packs' fragment stores, grown to what a
     * frame stores and no further: a deep view past it is stored in bands
     * of rows, each drawing the pack again. 0: 256 MiB, or an eighth of a
     * smaller gpu_budget. Other packs have none. */
    uint64_t store_budget;
    /* The most a frame puts in one GPU storage buffer binding (part files
     * and in-core scenes); 0: what the driver binds
     * (GL_MAX_SHADER_STORAGE_BLOCK_SIZE). Lower caps the frame's per-pixel
     * buffers: it is then drawn in more bands of rows (the image alike but
     * for pixel centres within rounding of a silhouette at a band's
     * edge). */
    uint64_t binding_limit;

    /* ---- host threads and the program cache ---- */
    /* Threads that read a part file's parts ahead of the GPU (they never
     * call GL), 1..64, checked at the first draw; 0: the cores there are,
     * less one, at least 1, unless read_on_draw_thread. */
    uint32_t reader_threads;
    /* 1: parts are read on the drawing thread, for comparison and
     * debugging (wins over reader_threads); 0 (default): reader threads. */
    int read_on_draw_thread;
    /* Where linked GL programs are kept across processes (GL program
     * binaries), so a later process with the same driver loads them
     * instead of compiling: a folder, made if missing; "off": none. NULL
     * (default): OIT_PROGRAM_CACHE from the environment where set (a
     * folder or "off"), else $XDG_CACHE_HOME/oit, else $HOME/.cache/oit.
     * An entry is named by a hash of the driver's strings and the
     * programs' sources and checked before use; a bad or refused one is
     * compiled and written again, and a folder that cannot be written, or
     * a driver without program binaries, means no cache, never an error.
     * Read at oit_renderer_create; the string need not outlive that call.
     * oit_renderer_get_desc gives the folder in use, or "off". */
    const char *program_cache;
} oit_renderer_desc;

#define OIT_RENDER_CACHE_OFF UINT64_MAX
/* oit_renderer_desc.epsilon: a threshold of exactly 0 for a method whose
 * default is not 0 (f2b, guarded); for the others, the same as 0. */
#define OIT_RENDER_EPSILON_ZERO (-1.0f)

/* A method a renderer runs (oit_renderer_desc.method). */
typedef struct oit_render_method_info {
    const char *name;
    uint32_t flags; /* oit_render_method_flag (oit/render_modes.h) */
} oit_render_method_info;

/* Every method, in the order the tools list them: *count of them (count
 * may be NULL), static. No GL needed. */
OIT_API const oit_render_method_info *oit_render_methods(uint32_t *count);

/* The one range check of desc, the one oit_renderer_create runs: K 0 or
 * 2..16; the byte budgets 0 or 64 KiB..1 TiB (cache_budget also
 * OIT_RENDER_CACHE_OFF, gpu_budget at least 1 MiB); epsilon in [0, 1);
 * pack, schedule and see_through their values. For a caller that wants
 * the errors before it makes a renderer: OIT_ERR_ARGUMENT whose message
 * starts with the field and the value ("oit_renderer_desc.upload_budget
 * = 1000: expected ..."), as every error about desc names its field.
 * capture, reader_threads and the budgets' sum are checked at the first
 * draw of a part file. No GL needed. */
OIT_API oit_status oit_renderer_desc_check(const oit_renderer_desc *desc, oit_error *err);

/* No GL needed: a renderer's GL objects are made at its first draw of a
 * method that uses GL (OIT_RENDER_METHOD_GL), in the GL 4.5 core context
 * current then, which every later draw must have current too. */
OIT_API oit_status oit_renderer_create(const oit_renderer_desc *desc, oit_renderer **out,
                                       oit_error *err);
OIT_API void oit_renderer_destroy(oit_renderer *r);
/* The descriptor r draws with, every zero resolved to the value in use
 * (as sokol_gfx's query_desc): after r drew a part file, K (the scene's
 * where 0 was given), upload_budget and cache_budget (the limits the ring
 * and the cache grow to: oit_draw_stats.ring_budget, cache_budget;
 * OIT_RENDER_CACHE_OFF where there is no cache, a resident scene
 * included), gpu_budget (the total, 0: none), capture (what the K-slot
 * fills use, ARRAY or STENCIL; AUTO where none do: COUNTED packs) and
 * read_on_draw_thread; after any draw, the method (its name where NULL
 * was given) and the shading's defaults for the
 * scene drawn last (alpha, colours, absorption, scene_scale, colour
 * space). pack stays as given (AUTO switches frame by frame; the draw's
 * figures say which ran), and so do epsilon and see_through. Before the
 * first draw: the descriptor as given. */
OIT_API void oit_renderer_get_desc(const oit_renderer *r, oit_renderer_desc *out);
/* The shading and see_through of r's later draws (oit_renderer_desc's),
 * checked as oit_renderer_create checks them; r keeps the GPU state it
 * built, so a viewer switches shading without building it again. */
OIT_API oit_status oit_renderer_set_shading(oit_renderer *r, const oit_render_shading *shading,
                                            int see_through, oit_error *err);
/* Builds what r's first draw of scene into memory (oit_renderer_draw_pixels)
 * builds: the part file's streamer, or the in-core method opened (its
 * programs, its self-tests, the triangles uploaded), so that a method the
 * driver cannot run fails here (OIT_ERR_GL where it lacks a feature, as
 * stencil routing; OIT_ERR_UNSUPPORTED where a limit refuses this input)
 * rather than at a draw. A GL method needs its context current. */
OIT_API oit_status oit_renderer_prepare(oit_renderer *r, oit_scene *scene, oit_error *err);
/* Frees r's GPU state for scene and lets the scene go when r drew it last
 * (else does nothing), so that a closed scene's memory is freed while r
 * lives on (Lifetime); the next draw of any scene builds its state anew.
 * Needs r's GL context current, like every call on r. r or scene NULL:
 * nothing. */
OIT_API void oit_renderer_release_scene(oit_renderer *r, const oit_scene *scene);


/* Draws scene as seen through frame into frame->framebuffer (see Result
 * above). The scene must stay open while r draws it; drawing a different
 * scene rebuilds r's per-scene GPU state (for an in-core scene: its
 * triangles, uploaded at its first draw). Any viewport the GL renders
 * works: one whose per-pixel state passes what one GPU storage buffer
 * binds (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, 128 MiB at the least: about
 * 6.7 M pixels transparent, 2.8 M translucent) is drawn in bands of rows,
 * each captured and blended in turn (the same image; its figures add up).
 * stats may be NULL; for an in-core scene only ms, fragments, max_layers,
 * packs (DFB's bands of rows, 1 unless the frame's fragments exceed one
 * storage buffer), batches, draw_calls, bytes_uploaded (the triangles, at
 * the first draw), gpu_bytes_peak, draw, the GPU times and the shading's
 * are filled, the rest are 0. */
OIT_API oit_status oit_renderer_draw(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                                     oit_draw_stats *stats, oit_error *err);

/* The frame of oit_renderer_draw resolved in memory instead of blended
 * into a framebuffer, as the tools write their images: width * height
 * pixels (frame's viewport size) of 4 floats into rgba (rgba_bytes at
 * least that many bytes, else OIT_ERR_ARGUMENT), row 0 at the TOP,
 *     rgb = C + T * background,  a = 1
 * with C and T as in Result, computed by the capture's own resolve pass (so
 * the bytes are those of the tools' PFMs for the same settings and
 * camera: oit_frame.camera), colour sRGB-encoded in both colour spaces.
 * background: rgb, sRGB-encoded (decoded for OIT_RENDER_COLOUR_LINEAR); a
 * negative component is 0; NULL or all 0: white, the tools' default.
 * frame's framebuffer, viewport_x and viewport_y are not read; a
 * depth_texture is OIT_ERR_UNSUPPORTED here. stats as oit_renderer_draw's
 * (ms includes the read-back). The GL state is kept as by
 * oit_renderer_draw. Every method draws images (oit_renderer_desc.method:
 * an in-core scene's methods other than dfb fill the figures they have). */
OIT_API oit_status oit_renderer_draw_image(oit_renderer *r, oit_scene *scene,
                                           const oit_frame *frame, const float background[3],
                                           float *rgba, size_t rgba_bytes,
                                           oit_draw_stats *stats, oit_error *err);

/* Where oit_renderer_draw_pixels writes; zero means none. */
typedef struct oit_pixels_desc {
    const float *background; /* rgb as oit_renderer_draw_image's          */
    float *rgba;             /* the image as oit_renderer_draw_image's      */
    size_t rgba_bytes;
    /* width * height each, row 0 at the top, or NULL. counts: the
     * fragments each pixel got (a method flagged OIT_RENDER_METHOD_COUNTS);
     * ambiguous: 1 where the pixel's centre lies within the ambiguity
     * radius of an edge, where rasterization and rays may disagree, else 0
     * (OIT_RENDER_METHOD_AMBIGUITY). Asked of a method without the flag:
     * OIT_ERR_UNSUPPORTED naming the field. */
    uint32_t *counts;
    uint8_t *ambiguous;
} oit_pixels_desc;

/* oit_renderer_draw_image with the per-pixel figures a method has. */
OIT_API oit_status oit_renderer_draw_pixels(oit_renderer *r, oit_scene *scene,
                                            const oit_frame *frame, const oit_pixels_desc *out,
                                            oit_draw_stats *stats, oit_error *err);


/* Every fragment the exact image composites at pixel (x, y) of frame's
 * viewport (y = 0 the TOP row, as oit_renderer_draw_image's rows), front
 * to back: its depth, point, colour, alpha, the transmittance in front of it,
 * its part and source triangle (include/oit/pick.h). The ray through the
 * pixel's centre is the Embree reference's, and the layers are ordered by
 * the tie rule every exact method follows (by depth key, then source
 * triangle), so for every exact method they are the fragments its image
 * composites there, except on the reference's ambiguity mask
 * (oit_pixels_desc.ambiguous), where the centre lies on an edge and
 * rasterization may take one triangle more or less. They do not depend on
 * the method: an approximate one (wboit, unsorted) lists the exact layers
 * too. An in-core scene drawn by the reference is picked through Embree
 * (its own hits); other in-core scenes and part files by walking the
 * triangles the ray may meet, a part file's one part at a time (bounded
 * memory). The first `capacity` layers go to layers (NULL with 0: only
 * count); *count says how many there are in all, so a second call with
 * room for them gets every one. Needs no GL context and draws nothing.
 * A model matrix places the triangles as the draws do (the walk then
 * serves the reference too). frame's depth_texture is
 * OIT_ERR_UNSUPPORTED (the pick lists the transparent scene alone); a
 * pixel outside the viewport is OIT_ERR_ARGUMENT. */
OIT_API oit_status oit_renderer_pick(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                                     int x, int y, oit_pick_layer *layers, size_t capacity,
                                     size_t *count, oit_error *err);

/* Every draw's GPU figures, oldest first, each once (a tool that prints
 * every frame's; oit_draw_stats has only the newest): 1 and *out when the
 * next draw's are in (wait 1: waits for them, as at the end of a run), 0
 * when none is. The renderer keeps the 64 newest that were not taken.
 * Never 1 where oit_renderer_gpu_absent says why not. */
OIT_API int oit_renderer_gpu_poll(oit_renderer *r, oit_draw_gpu *out, int wait);
/* NULL when r's draws are timed on the GPU (or r has not drawn yet), else
 * why not ("the driver reports 0 timestamp bits"). */
OIT_API const char *oit_renderer_gpu_absent(const oit_renderer *r);

/* ---- sort-last over several processes (oit_scene_desc.share_count) --- */

/* The shares front to back for frame (its view, projection, viewport size
 * and model: as oit_renderer_draw takes it; framebuffer and depth_texture
 * are not read): writes share_count share indices into order (capacity
 * order_count >= share_count, else OIT_ERR_ARGUMENT), the composite order
 * of the processes that draw the shares of one file (icetCompositeOrder
 * takes it, share i being the process that opened share i). Every scene
 * over the same file and share_count gives the same order for the same
 * frame, whatever its share_index; a whole scene gives {0}. No GL needed;
 * not to be called while another call uses scene. */
OIT_API oit_status oit_scene_share_order(oit_scene *scene, const oit_frame *frame,
                                         uint32_t *order, uint32_t order_count, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
