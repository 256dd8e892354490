/* One GPU budget over the streamer's ring, cache and capture
 * (oit_streamer_desc.gpu_budget, view/stream/streamer.h), on a part file of
 * several parts:
 *  - a driver that reports free memory (injected: a fake
 *    GL_NVX_gpu_memory_info): the total is half of it, the file is resident
 *    after the first frame (the second uploads 0 bytes), GPU memory at peak
 *    inside the total;
 *  - no driver figure (llvmpipe itself, and injected): no total, and the
 *    defaults of before, the same image;
 *  - a total below the file: not resident, every frame's GPU peak inside it,
 *    parts read again, the image that of the resident run;
 *  - finer budgets past the total, and a total below the least, refused
 *    with a message naming them.
 *
 * usage: test_gpu_budget FILE.oitp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "view/render/image/image.h"
#include "partfile/triangles.h"
#include "view/stream/pack.h"
#include "view/stream/streamer.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 96, H = 96, VIEWS = 3 };

static oit_view make_view(const oit_partfile *pf, float azimuth)
{
    oit_mesh_info info;
    oit_partfile_mesh_info(pf, &info);
    oit_view v = {0};
    v.width = W;
    v.height = H;
    oit_camera_default(&v.camera, info.bounds_min, info.bounds_max, azimuth, 20.0f);
    v.shading.attributes = info.attributes;
    v.shading.scene_scale = oit_scene_scale(info.bounds_min, info.bounds_max);
    oit_shading_resolve_defaults(&v.shading);
    return v;
}

typedef struct fake_driver {
    uint64_t free_bytes;
    const char *name;
} fake_driver;

static uint64_t fake_free(void *ctx, const char **source)
{
    const fake_driver *d = ctx;
    *source = d->name;
    return d->free_bytes;
}

static uint64_t file_bytes(const oit_partfile *pf)
{
    uint64_t all = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(pf); i++)
        all += oit_pack_part_bytes(&oit_partfile_parts(pf)[i]);
    return all;
}

typedef struct run {
    oit_image img[VIEWS][2];
    oit_stream_frame_stats ss[VIEWS][2];
    oit_stream_budget budget;
} run;

/* Each view twice; 0 when a call failed (err says why). */
static int render_views(oit_partfile *pf, const oit_streamer_desc *d, run *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    oit_streamer *s = NULL;
    oit_status st = oit_streamer_create(pf, d, &s, err);
    if (st == OIT_OK)
        oit_streamer_budget(s, &out->budget);
    for (int v = 0; v < VIEWS && st == OIT_OK; v++) {
        oit_view view = make_view(pf, 30.0f + 120.0f * (float)v);
        for (int f = 0; f < 2 && st == OIT_OK; f++)
            st = oit_streamer_render(s, &view, &out->img[v][f], NULL, &out->ss[v][f], err);
    }
    oit_streamer_destroy(s);
    return st == OIT_OK;
}

static void free_run(run *r)
{
    for (int v = 0; v < VIEWS; v++)
        for (int f = 0; f < 2; f++)
            oit_image_free(&r->img[v][f]);
}

static double max_diff(const oit_image *a, const oit_image *b)
{
    if (a->width != b->width || a->height != b->height)
        return INFINITY;
    double most = 0;
    for (size_t i = 0; i < (size_t)a->width * a->height * 4; i++)
        most = fmax(most, fabs((double)a->rgba[i] - (double)b->rgba[i]));
    return most;
}

static void print_budget(const char *name, const oit_stream_budget *b)
{
    printf("%s: total %llu ring %llu cache %llu capture %llu store %llu resident %d free %llu "
           "(%s)\n", name, (unsigned long long)b->total, (unsigned long long)b->ring,
           (unsigned long long)b->cache, (unsigned long long)b->capture,
           (unsigned long long)b->store, b->resident,
           (unsigned long long)b->free_bytes, b->source ? b->source : "?");
}

static oit_streamer_desc base_desc(void)
{
    return (oit_streamer_desc){.K = 8, .capture = OIT_RENDER_CAPTURE_ARRAY, .pack = OIT_RENDER_PACK_AUTO};
}

int main(int argc, char **argv)
{
    oit_partfile *pf = NULL;
    oit_gl *gl = test_gl_open_partfile(argc, argv, &pf);
    oit_error err = {0};
    uint64_t all = file_bytes(pf);
    printf("%s: %u parts, %llu bytes decoded\n", argv[1], oit_partfile_part_count(pf),
           (unsigned long long)all);
    CHECK(oit_partfile_part_count(pf) >= 8 && all >= (2ull << 20),
          "the file should have several parts and 2 MiB (it has %u, %llu bytes)",
          oit_partfile_part_count(pf), (unsigned long long)all);

    /* A driver that says how much is free. */
    fake_driver nvx = {.free_bytes = 8 * all + (256ull << 20), .name = "fake NVX"};
    oit_streamer_desc d = base_desc();
    d.free_query = fake_free;
    d.free_ctx = &nvx;
    run fits;
    CHECK(render_views(pf, &d, &fits, &err), "driver figure: %s", err.message);
    print_budget("driver figure", &fits.budget);
    CHECK(fits.budget.total == nvx.free_bytes / 2 && !strcmp(fits.budget.source, "fake NVX") &&
              fits.budget.free_bytes == nvx.free_bytes,
          "total %llu from %s, half of %llu expected", (unsigned long long)fits.budget.total,
          fits.budget.source, (unsigned long long)nvx.free_bytes);
    CHECK(fits.budget.resident, "a file of %llu bytes in a total of %llu not resident",
          (unsigned long long)all, (unsigned long long)fits.budget.total);
    for (int v = 0; v < VIEWS; v++)
        for (int f = 0; f < 2; f++) {
            const oit_stream_frame_stats *ss = &fits.ss[v][f];
            CHECK(v + f == 0 || ss->bytes_uploaded == 0,
                  "resident: view %d frame %d uploaded %llu bytes", v, f,
                  (unsigned long long)ss->bytes_uploaded);
            CHECK(ss->gpu_bytes_peak <= fits.budget.total, "resident: peak %llu > total %llu",
                  (unsigned long long)ss->gpu_bytes_peak, (unsigned long long)fits.budget.total);
        }

    /* No driver figure: llvmpipe's own answer, and an injected one. */
    run plain, none;
    oit_streamer_desc p = base_desc();
    CHECK(render_views(pf, &p, &plain, &err), "llvmpipe: %s", err.message);
    print_budget("llvmpipe", &plain.budget);
    fake_driver silent = {.free_bytes = 0, .name = "no driver figure (fake)"};
    d.free_ctx = &silent;
    CHECK(render_views(pf, &d, &none, &err), "no figure: %s", err.message);
    CHECK(plain.budget.total == 0 && none.budget.total == 0 && plain.budget.free_bytes == 0,
          "no driver figure, yet totals %llu and %llu", (unsigned long long)plain.budget.total,
          (unsigned long long)none.budget.total);
    CHECK(none.budget.capture == OIT_STREAM_FIRSTK_SLOTS_DEFAULT &&
              none.budget.store == OIT_STREAM_STORE_DEFAULT && none.budget.resident &&
              none.budget.ring == plain.budget.ring,
          "no total: capture %llu, resident %d, ring %llu: the old defaults expected",
          (unsigned long long)none.budget.capture, none.budget.resident,
          (unsigned long long)none.budget.ring);

    /* A total below the file. */
    run tight;
    oit_streamer_desc t = base_desc();
    t.free_query = fake_free;
    t.free_ctx = &nvx;
    t.gpu_budget = all * 3 / 4;
    CHECK(render_views(pf, &t, &tight, &err), "below the file: %s", err.message);
    print_budget("below the file", &tight.budget);
    CHECK(!tight.budget.resident && tight.budget.total == t.gpu_budget &&
              !strcmp(tight.budget.source, "oit_streamer_desc.gpu_budget"),
          "below the file: resident %d, total %llu from %s", tight.budget.resident,
          (unsigned long long)tight.budget.total, tight.budget.source);
    /* the store is a share of its own, not taken from the others' */
    const oit_stream_budget *tb = &tight.budget;
    CHECK(tb->store > 0 && tb->store <= t.gpu_budget / 8 &&
              tb->capture + tb->store + tb->ring + tb->cache <= t.gpu_budget,
          "below the file: capture %llu + store %llu + ring %llu + cache %llu past %llu",
          (unsigned long long)tb->capture, (unsigned long long)tb->store,
          (unsigned long long)tb->ring, (unsigned long long)tb->cache,
          (unsigned long long)t.gpu_budget);
    uint64_t reread = 0;
    for (int v = 0; v < VIEWS; v++)
        for (int f = 0; f < 2; f++) {
            const oit_stream_frame_stats *ss = &tight.ss[v][f];
            printf("below the file: view %d frame %d: peak %llu, uploaded %llu\n", v, f,
                   (unsigned long long)ss->gpu_bytes_peak,
                   (unsigned long long)ss->bytes_uploaded);
            CHECK(ss->gpu_bytes_peak <= t.gpu_budget, "view %d frame %d: GPU peak %llu > %llu",
                  v, f, (unsigned long long)ss->gpu_bytes_peak,
                  (unsigned long long)t.gpu_budget);
            reread += f == 1 ? ss->bytes_uploaded : 0;
            double diff = max_diff(&tight.img[v][f], &fits.img[v][f]);
            CHECK(diff <= 1e-6, "view %d frame %d: %.3g from the resident image", v, f, diff);
            CHECK(max_diff(&plain.img[v][f], &fits.img[v][f]) <= 1e-6,
                  "view %d frame %d: the default image changed", v, f);
        }
    CHECK(reread > 0, "a total below the file, yet no part read again");

    /* The same total with the compute capture: its resume cursors (16
     * bytes a pixel, the output's buffer at the frame's end), its records
     * and tile lists (a pack's triangles, 176 bytes each) are inside it
     * too; its image is that of the compute capture with the file
     * resident. */
    run comp, comp_fits;
    t.capture = OIT_RENDER_CAPTURE_COMPUTE;
    d.capture = OIT_RENDER_CAPTURE_COMPUTE;
    d.free_ctx = &nvx;
    CHECK(render_views(pf, &t, &comp, &err), "compute, below the file: %s", err.message);
    CHECK(render_views(pf, &d, &comp_fits, &err), "compute, resident: %s", err.message);
    print_budget("compute, below the file", &comp.budget);
    for (int v = 0; v < VIEWS; v++)
        for (int f = 0; f < 2; f++) {
            const oit_stream_frame_stats *ss = &comp.ss[v][f];
            double diff = max_diff(&comp.img[v][f], &comp_fits.img[v][f]);
            printf("compute, below the file: view %d frame %d: peak %llu, %.3g from resident\n",
                   v, f, (unsigned long long)ss->gpu_bytes_peak, diff);
            CHECK(diff <= 1e-6, "compute: view %d frame %d: %.3g from the resident image", v, f,
                  diff);
            CHECK(ss->gpu_bytes_peak <= t.gpu_budget,
                  "compute: view %d frame %d: GPU peak %llu > %llu", v, f,
                  (unsigned long long)ss->gpu_bytes_peak, (unsigned long long)t.gpu_budget);
        }

    /* Refusals. */
    oit_streamer *s = NULL;
    oit_streamer_desc x = base_desc();
    x.gpu_budget = 4ull << 20;
    x.upload_budget = 2ull << 20;
    x.cache_budget = 4ull << 20;
    CHECK(oit_streamer_create(pf, &x, &s, &err) == OIT_ERR_ARGUMENT &&
              strstr(err.message, "more than oit_streamer_desc.gpu_budget"),
          "finer budgets past the total: %s", s ? "accepted" : err.message);
    printf("refused: %s\n", err.message);
    oit_streamer_destroy(s);
    s = NULL;
    x = base_desc();
    x.gpu_budget = OIT_STREAM_GPU_BUDGET_MIN - 1;
    CHECK(oit_streamer_create(pf, &x, &s, &err) == OIT_ERR_ARGUMENT,
          "a total below the least: %s", s ? "accepted" : err.message);
    printf("refused: %s\n", err.message);
    oit_streamer_destroy(s);

    free_run(&fits);
    free_run(&plain);
    free_run(&none);
    free_run(&tight);
    free_run(&comp);
    free_run(&comp_fits);
    oit_partfile_close(pf);
    oit_gl_destroy(gl);
    return test_verdict();
}
