/* view/stream/schedule.h: the wavefront keeps the input's order between every
 * two parts whose rectangles share a pixel (across packs when packing), and
 * otherwise goes nearest first.
 *
 * Random rectangles with random depths, the input order taken as the
 * visibility order. Checked pixel-exactly against all pairs (O(n^2) here,
 * which the scheduler must not need): no overlapping pair is reversed, with
 * and without a packer; every pack is non-empty and respects the packer's
 * capacity; the result is a permutation; the first part drawn is the nearest
 * of those nothing must precede. The checker is shown to catch the order
 * that sorts by depth alone, so the test can fail. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/stream/schedule.h"

#define N 400
#define W 300
#define H 200

static int failures;

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "FAIL: %s\n", what);
        failures++;
    }
}

static uint32_t rng(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static int overlap(const int a[4], const int b[4])
{
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

/* Share a 32x32 bin (schedule.h's granularity of constraints). */
static int share_bin(const int a[4], const int b[4])
{
    return a[0] / 32 <= (b[2] - 1) / 32 && b[0] / 32 <= (a[2] - 1) / 32 &&
           a[1] / 32 <= (b[3] - 1) / 32 && b[1] / 32 <= (a[3] - 1) / 32;
}

/* A packer that holds at most `cap` parts and at most 2 parts on any pixel
 * (checked on the rectangles, exactly). */
typedef struct toy_packer {
    const int (*rects)[4];
    uint32_t members[N], count, cap;
    uint32_t pack_of[N], packs;
    int empty_refused;
} toy_packer;

static void toy_open(void *ctx)
{
    toy_packer *t = ctx;
    t->count = 0;
    t->packs++;
}

static int toy_join(void *ctx, uint32_t i)
{
    toy_packer *t = ctx;
    uint32_t hits = 0;
    for (uint32_t k = 0; k < t->count; k++)
        hits += overlap(t->rects[t->members[k]], t->rects[i]);
    if (t->count && (t->count >= t->cap || hits >= 2))
        return 0;
    t->members[t->count++] = i;
    t->pack_of[i] = t->packs - 1;
    return 1;
}

/* Reversed overlapping pairs: rank[j] < rank[i] for i < j in the input. */
static int violations(const int (*r)[4], const uint32_t *rank)
{
    int bad = 0;
    for (uint32_t i = 0; i < N; i++)
        for (uint32_t j = i + 1; j < N; j++)
            bad += overlap(r[i], r[j]) && rank[j] < rank[i];
    return bad;
}

static void make_scene(int (*r)[4], float *near, uint32_t seed)
{
    for (uint32_t i = 0; i < N; i++) {
        int w = 4 + (int)(rng(&seed) % 60), h = 4 + (int)(rng(&seed) % 40);
        int x = (int)(rng(&seed) % (W - 2)) - 10, y = (int)(rng(&seed) % (H - 2)) - 10;
        r[i][0] = x < 0 ? 0 : x;
        r[i][1] = y < 0 ? 0 : y;
        r[i][2] = x + w > W ? W : x + w;
        r[i][3] = y + h > H ? H : y + h;
        near[i] = (float)(rng(&seed) % 1000) / 10.0f; /* ties on purpose */
    }
}

/* perm sorted by (near, index), by insertion: small n, no comparator state. */
static void sort_by_near(uint32_t *perm, const float *near)
{
    for (uint32_t k = 0; k < N; k++) {
        uint32_t v = perm[k], j = k;
        for (; j > 0 && (near[perm[j - 1]] > near[v] ||
                         (near[perm[j - 1]] == near[v] && perm[j - 1] > v)); j--)
            perm[j] = perm[j - 1];
        perm[j] = v;
    }
}

int main(void)
{
    static int rects[N][4];
    static float near[N];
    static uint32_t perm[N], rank[N], seen[N];
    oit_error err = {0};
    oit_scheduler *s = NULL;
    if (oit_scheduler_create(N, &s, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: %s\n", err.message);
        return 1;
    }
    for (uint32_t seed = 1; seed <= 5; seed++) {
        make_scene(rects, near, seed);
        const int(*r)[4] = (const int(*)[4])rects;
        /* no packer: a pure reordering */
        check(oit_schedule_run(s, N, r, near, W, H, NULL, perm, &err) == OIT_OK, err.message);
        memset(seen, 0, sizeof seen);
        for (uint32_t k = 0; k < N; k++) {
            seen[perm[k]]++;
            rank[perm[k]] = k;
        }
        int perm_ok = 1;
        for (uint32_t i = 0; i < N; i++)
            perm_ok &= seen[i] == 1;
        check(perm_ok, "perm is not a permutation");
        int bad = violations(r, rank);
        check(bad == 0, "an overlapping pair was reversed");
        uint32_t first = UINT32_MAX;
        for (uint32_t i = 0; i < N; i++) {
            int free_ = 1;
            for (uint32_t j = 0; j < i && free_; j++)
                free_ = !share_bin(r[i], r[j]);
            if (free_ && (first == UINT32_MAX || near[i] < near[first]))
                first = i;
        }
        check(perm[0] == first, "the first part is not the nearest one that shares no bin "
              "with an earlier part");
        /* with a packer: packs are non-empty, within capacity, and no
         * overlapping pair lands in an earlier pack than its predecessor */
        toy_packer t = {.rects = r, .cap = 6};
        oit_schedule_packer sp = {&t, toy_open, toy_join};
        check(oit_schedule_run(s, N, r, near, W, H, &sp, perm, &err) == OIT_OK, err.message);
        int pack_bad = 0, order_bad = 0;
        for (uint32_t k = 1; k < N; k++)
            order_bad += t.pack_of[perm[k]] < t.pack_of[perm[k - 1]];
        for (uint32_t i = 0; i < N; i++)
            for (uint32_t j = i + 1; j < N; j++)
                pack_bad += overlap(r[i], r[j]) && t.pack_of[j] < t.pack_of[i];
        check(order_bad == 0, "a pack's parts are not consecutive in perm");
        check(pack_bad == 0, "an overlapping pair went to an earlier pack");
        check(t.packs >= (N + t.cap - 1) / t.cap && t.packs <= N, "pack count out of range");
        /* the checker catches an order by depth alone */
        for (uint32_t k = 0; k < N; k++)
            perm[k] = k;
        sort_by_near(perm, near);
        for (uint32_t k = 0; k < N; k++)
            rank[perm[k]] = k;
        int caught = violations(r, rank);
        check(caught > 0, "the checker misses a depth-only order");
        printf("seed %u: %d overlapping pairs reversed; %u packs of at most %u; depth-only order "
               "reverses %d overlapping pairs\n", seed, bad, t.packs, t.cap, caught);
    }
    /* Ties in near go to the earlier input (the header's promise, which
     * makes the schedule deterministic): eight parts in separate bins at
     * one depth come out in input order. */
    for (uint32_t i = 0; i < 8; i++) {
        int tie[4] = {(int)i * 37, 0, (int)i * 37 + 8, 16};
        memcpy(rects[i], tie, sizeof tie);
        near[i] = 2.5f;
    }
    check(oit_schedule_run(s, 8, (const int(*)[4])rects, near, W, H, NULL, perm, &err) == OIT_OK,
          err.message);
    int tie_order = 1;
    for (uint32_t k = 0; k < 8; k++)
        tie_order &= perm[k] == k;
    check(tie_order, "parts at one depth in separate bins are not kept in input order");
    check(oit_schedule_run(s, N + 1, (const int(*)[4])rects, near, W, H, NULL, perm, &err) ==
              OIT_ERR_ARGUMENT, "more parts than made for accepted");
    oit_scheduler_destroy(s);
    if (failures)
        return 1;
    printf("schedule: all checks passed\n");
    return 0;
}
