/* Part-file streaming renderer (streamer.h): creation, the frame and its
 * figures; the rest in streamer_memory.c, _packs.c and _adapt.c
 * (streamer_internal.h). */
#include "view/stream/streamer_internal.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

_Static_assert(OIT_PACK_MAX_LAYERS == OIT_CAPTURE_MAX_LAYERS &&
                   OIT_PACK_MAX_LAYERS == OIT_PARTFILE_MAX_LAYERS,
               "a wide part the file allows must fit the packer and the capture");

_Static_assert(OIT_PATHS == sizeof(((oit_stream_frame_stats *)0)->choice_ms) / sizeof(double),
               "a cost figure per path the judge weighs");


void oit_streamer_budget(const oit_streamer *s, oit_stream_budget *out)
{
    *out = s->budget;
}

void oit_streamer_resolved_desc(const oit_streamer *s, oit_streamer_desc *out)
{
    const oit_stream_budget *b = &s->budget;
    *out = s->desc;
    out->capture = s->choice.slots; /* AUTO where none ran: counted packs */
    out->upload_budget = b->ring;
    out->cache_budget = b->cache ? b->cache : OIT_STREAM_CACHE_OFF;
    out->slot_budget = b->capture;
    out->store_budget = b->store;
    out->gpu_budget = b->total;
    out->reader_threads = s->threads ? s->threads : OIT_STREAM_READ_INLINE;
    out->epsilon = s->epsilon;
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


const oit_capture_choice *oit_streamer_capture_choice(const oit_streamer *s)
{
    return &s->choice;
}

/* The pack mode's capture (mode: what the packs are cut for), its K-slot
 * fills as desc->capture asks (view/render/capture/capture.h's table). The
 * capture's settings: split_budget gave both budgets their values (the
 * counted and first-K captures store fragments beside their slots; 32
 * MiB, 2 a pixel at 1024x1024, split the packs of dense views, which then
 * drew again: bench/stream-vs-dfb-llvmpipe.md); first-K's pass 2 and
 * counted batches run without waits (a short frame is drawn again:
 * render); only auto's counted frames predict from first-K's counts. */
static oit_status create_capture(oit_streamer *s, const oit_streamer_desc *desc,
                                 oit_render_pack mode, oit_error *err)
{
    const oit_streamer_names n = oit_streamer_names_resolve(desc->names);
    oit_capture_desc cd = {
        .fill = desc->capture, .cut = mode, .K = desc->K, .faults = desc->capture_faults,
        .programs = desc->programs, .fill_name = n.capture, .cut_name = n.pack,
        .settings = {.epsilon = desc->epsilon, .slot_budget = s->budget.capture,
                     .store_budget = s->budget.store, .store_limit = desc->store_limit,
                     .timer = s->timer, .no_wait = 1, .no_counts = !s->adaptive}};
    oit_status st = oit_capture_create(&cd, &s->capture, err);
    if (st == OIT_OK)
        s->choice = *oit_capture_get_choice(s->capture);
    return st;
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
    oit_render_pack mode = desc->pack != OIT_RENDER_PACK_AUTO            ? desc->pack
                           : desc->capture == OIT_RENDER_CAPTURE_COMPUTE ? OIT_RENDER_PACK_COUNTED
                                                                         : OIT_RENDER_PACK_FIRSTK;
    /* counted and first-K packs store fragments and are cut front first */
    int stores = mode == OIT_RENDER_PACK_COUNTED || mode == OIT_RENDER_PACK_FIRSTK;
    s->adaptive = desc->pack == OIT_RENDER_PACK_AUTO && mode == OIT_RENDER_PACK_FIRSTK;
    oit_path seed = desc->frames == 1 ? OIT_PATH_COUNTED : OIT_PATH_FIRSTK;
    s->first_k = seed == OIT_PATH_FIRSTK;
    oit_choice_init(&s->judge, 1u << OIT_PATH_FIRSTK | 1u << OIT_PATH_COUNTED, seed);
    oit_status st = reader_threads(pf, desc->reader_threads, &s->threads, err);
    if (st == OIT_OK)
        st = oit_streamer_alloc_arrays(s, oit_partfile_part_count(pf), err);
    if (st == OIT_OK)
        st = make_shares(s, desc, err);
    if (st == OIT_OK)
        st = oit_streamer_number_triangles(s, &all_bytes, err);
    if (st == OIT_OK)
        st = oit_streamer_split_budget(s, &eff, stores, all_bytes, err);
    desc = &eff;
    uint64_t most = desc->upload_budget ? desc->upload_budget : OIT_STREAM_RING_DEFAULT;
    uint64_t budget = most;
    /* A ring as large as all the parts holds any pack, and the whole file
     * in one lap (resident, make_resident): a small model needs no 64 MiB
     * of GPU memory for it. */
    if (all_bytes < budget)
        budget = all_bytes > OIT_STREAM_RING_MIN ? all_bytes : OIT_STREAM_RING_MIN;
    if (st == OIT_OK && desc->capture == OIT_RENDER_CAPTURE_COMPUTE)
        budget = min_u64(budget, max_u64(oit_streamer_compute_pack_budget(desc->slot_budget),
                                         oit_streamer_largest_part(pf)));
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
    s->front_first = desc->epsilon > 0.0f && stores;
    s->front_now = s->front_first;
    if (st == OIT_OK)
        st = oit_streamer_create_upload(s, desc, budget, all_bytes, err);
    if (st == OIT_OK) {
        s->budget.resident = s->home != NULL;
        s->budget.ring = s->ring_limit;
        s->budget.cache = s->home ? 0 : s->cache_limit;
    }
    if (st == OIT_OK)
        st = create_capture(s, desc, mode, err);
    s->ahead = AHEAD_EXACT;
    if (st == OIT_OK && desc->epsilon > 0.0f) {
        s->epsilon = desc->epsilon;
        s->ahead = AHEAD_EPSILON;
        st = oit_saturation_create(&s->saturation, err);
    }
    if (st != OIT_OK) {
        oit_streamer_destroy(s);
        return st;
    }
    *out = s;
    return OIT_OK;
}


void oit_streamer_set_gpu_timer(oit_streamer *s, oit_gpu_timer *t)
{
    s->timer = t;
    oit_capture_settings cs = oit_capture_get_settings(s->capture);
    cs.timer = t;
    oit_capture_apply(s->capture, &cs);
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
            if (oit_streamer_is_mine(s, s->ordered[i]))
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
        oit_streamer_fit_frame_budget(s, view);
    if (st == OIT_OK)
        st = oit_streamer_fit_cache(s, pk, err);
    if (st == OIT_OK)
        st = oit_streamer_fit_ring(s, pk, err);
    if (st == OIT_OK && s->saturation)
        st = oit_saturation_begin(s->saturation, view->width, view->height,
                                  view->shading.mode == OIT_SHADING_TRANSLUCENT, err);
    if (st == OIT_OK)
        st = oit_streamer_draw_packs(s, pk, ss, err);
    if (st != OIT_OK) {
        oit_image discard = {0};
        oit_capture_end(s->capture, &discard, NULL, NULL);
        oit_image_free(&discard);
    }
    return st;
}


static void finish_stats(const oit_streamer *s, const oit_packing *pk, oit_frame_stats *fs,
                         oit_stream_frame_stats *ss)
{
    ss->parts_drawn = pk->part_count - ss->parts_skipped;
    ss->parts_culled += pk->culled;
    ss->parts_clipped = pk->clipped;
    ss->bytes_clipped = pk->clipped_bytes;
    ss->epsilon = s->epsilon;
    ss->capture_asked = oit_capture_asked_name(s->choice.asked);
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
                         uint32_t *counts, oit_frame_stats *fs, oit_stream_frame_stats *ss,
                         oit_error *err)
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
    oit_streamer_choose(s, view);
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
        oit_streamer_choice_stats(s, ss);
        if (st == OIT_OK)
            st = state ? oit_capture_end_gpu(s->capture, state, fs, err)
                       : oit_capture_end_counts(s->capture, out, counts, fs, err);
        again = st == OIT_OK && oit_capture_short(s->capture);
        waits += st == OIT_OK ? fs->host_waits + (uint32_t)again : 0;
        /* First-K's first frame sizes its pass-2 store by what the slots
         * hold, which a deep view outgrows: it is drawn again counted, the
         * path the fixed rule then suggests, so that its store is built in
         * the frame already slow, not in the next. The judge counts the
         * frame as first-K's, both draws its cost. */
        if (again && s->adaptive && s->first_k && oit_streamer_deep_view(view, fs)) {
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
        oit_streamer_adapt(s, fs, ss, oit_time_ms() - t0, state == NULL);
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
    return render(s, view, out, NULL, NULL, fs, ss, err);
}

oit_status oit_streamer_render_counts(oit_streamer *s, const oit_view *view, oit_image *out,
                                      uint32_t *counts, oit_frame_stats *fs,
                                      oit_stream_frame_stats *ss, oit_error *err)
{
    return render(s, view, out, NULL, counts, fs, ss, err);
}

oit_status oit_streamer_render_gpu(oit_streamer *s, const oit_view *view, unsigned *state,
                                   oit_frame_stats *fs, oit_stream_frame_stats *ss,
                                   oit_error *err)
{
    return render(s, view, NULL, state, NULL, fs, ss, err);
}
