/* The residency cache's bookkeeping (view/stream/residency.h), without GL:
 * placement within capacity and without overlap, hits, the two-frame
 * protection (parts used in this frame or the one before are never
 * evicted), eviction of idle parts, one failed sweep marking the frame
 * full, and a seeded random workload of orbit-like frames checked against
 * those invariants after every call. Every lookup is checked against the
 * cache's own view (peek), so a lookup that hands out an evicted part's
 * stale offset fails. */
#include <stdlib.h>
#include <string.h>

#include "view/stream/residency.h"
#include "tests/lib/test_check.h"

enum { UNIT = 256, PARTS = 400 };

/* Every resident range inside capacity, none overlapping, their sum the
 * cache's byte count. */
static void check_layout(oit_residency *r, const uint64_t *bytes, const char *when)
{
    uint64_t cap = oit_residency_capacity(r), sum = 0, *lo = calloc(PARTS, sizeof *lo);
    int *in = calloc(PARTS, sizeof *in);
    uint32_t count = 0;
    for (uint32_t p = 0; p < PARTS; p++) {
        uint64_t off;
        if (oit_residency_peek(r, p, &off)) {
            in[p] = 1;
            lo[p] = off;
            sum += bytes[p];
            count++;
            CHECK(off % UNIT == 0 && off + bytes[p] <= cap, "%s: part %u at %llu+%llu outside "
                  "%llu bytes", when, p, (unsigned long long)off, (unsigned long long)bytes[p],
                  (unsigned long long)cap);
        }
    }
    for (uint32_t a = 0; a < PARTS; a++)
        for (uint32_t b = a + 1; b < PARTS && in[a]; b++)
            if (in[b])
                CHECK(lo[a] + bytes[a] <= lo[b] || lo[b] + bytes[b] <= lo[a],
                      "%s: parts %u and %u overlap", when, a, b);
    CHECK(sum == oit_residency_bytes(r) && count == oit_residency_parts(r),
          "%s: %llu bytes in %u parts resident, the cache says %llu in %u", when,
          (unsigned long long)sum, count, (unsigned long long)oit_residency_bytes(r),
          oit_residency_parts(r));
    free(lo);
    free(in);
}

/* Ten parts of one unit fill a ten-unit cache; the next frame keeps them
 * (all used the frame before); two frames later the ones not used since go. */
static void protection(void)
{
    oit_residency *r = NULL;
    oit_error err = {0};
    CHECK(oit_residency_create(10 * UNIT, PARTS, &r, &err) == OIT_OK, "%s", err.message);
    if (!r)
        return;
    uint64_t off, bytes[PARTS];
    for (int p = 0; p < PARTS; p++)
        bytes[p] = UNIT;
    oit_residency_begin_frame(r); /* frame 1 */
    for (uint32_t p = 0; p < 10; p++)
        CHECK(oit_residency_insert(r, p, UNIT, &off), "frame 1: part %u found no room", p);
    CHECK(!oit_residency_insert(r, 10, UNIT, &off), "frame 1: an eleventh unit fitted");
    CHECK(!oit_residency_insert(r, 11, UNIT, &off), "frame 1: a full frame took a part");
    oit_residency_begin_frame(r); /* frame 2: parts of frame 1 are protected */
    CHECK(!oit_residency_insert(r, 10, UNIT, &off), "frame 2: evicted a part of frame 1");
    CHECK(oit_residency_lookup(r, 3, &off) && oit_residency_lookup(r, 4, &off),
          "frame 2: parts 3, 4 not resident");
    oit_residency_begin_frame(r); /* frame 3: 3 and 4 used in frame 2, the rest idle */
    CHECK(oit_residency_insert(r, 10, 2 * UNIT, &off), "frame 3: no room for a two-unit part");
    CHECK(oit_residency_lookup(r, 3, &off) && oit_residency_lookup(r, 4, &off),
          "frame 3: evicted parts used in frame 2");
    CHECK(oit_residency_lookup(r, 10, &off), "frame 3: part 10 not resident after insert");
    /* Part 10's two units came from evicting idle parts: looking those up
     * must miss, or the caller would draw whatever overwrote their bytes. */
    uint32_t gone = 0;
    for (uint32_t p = 0; p < 10; p++) {
        uint64_t at;
        if (!oit_residency_peek(r, p, &at)) {
            gone++;
            CHECK(!oit_residency_lookup(r, p, &off), "frame 3: evicted part %u still hits", p);
        }
    }
    CHECK(gone >= 2, "frame 3: %u parts evicted for a two-unit part", gone);
    bytes[10] = 2 * UNIT;
    check_layout(r, bytes, "frame 3");
    CHECK(!oit_residency_insert(r, 12, 11 * UNIT, &off), "a part larger than the cache fitted");
    oit_residency_destroy(r);
}

static uint32_t rng(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* An orbit-like workload: each frame uses a window of parts that slides
 * along, in shuffled order, inserting what misses. A part used in the
 * previous frame and resident at its end must hit. With capacity above the
 * working set, misses are the parts entering the window (and those that
 * found no room while their predecessors were still protected). */
static void random_frames(uint32_t seed0, uint64_t capacity_units, int expect_mostly_hits)
{
    uint32_t seed = seed0;
    oit_residency *r = NULL;
    oit_error err = {0};
    uint64_t bytes[PARTS];
    for (int p = 0; p < PARTS; p++)
        bytes[p] = (uint64_t)(1 + rng(&seed) % 8) * UNIT;
    CHECK(oit_residency_create(capacity_units * UNIT, PARTS, &r, &err) == OIT_OK, "%s",
          err.message);
    if (!r)
        return;
    uint8_t kept[PARTS] = {0}, used[PARTS];
    uint32_t order[PARTS];
    uint64_t hits = 0, misses = 0;
    for (int f = 0; f < 60; f++) {
        oit_residency_begin_frame(r);
        memset(used, 0, sizeof used);
        uint32_t first = (uint32_t)(f * 7) % PARTS, n = 80 + rng(&seed) % 60;
        for (uint32_t k = 0; k < n; k++)
            order[k] = (first + k) % PARTS;
        for (uint32_t k = n; k > 1; k--) {
            uint32_t j = rng(&seed) % k, t = order[k - 1];
            order[k - 1] = order[j];
            order[j] = t;
        }
        for (uint32_t k = 0; k < n; k++) {
            uint32_t p = order[k];
            uint64_t off;
            used[p] = 1;
            uint64_t seen = 0;
            int resident = oit_residency_peek(r, p, &seen);
            if (oit_residency_lookup(r, p, &off)) {
                CHECK(resident && off == seen, "seed %u frame %d: part %u hits at %llu, the "
                      "cache holds it %s", seed0, f, p, (unsigned long long)off,
                      resident ? "elsewhere" : "nowhere");
                hits++;
                continue;
            }
            CHECK(!resident, "seed %u frame %d: resident part %u missed", seed0, f, p);
            misses++;
            CHECK(!kept[p], "seed %u frame %d: part %u, used and resident in the frame "
                  "before, was evicted", seed0, f, p);
            oit_residency_insert(r, p, bytes[p], &off);
        }
        for (uint32_t p = 0; p < PARTS; p++) {
            uint64_t off;
            kept[p] = used[p] && oit_residency_peek(r, p, &off);
        }
        char when[48];
        snprintf(when, sizeof when, "seed %u frame %d", seed0, f);
        check_layout(r, bytes, when);
    }
    printf("seed %u, %llu units: %llu hits, %llu misses; %llu bytes in %u parts resident\n",
           seed0, (unsigned long long)capacity_units, (unsigned long long)hits,
           (unsigned long long)misses, (unsigned long long)oit_residency_bytes(r),
           oit_residency_parts(r));
    CHECK(hits > 0, "seed %u: no hit in 60 frames", seed0);
    if (expect_mostly_hits)
        CHECK(hits > 4 * misses, "seed %u: a cache above the working set hit %llu times, "
              "missed %llu", seed0, (unsigned long long)hits, (unsigned long long)misses);
    oit_residency_destroy(r);
}

int main(void)
{
    protection();
    /* Windows of 80..139 parts of 1..8 units: 1200 units hold any of them
     * with the two frames' worth the protection keeps; 200 hold a third. */
    for (uint32_t seed = 1; seed <= 4; seed++) {
        random_frames(seed, 1200, 1);
        random_frames(seed, 200, 0);
    }
    return test_verdict();
}
