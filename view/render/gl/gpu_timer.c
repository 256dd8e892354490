/* GL timestamp queries in a ring of frames (gpu_timer.h). */
#include "view/render/gl/gpu_timer.h"

#include <stdlib.h>
#include <string.h>

#include "view/render/gl/gl_util.h"

/* A frame of a million marks would be a bug in the caller; past this the
 * marks are let go and their time goes to the phase before them. */
#define MARKS_MAX (1u << 16)

enum { SLOT_FREE, SLOT_OPEN, SLOT_PENDING };

typedef struct slot {
    GLuint *queries;
    uint8_t *phases;
    uint32_t n, cap;
    uint64_t frame;
    int state;
} slot;

struct oit_gpu_timer {
    const char *absent; /* NULL: timestamps work */
    slot *slots;
    int frames, next, open; /* open: index of the frame being marked, or -1 */
    uint64_t count, dropped;
    oit_gpu_times *done; /* read, not yet polled: a FIFO of `frames` */
    int done_head, done_n;
};

const char *oit_gpu_phase_name(oit_gpu_phase p)
{
    static const char *const names[OIT_GPU_PHASES] = {"other", "upload", "pass1",
                                                      "pass2", "resolve", "readback",
                                                      "binning", "sweep"};
    return (unsigned)p < OIT_GPU_PHASES ? names[p] : "?";
}

static const char *probe(const oit_gpu_timer_desc *d)
{
    if (d && d->no_queries)
        return "timer queries switched off (testing)";
    /* Valid in every GL 4.5 core context (timer queries are core since
     * 3.3); a driver without a timer says 0 bits. No glGetError here: the
     * context may be the caller's (liboit), its errors not ours to take. */
    GLint bits = 0;
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
    return bits > 0 ? NULL : "the driver reports 0 timestamp bits";
}

oit_status oit_gpu_timer_create(const oit_gpu_timer_desc *desc, oit_gpu_timer **out,
                                oit_error *err)
{
    *out = NULL;
    oit_gpu_timer *t = calloc(1, sizeof *t);
    int frames = desc && desc->frames > 0 ? desc->frames : 4;
    if (t) {
        t->slots = calloc((size_t)frames, sizeof *t->slots);
        t->done = calloc((size_t)frames, sizeof *t->done);
    }
    if (!t || !t->slots || !t->done) {
        oit_gpu_timer_destroy(t);
        return oit_error_set(err, OIT_ERR_NOMEM, "gpu timer: cannot allocate %d frames",
                             frames);
    }
    t->frames = frames;
    t->open = -1;
    t->absent = probe(desc);
    *out = t;
    return OIT_OK;
}

void oit_gpu_timer_destroy(oit_gpu_timer *t)
{
    if (!t)
        return;
    for (int i = 0; t->slots && i < t->frames; i++) {
        slot *s = &t->slots[i];
        if (s->cap)
            glDeleteQueries((GLsizei)s->cap, s->queries);
        free(s->queries);
        free(s->phases);
    }
    free(t->slots);
    free(t->done);
    free(t);
}

const char *oit_gpu_timer_absent(const oit_gpu_timer *t)
{
    return t ? t->absent : "no timer";
}

static int live(const oit_gpu_timer *t)
{
    return t && !t->absent;
}

/* Room for one more mark in s (query objects are made once and reused). */
static int grow(slot *s)
{
    if (s->n < s->cap)
        return 1;
    if (s->cap >= MARKS_MAX)
        return 0;
    uint32_t cap = s->cap ? s->cap * 2 : 64;
    GLuint *q = realloc(s->queries, cap * sizeof *q);
    if (q)
        s->queries = q;
    uint8_t *p = q ? realloc(s->phases, cap) : NULL;
    if (!p)
        return 0;
    s->phases = p;
    glGenQueries((GLsizei)(cap - s->cap), s->queries + s->cap);
    s->cap = cap;
    return 1;
}

/* Whether every timestamp of s is in, asking GL without waiting. */
static int ready(const slot *s)
{
    for (uint32_t i = 0; i < s->n; i++) {
        GLuint ok = 0;
        glGetQueryObjectuiv(s->queries[i], GL_QUERY_RESULT_AVAILABLE, &ok);
        if (!ok)
            return 0;
    }
    return 1;
}

/* The figures of s (waiting for them, if GL has not finished). Each mark's
 * phase runs to the next timestamp; a clock that went back counts 0. */
static void collect(slot *s, oit_gpu_times *out)
{
    memset(out, 0, sizeof *out);
    out->frame = s->frame;
    GLuint64 prev = 0;
    for (uint32_t i = 0; i < s->n; i++) {
        GLuint64 ts = 0;
        glGetQueryObjectui64v(s->queries[i], GL_QUERY_RESULT, &ts);
        if (i > 0 && ts > prev) {
            double ms = (double)(ts - prev) / 1e6;
            out->phase_ms[s->phases[i - 1]] += ms;
            out->ms += ms;
        }
        prev = i == 0 || ts > prev ? ts : prev;
    }
    s->state = SLOT_FREE;
    s->n = 0;
}

static void push_done(oit_gpu_timer *t, const oit_gpu_times *x)
{
    if (t->done_n == t->frames) {
        t->done_head = (t->done_head + 1) % t->frames;
        t->done_n--;
        t->dropped++;
    }
    t->done[(t->done_head + t->done_n++) % t->frames] = *x;
}

void oit_gpu_timer_begin_frame(oit_gpu_timer *t)
{
    if (!live(t))
        return;
    if (t->open >= 0)
        oit_gpu_timer_end_frame(t);
    slot *s = &t->slots[t->next];
    if (s->state == SLOT_PENDING) {
        /* `frames` frames in flight: the oldest is waited for. */
        oit_gpu_times x;
        collect(s, &x);
        push_done(t, &x);
    }
    s->state = SLOT_OPEN;
    s->n = 0;
    t->open = t->next;
    oit_gpu_timer_mark(t, OIT_GPU_OTHER);
}

void oit_gpu_timer_mark(oit_gpu_timer *t, oit_gpu_phase p)
{
    if (!live(t) || t->open < 0 || (unsigned)p >= OIT_GPU_PHASES)
        return;
    slot *s = &t->slots[t->open];
    if (s->n > 0 && s->phases[s->n - 1] == p)
        return; /* the same phase goes on */
    if (!grow(s))
        return;
    glQueryCounter(s->queries[s->n], GL_TIMESTAMP);
    s->phases[s->n++] = (uint8_t)p;
}

uint64_t oit_gpu_timer_end_frame(oit_gpu_timer *t)
{
    if (!live(t) || t->open < 0)
        return 0;
    slot *s = &t->slots[t->open];
    /* The closing timestamp: its phase is never charged. */
    if (grow(s)) {
        glQueryCounter(s->queries[s->n], GL_TIMESTAMP);
        s->phases[s->n++] = OIT_GPU_OTHER;
    }
    /* The timestamp is taken when GL runs it: sent now, it is the frame's
     * end, not that of whatever flushes next (llvmpipe runs queries when
     * they are flushed). A flush waits for nothing. */
    glFlush();
    s->state = SLOT_PENDING;
    s->frame = ++t->count;
    t->open = -1;
    t->next = (t->next + 1) % t->frames;
    return s->frame;
}

/* The pending slot of the smallest frame number, or NULL. */
static slot *oldest_pending(oit_gpu_timer *t)
{
    slot *best = NULL;
    for (int i = 0; i < t->frames; i++) {
        slot *s = &t->slots[i];
        if (s->state == SLOT_PENDING && (!best || s->frame < best->frame))
            best = s;
    }
    return best;
}

int oit_gpu_timer_poll(oit_gpu_timer *t, oit_gpu_times *out, int wait)
{
    if (!live(t))
        return 0;
    if (t->done_n > 0) {
        *out = t->done[t->done_head];
        t->done_head = (t->done_head + 1) % t->frames;
        t->done_n--;
        return 1;
    }
    slot *s = oldest_pending(t);
    if (!s || (!wait && !ready(s)))
        return 0;
    collect(s, out);
    return 1;
}

uint64_t oit_gpu_timer_dropped(const oit_gpu_timer *t)
{
    return t ? t->dropped : 0;
}
