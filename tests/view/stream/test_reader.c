/* The part reader's threads (view/stream/reader.h), with an injected expand that
 * stamps each item's bytes and takes a planned time, so items finish out
 * of their order. For 0 (the submitting thread), 1, 2, 3 and 8 threads:
 *  - every item of every job is expanded exactly once, into its own bytes;
 *  - a job is collected only once all of its items are done, and jobs are
 *    collected in submission order, whatever order the items finished in
 *    (with 2 or more threads they are seen finishing out of order: the
 *    injection works);
 *  - a job with two failing items reports the first one in its order (the
 *    slow one, which finishes last), does not run its items after it, and
 *    the jobs behind it still complete;
 *  - cancel with jobs outstanding returns, and no item starts after it;
 *  - more than OIT_READER_MAX_THREADS threads, or fewer than 0, is refused.
 * No GL. A hang fails through the ctest timeout.
 *
 * usage: test_reader FILE.oitp (any part file: only its name is used) */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "view/stream/reader.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_partfile.h"

enum { JOBS = 12, MOST = 9, ITEMS = JOBS * MOST, STAMP = 8, FAIL_SLOW = 1000, FAIL_FAST = 1001 };

typedef struct plan {
    atomic_int runs[FAIL_FAST + 1];
    atomic_int done_seq[ITEMS]; /* when each item finished: 1, 2, ... */
    atomic_int seq;
    atomic_int started; /* items that began */
} plan;

static void sleep_ms(int ms)
{
    struct timespec t = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&t, NULL);
}

/* Item "part" p: the first item of each job sleeps longest, so later items
 * (taken by other threads) finish before it. */
static oit_status stamp(void *ctx, oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                        unsigned char *dst, oit_error *err)
{
    (void)pf;
    (void)buf;
    plan *pl = ctx;
    atomic_fetch_add(&pl->started, 1);
    if (part == FAIL_SLOW || part == FAIL_FAST) {
        sleep_ms(part == FAIL_SLOW ? 30 : 0);
        atomic_fetch_add(&pl->runs[part], 1);
        return oit_error_set(err, OIT_ERR_FORMAT, "stamp: part %u: planted failure", part);
    }
    sleep_ms(part % MOST == 0 ? 15 : (int)(part % 3));
    for (int i = 0; i < STAMP; i++)
        dst[i] = (unsigned char)(part * 7 + (unsigned)i + 1);
    atomic_fetch_add(&pl->runs[part], 1);
    atomic_store(&pl->done_seq[part], atomic_fetch_add(&pl->seq, 1) + 1);
    return OIT_OK;
}

static int stamped(const unsigned char *dst, uint32_t part)
{
    for (int i = 0; i < STAMP; i++)
        if (dst[(size_t)part * STAMP + i] != (unsigned char)(part * 7 + (unsigned)i + 1))
            return 0;
    return 1;
}

/* Jobs of 0..MOST items over parts 0..ITEMS: order, completeness, once. */
static void order_and_once(oit_reader *r, plan *pl, unsigned char *dst, int threads)
{
    oit_read_item items[JOBS][MOST];
    uint32_t count[JOBS];
    oit_error err = {0};
    CHECK(oit_reader_threads(r) == threads, "%d threads: it runs %d", threads,
          oit_reader_threads(r));
    uint32_t collected_items = 0;
    int out_of_order = 0;
    for (uint32_t j = 0; j < JOBS; j++) {
        count[j] = j % 4 == 3 ? 0 : MOST - j % 3; /* some empty jobs */
        for (uint32_t i = 0; i < count[j]; i++) {
            uint32_t part = j * MOST + i;
            items[j][i] = (oit_read_item){part, (uint64_t)part * STAMP};
        }
        CHECK(oit_reader_submit(r, items[j], count[j], &err) == OIT_OK, "%d threads: submit "
              "%u: %s", threads, j, err.message);
    }
    for (uint32_t j = 0; j < JOBS; j++) {
        CHECK(oit_reader_collect(r, &err) == OIT_OK, "%d threads: collect %u: %s", threads, j,
              err.message);
        for (uint32_t i = 0; i < count[j]; i++) {
            uint32_t part = j * MOST + i;
            CHECK(stamped(dst, part) && atomic_load(&pl->runs[part]) == 1,
                  "%d threads: job %u collected with item %u unstamped or run %d times",
                  threads, j, i, atomic_load(&pl->runs[part]));
            if (i > 0 && atomic_load(&pl->done_seq[part]) < atomic_load(&pl->done_seq[part - 1]))
                out_of_order++;
        }
        collected_items += count[j];
    }
    CHECK(oit_reader_outstanding(r) == 0, "%d threads: %u jobs outstanding after collecting",
          threads, oit_reader_outstanding(r));
    CHECK(oit_reader_collect(r, &err) == OIT_ERR_ARGUMENT, "%d threads: collected a job "
          "never submitted", threads);
    int runs = 0;
    for (uint32_t p = 0; p < ITEMS; p++)
        runs += atomic_load(&pl->runs[p]);
    CHECK((uint32_t)runs == collected_items, "%d threads: %d item runs for %u items", threads,
          runs, collected_items);
    CHECK(threads < 2 ? out_of_order == 0 : out_of_order > 0, "%d threads: %d items finished "
          "before the one ahead of them (the injection should %s)", threads, out_of_order,
          threads < 2 ? "keep the order on one thread" : "shuffle them");
    printf("%d threads: %u items in %d jobs, exactly once, collected in order; %d finished "
           "before the item ahead\n", threads, collected_items, JOBS, out_of_order);
}

/* A job whose item 1 fails slowly and item 3 fast: the error is item 1's
 * (the first in the job's order, though it fails last); the next job still
 * completes. */
static void first_error(oit_reader *r, plan *pl, unsigned char *dst, int threads)
{
    oit_read_item bad[6] = {{0, 0}, {FAIL_SLOW, 8}, {2, 16}, {FAIL_FAST, 24}, {4, 32}, {5, 40}};
    oit_read_item good[2] = {{6, 48}, {7, 56}};
    oit_error err = {0};
    CHECK(oit_reader_submit(r, bad, 6, &err) == OIT_OK, "submit: %s", err.message);
    CHECK(oit_reader_submit(r, good, 2, &err) == OIT_OK, "submit: %s", err.message);
    oit_status s = oit_reader_collect(r, &err);
    CHECK(s == OIT_ERR_FORMAT && strstr(err.message, "part 1000:"), "%d threads: the failing "
          "job gave %s '%s', not item 1's error (part 1000)", threads, oit_status_name(s),
          err.message);
    err = (oit_error){0};
    CHECK(oit_reader_collect(r, &err) == OIT_OK && stamped(dst, 6) && stamped(dst, 7),
          "%d threads: the job after a failed one did not complete: %s", threads, err.message);
    /* Without threads the job stops at its first failure, so item 3 never
     * runs; with them, it may have run before item 1 failed. Up to 3
     * threads are all busy (items 0 and 1 sleep) until item 3 fails, so
     * items 4 and 5 are never claimed; more threads may take them at once. */
    CHECK(threads > 3 || (atomic_load(&pl->runs[4]) == 0 && atomic_load(&pl->runs[5]) == 0 &&
                          (threads > 0 || atomic_load(&pl->runs[FAIL_FAST]) == 0)),
          "%d threads: items after the failing ones ran (item 4: %d, item 5: %d)", threads,
          atomic_load(&pl->runs[4]), atomic_load(&pl->runs[5]));
}

/* Cancel with a full queue: returns, and nothing starts afterwards. */
static void cancel_stops(oit_reader *r, plan *pl, unsigned char *dst, int threads)
{
    oit_read_item items[MOST];
    for (uint32_t i = 0; i < MOST; i++)
        items[i] = (oit_read_item){i, (uint64_t)i * STAMP};
    oit_error err = {0};
    /* the same parts in each job: only the count of runs matters here */
    for (uint32_t q = 0; q < OIT_READER_QUEUE; q++)
        oit_reader_submit(r, items, MOST, &err);
    oit_reader_cancel(r);
    int started = atomic_load(&pl->started);
    sleep_ms(40);
    CHECK(atomic_load(&pl->started) == started && oit_reader_outstanding(r) == 0,
          "%d threads: %d items started after cancel returned, %u jobs outstanding", threads,
          atomic_load(&pl->started) - started, oit_reader_outstanding(r));
    CHECK(threads == 0 || started < (int)(OIT_READER_QUEUE * MOST),
          "%d threads: cancel dropped nothing (%d items started)", threads, started);
}

/* test on a fresh reader of `threads` threads over stamp, its runs counted
 * in pl and its items stamped into dst (room for ITEMS). */
typedef void reader_test(oit_reader *r, plan *pl, unsigned char *dst, int threads);
static void run_rigged(oit_partfile *pf, int threads, reader_test *test)
{
    static plan pl;
    memset(&pl, 0, sizeof pl);
    unsigned char *dst = calloc(ITEMS, STAMP);
    oit_reader *r = NULL;
    oit_error err = {0};
    if (!dst || oit_reader_create_with(pf, dst, threads, stamp, &pl, &r, &err) != OIT_OK)
        CHECK(0, "%d threads: create: %s", threads, err.message);
    else
        test(r, &pl, dst, threads);
    oit_reader_destroy(r);
    free(dst);
}

int main(int argc, char **argv)
{
    oit_partfile *pf = test_partfile_arg(argc, argv);
    oit_error err = {0};
    static const int threads[] = {0, 1, 2, 3, 8};
    for (size_t t = 0; t < sizeof threads / sizeof *threads; t++) {
        run_rigged(pf, threads[t], order_and_once);
        run_rigged(pf, threads[t], first_error);
        run_rigged(pf, threads[t], cancel_stops);
    }
    oit_reader *r = NULL;
    CHECK(oit_reader_create(pf, NULL, OIT_READER_MAX_THREADS + 1, &r, &err) ==
              OIT_ERR_ARGUMENT && !r,
          "%d threads were not refused", OIT_READER_MAX_THREADS + 1);
    CHECK(oit_reader_create(pf, NULL, -1, &r, &err) == OIT_ERR_ARGUMENT && !r,
          "-1 threads were not refused");
    oit_partfile_close(pf);
    return test_verdict();
}
