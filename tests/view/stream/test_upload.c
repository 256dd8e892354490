/* The streamer's upload pipeline (view/stream/streamer.h, reader.h, upload.h,
 * residency.h) on a part file written by test_streamer:
 *  - one view rendered twice: with the residency cache the second render
 *    uploads 0 bytes and draws every part from the cache; without it, it
 *    uploads what the first did;
 *  - every image is bit-identical to the first: cache on or off, reader
 *    thread or none, an 8K upload ring (a dozen wraps and fence waits a
 *    frame), a cache smaller than the file (packs whose parts alternate
 *    between the ring and the cache);
 *  - draw calls: one multi-draw a pack when its parts all lie in the ring
 *    (one region) or all in the cache; with both, one per run of parts in
 *    one buffer, so between the packs and the parts;
 *  - a part corrupted in the file (one byte of its blob flipped, opened with
 *    defer_part_data) fails the render with OIT_ERR_FORMAT naming the file
 *    and the part, with and without the thread, again on a second render;
 *  - the ring's rules, which llvmpipe's images cannot show (it pulls
 *    vertices while the draw call is issued, so overwriting a region right
 *    after its draws leaves the image intact): an undrawn region is never
 *    reclaimed, a drawn one only once its fence completed;
 *  - the reader alone: jobs give the bytes oit_part_expand gives, a full
 *    queue is refused, destroy with jobs outstanding returns;
 *  - destroy right after create and after an error (the CI build runs this
 *    under ASan and LeakSanitizer).
 * A hang fails through the ctest timeout.
 *
 * usage: test_upload FILE.oitp */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_context.h"
#include "view/render/image/image.h"
#include "partfile/order.h"
#include "partfile/triangles.h"
#include "view/stream/reader.h"
#include "view/stream/streamer.h"
#include "view/stream/upload.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { W = 96, H = 96 };

static oit_view make_view(const oit_partfile *pf)
{
    oit_mesh_info info;
    oit_partfile_mesh_info(pf, &info);
    oit_view v = {0};
    v.width = W;
    v.height = H;
    oit_camera_default(&v.camera, info.bounds_min, info.bounds_max, 30.0f, 20.0f);
    v.shading.attributes = info.attributes;
    v.shading.scene_scale = oit_scene_scale(info.bounds_min, info.bounds_max);
    oit_shading_resolve_defaults(&v.shading);
    return v;
}

static oit_streamer_desc base_desc(void)
{
    return (oit_streamer_desc){.K = 8, .capture = OIT_RENDER_CAPTURE_ARRAY, .pack = OIT_RENDER_PACK_DISJOINT};
}

static int same_image(const oit_image *a, const oit_image *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->rgba, b->rgba, (size_t)a->width * a->height * 4 * sizeof(float)) == 0;
}

typedef struct run {
    oit_image img[2];
    oit_stream_frame_stats ss[2];
} run;

/* Renders the view twice with d; 0 when a call failed. */
static int render_twice(oit_partfile *pf, const oit_view *v, const oit_streamer_desc *d,
                        const char *name, run *out)
{
    oit_error err = {0};
    oit_streamer *s = NULL;
    memset(out, 0, sizeof *out);
    oit_status st = oit_streamer_create(pf, d, &s, &err);
    uint64_t overflow = 0;
    for (int f = 0; f < 2 && st == OIT_OK; f++) {
        oit_frame_stats fs = {0};
        st = oit_streamer_render(s, v, &out->img[f], &fs, &out->ss[f], &err);
        overflow += fs.overflow_pixels;
    }
    oit_streamer_destroy(s);
    CHECK(st == OIT_OK, "%s: %s", name, err.message);
    /* An overflowing pixel keeps the fragments that won its slots' atomics,
     * in no defined order: only frames without overflow can be bit-identical. */
    CHECK(overflow == 0, "%s: %llu overflow pixels", name, (unsigned long long)overflow);
    for (int f = 0; f < 2 && st == OIT_OK; f++) {
        const oit_stream_frame_stats *ss = &out->ss[f];
        int one_source = ss->cache_hits == 0 || ss->cache_hits == ss->parts_drawn;
        printf("%s: frame %d: %u packs, %llu parts, %llu draw calls\n", name, f, ss->packs,
               (unsigned long long)ss->parts_drawn, (unsigned long long)ss->draw_calls);
        CHECK(one_source ? ss->draw_calls == ss->packs
                         : ss->draw_calls >= ss->packs && ss->draw_calls <= ss->parts_drawn,
              "%s: frame %d: %llu draw calls for %u packs of %llu parts, %llu from the cache",
              name, f, (unsigned long long)ss->draw_calls, ss->packs,
              (unsigned long long)ss->parts_drawn, (unsigned long long)ss->cache_hits);
    }
    if (st == OIT_OK)
        printf("%s: frame 0: %llu parts, %llu bytes, %llu hits; frame 1: %llu parts, %llu "
               "bytes, %llu hits, %llu bytes cached; GPU peak %llu\n", name,
               (unsigned long long)out->ss[0].parts_drawn,
               (unsigned long long)out->ss[0].bytes_uploaded,
               (unsigned long long)out->ss[0].cache_hits,
               (unsigned long long)out->ss[1].parts_drawn,
               (unsigned long long)out->ss[1].bytes_uploaded,
               (unsigned long long)out->ss[1].cache_hits,
               (unsigned long long)out->ss[1].cache_bytes,
               (unsigned long long)out->ss[1].gpu_bytes_peak);
    return st == OIT_OK;
}

static void free_run(run *r)
{
    oit_image_free(&r->img[0]);
    oit_image_free(&r->img[1]);
}

static void residency_and_identity(oit_partfile *pf, const oit_view *v)
{
    run ref, r;
    oit_streamer_desc d = base_desc();
    if (!render_twice(pf, v, &d, "cache", &ref))
        return;
    uint64_t b0 = ref.ss[0].bytes_uploaded;
    CHECK(b0 > 0 && ref.ss[0].cache_hits == 0, "cache: first frame uploaded %llu bytes, %llu "
          "hits", (unsigned long long)b0, (unsigned long long)ref.ss[0].cache_hits);
    CHECK(ref.ss[1].bytes_uploaded == 0 && ref.ss[1].cache_hits == ref.ss[1].parts_drawn,
          "cache: second frame uploaded %llu bytes, %llu of %llu parts from the cache",
          (unsigned long long)ref.ss[1].bytes_uploaded,
          (unsigned long long)ref.ss[1].cache_hits, (unsigned long long)ref.ss[1].parts_drawn);
    CHECK(same_image(&ref.img[0], &ref.img[1]), "cache: the two frames differ");
    struct {
        const char *name;
        uint64_t cache, ring;
        int threads;
    } cfg[] = {{"no cache", OIT_STREAM_CACHE_OFF, 0, 0},
               {"no thread, no cache", OIT_STREAM_CACHE_OFF, 0, OIT_STREAM_READ_INLINE},
               {"no thread, cache", 0, 0, OIT_STREAM_READ_INLINE},
               {"1 thread, no cache", OIT_STREAM_CACHE_OFF, 0, 1},
               {"4 threads, no cache", OIT_STREAM_CACHE_OFF, 0, 4},
               {"8K ring, no cache", OIT_STREAM_CACHE_OFF, 8192, 0},
               {"8K ring, 3 threads, no cache", OIT_STREAM_CACHE_OFF, 8192, 3},
               {"8K ring, 16K cache", 16384, 8192, 0}};
    for (size_t c = 0; c < sizeof cfg / sizeof *cfg; c++) {
        d = base_desc();
        d.cache_budget = cfg[c].cache;
        d.upload_budget = cfg[c].ring;
        d.reader_threads = cfg[c].threads;
        if (!render_twice(pf, v, &d, cfg[c].name, &r))
            continue;
        for (int f = 0; f < 2; f++)
            CHECK(same_image(&ref.img[0], &r.img[f]), "%s: frame %d differs from the cached "
                  "run's first", cfg[c].name, f);
        CHECK(r.ss[0].bytes_uploaded == b0, "%s: first frame uploaded %llu bytes, not %llu",
              cfg[c].name, (unsigned long long)r.ss[0].bytes_uploaded,
              (unsigned long long)b0);
        uint64_t b1 = r.ss[1].bytes_uploaded, hits = r.ss[1].cache_hits;
        if (cfg[c].cache == OIT_STREAM_CACHE_OFF)
            CHECK(b1 == b0 && hits == 0, "%s: second frame uploaded %llu bytes, %llu hits",
                  cfg[c].name, (unsigned long long)b1, (unsigned long long)hits);
        else if (cfg[c].cache == 0)
            CHECK(b1 == 0, "%s: second frame uploaded %llu bytes", cfg[c].name,
                  (unsigned long long)b1);
        else
            CHECK(b1 > 0 && b1 < b0 && hits > 0 && r.ss[1].cache_bytes <= cfg[c].cache,
                  "%s: second frame uploaded %llu of %llu bytes, %llu hits, %llu cached",
                  cfg[c].name, (unsigned long long)b1, (unsigned long long)b0,
                  (unsigned long long)hits, (unsigned long long)r.ss[1].cache_bytes);
        free_run(&r);
    }
    free_run(&ref);
}

/* The file's bytes with one byte of `part`'s blob flipped. */
static uint8_t *corrupt_copy(const char *path, const oit_partfile *pf, uint32_t part,
                             size_t *size)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf = NULL;
    long n = -1;
    if (f && fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (buf = malloc((size_t)n)) && fread(buf, 1, (size_t)n, f) == (size_t)n) {
        buf[oit_partfile_parts(pf)[part].data_offset + 5] ^= 0x40;
        *size = (size_t)n;
    } else {
        free(buf);
        buf = NULL;
    }
    if (f)
        fclose(f);
    return buf;
}

/* The part halfway down the view's order: packs before it are drawn and
 * packs after it queued when its job fails. */
static uint32_t middle_part(const oit_partfile *pf, const oit_view *v)
{
    oit_order *o = NULL;
    oit_error err = {0};
    uint32_t *parts = calloc(oit_partfile_part_count(pf) + 1u, sizeof *parts), count = 0,
             pick = 0;
    if (parts && oit_order_create(pf, &o, &err) == OIT_OK &&
        oit_order_compute(o, v->camera.eye, parts, &count, &err) == OIT_OK && count > 0)
        pick = parts[count / 2];
    oit_order_destroy(o);
    free(parts);
    return pick;
}

static void corrupt_part(const char *path, oit_partfile *pf, const oit_view *v)
{
    uint32_t part = middle_part(pf, v);
    size_t size = 0;
    uint8_t *bytes = corrupt_copy(path, pf, part, &size);
    CHECK(bytes != NULL, "%s: cannot read", path);
    if (!bytes)
        return;
    char want_part[32];
    snprintf(want_part, sizeof want_part, "part %u:", part);
    static const int threads[] = {OIT_STREAM_READ_INLINE, 1, 3};
    for (int t = 0; t < 3; t++) {
        oit_error err = {0};
        oit_partfile *bad = NULL;
        oit_partfile_open_desc od = {.defer_part_data = true};
        oit_status st = oit_partfile_open_memory(bytes, size, "corrupt.oitp", &od, &bad, &err);
        CHECK(st == OIT_OK, "corrupt.oitp does not open deferred: %s", err.message);
        oit_streamer_desc d = base_desc();
        d.reader_threads = threads[t];
        oit_streamer *s = NULL;
        if (st == OIT_OK)
            st = oit_streamer_create(bad, &d, &s, &err);
        CHECK(st == OIT_OK, "streamer on corrupt.oitp: %s", err.message);
        for (int f = 0; f < 2 && st == OIT_OK; f++) {
            oit_image img = {0};
            oit_error e = {0};
            oit_status r = oit_streamer_render(s, v, &img, NULL, NULL, &e);
            printf("corrupt part %u, reader threads %d, render %d: %s: %s\n", part,
                   threads[t], f, oit_status_name(r), e.message);
            CHECK(r == OIT_ERR_FORMAT && strstr(e.message, "corrupt.oitp") &&
                      strstr(e.message, want_part),
                  "render %d gave %s: '%s', not a format error naming corrupt.oitp and %s", f,
                  oit_status_name(r), e.message, want_part);
            oit_image_free(&img);
        }
        oit_streamer_destroy(s);
        oit_partfile_close(bad);
    }
    free(bytes);
}

/* A 16K ring: two 8K packs fill it; a third waits for the first's fence. */
static void ring_rules(void)
{
    oit_error err = {0};
    oit_fence_queue *f = NULL;
    oit_upload *u = NULL;
    if (oit_fence_queue_create(&f, &err) != OIT_OK ||
        oit_upload_create(16384, &u, &err) != OIT_OK) {
        CHECK(0, "ring: %s", err.message);
        oit_fence_queue_destroy(f);
        return;
    }
    CHECK(oit_upload_map(u) != NULL, "ring: no mapping");
    uint64_t a = 1, b = 1, c = 1, tag = oit_fence_queue_tag(f);
    int got_a = 0, got_b = 0, got = 1;
    oit_upload_reserve(u, f, 8192, 0, &a, &got_a, NULL, &err);
    oit_upload_reserve(u, f, 8192, 0, &b, &got_b, NULL, &err);
    CHECK(got_a && got_b && a == 0 && b == 8192, "ring: two 8K regions at %llu, %llu (got "
          "%d, %d)", (unsigned long long)a, (unsigned long long)b, got_a, got_b);
    CHECK(oit_upload_reserve(u, f, 256, 1, &c, &got, NULL, &err) == OIT_OK && !got,
          "ring: a full ring of undrawn regions gave room (or failed: %s)", err.message);
    oit_upload_drawn(u, tag); /* the first region, drawn by work with no fence yet */
    got = 1;
    oit_upload_reserve(u, f, 4096, 0, &c, &got, NULL, &err);
    CHECK(!got, "ring: reused a drawn region before any fence followed its draws");
    got = 0;
    CHECK(oit_upload_reserve(u, f, 4096, 1, &c, &got, NULL, &err) == OIT_OK && got && c == 0,
          "ring: waiting gave %d at %llu: %s", got, (unsigned long long)c, err.message);
    uint64_t done = oit_fence_queue_poll(f);
    CHECK(done >= tag, "ring: region reused while its fence %llu had not completed (%llu)",
          (unsigned long long)tag, (unsigned long long)done);
    oit_upload_release_undrawn(u);
    got = 0;
    oit_upload_reserve(u, f, 16384, 0, &c, &got, NULL, &err);
    CHECK(got && c == 0, "ring: after releasing the undrawn regions 16K did not fit at 0");
    CHECK(oit_upload_reserve(u, f, 16640, 1, &c, &got, NULL, &err) == OIT_ERR_ARGUMENT,
          "ring: reserved more than its budget");
    oit_upload_destroy(u);
    oit_fence_queue_destroy(f);
}

/* The reader without a streamer: results, the queue bound, destroy with
 * work outstanding. */
static void reader_alone(oit_partfile *pf)
{
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    uint32_t n = oit_partfile_part_count(pf);
    uint64_t total = 0;
    oit_read_item *items = calloc(n, sizeof *items);
    for (uint32_t p = 0; items && p < n; p++) {
        items[p] = (oit_read_item){p, total};
        total += oit_part_sourced_bytes(parts[p].index_count / 3);
    }
    unsigned char *dst = malloc(total + 1), *want = malloc(total + 1);
    CHECK(items && dst && want, "out of memory");
    oit_error err = {0};
    /* What the GPU draws: the part's triangles as oit_part_expand gives them,
     * then its source indices as the file stores them. */
    oit_partfile_buffer buf = {0};
    for (uint32_t p = 0; items && dst && want && p < n; p++) {
        uint64_t tris = parts[p].index_count / 3;
        CHECK(oit_part_expand(pf, p, &buf, (oit_triangle *)(void *)(want + items[p].offset),
                              &err) == OIT_OK, "expand part %u: %s", p, err.message);
        oit_partfile_part_view v;
        CHECK(oit_partfile_part_data(pf, p, &buf, &v, &err) == OIT_OK, "%s", err.message);
        for (uint64_t t = 0; t < tris; t++) {
            uint32_t s = oit_partfile_source(&v, t);
            memcpy(want + items[p].offset + tris * sizeof(oit_triangle) + 4 * t, &s, 4);
        }
    }
    oit_partfile_buffer_free(&buf);
    oit_reader *r = NULL;
    if (items && dst && want && oit_reader_create(pf, dst, 1, &r, &err) == OIT_OK) {
        CHECK(oit_reader_collect(r, &err) == OIT_ERR_ARGUMENT, "collect with no job succeeded");
        CHECK(oit_reader_submit(r, items, n, &err) == OIT_OK, "submit: %s", err.message);
        CHECK(oit_reader_collect(r, &err) == OIT_OK, "collect: %s", err.message);
        CHECK(memcmp(dst, want, total) == 0, "the reader's triangles and source indices "
              "differ from oit_part_expand's and the file's");
        uint32_t q = 0;
        while (q < OIT_READER_QUEUE && oit_reader_submit(r, items, n, &err) == OIT_OK)
            q++;
        CHECK(q == OIT_READER_QUEUE && oit_reader_submit(r, items, n, &err) ==
                                           OIT_ERR_ARGUMENT,
              "the queue took %u jobs, then did not refuse one", q);
        oit_reader_destroy(r); /* with up to 16 jobs outstanding */
    }
    CHECK(oit_reader_create(pf, dst, 1, &r, &err) == OIT_OK, "reader: %s", err.message);
    oit_reader_destroy(r); /* right after create */
    free(items);
    free(dst);
    free(want);
}

int main(int argc, char **argv)
{
    oit_partfile *pf = NULL;
    oit_gl *gl = test_gl_open_partfile(argc, argv, &pf);
    oit_error err = {0};
    oit_view v = make_view(pf);
    oit_streamer *s = NULL;
    oit_streamer_desc d = base_desc();
    CHECK(oit_streamer_create(pf, &d, &s, &err) == OIT_OK, "create: %s", err.message);
    oit_streamer_destroy(s); /* right after create: the thread joins */
    residency_and_identity(pf, &v);
    corrupt_part(argv[1], pf, &v);
    ring_rules();
    reader_alone(pf);
    oit_partfile_close(pf);
    oit_gl_destroy(gl);
    return test_verdict();
}
