/* liboit's figures of a draw (oit_renderer_draw, _draw_image, _draw_pixels)
 * and of its GPU time (oit_renderer_gpu_poll): plain structs, included by
 * oit/liboit.h, which documents the calls that fill them. */
#ifndef OIT_DRAW_STATS_H
#define OIT_DRAW_STATS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_DRAW_GPU_PHASES 8

/* One draw's figures. Grouped by concept: the call and its time, the
 * fragments, the parts, the packs and their capture, the per-view choices,
 * the GPU memory, the shading. An in-core scene fills those
 * oit_renderer_draw names; the rest are 0 (NULL for strings). The strings
 * are liboit's, static or valid while the renderer draws the scene. */
typedef struct oit_draw_stats {
    /* ---- the call ---- */
    /* This draw's number (1: the renderer's first oit_renderer_draw or
     * oit_renderer_draw_image), which its GPU figures carry
     * (oit_renderer_gpu_poll, gpu_frame below). */
    uint64_t draw;
    double ms;               /* wall time of the call; the capture is finished
                                (its totals are read back), the final blend not */
    /* What drew: the method (oit_renderer_desc.method resolved) and the
     * device, the GL renderer's string ("llvmpipe (LLVM 15.0.6, 256 bits)")
     * or the reference's ("Embree 3.13.5 (CPU reference)"). */
    const char *method, *device;
    /* GPU time from GL timestamp queries, read without waiting: the figures
     * of draw number gpu_frame (usually an earlier call than this one), 0
     * and gpu_ms -1 when none is in yet or the driver has no timestamps.
     * Phases, in this order: other, upload (ring to cache copies), pass 1,
     * pass 2, resolve, read-back, binning and sweep (the compute capture,
     * OIT_RENDER_CAPTURE_COMPUTE); they add up to gpu_ms. */
    uint64_t gpu_frame;
    double gpu_ms;
    double gpu_phase_ms[OIT_DRAW_GPU_PHASES];
    /* host_waits: the times the host waited on the GPU between the draw's
     * first command and its final read-back (buffer read-backs, fences
     * that blocked; the final read-back not counted), 0 on warm draws of
     * the default packs. redraws: the times the draw was captured again
     * because a store sized ahead of the GPU's need proved short (the
     * figures are the last capture's, the image exact). */
    uint32_t host_waits, redraws;

    /* ---- fragments ---- */
    uint64_t fragments;
    uint32_t max_layers;      /* most fragments on one pixel in one pack        */
    /* The reference with a threshold (oit_renderer_desc.epsilon): fragments
     * behind pixels already saturated; 0 for every other method. */
    uint64_t fragments_saturated;
    uint64_t overflow_pixels; /* > K fragments in a K-slot pack: 0 for a
                                 correct file                                   */
    /* First-K or counted packs: the pixels that got more than capture_k
     * fragments in one pack (first-K: more than its slots), summed over
     * the packs. First-K's second pass took exactly these
     * (second_pass_pixels; second_pass_packs: the packs that had any, so
     * took a second geometry pass); counted packs count them from their
     * counts. OIT_RENDER_PACK_AUTO's rule suggests counted packs where any
     * did, first-K where none did. */
    uint64_t deep_pixels;
    uint64_t second_pass_pixels;
    uint32_t second_pass_packs;

    /* ---- parts ---- */
    uint64_t parts_drawn;
    uint64_t parts_culled;
    uint64_t parts_skipped;  /* epsilon > 0: footprint saturated, not drawn;
                                with depth_texture: also parts whose box lies
                                wholly behind it over their screen rectangle
                                (neither uploaded nor drawn; same image)      */
    uint64_t parts_clipped;  /* parts in view wholly cut away by
                                oit_frame.clip: neither uploaded nor drawn    */
    uint64_t bytes_clipped;  /* the upload bytes of those parts              */
    uint64_t bytes_uploaded; /* part bytes written for the GPU in this call    */
    uint64_t cache_hits;     /* parts drawn from the cache, not uploaded again */
    uint64_t cache_bytes;    /* bytes resident in the cache after the call     */
    uint64_t draw_calls;     /* GL geometry draws; a pack's parts go in one
                                multi-draw per run from the ring or the cache */
    uint32_t reader_threads; /* the threads that read parts (0: the drawing
                                thread)                                        */
    uint32_t resident;       /* the scene is read once into the ring and kept
                                (oit_renderer_desc.upload_budget)              */

    /* ---- packs and their capture ---- */
    uint32_t packs;
    /* Capture batches: packs, more where a pack's fragments overran the
     * capture's store (oit_renderer_desc.slot_budget) and it was captured
     * in several; for an in-core scene, DFB's bands. predicted_batches:
     * counted packs drawn at the offsets the last draw's counts of the same
     * view gave (one geometry pass where the view held still, a second for
     * the pixels whose fragments it did not hold), not counted first. */
    uint32_t batches, predicted_batches;
    /* The capture that ran ("counted", "first-k", "array", "stencil",
     * "compute"; the last pack's) and capture_k its K; capture_asked:
     * oit_renderer_desc.capture as given ("auto", "stencil", "array",
     * "compute"). */
    const char *capture;
    uint32_t capture_k;
    const char *capture_asked;
    /* How the K-slot fills were made: "stencil" (capture_slots_k samples a
     * pixel) or "array"; NULL where none ran (counted packs).
     * capture_fallback: where AUTO took array slots or fewer samples than
     * K, the self-test's reason, else "". */
    const char *capture_slots;
    uint32_t capture_slots_k;
    const char *capture_fallback;

    /* ---- the view's choices ---- */
    /* CPU milliseconds of the parts' visibility order and of their
     * packing, the per-view work that does not wait for GL. */
    double order_ms, pack_ms;
    /* auto_first_k: OIT_RENDER_PACK_AUTO took first-K packs (0: counted
     * ones, or a fixed pack). front_first: the packs were cut front first
     * (epsilon > 0 with counted or first-K packs). */
    uint32_t auto_first_k, front_first;
    /* OIT_RENDER_PACK_AUTO's choice of packs for this draw (NULL and -1
     * with a fixed pack, a compute capture or an in-core scene): choice the
     * path taken, "first-k" or "counted"; choice_why why ("seed": the first
     * draw; "new view": the view changed, so the last view's path with no
     * figures; "held"; "probe": tried for one draw, as a fixed rule
     * suggests (deep_pixels above 0 suggests counted, 0 suggests first-K;
     * counted draws over K try first-K every 256th draw), kept only if it
     * measures faster (a path that lost is not tried again on any view for
     * 8, 16, ... 256 draws); "kept: measured faster", "back: measured
     * slower", "measured faster"); and each path's cost as measured on this
     * view before the draw, the least wall time of its draws (where both
     * paths have GPU figures: the least over its draws of each one's larger
     * of wall and GPU time), -1 where not measured. */
    const char *choice, *choice_why;
    double choice_first_k_ms, choice_counted_ms;

    /* ---- GPU memory (bytes) ---- */
    uint64_t gpu_bytes_peak; /* all the GPU memory the call held at its peak:
                                a part file's capture and per-pixel state,
                                upload ring, cache and tiles together; an
                                in-core scene's buffers and its mesh       */
    uint64_t gpu_mesh_bytes; /* of that, an in-core scene's mesh (0 for part
                                files, whose parts are in the ring and cache) */
    /* The memory the renderer chose for a part file: the total (0: none),
     * its split (store_budget: 0 for packs without a store), the driver's
     * free memory (0: it reports none), and where the total came from:
     * budget_source "oit_renderer_desc.gpu_budget" where given, else the
     * driver's figure ("GL_NVX_gpu_memory_info", "GL_ATI_meminfo") or why
     * there is none. */
    uint64_t gpu_budget, ring_budget, cache_budget, capture_budget, store_budget;
    uint64_t gpu_free_bytes;
    const char *budget_source;

    /* ---- the shading ---- */
    /* see_through is oit_renderer_desc.see_through; opaque is 1 when the
     * scene's opaque triangles hid what is behind them (transparent
     * shading, not see-through, a scene with opaque triangles): fragments
     * behind them were neither stored nor counted. */
    uint32_t see_through, opaque;
} oit_draw_stats;

/* One draw's GPU time (oit_draw_stats.gpu_ms alike): its number
 * (oit_draw_stats.draw), the total and the phases. */
typedef struct oit_draw_gpu {
    uint64_t draw;
    double ms;
    double phase_ms[OIT_DRAW_GPU_PHASES];
} oit_draw_gpu;

#ifdef __cplusplus
}
#endif
#endif
