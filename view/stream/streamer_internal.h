/* The streamer's state and the functions its files share (streamer.h is
 * the interface). streamer.c: creation, the frame and its figures;
 * streamer_memory.c: the GPU budget's split and the cache, ring and
 * residency sized within it; streamer_packs.c: a frame's packs prepared,
 * read and captured in turn; streamer_adapt.c: the automatic pack mode's
 * and early termination's choices between frames. Each function is
 * documented at its definition. Internal to view/stream/. */
#ifndef OIT_STREAM_STREAMER_INTERNAL_H
#define OIT_STREAM_STREAMER_INTERNAL_H

#include "view/stream/streamer.h"

#include "base/clock.h"
#include "partfile/order.h"
#include "partfile/share.h"
#include "partfile/triangles.h"
#include "view/render/capture/opaque_tiles.h"
#include "view/render/capture/saturation.h"
#include "view/render/gl/gpu_mesh.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "view/stream/choice.h"
#include "view/stream/fence_queue.h"
#include "view/stream/reader.h"
#include "view/stream/residency.h"
#include "view/stream/upload.h"

/* Packs prepared ahead of the one being drawn. Without early termination
 * the ring's free space is the real bound; with it, a part read far ahead
 * misses the saturation of the packs between, so read one pack ahead only
 * (reading is wasted, not wrong, when a part turns out saturated). */
#define AHEAD_EXACT   OIT_READER_QUEUE
#define AHEAD_EPSILON 1u

/* Where a part of the frame's packing comes from. */
enum { SRC_SKIP, SRC_CACHE, SRC_RING };

/* Per pack of the frame: what its preparation reserved and queued. */
typedef struct pack_plan {
    uint64_t ring_bytes; /* 0: nothing read, no region, no reader job */
} pack_plan;

struct oit_streamer {
    oit_partfile *pf;
    oit_order *order;
    oit_shares *shares; /* NULL: every part is the streamer's */
    uint32_t share_index;
    oit_packer *packer;
    oit_fence_queue *fences;
    oit_upload *upload;
    oit_reader *reader;
    oit_residency *cache; /* NULL: no cache (yet) */
    GLuint cache_buffer;
    uint64_t cache_limit;   /* what the cache may grow to; 0: no cache */
    uint64_t cache_dropped; /* a smaller cache let go this frame, held until GL frees it */
    uint64_t ring_limit;    /* what the ring may grow to */
    uint64_t cache_all;     /* the cache's limit before the frame's pixels (fit_frame_budget) */
    int threads;            /* the reader's threads (0: none) */
    /* Resident ring: every part has a home in the ring and is read there
     * once (NULL: the ring is reused, the cache keeps parts). */
    uint64_t *home;
    uint8_t *loaded;
    uint64_t loaded_bytes;
    oit_capture *capture;
    oit_capture_choice choice;      /* capture: asked, what runs, and why  */
    oit_gpu_timer *timer;           /* oit_streamer_set_gpu_timer; NULL: none */
    oit_saturation *saturation;     /* only with epsilon > 0 */
    oit_opaque_depth opaque;        /* the caller's depth (oit_streamer_set_opaque) */
    oit_opaque_tiles *opaque_tiles; /* built at the first frame with one */
    float epsilon;
    /* Epsilon with counted or first-K packs: front-first packs (pack.h)
     * while they let whole parts be skipped; after a frame that skipped
     * none, plain packs, front first tried again every
     * OIT_STREAM_PROBE_FRAMES frames (adapt). */
    int front_first, front_now;
    uint32_t plain_frames;
    uint32_t ahead;
    uint32_t *ordered;
    /* Per position of the frame's packing (pk->parts[j]): */
    uint8_t *source;
    uint64_t *offset;               /* in the cache or the ring */
    oit_read_item *items;           /* a pack's reader job: its ring parts, in order */
    pack_plan *plans;               /* per pack */
    uint64_t fence_every, unfenced; /* ring bytes between fences, and since the last */
    oit_gpu_mesh **views;           /* one per part of the largest pack so far */
    uint32_t view_count;
    /* OIT_RENDER_PACK_AUTO without early termination: first-K or counted packs,
     * as the measured costs of each view say (view/stream/choice.h); the frame
     * is judged when it ends (frame_end). */
    int adaptive, first_k;
    oit_choice judge;
    struct {
        int open;              /* drawn, not yet judged (a render_gpu frame) */
        double ms;             /* the streamer's own wall time of it */
        oit_path suggest;      /* the fixed rule's next path */
        int adapted;           /* a frame has had its suggestion (adapt) */
        uint32_t deep_counted; /* counted frames of views over K (adapt) */
    } frame;
    oit_stream_budget budget; /* the split (split_budget) */
    oit_streamer_desc desc;   /* as given (oit_streamer_resolved_desc) */
};
static inline uint64_t min_u64(uint64_t a, uint64_t b)
{
    return a < b ? a : b;
}

static inline uint64_t max_u64(uint64_t a, uint64_t b)
{
    return a > b ? a : b;
}

/* streamer_memory.c */
uint64_t oit_streamer_largest_part(const oit_partfile *pf);
uint64_t oit_streamer_compute_pack_budget(uint64_t slot);
oit_status oit_streamer_split_budget(oit_streamer *s, oit_streamer_desc *d, int stores,
                                     uint64_t all_bytes, oit_error *err);
void oit_streamer_fit_frame_budget(oit_streamer *s, const oit_view *view);
int oit_streamer_is_mine(const oit_streamer *s, uint32_t part);
oit_status oit_streamer_number_triangles(oit_streamer *s, uint64_t *all_bytes, oit_error *err);
oit_status oit_streamer_alloc_arrays(oit_streamer *s, uint32_t n, oit_error *err);
oit_status oit_streamer_fit_cache(oit_streamer *s, const oit_packing *pk, oit_error *err);
oit_status oit_streamer_fit_ring(oit_streamer *s, const oit_packing *pk, oit_error *err);
oit_status oit_streamer_make_resident(oit_streamer *s, oit_error *err);
oit_status oit_streamer_create_upload(oit_streamer *s, const oit_streamer_desc *desc,
                                      uint64_t budget, uint64_t all_bytes, oit_error *err);

/* streamer_packs.c */
int oit_streamer_saturated(oit_streamer *s, const oit_packing *pk, uint32_t j);
oit_status oit_streamer_draw_packs(oit_streamer *s, const oit_packing *pk,
                                   oit_stream_frame_stats *ss, oit_error *err);

/* streamer_adapt.c */
void oit_streamer_choose(oit_streamer *s, const oit_view *view);
void oit_streamer_choice_stats(const oit_streamer *s, oit_stream_frame_stats *ss);
int oit_streamer_deep_view(const oit_view *view, const oit_frame_stats *fs);
void oit_streamer_adapt(oit_streamer *s, const oit_frame_stats *fs, oit_stream_frame_stats *ss,
                        double ms, int judged_now);

#endif
