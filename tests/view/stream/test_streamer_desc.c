/* oit_streamer_desc's one range check and its resolved read-back
 * (view/stream/streamer.h):
 *  - oit_streamer_desc_check: every byte budget accepted at both ends of its
 *    range and 0, refused one byte outside; the cache's "off"; epsilon in
 *    [0, 1) (NaN refused); pack and schedule enums; each refusal names the
 *    field in the caller's spelling, or the streamer's own without one;
 *  - oit_streamer_resolved_desc on FILE.oitp: the defaults resolved to what
 *    runs (ring, slots, cache, threads, capture) and given values kept.
 * usage: test_streamer_desc FILE.oitp (at least 512 KiB of parts, each less
 * than 256 KiB) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "partfile/triangles.h"
#include "view/stream/pack.h"
#include "view/stream/streamer.h"
#include "tests/lib/test_gl.h"

enum { UB, SB, CB, GB, EPS, PACK, SCHED, STB };

typedef struct range_case {
    int field;
    double value;
    int ok;
} range_case;

static void set_field(oit_streamer_desc *d, int field, double v)
{
    switch (field) {
    case UB: d->upload_budget = (uint64_t)v; break;
    case SB: d->slot_budget = (uint64_t)v; break;
    case CB: d->cache_budget = (uint64_t)v; break;
    case GB: d->gpu_budget = (uint64_t)v; break;
    case EPS: d->epsilon = (float)v; break;
    case PACK: d->pack = (oit_render_pack)(int)v; break;
    case STB: d->store_budget = (uint64_t)v; break;
    default: d->schedule = (oit_render_schedule)(int)v; break;
    }
}

static const char *const spelt[] = {"--upload-budget", "--slot-budget", "--cache-budget",
                                    "--gpu-budget", "--epsilon", "--pack", "--schedule",
                                    "--store-budget"};
static const char *const own[] = {"oit_streamer_desc.upload_budget",
                                  "oit_streamer_desc.slot_budget",
                                  "oit_streamer_desc.cache_budget",
                                  "oit_streamer_desc.gpu_budget", "oit_streamer_desc.epsilon",
                                  "oit_streamer_desc.pack", "oit_streamer_desc.schedule",
                                  "oit_streamer_desc.store_budget"};

static void check_ranges(void)
{
    const double lo = (double)OIT_STREAM_BUDGET_MIN, hi = (double)OIT_STREAM_BUDGET_MAX;
    const double g = (double)OIT_STREAM_GPU_BUDGET_MIN;
    const range_case cases[] = {
        {UB, 0, 1}, {UB, lo, 1}, {UB, lo - 1, 0}, {UB, 1, 0}, {UB, hi, 1}, {UB, hi + 1, 0},
        {SB, 0, 1}, {SB, lo, 1}, {SB, lo - 1, 0}, {SB, hi, 1}, {SB, hi + 1, 0},
        {STB, 0, 1}, {STB, lo, 1}, {STB, lo - 1, 0}, {STB, hi, 1}, {STB, hi + 1, 0},
        {CB, 0, 1}, {CB, lo, 1}, {CB, lo - 1, 0}, {CB, hi + 1, 0},
        {CB, (double)OIT_STREAM_CACHE_OFF, 1},
        {GB, 0, 1}, {GB, g, 1}, {GB, g - 1, 0}, {GB, hi, 1}, {GB, hi + 1, 0},
        {EPS, 0, 1}, {EPS, 0.999, 1}, {EPS, 1, 0}, {EPS, -0.001, 0}, {EPS, NAN, 0},
        {PACK, OIT_RENDER_PACK_FIRSTK, 1}, {PACK, OIT_RENDER_PACK_FIRSTK + 1, 0}, {PACK, -1, 0},
        {SCHED, OIT_RENDER_SCHEDULE_WAVE, 1}, {SCHED, OIT_RENDER_SCHEDULE_WAVE + 1, 0}};
    const oit_streamer_names names = {
        .upload_budget = spelt[UB], .slot_budget = spelt[SB], .cache_budget = spelt[CB],
        .gpu_budget = spelt[GB], .epsilon = spelt[EPS], .pack = spelt[PACK],
        .schedule = spelt[SCHED], .cache_off = "off", .store_budget = spelt[STB]};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const range_case *c = &cases[i];
        for (int named = 0; named < 2; named++) {
            oit_streamer_desc d = {0};
            /* CB = OFF is an exact 64-bit value a double cannot carry */
            if (c->field == CB && c->value == (double)OIT_STREAM_CACHE_OFF)
                d.cache_budget = OIT_STREAM_CACHE_OFF;
            else
                set_field(&d, c->field, c->value);
            oit_error err = {0};
            d.names = named ? &names : NULL;
            oit_status s = oit_streamer_desc_check(&d, &err);
            const char *name = named ? spelt[c->field] : own[c->field];
            CHECK((s == OIT_OK) == c->ok, "%s = %.17g: %s, expected %s", name, c->value,
                  s == OIT_OK ? "accepted" : err.message, c->ok ? "accepted" : "refused");
            CHECK(s == OIT_OK || (s == OIT_ERR_ARGUMENT && strstr(err.message, name)),
                  "%s = %.17g: the error does not name it: %s", name, c->value, err.message);
            if (s != OIT_OK && named && c->field == CB)
                CHECK(strstr(err.message, "off") != NULL, "the cache's error hides 'off': %s",
                      err.message);
        }
    }
}

static uint64_t silent_driver(void *ctx, const char **source)
{
    (void)ctx;
    *source = "no driver figure (test)";
    return 0;
}

/* The resolved descriptor of a streamer made from d, and its budget. */
static int resolve(oit_partfile *pf, const oit_streamer_desc *d, oit_streamer_desc *out,
                   oit_stream_budget *b)
{
    oit_error err = {0};
    oit_streamer *s = NULL;
    oit_status st = oit_streamer_create(pf, d, &s, &err);
    CHECK(st == OIT_OK, "create: %s", err.message);
    if (st != OIT_OK)
        return 0;
    oit_streamer_resolved_desc(s, out);
    oit_streamer_budget(s, b);
    oit_streamer_destroy(s);
    return 1;
}

static void check_resolved(oit_partfile *pf)
{
    uint64_t all = 0;
    for (uint32_t i = 0; i < oit_partfile_part_count(pf); i++)
        all += oit_pack_part_bytes(&oit_partfile_parts(pf)[i]);
    CHECK(all >= (512u << 10), "the file's parts take %llu bytes, 512 KiB wanted",
          (unsigned long long)all);

    /* Defaults: no total (the driver reports none), first-K stores. */
    oit_streamer_desc d = {.K = 8, .capture = OIT_RENDER_CAPTURE_ARRAY, .epsilon = 0.01f,
                           .reader_threads = OIT_STREAM_READ_INLINE,
                           .free_query = silent_driver};
    oit_streamer_desc r;
    oit_stream_budget b;
    if (resolve(pf, &d, &r, &b)) {
        printf("defaults: ring %llu slots %llu cache %llu gpu %llu threads %d\n",
               (unsigned long long)r.upload_budget, (unsigned long long)r.slot_budget,
               (unsigned long long)r.cache_budget, (unsigned long long)r.gpu_budget,
               r.reader_threads);
        uint64_t ring = all < OIT_STREAM_RING_DEFAULT ? all : OIT_STREAM_RING_DEFAULT;
        CHECK(r.upload_budget == ring && r.upload_budget == b.ring,
              "ring %llu, expected the file's %llu (budget %llu)",
              (unsigned long long)r.upload_budget, (unsigned long long)ring,
              (unsigned long long)b.ring);
        CHECK(r.slot_budget == OIT_STREAM_FIRSTK_SLOTS_DEFAULT &&
                  r.store_budget == OIT_STREAM_STORE_DEFAULT && b.store == r.store_budget,
              "slots %llu store %llu (budget %llu), expected first-K's %llu and the store's %llu",
              (unsigned long long)r.slot_budget, (unsigned long long)r.store_budget,
              (unsigned long long)b.store, (unsigned long long)OIT_STREAM_FIRSTK_SLOTS_DEFAULT,
              (unsigned long long)OIT_STREAM_STORE_DEFAULT);
        CHECK(b.resident && r.cache_budget == OIT_STREAM_CACHE_OFF,
              "resident %d, cache %llu: a file within the ring keeps no cache", b.resident,
              (unsigned long long)r.cache_budget);
        CHECK(r.gpu_budget == 0 && r.reader_threads == OIT_STREAM_READ_INLINE &&
                  r.epsilon == 0.01f && r.K == 8 && r.pack == OIT_RENDER_PACK_AUTO &&
                  r.capture == OIT_RENDER_CAPTURE_ARRAY,
              "gpu %llu threads %d epsilon %g K %d pack %d capture %d",
              (unsigned long long)r.gpu_budget, r.reader_threads, (double)r.epsilon, r.K,
              (int)r.pack, (int)r.capture);
    }

    /* Given: a ring below the file, no cache, threads, K-slot packs. */
    d = (oit_streamer_desc){.K = 8, .capture = OIT_RENDER_CAPTURE_ARRAY, .pack = OIT_RENDER_PACK_DISJOINT,
                            .upload_budget = 256u << 10, .cache_budget = OIT_STREAM_CACHE_OFF,
                            .reader_threads = 2, .free_query = silent_driver};
    if (resolve(pf, &d, &r, &b)) {
        CHECK(r.upload_budget == (256u << 10) && r.cache_budget == OIT_STREAM_CACHE_OFF &&
                  r.reader_threads == 2 && r.slot_budget == OIT_STREAM_SLOTS_DEFAULT &&
                  r.store_budget == 0 && r.epsilon == 0.0f && !b.resident,
              "given: ring %llu cache %llu threads %d slots %llu epsilon %g resident %d",
              (unsigned long long)r.upload_budget, (unsigned long long)r.cache_budget,
              r.reader_threads, (unsigned long long)r.slot_budget, (double)r.epsilon,
              b.resident);
    }

    /* A total: its figure, and the split inside it. */
    d = (oit_streamer_desc){.K = 8, .capture = OIT_RENDER_CAPTURE_ARRAY, .gpu_budget = 8u << 20,
                            .free_query = silent_driver};
    if (resolve(pf, &d, &r, &b)) {
        uint64_t cache = r.cache_budget == OIT_STREAM_CACHE_OFF ? 0 : r.cache_budget;
        CHECK(r.gpu_budget == (8u << 20) &&
                  r.upload_budget + cache + r.slot_budget + r.store_budget <= (8u << 20) &&
                  r.store_budget > 0,
              "total %llu: ring %llu + cache %llu + slots %llu + store %llu",
              (unsigned long long)r.gpu_budget, (unsigned long long)r.upload_budget,
              (unsigned long long)cache, (unsigned long long)r.slot_budget,
              (unsigned long long)r.store_budget);
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_streamer_desc FILE.oitp\n");
        return 2;
    }
    check_ranges();
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    oit_partfile *pf = NULL;
    CHECK(oit_partfile_open(argv[1], NULL, &pf, &err) == OIT_OK, "%s", err.message);
    if (pf)
        check_resolved(pf);
    oit_partfile_close(pf);
    return test_gl_verdict(gl);
}
