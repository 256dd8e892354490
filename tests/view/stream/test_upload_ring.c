/* The upload ring's rule (view/stream/upload.h) against a CPU model, over random
 * sequences of what the streamer does in any order: reserve regions of
 * random sizes (waiting or not), mark the oldest undrawn one drawn with the
 * fence tag of the moment, insert fences and leave them pending or wait for
 * them, and forget the undrawn regions (a failed frame) while drawn ones
 * are still in flight.
 * The model holds the live regions in reservation order, each undrawn or
 * drawn by work tagged s. After every reservation:
 *  - safety: the region handed out lies in the ring, starts at a multiple of
 *    OIT_PACK_ALIGN and overlaps no undrawn region and no drawn one whose
 *    tag no fence has covered yet (s > what the fence queue reports complete,
 *    or s past the last fence inserted): a GPU still reading it would draw
 *    the next pack's bytes (llvmpipe pulls vertices as a draw is issued, so
 *    no image shows this);
 *  - placement, where it is determined: with every fence waited for, a
 *    reservation that does not wait gets exactly the documented place (after
 *    the newest region, else at the start, else none); one that waits gets
 *    room exactly when dropping every drawn region would make it.
 * An empty ring must take a whole-budget region; a ring of undrawn regions
 * must never block (a wait on work that has no fence would hang: ctest's
 * timeout catches it). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/stream/fence_queue.h"
#include "view/stream/pack.h"
#include "view/stream/upload.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { MAXR = 4096 };

typedef struct mreg {
    uint64_t start, end, serial; /* serial 0: undrawn */
} mreg;

typedef struct model {
    uint64_t budget, head;
    mreg r[MAXR];
    int n;
} model;

typedef struct ring_case {
    oit_upload *u;
    oit_fence_queue *f;
    model m;
    int pending; /* a fence may be pending: completion not determined */
    uint32_t seed;
    const char *name;
    int step;
    uint64_t reserves, reused, waits, releases;
} ring_case;

static uint32_t rng(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static uint64_t issued(const ring_case *c)
{
    return oit_fence_queue_tag(c->f) - 1;
}

/* Drops the oldest drawn regions whose work completed (upload.h). */
static void model_reclaim(model *m, uint64_t completed)
{
    int k = 0;
    while (k < m->n && m->r[k].serial && m->r[k].serial <= completed)
        k++;
    memmove(m->r, m->r + k, (size_t)(m->n - k) * sizeof *m->r);
    m->n -= k;
    if (!m->n)
        m->head = 0;
}

/* The documented place: after the newest region, else wrapped to the
 * start, before the oldest; UINT64_MAX when neither fits. */
static uint64_t model_place(const model *m, uint64_t bytes)
{
    if (!m->n)
        return 0;
    uint64_t tail = m->r[0].start;
    if (tail < m->head)
        return m->budget - m->head >= bytes ? m->head : bytes <= tail ? 0 : UINT64_MAX;
    return tail - m->head >= bytes ? m->head : UINT64_MAX;
}

/* Whether bytes fit once every drawn region is gone (what a waiting
 * reservation reaches). */
static int model_fits_after_wait(const model *m, uint64_t bytes)
{
    model t = *m;
    model_reclaim(&t, UINT64_MAX);
    return model_place(&t, bytes) != UINT64_MAX;
}

static void model_push(model *m, uint64_t start, uint64_t bytes)
{
    if (m->n == MAXR) {
        CHECK(0, "model: more than %d live regions", MAXR);
        return;
    }
    m->r[m->n++] = (mreg){start, start + bytes, 0};
    m->head = start + bytes;
}

static void model_drawn(model *m, uint64_t serial)
{
    for (int i = 0; i < m->n; i++)
        if (!m->r[i].serial) {
            m->r[i].serial = serial;
            return;
        }
}

static void model_release_undrawn(model *m)
{
    int k = 0;
    while (k < m->n && m->r[k].serial)
        k++;
    m->n = k;
    m->head = k ? m->r[k - 1].end : 0;
}

/* A random size: mostly small, some a good part of the ring, a few all of
 * it. */
static uint64_t random_bytes(ring_case *c)
{
    uint64_t units = c->m.budget / OIT_PACK_ALIGN;
    uint32_t k = rng(&c->seed) % 16;
    uint64_t u = k < 10 ? 1 + rng(&c->seed) % (units / 8 + 1)
               : k < 15 ? 1 + rng(&c->seed) % units
                        : units;
    return u * OIT_PACK_ALIGN;
}

/* One reservation, checked against the model. */
static void reserve(ring_case *c, int wait)
{
    uint64_t bytes = random_bytes(c), off = UINT64_MAX;
    int got = 0, exact = !wait && !c->pending;
    /* with nothing pending, the ring's poll sees exactly the fences waited for */
    uint64_t before = oit_fence_queue_poll(c->f);
    model_reclaim(&c->m, before);
    uint64_t want = model_place(&c->m, bytes);
    int want_wait = model_fits_after_wait(&c->m, bytes);
    oit_error err = {0};
    oit_status st = oit_upload_reserve(c->u, c->f, bytes, wait, &off, &got, NULL, &err);
    c->pending |= wait; /* a wait retires fences up to the one it needs */
    uint64_t done = oit_fence_queue_poll(c->f), last = issued(c);
    c->reserves++;
    if (st != OIT_OK) {
        CHECK(0, "%s step %d: reserve %llu bytes: %s", c->name, c->step,
              (unsigned long long)bytes, err.message);
        return;
    }
    CHECK(done <= last, "%s step %d: the fence queue reports serial %llu complete, only %llu "
          "fences were inserted", c->name, c->step, (unsigned long long)done,
          (unsigned long long)last);
    if (exact)
        CHECK(got == (want != UINT64_MAX) && (!got || off == want),
              "%s step %d: %llu bytes without waiting, all fences complete: got %d at %llu, "
              "the documented place is %s%llu", c->name, c->step, (unsigned long long)bytes,
              got, (unsigned long long)off, want == UINT64_MAX ? "none " : "",
              (unsigned long long)(want == UINT64_MAX ? 0 : want));
    else if (wait)
        CHECK(got == want_wait, "%s step %d: a waiting reserve of %llu bytes got %d; once the "
              "drawn regions are reclaimed it %s", c->name, c->step, (unsigned long long)bytes,
              got, want_wait ? "fits" : "does not fit (an undrawn one is in the way)");
    if (!got)
        return;
    c->waits += (uint64_t)wait;
    CHECK(off % OIT_PACK_ALIGN == 0 && off + bytes <= c->m.budget,
          "%s step %d: region %llu + %llu outside a %llu-byte ring or unaligned", c->name,
          c->step, (unsigned long long)off, (unsigned long long)bytes,
          (unsigned long long)c->m.budget);
    /* Safety: every live region it overlaps must be drawn and fenced. */
    int keep = 0;
    for (int i = 0; i < c->m.n; i++) {
        const mreg *r = &c->m.r[i];
        if (!(off < r->end && r->start < off + bytes)) {
            c->m.r[keep++] = *r;
            continue;
        }
        CHECK(r->serial && r->serial <= done && r->serial <= last,
              "%s step %d: region %llu..%llu handed out over live region %llu..%llu, %s "
              "(fences complete up to %llu, %llu inserted)", c->name, c->step,
              (unsigned long long)off, (unsigned long long)(off + bytes),
              (unsigned long long)r->start, (unsigned long long)r->end,
              r->serial ? "drawn by work not yet fenced" : "undrawn",
              (unsigned long long)done, (unsigned long long)last);
        c->reused++;
    }
    /* what the ring dropped to make room is older than what it kept */
    c->m.n = keep;
    model_reclaim(&c->m, done);
    model_push(&c->m, off, bytes);
}

static void step(ring_case *c)
{
    uint32_t k = rng(&c->seed) % 100;
    oit_error err = {0};
    if (k < 40) {
        reserve(c, rng(&c->seed) % 4 == 0);
    } else if (k < 70) {
        uint64_t tag = oit_fence_queue_tag(c->f);
        oit_upload_drawn(c->u, tag);
        model_drawn(&c->m, tag);
    } else if (k < 80) {
        CHECK(oit_fence_queue_insert(c->f, &err) == OIT_OK, "%s: insert: %s", c->name,
              err.message);
        c->pending = 1;
    } else if (k < 94) {
        /* every fence so far waited for: completion is determined again */
        if (issued(c) > 0)
            CHECK(oit_fence_queue_wait(c->f, issued(c), NULL, &err) == OIT_OK, "%s: wait: %s",
                  c->name, err.message);
        c->pending = 0;
    } else {
        oit_upload_release_undrawn(c->u);
        model_release_undrawn(&c->m);
        c->releases++;
    }
}

static void run_case(uint64_t budget, uint32_t seed, int steps, const char *name)
{
    ring_case c = {.seed = seed, .name = name};
    c.m.budget = budget;
    oit_error err = {0};
    if (oit_fence_queue_create(&c.f, &err) != OIT_OK ||
        oit_upload_create(budget, &c.u, &err) != OIT_OK) {
        CHECK(0, "%s: %s", name, err.message);
        oit_fence_queue_destroy(c.f);
        return;
    }
    int before = test_failures;
    for (c.step = 0; c.step < steps && test_failures - before < 4; c.step++)
        step(&c);
    /* Everything drawn and fenced: the whole budget fits at 0. */
    while (c.m.n) {
        oit_upload_drawn(c.u, oit_fence_queue_tag(c.f));
        model_drawn(&c.m, oit_fence_queue_tag(c.f));
        if (c.m.r[c.m.n - 1].serial)
            break;
    }
    uint64_t off = 1;
    int got = 0;
    CHECK(oit_upload_reserve(c.u, c.f, budget, 1, &off, &got, NULL, &err) == OIT_OK && got &&
              off == 0,
          "%s: with every region drawn the whole %llu bytes did not fit at 0 (got %d at %llu)",
          name, (unsigned long long)budget, got, (unsigned long long)off);
    printf("%s: %llu-byte ring, %d steps: %llu reservations (%llu waited), %llu regions "
           "reused, %llu releases, %llu fences\n", name, (unsigned long long)budget, c.step,
           (unsigned long long)c.reserves, (unsigned long long)c.waits,
           (unsigned long long)c.reused, (unsigned long long)c.releases,
           (unsigned long long)issued(&c));
    oit_upload_destroy(c.u);
    oit_fence_queue_destroy(c.f);
}

/* The fence queue's serials (fence_queue.h), on which the model's tags
 * rest: work issued before the first fence carries 1, each insert moves the
 * tag on by one, a wait on a tag with no fence yet inserts it, and nothing
 * is reported complete past the newest fence. */
static void fence_serials(void)
{
    oit_error err = {0};
    oit_fence_queue *f = NULL;
    if (oit_fence_queue_create(&f, &err) != OIT_OK) {
        CHECK(0, "fence queue: %s", err.message);
        return;
    }
    CHECK(oit_fence_queue_tag(f) == 1 && oit_fence_queue_poll(f) == 0,
          "a new queue tags %llu and reports %llu complete, not 1 and 0",
          (unsigned long long)oit_fence_queue_tag(f),
          (unsigned long long)oit_fence_queue_poll(f));
    for (uint64_t k = 1; k <= 5; k++) {
        uint64_t tag = oit_fence_queue_tag(f);
        CHECK(oit_fence_queue_insert(f, &err) == OIT_OK, "insert: %s", err.message);
        CHECK(oit_fence_queue_tag(f) == tag + 1 && oit_fence_queue_poll(f) <= tag,
              "after fence %llu: tag %llu, %llu reported complete", (unsigned long long)k,
              (unsigned long long)oit_fence_queue_tag(f),
              (unsigned long long)oit_fence_queue_poll(f));
    }
    uint64_t tag = oit_fence_queue_tag(f);
    CHECK(oit_fence_queue_wait(f, tag, NULL, &err) == OIT_OK, "wait: %s", err.message);
    CHECK(oit_fence_queue_tag(f) == tag + 1 && oit_fence_queue_poll(f) == tag,
          "a wait on tag %llu with no fence: tag now %llu, %llu complete (want %llu, %llu)",
          (unsigned long long)tag, (unsigned long long)oit_fence_queue_tag(f),
          (unsigned long long)oit_fence_queue_poll(f), (unsigned long long)(tag + 1),
          (unsigned long long)tag);
    oit_fence_queue_destroy(f);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    fence_serials();
    static const uint64_t budgets[] = {4 * OIT_PACK_ALIGN, 16 * OIT_PACK_ALIGN,
                                       37 * OIT_PACK_ALIGN, 256 * OIT_PACK_ALIGN};
    for (int i = 0; i < 24; i++) {
        char name[32];
        snprintf(name, sizeof name, "ring %d", i);
        run_case(budgets[i % 4], 0x9e3779b9u * (uint32_t)(i + 1), 600, name);
    }
    return test_gl_verdict(gl);
}
