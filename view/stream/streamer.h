/* The per-frame driver of the part-file renderer: order the parts for the
 * eye (partfile/order.h), cut the order into packs (pack.h), and per pack get its
 * parts onto the GPU and capture them as one batch (view/render/capture/capture.h),
 * composited behind the packs before it.
 *
 * Upload pipeline. The order is known before the first draw, so packs are
 * prepared ahead: the render thread decides each part's source (skipped:
 * its footprint is saturated; cached: resident from an earlier frame,
 * residency.h; otherwise read), reserves the read parts a region of the
 * persistently mapped ring (upload.h) and queues them to the reader thread
 * (reader.h), which validates and expands them into the ring while the GPU
 * draws earlier packs. Draws collect packs in order; a part read in this
 * frame is copied on the GPU into the residency cache when it finds room
 * there. Requires a current GL context for its whole life, on the thread
 * that calls every function here. */
#ifndef OIT_STREAM_STREAMER_H
#define OIT_STREAM_STREAMER_H

#include "oit/partfile.h"
#include "partfile/order.h"
#include "partfile/share.h"
#include "view/render/capture/capture.h"
#include "view/render/capture/capture_choice.h"
#include "view/render/gl/gpu_memory.h"
#include "view/stream/pack.h"
#include "view/stream/reader.h"

/* The names a caller spells oit_streamer_desc's fields in, for the
 * streamer's errors and figures (liboit's: "oit_renderer_desc.upload_budget";
 * cache_off spells OIT_STREAM_CACHE_OFF, "OIT_RENDER_CACHE_OFF"). A NULL
 * name: the streamer's own ("oit_streamer_desc.upload_budget"). */
typedef struct oit_streamer_names {
    const char *upload_budget, *slot_budget, *cache_budget, *gpu_budget, *epsilon, *pack,
        *schedule, *cache_off, *store_budget, *capture;
} oit_streamer_names;

/* names with every NULL one (or all, names NULL) the streamer's own. */
oit_streamer_names oit_streamer_names_resolve(const oit_streamer_names *names);

typedef struct oit_streamer_desc {
    int K;                    /* capture layers, 2..16; every part's bound <= K */
    /* How K-slot fills are made (oit/render_modes.h):
     * OIT_RENDER_CAPTURE_AUTO (0), _STENCIL or _ARRAY, for the K-slot packs
     * (BUDGET, DISJOINT) and for first-K's first pass (FIRSTK, AUTO);
     * counted packs have none (STENCIL is then refused). AUTO: stencil
     * routing where its self-test passes on this driver
     * (view/render/capture/capture_choice.h: at K for K-slot packs; first-K also
     * takes the largest power of two below K that passes), else array
     * slots, the self-test's reason kept (oit_stream_frame_stats). STENCIL
     * where no try passes: OIT_ERR_GL (the driver's limit) with the reason.
     * OIT_RENDER_PACK_COUNTED always takes the capture OIT_CAPTURE_COUNTED,
     * OIT_RENDER_PACK_FIRSTK OIT_CAPTURE_FIRSTK (K: its most slots a
     * pixel). OIT_RENDER_CAPTURE_COMPUTE (view/render/capture/capture_compute.h)
     * captures the packs of BUDGET, DISJOINT and COUNTED, exactly (no
     * per-pixel limit); with OIT_RENDER_PACK_AUTO it takes
     * OIT_RENDER_PACK_COUNTED's, the largest; FIRSTK, whose first pass is a
     * K-slot fill, is refused (oit_streamer_desc_check) */
    oit_render_capture capture;
    unsigned capture_faults;  /* testing: OIT_CAPTURE_FAULT_* and _TEST_* (capture.h) */
    /* where the capture's programs are built through (the caller's, which
     * outlives the streamer: view/render/gl/program_cache.h); NULL: compiled */
    oit_program_cache *programs;
    /* OIT_RENDER_PACK_AUTO (0): first-K or counted packs, as this process measured
     * them on each view (view/stream/choice.h): first-K first; counted tried for
     * a frame when any pixel took the second pass, first-K again from
     * counted, each kept only where it measured faster (the
     * image is the same either way). With early termination the counted and first-K
     * packs are cut front first (oit_packer_set_front_first), so that
     * saturated tiles can skip the parts behind them */
    oit_render_pack pack;
    oit_render_schedule schedule; /* 0: the tree's order (pack.h) */
    uint64_t upload_budget;   /* ring bytes at most; 0: OIT_STREAM_RING_DEFAULT
                                 (or the total's share); never more than
                                 the file's parts take (at least
                                 OIT_STREAM_RING_MIN). The ring starts at
                                 OIT_STREAM_RING_MIN and grows between frames to
                                 what a frame reads, as far as consecutive packs
                                 use it.
                                 A file within it and the cache budget is read
                                 once into the ring, every part at a home of its
                                 own, and drawn from there (cache_hits): no cache
                                 buffer beside it */
    uint64_t slot_budget;     /* capture slot bytes (oit_capture_settings);
                                 0: OIT_STREAM_FIRSTK_SLOTS_DEFAULT for counted
                                 and first-K packs, else OIT_STREAM_SLOTS_DEFAULT */
    uint64_t store_budget;    /* counted and first-K fragment store bytes
                                 (oit_capture_settings); 0:
                                 OIT_STREAM_STORE_DEFAULT, or an eighth of a
                                 smaller total; unused by other packs */
    float epsilon;            /* early termination (oit_capture_settings), in
                                 [0, 1); 0: exact */
    uint64_t cache_budget;    /* residency cache bytes at most; 0:
                                 OIT_STREAM_CACHE_DEFAULT; OIT_STREAM_CACHE_OFF:
                                 no cache. Made at the first frame and grown
                                 (geometrically, dropped and refilled) to the
                                 parts a frame's packing holds */
    int reader_threads;       /* threads that read and decode parts ahead of the
                                 GPU (reader.h), 1..OIT_READER_MAX_THREADS; 0:
                                 the cores there are, less one (the render
                                 thread's), at least 1; OIT_STREAM_READ_INLINE:
                                 none, parts are read on the render thread (for
                                 comparison and debugging) */
    uint64_t store_limit;     /* the capture's (oit_capture_settings); 0:
                                 the driver's binding; lower only to test */
    /* One total for the ring, the cache and the capture together
     * (oit_stream_budget has the split); 0: OIT_STREAM_FREE_SHARE of the
     * free GPU memory the driver reports, or, where it reports none,
     * no total (the defaults above, as before). At least
     * OIT_STREAM_GPU_BUDGET_MIN. The finer budgets above stay inside it:
     * given ones that add up to more are refused. */
    uint64_t gpu_budget;
    /* The free-memory query (view/render/gl/gpu_memory.h); NULL: the driver's.
     * Tests inject a fake driver here. */
    oit_gpu_free_query free_query;
    void *free_ctx;
    /* Sort-last rendering (partfile/share.h): share_count 0 or 1 (default),
     * every part; 2..OIT_SHARES_MAX, only the parts of share share_index
     * (< share_count) are ordered, read and drawn, and the ring and cache
     * are sized by that share's bytes. The frame's C and T are then the
     * share's, to be blended with the other shares' in the order
     * oit_streamer_share_order gives. */
    uint32_t share_count, share_index;
    /* The frames the caller expects to draw: 1, a one-image run, where
     * OIT_RENDER_PACK_AUTO starts with counted packs (stored exactly, as DFB
     * stores a frame) instead of first-K ones, whose K-slot store (up to
     * the slot budget, 64 MiB at 1024x1024) only later frames amortize: the
     * demo's one-image run at 1024x1024 on llvmpipe, 0.70 s against 0.93 s;
     * 0 (default): many. A hint: any number of frames may be drawn. */
    uint32_t frames;
    /* How the errors and figures name the fields above (static, or
     * outliving the streamer); NULL: the streamer's own names. */
    const oit_streamer_names *names;
} oit_streamer_desc;

/* Half the free memory the driver reports: the rest is the embedding
 * application's (its own geometry, textures, framebuffers), the driver's
 * and other processes', and room for fragmentation; half of an H200's
 * 139 GB holds every model we have resident, where the fixed 256 MiB
 * cache made the 12M plant (580 MB) stream every frame. */
#define OIT_STREAM_FREE_SHARE_NUM 1
#define OIT_STREAM_FREE_SHARE_DEN 2
#define OIT_STREAM_GPU_BUDGET_MIN (1ull << 20)

/* The memory a streamer chose, readable back (oit_streamer_budget). */
typedef struct oit_stream_budget {
    uint64_t total;      /* ring + cache + capture at most; 0: no total */
    uint64_t ring;       /* the upload ring's limit */
    uint64_t cache;      /* the residency cache's limit (0: none, or resident) */
    uint64_t capture;    /* the capture's slot budget (its per-pixel buffers
                            are taken from the cache's share frame by frame) */
    uint64_t store;      /* the capture's fragment store budget; 0: none (packs
                            other than counted and first-K) */
    uint64_t free_bytes; /* what the driver reported free; 0: nothing */
    const char *source;  /* the gpu_budget field's name (oit_streamer_names:
                            given), "GL_NVX_gpu_memory_info", "default", ... */
    int resident;        /* every part read once and kept */
} oit_stream_budget;

/* 256 MiB: ~5.6 M triangles at 48 bytes, the visible working set of most
 * views of multi-million-triangle models, and a small share of any GL 4.5
 * GPU. The buffer grows to what the frames draw, never beyond the file's
 * own part bytes, so small files and narrow views pay only for what they
 * hold. */
#define OIT_STREAM_CACHE_DEFAULT (256ull << 20)
#define OIT_STREAM_CACHE_OFF UINT64_MAX
/* Slot budgets: 64 MiB of first-K slots (4 fragments a pixel at
 * 1024x1024), 32 MiB of K-slot array slots. */
#define OIT_STREAM_FIRSTK_SLOTS_DEFAULT (64ull << 20)
#define OIT_STREAM_SLOTS_DEFAULT (32ull << 20)
/* The fragment store's: grown to what a frame stores, no further. A deep
 * view past it is stored in bands of rows, each drawing the pack again:
 * at 64 MiB, oitgen's hard stack case at 1024x1024 took 44 bands and
 * 19-20 s a frame on llvmpipe, at 256 MiB 22 (one binding each there)
 * and 13.4 s, against DFB's 17.4 (bench/never-slower-llvmpipe.md). The
 * room past one binding holds the counted batches' predictions. */
#define OIT_STREAM_STORE_DEFAULT (256ull << 20)
#define OIT_STREAM_PROBE_FRAMES 8u
/* The ring when no total splits the memory, and a total's most for it: it
 * only has to hold consecutive packs, and 64 MiB hold the largest packs of
 * the 12M plant (bench/stream-vs-dfb-llvmpipe.md). */
#define OIT_STREAM_RING_DEFAULT (64ull << 20)
#define OIT_STREAM_RING_MIN (64ull << 10)
#define OIT_STREAM_READ_INLINE (-1)
/* The range a caller may give each byte budget (oit_streamer_desc_check):
 * 64 KiB, the least ring (smaller budgets only split every pack; tests
 * drive smaller rings into oit_streamer_create directly), up to 1 TiB. */
#define OIT_STREAM_BUDGET_MIN OIT_STREAM_RING_MIN
#define OIT_STREAM_BUDGET_MAX (1ull << 40)

/* The one range check of the settings a caller gives (every zero is the
 * default): upload_budget, slot_budget and store_budget 0 or
 * OIT_STREAM_BUDGET_MIN..MAX,
 * cache_budget that or OIT_STREAM_CACHE_OFF, gpu_budget 0 or
 * OIT_STREAM_GPU_BUDGET_MIN..OIT_STREAM_BUDGET_MAX, epsilon in [0, 1), pack
 * and schedule one of their enums, capture COMPUTE not with pack FIRSTK
 * (no K-slot first pass). OIT_ERR_ARGUMENT names the setting (in
 * d->names' spelling) and the value. capture and
 * reader_threads are checked by oit_streamer_create (capture_choice.h,
 * reader.h), K by the capture. */
oit_status oit_streamer_desc_check(const oit_streamer_desc *d, oit_error *err);

/* The streamer's own per-frame figures, beside oit_frame_stats. */
typedef struct oit_stream_frame_stats {
    uint32_t packs;          /* captured (a pack whose parts were all skipped is not) */
    uint64_t parts_drawn;
    uint64_t parts_culled;   /* boxes outside the view volume: no fragment */
    uint64_t parts_clipped;  /* boxes in the view volume wholly on the removed
                                side of a section plane (view/render/image/clip.h):
                                neither uploaded nor drawn */
    uint64_t bytes_clipped;  /* the upload bytes those parts would take      */
    uint64_t parts_skipped;  /* epsilon > 0: footprint saturated (view/render/capture/saturation.h),
                                neither uploaded nor drawn */
    uint64_t bytes_uploaded; /* part bytes the CPU wrote into the upload ring,
                                read-ahead of parts then skipped included  */
    uint64_t cache_hits;     /* parts drawn from the residency cache        */
    uint64_t cache_bytes;    /* bytes resident in the cache after the frame */
    uint64_t gpu_bytes_peak; /* capture buffers and textures (per-pixel
                                state, multi-draw commands too) + upload
                                ring + cache + saturation and opaque tiles +
                                the parts' draw records                     */
    uint64_t draw_calls;     /* GL draw commands for geometry (a multi-draw
                                is 1): oit_capture_draw_calls                */
    /* CPU milliseconds of the per-view work that does not wait for GL: the
     * visibility order of the parts and their packing. On a GPU fast
     * enough to hide the rest, these bound the frame rate. */
    double order_ms, pack_ms;
    float epsilon;           /* the early-termination threshold it ran with */
    int first_k;             /* the automatic mode took first-K packs (else
                                counted, or a fixed pack: 0) */
    /* The automatic mode (view/stream/choice.h): the path it took ("first-k",
     * "counted"), why ("seed", "held", "probe", ...: oit_choice.why), and
     * the costs per path (oit_path) it chose from, measured on this view
     * before the frame (-1: not measured; both -1 with a fixed pack,
     * the strings NULL). */
    const char *choice_path, *choice_why;
    double choice_ms[2];
    int front_first;         /* the packs were cut front first (pack.h): early
                                termination with counted or first-K packs */
    /* desc.capture as asked ("auto", "stencil", "array") and, where auto took
     * array slots or fewer samples than K, the self-test's reason ("" where
     * it did not), copied: the figures outlive the streamer. What ran:
     * oit_frame_stats's capture_slots. */
    const char *capture_asked;
    char capture_fallback[sizeof(((oit_capture_choice *)0)->reason)];
    oit_stream_budget budget; /* the memory the streamer chose (split_budget) */
    int reader_threads;      /* threads reading parts (0: the render thread) */
} oit_stream_frame_stats;

typedef struct oit_streamer oit_streamer;

/* pf must outlive the streamer; parts are validated on first use, so pf may
 * be opened with defer_part_data. */
oit_status oit_streamer_create(oit_partfile *pf, const oit_streamer_desc *desc,
                               oit_streamer **out, oit_error *err);
void oit_streamer_destroy(oit_streamer *s);
/* What desc.capture chose at creation (its reason string lives as long as s). */
const oit_capture_choice *oit_streamer_capture_choice(const oit_streamer *s);
void oit_streamer_budget(const oit_streamer *s, oit_stream_budget *out);
/* The descriptor s runs with, every default resolved: pack (AUTO stays
 * AUTO: it switches between FIRSTK and COUNTED frame by frame), capture
 * (what K-slot fills use: ARRAY or STENCIL; COUNTED and FIRSTK packs have
 * none: AUTO), the ring, cache (OIT_STREAM_CACHE_OFF: none, or resident),
 * slot and GPU budgets (0: no total) of oit_streamer_budget, reader_threads
 * (OIT_STREAM_READ_INLINE: the render thread) and epsilon; the rest as
 * given. */
void oit_streamer_resolved_desc(const oit_streamer *s, oit_streamer_desc *out);

/* The caller's opaque depth for the next frames (oit_capture_set_opaque);
 * NULL: none. */
void oit_streamer_set_opaque(oit_streamer *s, const oit_opaque_depth *o);

/* GPU phases of the next frames are marked on t (view/render/gl/gpu_timer.h):
 * the ring's parts copied into the residency cache as uploads, the
 * capture's passes as it marks them; NULL: none. Not owned. */
struct oit_gpu_timer;
void oit_streamer_set_gpu_timer(oit_streamer *s, struct oit_gpu_timer *t);

/* Bytes a pixel of view takes in the streamer's largest per-pixel buffer
 * (oit_capture_pixel_bytes): a frame past one storage binding is refused,
 * to be rendered in bands of rows (view/render/gl/band.h). */
uint64_t oit_streamer_pixel_bytes(const oit_view *view);
/* acc takes the figures of a band of its frame: counts, bytes and times add
 * up, the GPU peak takes the larger, the rest (cache_bytes, epsilon, modes)
 * are the band's, the last. */
void oit_stream_frame_stats_add(oit_stream_frame_stats *acc, const oit_stream_frame_stats *band);

/* The shares front to back for view (partfile/share.h, oit_shares_order):
 * share_count indices into order; with share_count <= 1, just 0. Every
 * streamer over the same file and share_count gives the same order. */
oit_status oit_streamer_share_order(oit_streamer *s, const oit_view *view, uint32_t *order,
                                    oit_error *err);
/* The same without a streamer (no GL; liboit's oit_scene_share_order):
 * order over the file that shares cut, scratch a part count of uint32_t,
 * out oit_shares_count(shares) indices. */
oit_status oit_shares_view_order(oit_order *order, oit_shares *shares, const oit_view *view,
                                 uint32_t *scratch, uint32_t *out, oit_error *err);
/* Parts and triangles of the streamer's share (all the file's without one). */
void oit_streamer_share_size(const oit_streamer *s, uint32_t *parts, uint64_t *triangles);

/* The frame rendered last ended (its image is in the caller's hands) after
 * wall_ms, from the caller's start of it; its GPU timer figure will come
 * as frame gpu_tag (0: none). The automatic pack mode judges a
 * render_gpu frame on that time (without this call: on the streamer's own
 * time, at the next render); oit_streamer_render's frames end with their
 * read-back and are judged on their own time, so for them this only tags
 * the GPU figure. */
void oit_streamer_frame_end(oit_streamer *s, double wall_ms, uint64_t gpu_tag);
/* GPU timer frame gpu_tag took gpu_ms (gpu_timer.h); the automatic mode
 * weighs it beside the wall times (view/stream/choice.h). */
void oit_streamer_gpu_figure(oit_streamer *s, uint64_t gpu_tag, double gpu_ms);

/* Renders one view into out: empty ({0}: allocated by the call) or an
 * image of the view's size, written in place (oit_capture_end). fs and ss
 * may be NULL. */
oit_status oit_streamer_render(oit_streamer *s, const oit_view *view, oit_image *out,
                               oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err);
/* The same, with each pixel's fragment count (oit_capture_end_counts:
 * width*height, row 0 at the top) into counts; NULL: none. */
oit_status oit_streamer_render_counts(oit_streamer *s, const oit_view *view, oit_image *out,
                                      uint32_t *counts, oit_frame_stats *fs,
                                      oit_stream_frame_stats *ss, oit_error *err);
/* The same without the read-back: *state receives the capture's per-pixel
 * state buffer (oit_capture_end_gpu), valid until the next render. */
oit_status oit_streamer_render_gpu(oit_streamer *s, const oit_view *view, unsigned *state,
                                   oit_frame_stats *fs, oit_stream_frame_stats *ss,
                                   oit_error *err);

#endif
