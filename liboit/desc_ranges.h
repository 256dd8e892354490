/* The values each numeric field of oit_renderer_desc accepts, as one
 * table: oit_renderer_desc_check (liboit.c) checks the fields liboit owns
 * from it, and tests/liboit/test_liboit_desc.c drives every field of it at
 * its bounds through that check, so a range cannot change in one place and
 * not the other. The streamer owns the byte budgets', epsilon's and
 * schedule's ranges (oit_streamer_desc_check, shared with oitstream); their
 * rows state the same constants, so the test drives them through liboit's
 * spelling onto the streamer's descriptor too. Fields checked at the first
 * draw (capture, reader_threads, read_on_draw_thread, the budgets' sum)
 * and binding_limit (any value) are not here. Header-only: liboit.so
 * exports only its public API. */
#ifndef OIT_LIBOIT_DESC_RANGES_H
#define OIT_LIBOIT_DESC_RANGES_H

#include <stddef.h>
#include <stdint.h>

#include "oit/liboit.h"
#include "view/render/capture/capture.h"
#include "view/stream/streamer.h"

typedef enum oit_desc_type {
    OIT_DESC_U32, /* uint32_t */
    OIT_DESC_U64, /* uint64_t */
    OIT_DESC_INT, /* int, or an enum of int's size */
    OIT_DESC_F32  /* float: [lo, hi), NaN refused */
} oit_desc_type;

typedef struct oit_desc_range {
    const char *field;  /* oit_renderer_desc's field, as its error names it */
    size_t offset;      /* offsetof(oit_renderer_desc, field) */
    oit_desc_type type;
    /* accepted: lo..hi (F32: [lo, hi)), and 0 where zero_default */
    double lo, hi;
    int zero_default;
    uint64_t also;      /* one more accepted value (U64 only; 0: none) */
    int liboit_checks;  /* 1: oit_renderer_desc_check checks it from here;
                           0: oit_streamer_desc_check, with these bounds */
    const char *expect; /* what the error says was expected */
} oit_desc_range;

#define OIT_DESC_ROW(f, t) #f, offsetof(oit_renderer_desc, f), t

static const oit_desc_range oit_desc_ranges[] = {
    {OIT_DESC_ROW(K, OIT_DESC_U32), OIT_CAPTURE_K_MIN, OIT_CAPTURE_K_MAX, 1, 0, 1,
     "0 (the scene's K) or 2..16"},
    {OIT_DESC_ROW(pack, OIT_DESC_INT), OIT_RENDER_PACK_AUTO, OIT_RENDER_PACK_FIRSTK, 0, 0, 1,
     "an oit_render_pack"},
    {OIT_DESC_ROW(see_through, OIT_DESC_INT), 0, 1, 0, 0, 1, "0 or 1"},
    {OIT_DESC_ROW(schedule, OIT_DESC_INT), OIT_RENDER_SCHEDULE_TREE, OIT_RENDER_SCHEDULE_WAVE, 0,
     0, 0, "an oit_render_schedule"},
    {OIT_DESC_ROW(epsilon, OIT_DESC_F32), 0.0, 1.0, 0, 0, 0, "[0, 1)"},
    {OIT_DESC_ROW(upload_budget, OIT_DESC_U64), (double)OIT_STREAM_BUDGET_MIN,
     (double)OIT_STREAM_BUDGET_MAX, 1, 0, 0, "64 KiB..1 TiB"},
    {OIT_DESC_ROW(slot_budget, OIT_DESC_U64), (double)OIT_STREAM_BUDGET_MIN,
     (double)OIT_STREAM_BUDGET_MAX, 1, 0, 0, "64 KiB..1 TiB"},
    {OIT_DESC_ROW(store_budget, OIT_DESC_U64), (double)OIT_STREAM_BUDGET_MIN,
     (double)OIT_STREAM_BUDGET_MAX, 1, 0, 0, "64 KiB..1 TiB"},
    {OIT_DESC_ROW(cache_budget, OIT_DESC_U64), (double)OIT_STREAM_BUDGET_MIN,
     (double)OIT_STREAM_BUDGET_MAX, 1, OIT_RENDER_CACHE_OFF, 0, "64 KiB..1 TiB or off"},
    {OIT_DESC_ROW(gpu_budget, OIT_DESC_U64), (double)OIT_STREAM_GPU_BUDGET_MIN,
     (double)OIT_STREAM_BUDGET_MAX, 1, 0, 0, "1 MiB..1 TiB"},
};

#define OIT_DESC_RANGES (sizeof oit_desc_ranges / sizeof oit_desc_ranges[0])

#undef OIT_DESC_ROW

#endif
