/* The streamer's GPU memory (streamer_internal.h): the budget's split
 * between ring, cache, slots and store, and the cache, ring and resident
 * file sized within their shares. */
#include "view/stream/streamer_internal.h"

#include <stdlib.h>
#include <string.h>

/* The bytes of the file's largest part (oit_pack_part_bytes). */
uint64_t oit_streamer_largest_part(const oit_partfile *pf)
{
    uint64_t most = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(pf); i++)
        most = max_u64(most, oit_pack_part_bytes(&oit_partfile_parts(pf)[i]));
    return most;
}

/* The pack bytes whose triangles the compute capture holds within its
 * share (slot: the capture's budget; 0: no bound). */
uint64_t oit_streamer_compute_pack_budget(uint64_t slot)
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
oit_status oit_streamer_split_budget(oit_streamer *s, oit_streamer_desc *d, int stores,
                                     uint64_t all_bytes, oit_error *err)
{
    oit_stream_budget *b = &s->budget;
    const char *src = "default";
    const oit_streamer_names n = oit_streamer_names_resolve(d->names);
    oit_gpu_free_query query = d->free_query ? d->free_query : oit_gpu_free_bytes;
    b->free_bytes = query(d->free_ctx, &src);
    uint64_t slots = stores ? OIT_STREAM_FIRSTK_SLOTS_DEFAULT : OIT_STREAM_SLOTS_DEFAULT;
    uint64_t store = stores ? OIT_STREAM_STORE_DEFAULT : 0;
    if (d->gpu_budget) {
        b->total = d->gpu_budget;
        b->source = n.gpu_budget;
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
                   : d->cache_budget                       ? d->cache_budget
                                                           : OIT_STREAM_CACHE_DEFAULT;
        return OIT_OK;
    }
    const char *name = oit_partfile_name(s->pf);
    if (b->total < OIT_STREAM_GPU_BUDGET_MIN)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: a GPU budget of %llu bytes (%s); at "
                             "least %llu",
                             name, (unsigned long long)b->total, b->source,
                             (unsigned long long)OIT_STREAM_GPU_BUDGET_MIN);
    b->capture = d->slot_budget ? d->slot_budget : min_u64(slots, b->total / 8);
    b->store = stores && d->store_budget ? d->store_budget : min_u64(store, b->total / 8);
    /* The compute capture's records and tile lists hold a pack's
     * triangles (its packs are cut to its share, compute_pack_budget): at
     * least those of the largest part, which no pack splits. */
    if (d->capture == OIT_RENDER_CAPTURE_COMPUTE && !d->slot_budget)
        b->capture =
            max_u64(b->capture, (oit_streamer_largest_part(s->pf) + sizeof(oit_triangle) - 1) /
                                    sizeof(oit_triangle) * OIT_COMPUTE_CAPTURE_TRIANGLE_BYTES);
    uint64_t held = b->capture + b->store;
    uint64_t left = held < b->total ? b->total - held : 0;
    int off = d->cache_budget == OIT_STREAM_CACHE_OFF;
    uint64_t pixels = min_u64(b->total / 8, PIXEL_ROOM);
    int fits = !off && !d->upload_budget && !d->cache_budget && left > pixels &&
               all_bytes <= left - pixels;
    b->ring = d->upload_budget ? d->upload_budget
              : fits           ? all_bytes
                               : min_u64(OIT_STREAM_RING_DEFAULT, left / 4);
    b->cache = off               ? 0
               : d->cache_budget ? d->cache_budget
               : fits            ? all_bytes
               : left > b->ring  ? left - b->ring
                                 : 0;
    /* as create_upload decides: resident, the ring is the only copy */
    int resident = !off && all_bytes <= b->ring && all_bytes <= b->cache;
    uint64_t sum = held + b->ring + (resident ? 0 : b->cache);
    if (sum > b->total && d->gpu_budget)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: %s %llu + %s %llu + %s %llu + %s %llu = %llu bytes, more "
                             "than %s %llu",
                             name, n.upload_budget, (unsigned long long)b->ring, n.cache_budget,
                             (unsigned long long)b->cache, n.slot_budget,
                             (unsigned long long)b->capture, n.store_budget,
                             (unsigned long long)b->store, (unsigned long long)sum, n.gpu_budget,
                             (unsigned long long)b->total);
    if (sum > b->total)
        b->total = sum; /* finer budgets given past the driver's share win */
    d->slot_budget = b->capture;
    d->store_budget = b->store;
    d->upload_budget = b->ring > OIT_STREAM_RING_MIN ? b->ring : OIT_STREAM_RING_MIN;
    d->cache_budget = off        ? OIT_STREAM_CACHE_OFF
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
void oit_streamer_fit_frame_budget(oit_streamer *s, const oit_view *view)
{
    const oit_stream_budget *b = &s->budget;
    if (!b->total || s->home || !b->cache)
        return;
    uint64_t pixel =
        (uint64_t)view->width * view->height * (oit_capture_pixel_bytes(view) + PIXEL_EXTRA);
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

/* A part of the streamer's share (all are, without one). */
int oit_streamer_is_mine(const oit_streamer *s, uint32_t part)
{
    return !s->shares || oit_shares_of_part(s->shares, part) == s->share_index;
}

/* Primitive ids are the triangles' source indices, uploaded with them
 * (partfile/triangles.h), as the in-core mesh's positions order; they must fit
 * the 31 bits a fragment carries. *all_bytes: what every part takes in the
 * ring, the most a cache needs. */
oit_status oit_streamer_number_triangles(oit_streamer *s, uint64_t *all_bytes, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    oit_partfile_summary sum;
    oit_partfile_get_summary(s->pf, &sum);
    if (sum.triangles_in > 0x80000000ull)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "%s: more than 2^31 source triangles; "
                             "primitive ids would not fit a fragment",
                             oit_partfile_name(s->pf));
    *all_bytes = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(s->pf); i++)
        *all_bytes += oit_streamer_is_mine(s, i) ? oit_pack_part_bytes(&parts[i]) : 0;
    return OIT_OK;
}

oit_status oit_streamer_alloc_arrays(oit_streamer *s, uint32_t n, oit_error *err)
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
oit_status oit_streamer_fit_cache(oit_streamer *s, const oit_packing *pk, oit_error *err)
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
oit_status oit_streamer_fit_ring(oit_streamer *s, const oit_packing *pk, oit_error *err)
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
oit_status oit_streamer_make_resident(oit_streamer *s, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    uint32_t n = oit_partfile_part_count(s->pf);
    s->home = calloc((size_t)n + 1, sizeof *s->home);
    s->loaded = calloc((size_t)n + 1, 1);
    if (!s->home || !s->loaded)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the streamer (%u parts)",
                             oit_partfile_name(s->pf), n);
    for (uint32_t i = 1; i <= n; i++)
        s->home[i] = s->home[i - 1] +
                     (oit_streamer_is_mine(s, i - 1) ? oit_pack_part_bytes(&parts[i - 1]) : 0);
    return OIT_OK;
}

static int fits_resident(const oit_streamer_desc *desc, uint64_t budget, uint64_t all_bytes)
{
    uint64_t cache = desc->cache_budget ? desc->cache_budget : OIT_STREAM_CACHE_DEFAULT;
    return desc->cache_budget != OIT_STREAM_CACHE_OFF && all_bytes <= budget && all_bytes <= cache;
}

/* A resident ring is the file's size from the start; a reused one starts
 * at OIT_STREAM_RING_MIN and grows with the frames (fit_ring). */
oit_status oit_streamer_create_upload(oit_streamer *s, const oit_streamer_desc *desc,
                                      uint64_t budget, uint64_t all_bytes, oit_error *err)
{
    int resident = fits_resident(desc, budget, all_bytes);
    s->ring_limit = budget;
    oit_status st = oit_fence_queue_create(&s->fences, err);
    if (st == OIT_OK)
        st = make_ring(s, resident || budget < OIT_STREAM_RING_MIN ? budget : OIT_STREAM_RING_MIN,
                       err);
    if (st == OIT_OK && resident)
        st = oit_streamer_make_resident(s, err);
    else if (st == OIT_OK)
        limit_cache(s, desc->cache_budget, all_bytes);
    return st;
}
