/* The per-frame driver of the part-file renderer: order the parts for the
 * eye (order.h), cut the order into packs (pack.h), and per pack upload its
 * parts through the bounded ring (upload.h) and capture them as one batch
 * (render/capture.h), composited behind the packs before it. Requires a
 * current GL context for its whole life. */
#ifndef OIT_STREAM_STREAMER_H
#define OIT_STREAM_STREAMER_H

#include "oit/partfile.h"
#include "render/capture.h"
#include "stream/pack.h"

typedef struct oit_streamer_desc {
    int K;                    /* capture layers, 2..16; every part's bound <= K */
    oit_capture_kind capture; /* backend of the K-slot packs; OIT_PACK_COUNTED
                                 always takes OIT_CAPTURE_COUNTED */
    /* OIT_PACK_AUTO (0): counted when epsilon is 0; with early termination
     * disjoint K-slot packs, since skipping whole parts needs the many packs
     * of the K-slot rules (the counted capture takes a frame in a few) */
    oit_pack_mode pack;
    oit_pack_schedule schedule; /* 0: the tree's order (pack.h) */
    uint64_t upload_budget;   /* ring bytes; 0: 64 MiB */
    uint64_t slot_budget;     /* capture slot bytes (oit_capture_set_slot_budget);
                                 0: 32 MiB */
    float epsilon;            /* early termination (oit_capture_set_epsilon); 0: exact */
} oit_streamer_desc;

/* The streamer's own per-frame figures, beside oit_frame_stats. */
typedef struct oit_stream_frame_stats {
    uint32_t packs;          /* captured (a pack whose parts were all skipped is not) */
    uint64_t parts_drawn;
    uint64_t parts_culled;   /* boxes outside the view volume: no fragment */
    uint64_t parts_skipped;  /* epsilon > 0: footprint saturated (render/saturation.h),
                                neither uploaded nor drawn */
    uint64_t bytes_uploaded;
    uint64_t gpu_bytes_peak; /* capture buffers + upload ring              */
    float epsilon;           /* the early-termination threshold it ran with */
} oit_stream_frame_stats;

typedef struct oit_streamer oit_streamer;

/* pf must outlive the streamer; parts are validated on first use, so pf may
 * be opened with defer_part_data. */
oit_status oit_streamer_create(oit_partfile *pf, const oit_streamer_desc *desc,
                               oit_streamer **out, oit_error *err);
void oit_streamer_destroy(oit_streamer *s);

/* Renders one view into out (allocated by the call). fs and ss may be NULL. */
oit_status oit_streamer_render(oit_streamer *s, const oit_view *view, oit_image *out,
                               oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err);
/* The same without the read-back: *state receives the capture's per-pixel
 * state buffer (oit_capture_end_gpu), valid until the next render. */
oit_status oit_streamer_render_gpu(oit_streamer *s, const oit_view *view, unsigned *state,
                                   oit_frame_stats *fs, oit_stream_frame_stats *ss,
                                   oit_error *err);

#endif
