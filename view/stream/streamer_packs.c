/* A frame's packs (streamer_internal.h): each prepared ahead (its parts'
 * sources, ring region and reader job), then read, captured and retired
 * in order, so that reading overlaps the GPU's work. */
#include "view/stream/streamer_internal.h"

#include <stdlib.h>
#include <string.h>

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
        oit_status st =
            oit_gpu_mesh_create_view(oit_upload_buffer(s->upload), &s->views[s->view_count], err);
        if (st != OIT_OK)
            return st;
    }
    return OIT_OK;
}

int oit_streamer_saturated(oit_streamer *s, const oit_packing *pk, uint32_t j)
{
    if (s->opaque.enabled) {
        const oit_partfile_part *part = &oit_partfile_parts(s->pf)[pk->parts[j]];
        if (oit_opaque_tiles_behind(s->opaque_tiles, part->bounds_min, part->bounds_max,
                                    pk->part_rects[j]))
            return 1;
    }
    return s->saturation && oit_saturation_covered(s->saturation, pk->part_rects[j], s->epsilon);
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
        if (oit_streamer_saturated(s, pk, j)) {
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
    oit_gpu_mesh_set_buffer(view,
                            cached && s->cache ? s->cache_buffer : oit_upload_buffer(s->upload));
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
 * whose footprint is oit_streamer_saturated (saturation.h: the capture would drop all
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
        if (s->source[j] == SRC_SKIP || oit_streamer_saturated(s, pk, j)) {
            ss->parts_skipped++;
            continue;
        }
        use_part(s, pk, j, s->views[drawn++], ss);
    }
    if (st == OIT_OK && drawn > 0) {
        ss->packs++;
        st = oit_capture_batch_layers(s->capture, (const oit_gpu_mesh *const *)s->views, (int)drawn,
                                      pk->rects[i], (int)pk->layers[i], err);
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
static oit_status prepare_ahead(oit_streamer *s, const oit_packing *pk, uint32_t i, uint32_t *next,
                                oit_error *err)
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
oit_status oit_streamer_draw_packs(oit_streamer *s, const oit_packing *pk,
                                   oit_stream_frame_stats *ss, oit_error *err)
{
    uint32_t next = 0;
    oit_status st = OIT_OK;
    for (uint32_t i = 0; st == OIT_OK && i < pk->pack_count; i++) {
        /* Front-first packs are few and grow: each should see what the
         * packs before it oit_streamer_saturated (saturation.h). */
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
