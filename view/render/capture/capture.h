/* Capture of one batch of geometry into a bounded K-fragment A-buffer, then
 * per-pixel sort and front-to-back composite into the frame's accumulation
 * (Vlcek et al.'s transmittance formulation), restricted to the batch's screen
 * rectangle. Four backends behind this one interface, each its own state
 * and table of operations (capture_backend.h); the K-slot ones:
 *  - OIT_CAPTURE_ARRAY: K slots per pixel filled through an atomic counter;
 *    portable, and counts overflow exactly.
 *  - OIT_CAPTURE_STENCIL: stencil routing over K MSAA samples (Wang & Xie);
 *    only offered where K samples are K true multisamples (a driver that
 *    says otherwise, GL_NV_internalformat_sample_query, is refused) and a
 *    start-up self-test shows the driver routes one fragment to each sample
 *    (it does not on llvmpipe, see design.md; nor on NVIDIA at 16 samples
 *    of an integer format, 8 multisamples x 2 supersamples).
 * A pixel that receives more than K fragments in one batch counts once in
 * overflow_pixels; its extra fragments are lost, which is why a correct part
 * file must give zero. The counted and first-K backends have no such limit
 * (OIT_CAPTURE_COUNTED, OIT_CAPTURE_FIRSTK below). */
#ifndef OIT_RENDER_CAPTURE_H
#define OIT_RENDER_CAPTURE_H

#include "oit/render_modes.h"
#include "view/render/capture/capture_choice.h"
#include "view/render/gl/gpu_mesh.h"
#include "view/render/gl/frag_glsl.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum oit_capture_kind {
    OIT_CAPTURE_AUTO = 0, /* stencil when its self-test passes, else array */
    OIT_CAPTURE_ARRAY,
    OIT_CAPTURE_STENCIL,
    /* no per-pixel limit: each batch counted, stored and sorted as DFB does,
     * within the slot budget as a fragment budget (capture_counted.h) */
    OIT_CAPTURE_COUNTED,
    /* no per-pixel limit either: each batch drawn once into up to K slots a
     * pixel within the slot budget while every fragment is counted; only
     * the pixels that got more are drawn again, stored and sorted
     * (capture_firstk.h); a batch too wide for 2 slots a pixel is counted */
    OIT_CAPTURE_FIRSTK,
    /* no per-pixel limit, no raster pipeline: each batch binned into tiles,
     * rasterized, ordered and composited in compute shaders
     * (capture_compute.h); K is not used */
    OIT_CAPTURE_COMPUTE
} oit_capture_kind;

/* GPU bytes a triangle of a batch takes in the compute capture beside its
 * geometry: its record (160) and four tile-list entries (capture_compute.h);
 * a budget holding its batches holds this much a triangle of the
 * largest. */
#define OIT_COMPUTE_CAPTURE_TRIANGLE_BYTES 176u

typedef struct oit_capture oit_capture;

/* Testing: what a driver may do, forced on the stencil backend's fill (the
 * self-test's and every batch's), so that a test can see the self-test
 * refuse it where the driver itself does not do it. */
enum {
    /* the fill shader run once per covered sample (GL_SAMPLE_SHADING,
     * minimum 1, multisampling on): more than once a pixel, each with its
     * own coverage, as NVIDIA's 8 multisamples x 2 supersamples do */
    OIT_CAPTURE_FAULT_SAMPLE_SHADING = 1u << 0,
    /* not a fault but a stand-in: the routed fills put each fragment in
     * the sample stencil routing would (capture_stencil.h, by_copy)
     * without the stencil, so that a driver that does not route
     * (llvmpipe) passes the self-test and renders the stencil paths
     * exactly; only the routing draw itself is left untested there */
    OIT_CAPTURE_TEST_ROUTE_BY_COPY = 1u << 1,
    /* the compute capture's tile lists one entry long, never grown: every
     * tile takes the path of an overflowed list */
    OIT_CAPTURE_TEST_COMPUTE_LIST_SHORT = 1u << 2,
    /* the compute capture takes the driver for one that runs loops to
     * their end (no read-back of the sweep's pending pixels) */
    OIT_CAPTURE_TEST_COMPUTE_NO_PROBE = 1u << 3
};

/* The settings a capture takes for every frame, given at creation
 * (oit_capture_desc.settings) and changed between frames with
 * oit_capture_apply; zero fields mean the default. The image is the same
 * whatever the budgets, limits and no_wait. */
struct oit_gpu_timer;
typedef struct oit_capture_settings {
    /* Early termination (DESIGN.md): a pixel whose carried transmittance
     * is below epsilon in every channel drops its fragments, so the image
     * differs from the exact one by at most epsilon per channel. 0 (a
     * negative reads as 0) keeps the image exact. */
    float epsilon;
    /* The array backend's slots grow to K for each pixel of the largest
     * batch rectangle so far, and to one output value a pixel of the
     * frame, at most K slots for every pixel (K x 16 bytes a pixel: 128 MiB
     * at 1024x1024, K = 8); they then take at most slot_budget bytes (at
     * least one row of K): a frame whose full slots exceed it captures
     * every batch in screen tiles that fit, one draw of the batch per tile,
     * and writes its output into the idle slots. 0: no limit. */
    uint64_t slot_budget;
    /* The most bytes the counted and first-K captures' fragment stores
     * take: counted's store (a batch whose fragments pass it is stored in
     * bands of rows) with its predictions, and first-K's second pass store
     * (whose first bytes are its slots, which slot_budget bounds). Apart
     * from the slot budget because a deep view's bands each draw the pack
     * again, while first-K's slots are cleared and resolved every frame
     * whatever they hold. 0: slot_budget's. */
    uint64_t store_budget;
    /* The most bytes the counted, first-K and compute captures put in one
     * storage buffer: what is stored past it is taken in pieces (a batch's
     * meshes in halves, then one mesh's rows in bands, as first-K's second
     * pass). 0: what this driver binds (GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
     * lower only to test those pieces. */
    uint64_t store_limit;
    /* GPU phases are marked on timer (view/render/gl/gpu_timer.h; NULL: none),
     * which the capture does not own. */
    struct oit_gpu_timer *timer;
    /* OIT_CAPTURE_FIRSTK: 1 drives first-K's second pass on the GPU, so
     * that the host never waits within a frame (oit_frame_stats.host_waits):
     * the pass-2 store is sized ahead from what earlier frames' packs
     * needed (at least what the slots hold; the first frame's, what they
     * hold), the GPU decides where pass 2 runs, if at all (indirect
     * dispatches, draws of 0 instances). A pack that needs more than the
     * store holds leaves pixels out: the frame ends short
     * (oit_capture_short) and must be drawn again, which the measured need
     * then fits, within the slot budget and one storage binding (past them
     * the host splits pass 2 in bands as with 0). 0: the host reads each
     * pack's overflow back and sizes pass 2 exactly; never short.
     * OIT_CAPTURE_COUNTED (and first-K's counted packs) likewise, from the
     * second frame on: each batch's store sized ahead from the most an
     * earlier frame's batch took, opened by a judge on the GPU; a batch
     * that needs more ends the frame short (capture_counted.h). */
    int no_wait;
    /* OIT_CAPTURE_FIRSTK: 0 has the first frame of a view (oit_view_key)
     * keep its pass 1 counts, so that a counted frame of the same view
     * after it is predicted from them (capture_counted.h) instead of
     * counted first; 1 keeps none (a copy of the counts a batch, for at
     * most OIT_COUNTED_PREDICTED_BATCHES batches, saved). The streamer's
     * automatic mode keeps them where its rule suggests counted next. */
    int no_counts;
} oit_capture_settings;

/* A capture, resolved once at oit_capture_create from two independent
 * axes, the K-slot fill and the cut its batches come in (liboit's modes,
 * oit/render_modes.h); zero fields mean the default (but K):
 *   fill \ cut     BUDGET, DISJOINT    COUNTED            FIRSTK, AUTO (0)
 *   ARRAY           array               counted            first-K
 *   STENCIL         stencil             refused            first-K, routed
 *   AUTO (0)        stencil or array    counted            first-K, routed or not
 *   COMPUTE         compute             compute            compute
 * Where AUTO may route, stencil routing is taken where its self-test
 * passes (capture_choice.h: at K for K-slot batches; first-K also takes
 * the largest power of two below K that passes), else array slots, the
 * reason kept (oit_capture_get_choice). STENCIL where no try passes:
 * OIT_ERR_GL (the driver's limit) with the reason, the sample mode's numbers where it
 * is that (and the largest K of true multisamples where the driver
 * tells). */
typedef struct oit_capture_desc {
    oit_render_capture fill;
    oit_render_pack cut;
    int K; /* OIT_CAPTURE_K_MIN..OIT_CAPTURE_K_MAX */
    /* Testing: the samples a pixel the fill is routed into, exactly, after
     * the self-test passed at that count (no choice, no fallback): fill
     * STENCIL only; K for K-slot batches, 2..K for first-K's first pass
     * (capture_firstk.h), which keeps a pixel's first stencil_k fragments
     * in the samples while it counts every fragment (pixels that got more
     * take the second pass, as with array slots; the target holds
     * stencil_k samples of the whole frame, outside the slot budget: 20
     * bytes a sample, 160 MiB at 1024x1024, 8 samples). 0: chosen. */
    int stencil_k;
    unsigned faults; /* testing: OIT_CAPTURE_FAULT_* and _TEST_* above */
    /* The capture's programs are built through programs
     * (view/render/gl/program_cache.h; NULL: compiled), which must outlive it. */
    oit_program_cache *programs;
    /* How the errors name fill and cut, in the caller's spelling
     * ("oit_renderer_desc.capture"); NULL: "capture fill", "capture cut". */
    const char *fill_name, *cut_name;
    oit_capture_settings settings;
} oit_capture_desc;

oit_status oit_capture_create(const oit_capture_desc *desc, oit_capture **out, oit_error *err);

/* The samples of c's routed fills; 0: none (array slots). */
int oit_capture_routed_k(const oit_capture *c);
/* What oit_capture_create chose for the fill (capture_choice.h): asked,
 * the slots that run (AUTO where no K-slot fill does: counted, compute),
 * the samples routed, the self-test's reason where AUTO fell back. */
struct oit_capture_choice;
const struct oit_capture_choice *oit_capture_get_choice(const oit_capture *c);
/* "array", "stencil", "counted", "first-k", "compute" (NULL for AUTO or
 * unknown). */
const char *oit_capture_kind_name(oit_capture_kind kind);
void oit_capture_destroy(oit_capture *c);
oit_capture_kind oit_capture_backend(const oit_capture *c);

/* The caller's opaque depth (frag_glsl.h, oit_opaque_depth) from the next
 * oit_capture_begin on; NULL: none (the default). Fragments behind it are
 * neither counted nor stored; the texture must be bound at unit
 * OIT_TEX_OPAQUE_DEPTH while the frame is captured. */
void oit_capture_set_opaque(oit_capture *c, const oit_opaque_depth *o);

/* The GL buffer of the frame's width*height per-pixel states (packed as
 * frag_glsl.h's oit_glsl_state_io reads them, in the frame's shading; GL
 * rows, bottom first), for passes that read the carried transmittance
 * between batches (saturation.h). Valid until the next oit_capture_begin. */
unsigned oit_capture_state_buffer(const oit_capture *c);

/* GL draw calls made for geometry since the frame's oit_capture_begin: the
 * meshes of a batch are drawn with oit_gpu_mesh_draw_many, once per fill
 * (twice for the counted capture: count and store; once per tile when
 * tiled; first-K: once, and once more per band where pixels overflowed),
 * a multi-draw counting 1. */
uint64_t oit_capture_draw_calls(const oit_capture *c);

/* c's settings (oit_capture_desc.settings as given, or as last applied). */
oit_capture_settings oit_capture_get_settings(const oit_capture *c);
/* settings for every frame from the next oit_capture_begin on (epsilon:
 * from the next batch on). */
void oit_capture_apply(oit_capture *c, const oit_capture_settings *settings);

/* OIT_CAPTURE_FIRSTK only: 0 captures every batch from the next one on as
 * OIT_CAPTURE_COUNTED does (count, store, sort: no slots), 1 (the default)
 * goes back to first-K. Deep views overflow most pixels' slots and pay both
 * passes of first-K and then the store again; counted packs pay two passes
 * whatever the depth. The streamer's automatic mode switches by the
 * frame's figures (streamer.h). The image is the same either way. */
void oit_capture_set_first_k(oit_capture *c, int on);

/* OIT_CAPTURE_FIRSTK, after a frame: the counted capture built and sized
 * for that frame's fragments, for a next frame drawn counted
 * (oit_capture_set_first_k 0) to start warm and without waits; nothing
 * once counted packs have been measured, or for other captures. */
void oit_capture_ready_counted(oit_capture *c);
/* 1 when the frame that oit_capture_end or _end_gpu just ended is short
 * (oit_capture_settings.no_wait): its image is not exact, draw it again. */
int oit_capture_short(const oit_capture *c);

/* Bytes a pixel of v takes in the capture's largest per-pixel buffer that
 * must hold the whole frame in one storage binding: its state (shade.h),
 * carried across batches. What else it stores past one binding it takes in
 * pieces (tiles, bands of rows); a frame whose state does not fit is
 * refused by oit_capture_begin, to be rendered in bands (view/render/gl/band.h). */
uint64_t oit_capture_pixel_bytes(const oit_view *v);

/* The frame's count of the host's waits on the GPU (view/render/gl/host_wait.h),
 * zeroed by oit_capture_begin, reported as oit_frame_stats.host_waits: the
 * caller counts its own waits within the frame on it. */
struct oit_host_waits;
struct oit_host_waits *oit_capture_host_waits(oit_capture *c);

/* Starts a frame: C = 0, T = 1, translucency state cleared. */
oit_status oit_capture_begin(oit_capture *c, const oit_view *view, oit_error *err);
/* Captures meshes[0..n) as one batch and composites it behind what the frame
 * already holds. rect = {x0, y0, x1, y1} in pixels, row 0 at the top, x1/y1
 * exclusive; NULL means the whole frame. */
oit_status oit_capture_batch(oit_capture *c, const oit_gpu_mesh *const *meshes,
                             int n, const int rect[4], oit_error *err);
/* The widest batch oit_capture_batch_layers takes. */
#define OIT_CAPTURE_MAX_LAYERS 64

/* As oit_capture_batch for a batch that may give up to `layers` fragments
 * per pixel. layers <= K is an ordinary batch. A wider one (a wide part,
 * prepare/partition/kd.h) is captured in screen tiles small enough that `layers`
 * slots per pixel fit the frame's K slots per pixel: the same bytes, one
 * extra draw of the batch per tile. Exact as long as no pixel gets more than
 * `layers` (overflow counts it as usual). Both backends use array slots for
 * it. */
oit_status oit_capture_batch_layers(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                                    const int rect[4], int layers, oit_error *err);
/* Resolves the frame into out and fills stats. out is empty ({0}: the call
 * allocates it) or holds an image of the frame's size, whose pixels are
 * written in place and which the call never frees (oit_image_reserve). */
oit_status oit_capture_end(oit_capture *c, oit_image *out,
                           oit_frame_stats *stats, oit_error *err);
/* oit_capture_end that also writes each pixel's fragment count (those its
 * state took: oit_frame_stats.fragments pixel by pixel) into counts,
 * width*height, row 0 at the top; NULL: none. */
oit_status oit_capture_end_counts(oit_capture *c, oit_image *out, uint32_t *counts,
                                  oit_frame_stats *stats, oit_error *err);
/* Ends the frame without reading the image back: *state receives the GL
 * buffer holding width*height per-pixel states (oit_glsl_state_io reads
 * them: C and T before the background; GL rows, bottom first), owned by c
 * and valid until the
 * next oit_capture_begin. Only the 16-byte totals are read back for stats. */
oit_status oit_capture_end_gpu(oit_capture *c, unsigned *state, oit_frame_stats *stats,
                               oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
