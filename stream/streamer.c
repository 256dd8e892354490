/* Part-file streaming renderer (streamer.h). */
#include "stream/streamer.h"

#include <stdlib.h>
#include <string.h>

#include "render/gpu_mesh.h"
#include "render/image.h"
#include "render/saturation.h"
#include "stream/order.h"
#include "stream/upload.h"

_Static_assert(OIT_PACK_MAX_LAYERS == OIT_CAPTURE_MAX_LAYERS &&
                   OIT_PACK_MAX_LAYERS == OIT_PARTFILE_MAX_LAYERS,
               "a wide part the file allows must fit the packer and the capture");

struct oit_streamer {
    oit_partfile *pf;
    oit_order *order;
    oit_packer *packer;
    oit_upload *upload;
    oit_capture *capture;
    oit_saturation *saturation; /* only with epsilon > 0 */
    float epsilon;
    uint32_t *ordered;
    uint32_t *first_prim; /* per part: its first triangle across the file */
    uint8_t *validated;
    oit_gpu_mesh **views; /* one per part of the largest pack so far */
    uint32_t view_count;
};

void oit_streamer_destroy(oit_streamer *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; i < s->view_count; i++)
        oit_gpu_mesh_destroy(s->views[i]);
    free(s->views);
    oit_saturation_destroy(s->saturation);
    oit_capture_destroy(s->capture);
    oit_upload_destroy(s->upload);
    oit_packer_destroy(s->packer);
    oit_order_destroy(s->order);
    free(s->ordered);
    free(s->first_prim);
    free(s->validated);
    free(s);
}

/* Primitive ids follow the file's triangle order, as in the in-core mesh
 * (part_triangles.h); they must fit the 31 bits a fragment carries. */
static oit_status number_triangles(oit_streamer *s, uint64_t *max_part_bytes, oit_error *err)
{
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    uint64_t first = 0;
    *max_part_bytes = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(s->pf); i++) {
        s->first_prim[i] = (uint32_t)first;
        first += parts[i].index_count / 3;
        uint64_t b = parts[i].index_count / 3 * sizeof(oit_triangle);
        *max_part_bytes = b > *max_part_bytes ? b : *max_part_bytes;
        if (first > 0x80000000ull)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: more than 2^31 triangles; "
                                 "primitive ids would not fit a fragment",
                                 oit_partfile_name(s->pf));
    }
    return OIT_OK;
}

oit_status oit_streamer_create(oit_partfile *pf, const oit_streamer_desc *desc,
                               oit_streamer **out, oit_error *err)
{
    *out = NULL;
    uint32_t n = oit_partfile_part_count(pf);
    oit_streamer *s = calloc(1, sizeof *s);
    if (s) {
        s->pf = pf;
        s->ordered = calloc((size_t)n + 1, sizeof *s->ordered);
        s->first_prim = calloc((size_t)n + 1, sizeof *s->first_prim);
        s->validated = calloc((size_t)n + 1, 1);
    }
    if (!s || !s->ordered || !s->first_prim || !s->validated) {
        oit_streamer_destroy(s);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the streamer (%u parts)",
                             oit_partfile_name(pf), n);
    }
    uint64_t budget = desc->upload_budget ? desc->upload_budget : 64ull << 20, max_part = 0;
    oit_pack_mode mode = desc->pack != OIT_PACK_AUTO ? desc->pack
                         : desc->epsilon > 0.0f ? OIT_PACK_DISJOINT
                                                : OIT_PACK_COUNTED;
    oit_status st = number_triangles(s, &max_part, err);
    if (st == OIT_OK)
        st = oit_order_create(pf, &s->order, err);
    if (st == OIT_OK)
        st = oit_packer_create(pf, mode, desc->K, budget, &s->packer, err);
    if (st == OIT_OK)
        oit_packer_set_schedule(s->packer, desc->schedule);
    if (st == OIT_OK)
        st = oit_upload_create(budget, max_part, &s->upload, err);
    if (st == OIT_OK)
        st = oit_capture_create(mode == OIT_PACK_COUNTED ? OIT_CAPTURE_COUNTED : desc->capture,
                                desc->K, &s->capture, err);
    if (st == OIT_OK)
        oit_capture_set_slot_budget(s->capture, desc->slot_budget ? desc->slot_budget
                                                                  : 32ull << 20);
    if (st == OIT_OK && desc->epsilon > 0.0f) {
        s->epsilon = desc->epsilon;
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

/* Uploads and captures pack i, leaving out the parts whose footprint is
 * saturated (saturation.h: the capture would drop all their fragments). */
static oit_status draw_pack(oit_streamer *s, const oit_packing *pk, uint32_t i,
                            oit_stream_frame_stats *ss, oit_error *err)
{
    uint32_t first = pk->pack_first[i], n = pk->pack_first[i + 1] - first, drawn = 0;
    oit_status st = reserve_views(s, n, err);
    if (st == OIT_OK)
        st = oit_upload_begin_pack(s->upload, pk->bytes[i], err);
    const oit_partfile_part *parts = oit_partfile_parts(s->pf);
    for (uint32_t k = 0; k < n && st == OIT_OK; k++) {
        uint32_t p = pk->parts[first + k];
        if (s->saturation && oit_saturation_covered(s->saturation, pk->part_rects[first + k],
                                                    s->epsilon)) {
            ss->parts_skipped++;
            continue;
        }
        uint64_t offset = 0;
        if (!s->validated[p] && (st = oit_partfile_validate_part(s->pf, p, err)) != OIT_OK)
            break;
        s->validated[p] = 1;
        st = oit_upload_part(s->upload, s->pf, p, &offset, err);
        oit_gpu_mesh_set_range(s->views[drawn++], offset, (size_t)(parts[p].index_count / 3),
                               s->first_prim[p]);
        ss->bytes_uploaded += parts[p].index_count / 3 * sizeof(oit_triangle);
    }
    if (st != OIT_OK || drawn == 0)
        return st;
    ss->packs++;
    st = oit_capture_batch_layers(s->capture, (const oit_gpu_mesh *const *)s->views, (int)drawn,
                                  pk->rects[i], (int)pk->layers[i], err);
    if (st == OIT_OK && s->saturation)
        st = oit_saturation_update(s->saturation, oit_capture_state_buffer(s->capture),
                                   pk->rects[i], err);
    return st;
}

/* Captures every pack of the view; on failure the frame is ended and
 * discarded. */
static oit_status capture_frame(oit_streamer *s, const oit_view *view, oit_packing *pk,
                                oit_stream_frame_stats *ss, oit_error *err)
{
    memset(ss, 0, sizeof *ss);
    uint32_t count = 0;
    oit_status st = oit_capture_begin(s->capture, view, err);
    if (st == OIT_OK)
        st = oit_order_compute(s->order, view->camera.eye, s->ordered, &count, err);
    if (st == OIT_OK)
        st = oit_packer_run(s->packer, view, s->ordered, count, pk, err);
    if (st == OIT_OK && s->saturation)
        st = oit_saturation_begin(s->saturation, view->width, view->height, err);
    for (uint32_t i = 0; st == OIT_OK && i < pk->pack_count; i++)
        st = draw_pack(s, pk, i, ss, err);
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
    ss->parts_culled = pk->culled;
    ss->epsilon = s->epsilon;
    ss->gpu_bytes_peak = fs->gpu_bytes_peak + oit_upload_gpu_bytes(s->upload) +
                         (s->saturation ? oit_saturation_gpu_bytes(s->saturation) : 0);
    fs->gpu_bytes_peak = ss->gpu_bytes_peak;
}

oit_status oit_streamer_render(oit_streamer *s, const oit_view *view, oit_image *out,
                               oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err)
{
    oit_stream_frame_stats local;
    oit_frame_stats flocal;
    ss = ss ? ss : &local;
    fs = fs ? fs : &flocal;
    oit_packing pk;
    oit_status st = capture_frame(s, view, &pk, ss, err);
    if (st == OIT_OK)
        st = oit_capture_end(s->capture, out, fs, err);
    if (st == OIT_OK)
        finish_stats(s, &pk, fs, ss);
    return st;
}

oit_status oit_streamer_render_gpu(oit_streamer *s, const oit_view *view, unsigned *state,
                                   oit_frame_stats *fs, oit_stream_frame_stats *ss,
                                   oit_error *err)
{
    oit_stream_frame_stats local;
    oit_frame_stats flocal;
    ss = ss ? ss : &local;
    fs = fs ? fs : &flocal;
    oit_packing pk;
    oit_status st = capture_frame(s, view, &pk, ss, err);
    if (st == OIT_OK)
        st = oit_capture_end_gpu(s->capture, state, fs, err);
    if (st == OIT_OK)
        finish_stats(s, &pk, fs, ss);
    return st;
}
