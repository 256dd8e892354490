/* Part-file streaming renderer (streamer.h). */
#include "stream/streamer.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/clock.h"
#include "render/gl/gpu_mesh.h"
#include "render/gl/gpu_timer.h"
#include "render/image/image.h"
#include "render/capture/opaque_tiles.h"
#include "render/capture/saturation.h"
#include "stream/choice.h"
#include "stream/fence_queue.h"
#include "partfile/order.h"
#include "partfile/share.h"
#include "partfile/triangles.h"
#include "stream/reader.h"
#include "stream/residency.h"
#include "stream/upload.h"

_Static_assert(OIT_PACK_MAX_LAYERS == OIT_CAPTURE_MAX_LAYERS &&
                   OIT_PACK_MAX_LAYERS == OIT_PARTFILE_MAX_LAYERS,
               "a wide part the file allows must fit the packer and the capture");

_Static_assert(OIT_PATHS == sizeof(((oit_stream_frame_stats *)0)->choice_ms) / sizeof(double),
               "a cost figure per path the judge weighs");

/* Packs prepared ahead of the one being drawn. Without early termination
 * the ring's free space is the real bound; with it, a part read far ahead
 * misses the saturation of the packs between, so read one pack ahead only
 * (reading is wasted, not wrong, when a part turns out saturated). */
#define AHEAD_EXACT OIT_READER_QUEUE
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
    oit_capture_choice choice; /* --capture: asked, what runs, and why */
    oit_gpu_timer *timer; /* oit_streamer_set_gpu_timer; NULL: none */
    oit_saturation *saturation; /* only with epsilon > 0 */
    oit_opaque_depth opaque;    /* the caller's depth (oit_streamer_set_opaque) */
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
    uint64_t *offset;     /* in the cache or the ring */
    oit_read_item *items; /* a pack's reader job: its ring parts, in order */
    pack_plan *plans;     /* per pack */
    uint64_t fence_every, unfenced; /* ring bytes between fences, and since the last */
    oit_gpu_mesh **views; /* one per part of the largest pack so far */
    uint32_t view_count;
    /* OIT_PACK_AUTO without early termination: first-K or counted packs,
     * as the measured costs of each view say (stream/choice.h); the frame
     * is judged when it ends (frame_end). */
    int adaptive, first_k;
    oit_choice judge;
    struct {
        int open;        /* drawn, not yet judged (a render_gpu frame) */
        double ms;       /* the streamer's own wall time of it */
        oit_path suggest; /* the fixed rule's next path */
        int adapted;     /* a frame has had its suggestion (adapt) */
        uint32_t deep_counted; /* counted frames of views over K (adapt) */
    } frame;
    oit_stream_budget budget; /* the split (split_budget) */
    oit_streamer_desc desc;   /* as given (oit_streamer_resolved_desc) */
};

void oit_streamer_budget(const oit_streamer *s, oit_stream_budget *out)
{
    *out = s->budget;
}

void oit_streamer_resolved_desc(const oit_streamer *s, oit_streamer_desc *out)
{
    const oit_stream_budget *b = &s->budget;
    *out = s->desc;
    out->capture = s->choice.slots;
    out->upload_budget = b->ring;
    out->cache_budget = b->cache ? b->cache : OIT_STREAM_CACHE_OFF;
    out->slot_budget = b->capture;
    out->store_budget = b->store;
    out->gpu_budget = b->total;
    out->reader_threads = s->threads ? s->threads : OIT_STREAM_READ_INLINE;
    out->epsilon = s->epsilon;
}

static uint64_t min_u64(uint64_t a, uint64_t b)
{
    return a < b ? a : b;
}

static uint64_t max_u64(uint64_t a, uint64_t b)
{
    return a > b ? a : b;
}

/* The bytes of the file's largest part (oit_pack_part_bytes). */
static uint64_t largest_part(const oit_partfile *pf)
{
    uint64_t most = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(pf); i++)
        most = max_u64(most, oit_pack_part_bytes(&oit_partfile_parts(pf)[i]));
    return most;
}

/* The pack bytes whose triangles the compute capture holds within its
 * share (slot: the capture's budget; 0: no bound). */
static uint64_t compute_pack_budget(uint64_t slot)
{
    return slot ? slot / OIT_COMPUTE_CAPTURE_TRIANGLE_BYTES * sizeof(oit_triangle) : UINT64_MAX;
}

/* Room a resident file leaves for the frame's per-pixel buffers (an
 * eighth of a smaller total): 64 MiB hold 1024x1024 at 64 bytes a pixel. */
#define PIXEL_ROOM (64ull << 20)

/* The total's split (streamer.h): the capture's slots and store first
 * (their defaults, or each an eighth of a small total), the file resident where it fits
 * what is left less PIXEL_ROOM for the frame's per-pixel buffers, else a
 * ring of a quarter of the rest (64 MiB at most: it only has to hold
 * consecutive packs) and the cache the remainder. Given finer budgets
 * replace their shares. *d receives the budgets the streamer runs with. */
static oit_status split_budget(oit_streamer *s, oit_streamer_desc *d, int stores,
                               uint64_t all_bytes, oit_error *err)
{
    oit_stream_budget *b = &s->budget;
    const char *src = "default";
    oit_gpu_free_query query = d->free_query ? d->free_query : oit_gpu_free_bytes;
    b->free_bytes = query(d->free_ctx, &src);
    uint64_t slots = stores ? OIT_STREAM_FIRSTK_SLOTS_DEFAULT : OIT_STREAM_SLOTS_DEFAULT;
    uint64_t store = stores ? OIT_STREAM_STORE_DEFAULT : 0;
    if (d->gpu_budget) {
        b->total = d->gpu_budget;
        b->source = "--gpu-budget";
    } else if (b->free_bytes) {
        b->total = b->free_bytes / OIT_STREAM_FREE_SHARE_DEN * OIT_STREAM_FREE_SHARE_NUM;
        b->source = src;
    } else {
        /* No total: the parts' own defaults, as before there was one. */
        b->source = src;
        b->capture = d->slot_budget ? d->slot_budget : slots;
        b->store = stores && d->store_budget ? d->store_budget : store;
        b->ring = d->upload_budget ? d->upload_budget : OIT_STREAM_RING_DEFAULT;
        b->cache = d->cache_budget == OIT_STREAM_CACHE_OFF ? 0
                   : d->cache_budget                     ? d->cache_budget
                                                         : OIT_STREAM_CACHE_DEFAULT;
        return OIT_OK;
    }
    const char *name = oit_partfile_name(s->pf);
    if (b->total < OIT_STREAM_GPU_BUDGET_MIN)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: a GPU budget of %llu bytes (%s); at "
                             "least %llu", name, (unsigned long long)b->total, b->source,
                             (unsigned long long)OIT_STREAM_GPU_BUDGET_MIN);
    b->capture = d->slot_budget ? d->slot_budget : min_u64(slots, b->total / 8);
    b->store = stores && d->store_budget ? d->store_budget : min_u64(store, b->total / 8);
    /* The compute capture's records and tile lists hold a pack's
     * triangles (its packs are cut to its share, compute_pack_budget): at
     * least those of the largest part, which no pack splits. */
    if (d->capture == OIT_CAPTURE_COMPUTE && !d->slot_budget)
        b->capture = max_u64(b->capture, (largest_part(s->pf) + sizeof(oit_triangle) - 1) /
                                             sizeof(oit_triangle) *
                                             OIT_COMPUTE_CAPTURE_TRIANGLE_BYTES);
    uint64_t held = b->capture + b->store;
    uint64_t left = held < b->total ? b->total - held : 0;
    int off = d->cache_budget == OIT_STREAM_CACHE_OFF;
    uint64_t pixels = min_u64(b->total / 8, PIXEL_ROOM);
    int fits = !off && !d->upload_budget && !d->cache_budget && left > pixels &&
               all_bytes <= left - pixels;
    b->ring = d->upload_budget ? d->upload_budget
              : fits           ? all_bytes
                               : min_u64(OIT_STREAM_RING_DEFAULT, left / 4);
    b->cache = off ? 0 : d->cache_budget ? d->cache_budget : fits ? all_bytes
               : left > b->ring ? left - b->ring : 0;
    /* as create_upload decides: resident, the ring is the only copy */
    int resident = !off && all_bytes <= b->ring && all_bytes <= b->cache;
    uint64_t sum = held + b->ring + (resident ? 0 : b->cache);
    if (sum > b->total && d->gpu_budget)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: --upload-budget %llu + --cache-budget "
                             "%llu + --slot-budget %llu + --store-budget %llu = %llu bytes, "
                             "more than --gpu-budget %llu", name, (unsigned long long)b->ring,
                             (unsigned long long)b->cache, (unsigned long long)b->capture,
                             (unsigned long long)b->store, (unsigned long long)sum,
                             (unsigned long long)b->total);
    if (sum > b->total)
        b->total = sum; /* finer budgets given past the driver's share win */
    d->slot_budget = b->capture;
    d->store_budget = b->store;
    d->upload_budget = b->ring > OIT_STREAM_RING_MIN ? b->ring : OIT_STREAM_RING_MIN;
    d->cache_budget = off ? OIT_STREAM_CACHE_OFF
                      : b->cache ? b->cache - b->cache % OIT_PACK_ALIGN
                                 : OIT_STREAM_CACHE_OFF;
    return OIT_OK;
}

/* Bytes a pixel beyond the state: counts (4), first-K's segment table
 * (8), the output where it has a buffer of its own (16; the compute
 * capture's resume cursors, through which its output passes), rounded
 * up. */
#define PIXEL_EXTRA 32u

/* Under a total, the frame's per-pixel capture buffers (counts, state,
 * output, segments) come out of the cache's share: the cache's limit is
 * what the total leaves, and a cache past it is let go. */
static void fit_frame_budget(oit_streamer *s, const oit_view *view)
{
    const oit_stream_budget *b = &s->budget;
    if (!b->total || s->home || !b->cache)
        return;
    uint64_t pixel = (uint64_t)view->width * view->height *
                     (oit_capture_pixel_bytes(view) + PIXEL_EXTRA);
    uint64_t used = b->capture + b->store + s->ring_limit + pixel;
    uint64_t room = used < b->total ? b->total - used : 0;
    room = min_u64(room, b->cache);
    s->cache_limit = min_u64(room - room % OIT_PACK_ALIGN, s->cache_all);
    if (s->cache && oit_residency_capacity(s->cache) > s->cache_limit) {
        oit_residency_destroy(s->cache);
        s->cache = NULL;
        glDeleteBuffers(1, &s->cache_buffer);
        s->cache_buffer = 0;
    }
}

void oit_streamer_destroy(oit_streamer *s)
{
    if (!s)
        return;
    /* The reader first: it may still write into the ring's mapping. */
    oit_reader_destroy(s->reader);
    for (uint32_t i = 0; i < s->view_count; i++)
        oit_gpu_mesh_destroy(s->views[i]);
    free(s->views);
    oit_saturation_destroy(s->saturation);
    oit_opaque_tiles_destroy(s->opaque_tiles);
    oit_capture_destroy(s->capture);
    if (s->cache_buffer)
        glDeleteBuffers(1, &s->cache_buffer);
    oit_residency_destroy(s->cache);
    oit_upload_destroy(s->upload);
    oit_fence_queue_destroy(s->fences);
    oit_packer_destroy(s->packer);
    oit_order_destroy(s->order);
    oit_shares_destroy(s->shares);
    free(s->ordered);
    free(s->source);
    free(s->offset);
    free(s->items);
    free(s->plans);
    free(s->home);
    free(s->loaded);
    free(s);
}

/* A part of the streamer's share (all are, without one). */
static int is_mine(const oit_streamer *s, uint32_t part)
{
    return !s->shares || oit_shares_of_part(s->shares, part) == s->share_index;
}

/* Primitive ids are the triangles' source indices, uploaded with them
 * (partfile/triangles.h), as the in-core mesh's positions order; they must fit
 * the 31 bits a fragment carries. *all_bytes: what every part takes in the
 * ring, the most a cache needs. */
static oit_status number_triangles(oit_streamer *s, uint64_t *all_bytes, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    oit_partfile_summary sum;
    oit_partfile_get_summary(s->pf, &sum);
    if (sum.triangles_in > 0x80000000ull)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: more than 2^31 source triangles; "
                             "primitive ids would not fit a fragment",
                             oit_partfile_name(s->pf));
    *all_bytes = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(s->pf); i++)
        *all_bytes += is_mine(s, i) ? oit_pack_part_bytes(&parts[i]) : 0;
    return OIT_OK;
}

static oit_status alloc_arrays(oit_streamer *s, uint32_t n, oit_error *err)
{
    size_t m = (size_t)n + 1;
    s->ordered = calloc(m, sizeof *s->ordered);
    s->source = calloc(m, sizeof *s->source);
    s->offset = calloc(m, sizeof *s->offset);
    s->items = calloc(m, sizeof *s->items);
    s->plans = calloc(m, sizeof *s->plans);
    if (!s->ordered || !s->source || !s->offset || !s->items || !s->plans)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the streamer (%u parts)",
                             oit_partfile_name(s->pf), n);
    return OIT_OK;
}

/* The cache buffer lives in GPU memory (no CPU access): it is filled by GL
 * copies from the ring, so a discrete GPU draws cached parts from its own
 * memory rather than across the bus. It is made when a frame needs it
 * (fit_cache), at most the budget or all the parts. */
static void limit_cache(oit_streamer *s, uint64_t budget, uint64_t all_bytes)
{
    if (budget == OIT_STREAM_CACHE_OFF)
        return;
    budget = budget ? budget : OIT_STREAM_CACHE_DEFAULT;
    uint64_t bytes = budget < all_bytes ? budget : all_bytes;
    s->cache_limit = bytes - bytes % OIT_PACK_ALIGN;
    s->cache_all = s->cache_limit;
}

/* Grows the cache to the parts of the frame's packing (all of this frame
 * it could keep), geometrically, up to its limit. The grown cache starts
 * empty: copying what the smaller one kept would hold both at once, and a
 * frame after growth reads its parts once more, which geometric growth
 * makes rare. */
static oit_status fit_cache(oit_streamer *s, const oit_packing *pk, oit_error *err)
{
    uint64_t cap = s->cache ? oit_residency_capacity(s->cache) : 0, need = 0;
    s->cache_dropped = 0;
    if (cap >= s->cache_limit)
        return OIT_OK;
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    for (uint32_t j = 0; j < pk->part_count; j++)
        need += oit_pack_part_bytes(&parts[pk->parts[j]]);
    if (need <= cap)
        return OIT_OK;
    uint64_t bytes = need > 2 * cap ? need : 2 * cap;
    bytes = bytes < s->cache_limit ? bytes : s->cache_limit;
    bytes -= bytes % OIT_PACK_ALIGN;
    s->cache_dropped = cap;
    oit_residency_destroy(s->cache);
    s->cache = NULL;
    glDeleteBuffers(1, &s->cache_buffer);
    s->cache_buffer = 0;
    oit_status st = oit_residency_create(bytes, oit_partfile_part_count(s->pf), &s->cache, err);
    if (st != OIT_OK)
        return st;
    oit_residency_begin_frame(s->cache);
    glCreateBuffers(1, &s->cache_buffer);
    glNamedBufferStorage(s->cache_buffer, (GLsizeiptr)bytes, NULL, 0);
    oit_gl_poison_buffer(s->cache_buffer);
    st = oit_gl_check("residency cache: glNamedBufferStorage", err);
    if (st != OIT_OK)
        oit_error_prefix(err, oit_partfile_name(s->pf));
    return st;
}

/* A ring of `bytes`, its reader writing into its mapping. */
static oit_status make_ring(oit_streamer *s, uint64_t bytes, oit_error *err)
{
    oit_status st = oit_upload_create(bytes, &s->upload, err);
    if (st == OIT_OK)
        st = oit_reader_create(s->pf, oit_upload_map(s->upload), s->threads, &s->reader, err);
    if (st != OIT_OK) {
        oit_upload_destroy(s->upload);
        s->upload = NULL;
    }
    /* A few fences per lap of the ring: enough that reclaiming a region
     * waits for little more than its own pack. */
    s->fence_every = bytes / 4;
    s->unfenced = 0;
    return st;
}

/* The most that consecutive packs take together within the budget: the
 * ring never holds more at once (the 2M plant's two packs of 52 MB, one
 * at a time in a 64 MiB ring), so more would be memory never used. */
static uint64_t widest_window(const oit_packing *pk, uint64_t budget)
{
    uint64_t best = 0, sum = 0;
    for (uint32_t lo = 0, hi = 0; hi < pk->pack_count; hi++) {
        sum += pk->bytes[hi];
        while (sum > budget && lo < hi)
            sum -= pk->bytes[lo++];
        best = sum > best ? sum : best;
    }
    return best;
}

/* Grows the ring to what the frame reads (its parts the cache does not
 * hold, as far as consecutive packs can use it; at least its largest pack
 * whole: a cached part may be evicted before its pack is planned),
 * geometrically, up to the budget. Only between packings, when nothing is
 * outstanding: the ring is waited for (GL may still draw from it) and
 * replaced with its reader. */
static oit_status fit_ring(oit_streamer *s, const oit_packing *pk, oit_error *err)
{
    uint64_t cap = s->upload ? oit_upload_gpu_bytes(s->upload) : 0, read = 0, largest = 0, at = 0;
    if (s->home || cap >= s->ring_limit)
        return OIT_OK;
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    for (uint32_t i = 0; i < pk->pack_count; i++)
        largest = pk->bytes[i] > largest ? pk->bytes[i] : largest;
    for (uint32_t j = 0; j < pk->part_count; j++)
        if (!s->cache || !oit_residency_peek(s->cache, pk->parts[j], &at))
            read += oit_pack_part_bytes(&parts[pk->parts[j]]);
    uint64_t wide = widest_window(pk, s->ring_limit);
    uint64_t need = read < wide ? read : wide;
    need = need > largest ? need : largest;
    if (need <= cap)
        return OIT_OK;
    uint64_t bytes = need > 2 * cap ? need : 2 * cap;
    bytes = bytes < s->ring_limit ? bytes : s->ring_limit;
    oit_status st = oit_fence_queue_wait(s->fences, oit_fence_queue_tag(s->fences),
                                         oit_capture_host_waits(s->capture), err);
    if (st != OIT_OK)
        return st;
    /* The reader first: it may still write into the ring's mapping. */
    oit_reader_destroy(s->reader);
    oit_upload_destroy(s->upload);
    s->reader = NULL;
    s->upload = NULL;
    return make_ring(s, bytes, err);
}

/* A file that fits both the ring and the cache budget is read once into a
 * ring of its size, each part at a home of its own, and drawn from there in
 * every frame: one copy of its parts on the GPU where a reused ring and a
 * cache would hold two (a ring as large as the file holds any pack). */
static oit_status make_resident(oit_streamer *s, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    uint32_t n = oit_partfile_part_count(s->pf);
    s->home = calloc((size_t)n + 1, sizeof *s->home);
    s->loaded = calloc((size_t)n + 1, 1);
    if (!s->home || !s->loaded)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the streamer (%u parts)",
                             oit_partfile_name(s->pf), n);
    for (uint32_t i = 1; i <= n; i++)
        s->home[i] = s->home[i - 1] + (is_mine(s, i - 1) ? oit_pack_part_bytes(&parts[i - 1]) : 0);
    return OIT_OK;
}

static int fits_resident(const oit_streamer_desc *desc, uint64_t budget, uint64_t all_bytes)
{
    uint64_t cache = desc->cache_budget ? desc->cache_budget : OIT_STREAM_CACHE_DEFAULT;
    return desc->cache_budget != OIT_STREAM_CACHE_OFF && all_bytes <= budget &&
           all_bytes <= cache;
}

/* A resident ring is the file's size from the start; a reused one starts
 * at OIT_STREAM_RING_MIN and grows with the frames (fit_ring). */
static oit_status create_upload(oit_streamer *s, const oit_streamer_desc *desc, uint64_t budget,
                                uint64_t all_bytes, oit_error *err)
{
    int resident = fits_resident(desc, budget, all_bytes);
    s->ring_limit = budget;
    oit_status st = oit_fence_queue_create(&s->fences, err);
    if (st == OIT_OK)
        st = make_ring(s, resident || budget < OIT_STREAM_RING_MIN ? budget : OIT_STREAM_RING_MIN,
                       err);
    if (st == OIT_OK && resident)
        st = make_resident(s, err);
    else if (st == OIT_OK)
        limit_cache(s, desc->cache_budget, all_bytes);
    return st;
}

const oit_capture_choice *oit_streamer_capture_choice(const oit_streamer *s)
{
    return &s->choice;
}

/* A routed capture at stencil_k samples, kept once its self-test passes. */
typedef struct routed_try {
    oit_capture_kind kind;
    int K;
    unsigned faults;
    oit_program_cache *programs;
    oit_capture *made;
} routed_try;

static oit_status try_routed(void *ctx, int stencil_k, oit_error *err)
{
    routed_try *t = ctx;
    return oit_capture_create_cached(t->programs, t->kind, t->K, stencil_k, t->faults, &t->made,
                                     err);
}

/* The pack mode's capture, its K-slot fills as --capture chooses. */
static oit_status create_capture(oit_streamer *s, const oit_streamer_desc *desc,
                                 oit_pack_mode mode, oit_error *err)
{
    /* No K-slot fill and no per-pixel limit: exact with every pack mode. */
    if (desc->capture == OIT_CAPTURE_COMPUTE) {
        s->choice.asked = desc->capture;
        return oit_capture_create_cached(desc->programs, OIT_CAPTURE_COMPUTE, desc->K, 0,
                                         desc->capture_faults, &s->capture, err);
    }
    if (mode == OIT_PACK_COUNTED) {
        s->choice.asked = desc->capture;
        if (desc->capture != OIT_CAPTURE_AUTO && desc->capture != OIT_CAPTURE_ARRAY)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "--capture %s: counted packs have no "
                                 "K-slot fill to route (--pack first-k, budget or disjoint)",
                                 oit_capture_kind_name(desc->capture)
                                     ? oit_capture_kind_name(desc->capture) : "?");
        return oit_capture_create_cached(desc->programs, OIT_CAPTURE_COUNTED, desc->K, 0,
                                         desc->capture_faults, &s->capture, err);
    }
    int firstk = mode == OIT_PACK_FIRSTK;
    routed_try t = {firstk ? OIT_CAPTURE_FIRSTK : OIT_CAPTURE_STENCIL, desc->K,
                    desc->capture_faults, desc->programs, NULL};
    oit_status st = oit_capture_choose(desc->capture, desc->K, firstk, try_routed, &t,
                                       &s->choice, err);
    if (st != OIT_OK || t.made) {
        s->capture = t.made;
        return st;
    }
    return oit_capture_create_cached(desc->programs, firstk ? OIT_CAPTURE_FIRSTK : OIT_CAPTURE_ARRAY,
                                     desc->K, 0, desc->capture_faults, &s->capture, err);
}

/* desc's reader_threads resolved: the render thread draws, the others
 * decode (on a GPU, decoding is the CPU's share of the upload). */
static oit_status reader_threads(const oit_partfile *pf, int want, int *threads, oit_error *err)
{
    if (want == OIT_STREAM_READ_INLINE) {
        *threads = 0;
        return OIT_OK;
    }
    if (want < 0 || want > OIT_READER_MAX_THREADS)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %d reader threads: expected 1..%d, 0 "
                             "(the cores less one) or %d (the render thread)",
                             oit_partfile_name(pf), want, OIT_READER_MAX_THREADS,
                             OIT_STREAM_READ_INLINE);
    long others = sysconf(_SC_NPROCESSORS_ONLN) - 1;
    others = others < 1 ? 1 : others > OIT_READER_MAX_THREADS ? OIT_READER_MAX_THREADS : others;
    *threads = want ? want : (int)others;
    return OIT_OK;
}

static oit_status make_shares(oit_streamer *s, const oit_streamer_desc *desc, oit_error *err)
{
    oit_status st = oit_shares_check(s->pf, desc->share_count, desc->share_index, err);
    s->share_index = desc->share_index;
    if (st == OIT_OK && desc->share_count > 1)
        st = oit_shares_create(s->pf, desc->share_count, &s->shares, err);
    return st;
}

void oit_streamer_share_size(const oit_streamer *s, uint32_t *parts, uint64_t *triangles)
{
    if (s->shares) {
        *parts = oit_shares_parts(s->shares, s->share_index);
        *triangles = oit_shares_triangles(s->shares, s->share_index);
        return;
    }
    oit_partfile_summary sum = {0};
    oit_partfile_get_summary(s->pf, &sum);
    *parts = oit_partfile_part_count(s->pf);
    *triangles = sum.triangles;
}

oit_status oit_streamer_create(oit_partfile *pf, const oit_streamer_desc *desc,
                               oit_streamer **out, oit_error *err)
{
    *out = NULL;
    oit_streamer *s = calloc(1, sizeof *s);
    if (!s)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the streamer",
                             oit_partfile_name(pf));
    s->pf = pf;
    s->desc = *desc;
    oit_streamer_desc eff = *desc;
    uint64_t all_bytes = 0;
    /* The compute capture has no per-pixel limit and no second pass: the
     * counted rule's packs (cut only by the upload budget) are the largest
     * exact ones, and fewer packs are fewer binnings and read-backs. */
    oit_pack_mode mode = desc->pack != OIT_PACK_AUTO            ? desc->pack
                         : desc->capture == OIT_CAPTURE_COMPUTE ? OIT_PACK_COUNTED
                                                                : OIT_PACK_FIRSTK;
    s->adaptive = desc->pack == OIT_PACK_AUTO && mode == OIT_PACK_FIRSTK;
    oit_path seed = desc->frames == 1 ? OIT_PATH_COUNTED : OIT_PATH_FIRSTK;
    s->first_k = seed == OIT_PATH_FIRSTK;
    oit_choice_init(&s->judge, 1u << OIT_PATH_FIRSTK | 1u << OIT_PATH_COUNTED, seed);
    oit_status st = reader_threads(pf, desc->reader_threads, &s->threads, err);
    if (st == OIT_OK)
        st = alloc_arrays(s, oit_partfile_part_count(pf), err);
    if (st == OIT_OK)
        st = make_shares(s, desc, err);
    if (st == OIT_OK)
        st = number_triangles(s, &all_bytes, err);
    if (st == OIT_OK)
        st = split_budget(s, &eff, mode == OIT_PACK_COUNTED || mode == OIT_PACK_FIRSTK,
                          all_bytes, err);
    desc = &eff;
    uint64_t most = desc->upload_budget ? desc->upload_budget : OIT_STREAM_RING_DEFAULT;
    uint64_t budget = most;
    /* A ring as large as all the parts holds any pack, and the whole file
     * in one lap (resident, make_resident): a small model needs no 64 MiB
     * of GPU memory for it. */
    if (all_bytes < budget)
        budget = all_bytes > OIT_STREAM_RING_MIN ? all_bytes : OIT_STREAM_RING_MIN;
    if (st == OIT_OK && desc->capture == OIT_CAPTURE_COMPUTE)
        budget = min_u64(budget, max_u64(compute_pack_budget(desc->slot_budget),
                                         largest_part(pf)));
    /* The packer checks every part of the file against the budget, other
     * shares' too (an empty share included). */
    for (uint32_t i = 0; s->shares && i < oit_partfile_part_count(pf); i++) {
        uint64_t b = oit_pack_part_bytes(&oit_partfile_parts(pf)[i]);
        budget = b > budget && b <= most ? b : budget;
    }
    if (st == OIT_OK)
        st = oit_order_create(pf, &s->order, err);
    if (st == OIT_OK)
        st = oit_packer_create(pf, mode, desc->K, budget, &s->packer, err);
    if (st == OIT_OK)
        oit_packer_set_schedule(s->packer, desc->schedule);
    s->front_first = desc->epsilon > 0.0f && (mode == OIT_PACK_FIRSTK || mode == OIT_PACK_COUNTED);
    s->front_now = s->front_first;
    if (st == OIT_OK)
        st = create_upload(s, desc, budget, all_bytes, err);
    if (st == OIT_OK) {
        s->budget.resident = s->home != NULL;
        s->budget.ring = s->ring_limit;
        s->budget.cache = s->home ? 0 : s->cache_limit;
    }
    if (st == OIT_OK)
        st = create_capture(s, desc, mode, err);
    /* The counted and first-K captures store fragments beside their slots;
     * 32 MiB (2 a pixel at 1024x1024) split the packs of dense views, which
     * then drew again (bench/stream-vs-dfb-llvmpipe.md). split_budget gave
     * both budgets their values. */
    if (st == OIT_OK) {
        oit_capture_set_slot_budget(s->capture, s->budget.capture);
        oit_capture_set_store_budget(s->capture, s->budget.store);
        /* only auto's counted frames predict from first-K's counts */
        oit_capture_set_keep_counts(s->capture, s->adaptive);
    }
    if (st == OIT_OK)
        oit_capture_set_store_limit(s->capture, desc->store_limit);
    /* first-K's pass 2 and counted batches without waits; a short frame is
     * drawn again (render) */
    if (st == OIT_OK)
        oit_capture_set_no_wait(s->capture, 1);
    s->ahead = AHEAD_EXACT;
    if (st == OIT_OK && desc->epsilon > 0.0f) {
        s->epsilon = desc->epsilon;
        s->ahead = AHEAD_EPSILON;
        oit_capture_set_epsilon(s->capture, desc->epsilon);
        st = oit_saturation_create(&s->saturation, err);
    }
    if (st != OIT_OK) {
        oit_streamer_destroy(s);
        return st;
    }
    *out = s;
    return OIT_OK;
}

/* Grows the pool of mesh views to n (only when a pack is larger than all
 * before it, so steady frames allocate nothing). */
static oit_status reserve_views(oit_streamer *s, uint32_t n, oit_error *err)
{
    if (n <= s->view_count)
        return OIT_OK;
    oit_gpu_mesh **v = realloc(s->views, (size_t)n * sizeof *v);
    if (!v)
        return oit_error_set(err, OIT_ERR_NOMEM, "streamer: cannot hold %u mesh views", n);
    s->views = v;
    for (; s->view_count < n; s->view_count++) {
        oit_status st = oit_gpu_mesh_create_view(oit_upload_buffer(s->upload),
                                                 &s->views[s->view_count], err);
        if (st != OIT_OK)
            return st;
    }
    return OIT_OK;
}

static int saturated(oit_streamer *s, const oit_packing *pk, uint32_t j)
{
    if (s->opaque.enabled) {
        const oit_partfile_part *part = &oit_partfile_parts(s->pf)[pk->parts[j]];
        if (oit_opaque_tiles_behind(s->opaque_tiles, part->bounds_min, part->bounds_max,
                                    pk->part_rects[j]))
            return 1;
    }
    return s->saturation &&
           oit_saturation_covered(s->saturation, pk->part_rects[j], s->epsilon);
}

/* Decides where pack i's parts come from; returns the ring bytes the read
 * ones need (their offsets relative to the pack's region). Repeatable: a
 * preparation that found no room runs it again later. */
static uint64_t plan_sources(oit_streamer *s, const oit_packing *pk, uint32_t i)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    uint64_t bytes = 0;
    for (uint32_t j = pk->pack_first[i]; j < pk->pack_first[i + 1]; j++) {
        uint32_t p = pk->parts[j];
        if (saturated(s, pk, j)) {
            s->source[j] = SRC_SKIP;
        } else if (s->home) {
            s->source[j] = s->loaded[p] ? SRC_CACHE : SRC_RING;
            s->offset[j] = s->home[p];
            bytes += s->loaded[p] ? 0 : oit_pack_part_bytes(&parts[p]);
        } else if (s->cache && oit_residency_lookup(s->cache, p, &s->offset[j])) {
            s->source[j] = SRC_CACHE;
        } else {
            s->source[j] = SRC_RING;
            s->offset[j] = bytes;
            bytes += oit_pack_part_bytes(&parts[p]);
        }
    }
    return bytes;
}

/* Prepares pack i: sources, ring region, reader job. With wait it blocks
 * until the ring has room; without, *got = 0 when it has none yet. */
static oit_status prepare_pack(oit_streamer *s, const oit_packing *pk, uint32_t i, int wait,
                               int *got, oit_error *err)
{
    uint64_t bytes = plan_sources(s, pk, i), base = 0;
    s->plans[i].ring_bytes = bytes;
    *got = 1;
    if (bytes == 0)
        return OIT_OK;
    /* Resident: the parts' homes are theirs alone, never reclaimed. */
    oit_status st = s->home ? OIT_OK
                            : oit_upload_reserve(s->upload, s->fences, bytes, wait, &base, got,
                                                 oit_capture_host_waits(s->capture), err);
    if (st != OIT_OK || !*got)
        return st;
    uint32_t first = pk->pack_first[i], n = 0;
    for (uint32_t j = first; j < pk->pack_first[i + 1]; j++)
        if (s->source[j] == SRC_RING) {
            s->offset[j] += base;
            s->items[first + n++] = (oit_read_item){pk->parts[j], s->offset[j]};
        }
    return oit_reader_submit(s->reader, &s->items[first], n, err);
}

/* Points the next view at part j of the packing and, for a part read in
 * this frame, copies it into the cache when there is room. */
static void use_part(oit_streamer *s, const oit_packing *pk, uint32_t j, oit_gpu_mesh *view,
                     oit_stream_frame_stats *ss)
{
    const oit_partfile_part *part = &oit_partfile_parts(s->pf)[pk->parts[j]];
    uint64_t bytes = oit_part_sourced_bytes(part->index_count / 3), at = 0;
    int cached = s->source[j] == SRC_CACHE;
    oit_gpu_mesh_set_buffer(view, cached && s->cache ? s->cache_buffer
                                                     : oit_upload_buffer(s->upload));
    oit_gpu_mesh_set_range_sourced(view, s->offset[j], (size_t)(part->index_count / 3));
    ss->cache_hits += (uint64_t)cached;
    if (!cached && s->cache &&
        oit_residency_insert(s->cache, pk->parts[j], oit_pack_part_bytes(part), &at)) {
        oit_gpu_timer_mark(s->timer, OIT_GPU_UPLOAD);
        glCopyNamedBufferSubData(oit_upload_buffer(s->upload), s->cache_buffer,
                                 (GLintptr)s->offset[j], (GLintptr)at, (GLsizeiptr)bytes);
    }
}

/* Counts what pack i read, and lets its ring region go once the work issued
 * so far completes, fencing every fence_every bytes. */
static oit_status retire_region(oit_streamer *s, const oit_packing *pk, uint32_t i,
                                oit_stream_frame_stats *ss, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    if (s->plans[i].ring_bytes == 0)
        return OIT_OK;
    for (uint32_t j = pk->pack_first[i]; j < pk->pack_first[i + 1]; j++)
        if (s->source[j] == SRC_RING) {
            const oit_partfile_part *part = &parts[pk->parts[j]];
            ss->bytes_uploaded += oit_part_sourced_bytes(part->index_count / 3);
            if (s->home && !s->loaded[pk->parts[j]]) {
                s->loaded[pk->parts[j]] = 1;
                s->loaded_bytes += oit_pack_part_bytes(part);
            }
        }
    if (s->home)
        return OIT_OK;
    oit_upload_drawn(s->upload, oit_fence_queue_tag(s->fences));
    s->unfenced += s->plans[i].ring_bytes;
    if (s->unfenced < s->fence_every)
        return OIT_OK;
    s->unfenced = 0;
    return oit_fence_queue_insert(s->fences, err);
}

/* The mapped file pages of the parts pack i read are let go once their
 * triangles are in the ring: otherwise every part ever read stays in the
 * process (the 2M plant's 38 MB), beside its copy on the GPU. A part read
 * again faults them back in from the page cache. */
static void drop_read_pages(oit_streamer *s, const oit_packing *pk, uint32_t i)
{
    for (uint32_t j = pk->pack_first[i]; j < pk->pack_first[i + 1]; j++)
        if (s->source[j] == SRC_RING)
            oit_partfile_drop_part_data(s->pf, pk->parts[j], 1);
}

/* Collects pack i from the reader and captures it, leaving out the parts
 * whose footprint is saturated (saturation.h: the capture would drop all
 * their fragments); they may have saturated since the pack was prepared.
 * Once collected, the region is retired even when the capture fails: GL
 * may already read it. */
static oit_status draw_pack(oit_streamer *s, const oit_packing *pk, uint32_t i,
                            oit_stream_frame_stats *ss, oit_error *err)
{
    uint32_t first = pk->pack_first[i], n = pk->pack_first[i + 1] - first, drawn = 0;
    oit_status st = s->plans[i].ring_bytes ? oit_reader_collect(s->reader, err) : OIT_OK;
    if (st != OIT_OK)
        return st;
    drop_read_pages(s, pk, i);
    st = reserve_views(s, n, err);
    for (uint32_t j = first; j < first + n && st == OIT_OK; j++) {
        if (s->source[j] == SRC_SKIP || saturated(s, pk, j)) {
            ss->parts_skipped++;
            continue;
        }
        use_part(s, pk, j, s->views[drawn++], ss);
    }
    if (st == OIT_OK && drawn > 0) {
        ss->packs++;
        st = oit_capture_batch_layers(s->capture, (const oit_gpu_mesh *const *)s->views,
                                      (int)drawn, pk->rects[i], (int)pk->layers[i], err);
    }
    /* No pack after the last one reads the tiles it would recompute. */
    oit_gpu_timer_mark(s->timer, OIT_GPU_OTHER);
    if (st == OIT_OK && drawn > 0 && s->saturation && i + 1 < pk->pack_count)
        st = oit_saturation_update(s->saturation, oit_capture_state_buffer(s->capture),
                                   pk->rects[i], err);
    oit_status rs = retire_region(s, pk, i, ss, st == OIT_OK ? err : NULL);
    return st != OIT_OK ? st : rs;
}

/* Prepares packs from *next on while they stay within `ahead` of pack i
 * and the ring has room; pack i itself is waited for. */
static oit_status prepare_ahead(oit_streamer *s, const oit_packing *pk, uint32_t i,
                                uint32_t *next, oit_error *err)
{
    while (*next < pk->pack_count && *next - i <= s->ahead &&
           oit_reader_outstanding(s->reader) < OIT_READER_QUEUE) {
        int got = 0;
        oit_status st = prepare_pack(s, pk, *next, *next == i, &got, err);
        if (st != OIT_OK)
            return st;
        if (!got)
            break;
        ++*next;
    }
    if (*next <= i)
        return oit_error_set(err, OIT_ERR_GL, "upload: pack %u found no room in the ring", i);
    return OIT_OK;
}

/* Draws every pack of the view, preparing later ones while earlier ones
 * draw. On failure the reader's outstanding work is dropped and the ring
 * forgets the regions of the packs that never reached GL. */
static oit_status draw_packs(oit_streamer *s, const oit_packing *pk,
                             oit_stream_frame_stats *ss, oit_error *err)
{
    uint32_t next = 0;
    oit_status st = OIT_OK;
    for (uint32_t i = 0; st == OIT_OK && i < pk->pack_count; i++) {
        /* Front-first packs are few and grow: each should see what the
         * packs before it saturated (saturation.h). */
        if (s->front_now && s->saturation)
            st = oit_saturation_wait(s->saturation, oit_capture_host_waits(s->capture), err);
        if (st == OIT_OK)
            st = prepare_ahead(s, pk, i, &next, err);
        if (st == OIT_OK)
            st = draw_pack(s, pk, i, ss, err);
    }
    if (st != OIT_OK) {
        oit_reader_cancel(s->reader);
        oit_upload_release_undrawn(s->upload);
    }
    return st;
}

void oit_streamer_set_gpu_timer(oit_streamer *s, oit_gpu_timer *t)
{
    s->timer = t;
    oit_capture_set_gpu_timer(s->capture, t);
}

void oit_streamer_set_opaque(oit_streamer *s, const oit_opaque_depth *o)
{
    oit_capture_set_opaque(s->capture, o);
    memset(&s->opaque, 0, sizeof s->opaque);
    if (o && o->enabled)
        s->opaque = *o;
}

/* The view's frustum planes, eye and direction in model space, where the
 * parts are: through the model matrix (a plane p on M x is M^T p on x; an
 * affine map keeps which side of a plane a point lies on). */
static oit_status view_in_model(const oit_view *view, float planes[6][4], float eye[3],
                                float dir[3], oit_error *err)
{
    oit_camera_frustum(&view->camera, (float)view->width / (float)view->height, planes);
    double model[16], meye[3], mdir[3];
    int modelled = oit_view_model(view, model);
    if (modelled) {
        for (int i = 0; i < 6; i++) {
            double p[4];
            for (int j = 0; j < 4; j++)
                p[j] = planes[i][0] * model[j * 4] + planes[i][1] * model[j * 4 + 1] +
                       planes[i][2] * model[j * 4 + 2] + planes[i][3] * model[j * 4 + 3];
            for (int j = 0; j < 4; j++)
                planes[i][j] = (float)p[j];
        }
        if (!oit_view_model_eye(view, meye, mdir))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "the model matrix is singular");
    }
    const oit_camera *c = &view->camera;
    for (int k = 0; k < 3; k++) {
        eye[k] = modelled ? (float)meye[k] : c->eye[k];
        dir[k] = modelled ? (float)mdir[k] : c->target[k] - c->eye[k];
    }
    return OIT_OK;
}

oit_status oit_shares_view_order(oit_order *order, oit_shares *shares, const oit_view *view,
                                 uint32_t *scratch, uint32_t *out, oit_error *err)
{
    /* The whole order, unculled: every process computes the same one from
     * the same file and view, whatever its share. */
    float planes[6][4], eye[3], dir[3];
    uint32_t count = 0;
    oit_status st = view_in_model(view, planes, eye, dir, err);
    if (st == OIT_OK && view->camera.projection == OIT_PROJ_ORTHOGRAPHIC)
        st = oit_order_compute_parallel(order, dir, NULL, scratch, &count, err);
    else if (st == OIT_OK)
        st = oit_order_compute(order, eye, scratch, &count, err);
    if (st == OIT_OK)
        oit_shares_order(shares, scratch, count, out);
    return st;
}

oit_status oit_streamer_share_order(oit_streamer *s, const oit_view *view, uint32_t *order,
                                    oit_error *err)
{
    if (!s->shares) {
        order[0] = 0;
        return OIT_OK;
    }
    return oit_shares_view_order(s->order, s->shares, view, s->ordered, order, err);
}

/* Captures every pack of the view; on failure the frame is ended and
 * discarded. */
static oit_status capture_frame(oit_streamer *s, const oit_view *view, oit_packing *pk,
                                oit_stream_frame_stats *ss, oit_error *err)
{
    memset(ss, 0, sizeof *ss);
    uint32_t count = 0;
    if (s->cache)
        oit_residency_begin_frame(s->cache);
    oit_status st = oit_capture_begin(s->capture, view, err);
    /* Parts wholly behind the caller's opaque depth are skipped as
     * saturated ones are (opaque_tiles.h). */
    if (st == OIT_OK && s->opaque.enabled && !s->opaque_tiles)
        st = oit_opaque_tiles_create(&s->opaque_tiles, err);
    if (st == OIT_OK && s->opaque_tiles)
        st = oit_opaque_tiles_begin(s->opaque_tiles, view, &s->opaque,
                                     oit_capture_host_waits(s->capture), err);
    /* Whole grid ranges outside the view are left out of the order; the
     * packer still culls part by part what remains. */
    float planes[6][4], eye[3], dir[3];
    if (st == OIT_OK)
        st = view_in_model(view, planes, eye, dir, err);
    double t0 = oit_time_ms();
    if (st == OIT_OK && view->camera.projection == OIT_PROJ_ORTHOGRAPHIC) {
        /* Parallel rays: near sides by the view direction, not an eye. */
        st = oit_order_compute_parallel(s->order, dir, (const float(*)[4])planes, s->ordered,
                                        &count, err);
    } else if (st == OIT_OK) {
        st = oit_order_compute_culled(s->order, eye, (const float(*)[4])planes, s->ordered,
                                      &count, err);
    }
    /* Another share's parts are another process's (a subsequence of a
     * visibility order is one of its parts). */
    uint32_t mine = count;
    if (s->shares) {
        mine = 0;
        for (uint32_t i = 0; i < count; i++)
            if (is_mine(s, s->ordered[i]))
                s->ordered[mine++] = s->ordered[i];
    }
    count = mine;
    double t1 = oit_time_ms();
    oit_packer_set_front_first(s->packer, s->front_now);
    if (st == OIT_OK)
        st = oit_packer_run(s->packer, view, s->ordered, count, pk, err);
    ss->order_ms = t1 - t0;
    /* Parts the order left out lie outside the view, as the packer's do. */
    uint32_t own = 0;
    uint64_t own_triangles = 0;
    oit_streamer_share_size(s, &own, &own_triangles);
    ss->parts_culled = own - count;
    ss->pack_ms = oit_time_ms() - t1;
    /* The packing tells what the frame will hold: the ring and the cache
     * grow to it before the first part is read. */
    if (st == OIT_OK)
        fit_frame_budget(s, view);
    if (st == OIT_OK)
        st = fit_cache(s, pk, err);
    if (st == OIT_OK)
        st = fit_ring(s, pk, err);
    if (st == OIT_OK && s->saturation)
        st = oit_saturation_begin(s->saturation, view->width, view->height,
                                  view->shading.mode == OIT_SHADING_TRANSLUCENT, err);
    if (st == OIT_OK)
        st = draw_packs(s, pk, ss, err);
    if (st != OIT_OK) {
        oit_image discard = {0};
        oit_capture_end(s->capture, &discard, NULL, NULL);
        oit_image_free(&discard);
    }
    return st;
}

/* Early termination's choice for the next frame: front-first packs while
 * they let whole parts be skipped; after a frame that skipped none, plain
 * packs, front first tried again every OIT_STREAM_PROBE_FRAMES frames. */
static void adapt_front(oit_streamer *s, oit_stream_frame_stats *ss)
{
    ss->front_first = s->front_now;
    if (s->front_now && ss->parts_skipped == 0)
        s->front_now = 0, s->plain_frames = 0;
    else if (s->front_first && !s->front_now && ++s->plain_frames >= OIT_STREAM_PROBE_FRAMES)
        s->front_now = 1;
}

/* The automatic mode's path for this frame (stream/choice.h). A frame
 * still open is judged first, on the streamer's own time. */
static void choose(oit_streamer *s, const oit_view *view)
{
    if (!s->adaptive)
        return;
    if (s->frame.open)
        oit_choice_end(&s->judge, s->frame.ms, s->frame.suggest);
    s->frame.open = 0;
    oit_path p = oit_choice_begin(&s->judge, oit_view_key(view));
    s->first_k = p == OIT_PATH_FIRSTK;
    oit_capture_set_first_k(s->capture, s->first_k);
    /* a first-K frame keeps its counts for a counted probe of its view
     * where the rule may suggest one */
    oit_capture_set_keep_counts(s->capture,
                                !s->frame.adapted || s->frame.suggest == OIT_PATH_COUNTED);
}

/* What the frame's path was chosen from (the judge's figures before the
 * frame ends). */
static void choice_stats(const oit_streamer *s, oit_stream_frame_stats *ss)
{
    ss->choice_ms[OIT_PATH_FIRSTK] = ss->choice_ms[OIT_PATH_COUNTED] = -1.0;
    if (!s->adaptive)
        return;
    for (int i = 0; i < OIT_PATHS; i++)
        ss->choice_ms[i] = oit_choice_cost(&s->judge, (oit_path)i);
    ss->choice_path = oit_path_name(s->judge.path);
    ss->choice_why = s->judge.why;
}

/* A first frame more than 1 pixel in 50 of which got more than K
 * fragments in a pack (first-K's second pass took them; a counted frame's
 * counts say it would have) is drawn again counted where it ended short
 * (render): the engine and the 1M plant at 1024x1024, 26-64 layers, send
 * 5-16% there and were 20-30% faster counted. */
static int deep_view(const oit_view *view, const oit_frame_stats *fs)
{
    return fs->deep_pixels * 50 > (uint64_t)view->width * view->height;
}

/* The fixed rule's seed: a frame where any pixel got more than K
 * fragments in a pack suggests counted packs, one where none did
 * suggests first-K. First-K draws a pack again for such pixels, however
 * few, while a still view's next counted frame is predicted from this
 * one's counts: one geometry pass, no second (the 332K-triangle CAD
 * assembly at 128x128 on llvmpipe: 29 pixels over K, first-K's pass 2 73
 * ms of a 148 ms frame, DFB 124). A moving view takes no probe (a probe
 * is a view's, stream/choice.h). A counted frame over K still suggests
 * first-K every OIT_CHOICE_BAR_MOST-th frame, so that the rule never
 * decides alone; the judge keeps a suggested path only if it measures
 * faster. */
static int over_k(const oit_frame_stats *fs)
{
    return fs->deep_pixels > 0;
}

static void adapt(oit_streamer *s, const oit_frame_stats *fs, oit_stream_frame_stats *ss,
                  double ms, int judged_now)
{
    adapt_front(s, ss);
    ss->first_k = s->adaptive ? s->first_k : 0;
    if (!s->adaptive)
        return;
    int over = over_k(fs);
    oit_path suggest = over ? OIT_PATH_COUNTED : OIT_PATH_FIRSTK;
    if (!s->first_k && over && ++s->frame.deep_counted % OIT_CHOICE_BAR_MOST == 0)
        suggest = OIT_PATH_FIRSTK;
    /* the probe's programs and store made in this frame, not the probe's:
     * its time is what the judge weighs (the 1M plant at 1024x1024: the
     * cold probe took 955 ms against 852 warm, DFB 768) */
    if (s->first_k && suggest == OIT_PATH_COUNTED)
        oit_capture_ready_counted(s->capture);
    s->frame.ms = ms;
    s->frame.suggest = suggest;
    s->frame.adapted = 1;
    s->frame.open = 1;
    if (judged_now)
        oit_streamer_frame_end(s, ms, 0);
}

void oit_streamer_frame_end(oit_streamer *s, double wall_ms, uint64_t gpu_tag)
{
    if (!s->adaptive)
        return;
    if (s->frame.open)
        oit_choice_end(&s->judge, wall_ms, s->frame.suggest);
    s->frame.open = 0;
    oit_choice_tag_gpu(&s->judge, gpu_tag);
}

void oit_streamer_gpu_figure(oit_streamer *s, uint64_t gpu_tag, double gpu_ms)
{
    if (s->adaptive)
        oit_choice_gpu(&s->judge, gpu_tag, gpu_ms);
}

static void finish_stats(const oit_streamer *s, const oit_packing *pk, oit_frame_stats *fs,
                         oit_stream_frame_stats *ss)
{
    ss->parts_drawn = pk->part_count - ss->parts_skipped;
    ss->parts_culled += pk->culled;
    ss->parts_clipped = pk->clipped;
    ss->bytes_clipped = pk->clipped_bytes;
    ss->epsilon = s->epsilon;
    ss->capture_asked = s->choice.asked == OIT_CAPTURE_AUTO ? "auto"
                                                             : oit_capture_kind_name(s->choice.asked);
    memcpy(ss->capture_fallback, s->choice.reason, sizeof ss->capture_fallback);
    ss->budget = s->budget;
    ss->reader_threads = s->threads;
    ss->draw_calls = oit_capture_draw_calls(s->capture);
    ss->cache_bytes = s->cache ? oit_residency_bytes(s->cache) : s->loaded_bytes;
    uint64_t views = 0; /* their draw records: the triangles are the ring's or cache's */
    for (uint32_t i = 0; i < s->view_count; i++)
        views += oit_gpu_mesh_bytes(s->views[i]);
    ss->gpu_bytes_peak = fs->gpu_bytes_peak + views + oit_upload_gpu_bytes(s->upload) +
                         (s->cache ? oit_residency_capacity(s->cache) : 0) + s->cache_dropped +
                         (s->saturation ? oit_saturation_gpu_bytes(s->saturation) : 0) +
                         oit_opaque_tiles_gpu_bytes(s->opaque_tiles);
    fs->gpu_bytes_peak = ss->gpu_bytes_peak;
}

/* A frame that ends in the image out, or (state set) in the capture's state
 * buffer, *state. */
static oit_status render(oit_streamer *s, const oit_view *view, oit_image *out, unsigned *state,
                         oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err)
{
    oit_stream_frame_stats local;
    oit_frame_stats flocal;
    ss = ss ? ss : &local;
    fs = fs ? fs : &flocal;
    /* A share's C and T are blended with the others' as one RGBA image a
     * process; the absorbing medium between surfaces of different shares
     * and the per-channel T cannot pass through that. */
    if (s->shares && view->shading.mode == OIT_SHADING_TRANSLUCENT)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: shading translucent over shares: "
                             "the absorbing medium and its per-channel transmittance cross "
                             "share boundaries, which an RGBA blend of the shares cannot "
                             "carry; render it whole", oit_partfile_name(s->pf));
    double t0 = oit_time_ms();
    choose(s, view);
    oit_packing pk;
    oit_status st = OIT_OK;
    /* A frame that ended short (oit_capture_short) is drawn again with the
     * store it measured: never returned (the redraw writes the same image
     * in place); its waits are the frame's, and its final read-back one
     * more; the bytes it uploaded, those of every draw (a redraw finds
     * the parts the first draw brought up in the cache). */
    uint32_t waits = 0, redraws = 0;
    uint64_t uploaded = 0;
    for (int again = 1; st == OIT_OK && again; redraws++) {
        if (redraws > 2)
            return oit_error_set(err, OIT_ERR_GL, "%s: a store sized ahead still short after "
                                 "%u redraws", oit_partfile_name(s->pf), redraws - 1);
        st = capture_frame(s, view, &pk, ss, err);
        uploaded += ss->bytes_uploaded;
        ss->bytes_uploaded = uploaded;
        choice_stats(s, ss);
        if (st == OIT_OK)
            st = state ? oit_capture_end_gpu(s->capture, state, fs, err)
                       : oit_capture_end(s->capture, out, fs, err);
        again = st == OIT_OK && oit_capture_short(s->capture);
        waits += st == OIT_OK ? fs->host_waits + (uint32_t)again : 0;
        /* First-K's first frame sizes its pass-2 store by what the slots
         * hold, which a deep view outgrows: it is drawn again counted, the
         * path the fixed rule then suggests, so that its store is built in
         * the frame already slow, not in the next. The judge counts the
         * frame as first-K's, both draws its cost. */
        if (again && s->adaptive && s->first_k && deep_view(view, fs)) {
            s->first_k = 0;
            oit_capture_set_first_k(s->capture, 0);
        }
    }
    fs->host_waits = waits;
    fs->redraws = redraws - 1;
    if (st == OIT_OK)
        finish_stats(s, &pk, fs, ss);
    /* A frame read back here ends here; one left on the GPU ends at the
     * caller's oit_streamer_frame_end (or, without one, at the next). */
    if (st == OIT_OK)
        adapt(s, fs, ss, oit_time_ms() - t0, state == NULL);
    return st;
}

uint64_t oit_streamer_pixel_bytes(const oit_view *view)
{
    return oit_capture_pixel_bytes(view);
}

void oit_stream_frame_stats_add(oit_stream_frame_stats *acc, const oit_stream_frame_stats *band)
{
    uint64_t peak = acc->gpu_bytes_peak > band->gpu_bytes_peak ? acc->gpu_bytes_peak
                                                              : band->gpu_bytes_peak;
    oit_stream_frame_stats sum = *band;
    sum.packs += acc->packs;
    sum.parts_drawn += acc->parts_drawn;
    sum.parts_culled += acc->parts_culled;
    sum.parts_clipped += acc->parts_clipped;
    sum.bytes_clipped += acc->bytes_clipped;
    sum.parts_skipped += acc->parts_skipped;
    sum.bytes_uploaded += acc->bytes_uploaded;
    sum.cache_hits += acc->cache_hits;
    sum.draw_calls += acc->draw_calls;
    sum.order_ms += acc->order_ms;
    sum.pack_ms += acc->pack_ms;
    sum.gpu_bytes_peak = peak;
    *acc = sum;
}

oit_status oit_streamer_render(oit_streamer *s, const oit_view *view, oit_image *out,
                               oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err)
{
    return render(s, view, out, NULL, fs, ss, err);
}

oit_status oit_streamer_render_gpu(oit_streamer *s, const oit_view *view, unsigned *state,
                                   oit_frame_stats *fs, oit_stream_frame_stats *ss,
                                   oit_error *err)
{
    return render(s, view, NULL, state, fs, ss, err);
}
