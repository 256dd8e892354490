/* GL fences by serial (fence_queue.h). */
#include "view/stream/fence_queue.h"

#include <stdlib.h>

#include "view/render/gl/gl_util.h"

/* Pending fences in insertion order, a growable circular array: fence k
 * (k counted from 1) has serial k, so the oldest pending one is
 * completed + 1. */
struct oit_fence_queue {
    GLsync *ring;
    uint32_t cap, first, count;
    uint64_t issued;    /* serial of the newest fence inserted */
    uint64_t completed; /* every serial <= this has signalled */
};

oit_status oit_fence_queue_create(oit_fence_queue **out, oit_error *err)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return oit_error_set(err, OIT_ERR_NOMEM, "fence queue: out of memory");
    return OIT_OK;
}

void oit_fence_queue_destroy(oit_fence_queue *q)
{
    if (!q)
        return;
    for (uint32_t i = 0; i < q->count; i++)
        glDeleteSync(q->ring[(q->first + i) % q->cap]);
    free(q->ring);
    free(q);
}

uint64_t oit_fence_queue_tag(const oit_fence_queue *q)
{
    return q->issued + 1;
}

static oit_status grow(oit_fence_queue *q, oit_error *err)
{
    uint32_t cap = q->cap ? 2 * q->cap : 16;
    GLsync *r = malloc((size_t)cap * sizeof *r);
    if (!r)
        return oit_error_set(err, OIT_ERR_NOMEM, "fence queue: cannot hold %u fences", cap);
    for (uint32_t i = 0; i < q->count; i++)
        r[i] = q->ring[(q->first + i) % q->cap];
    free(q->ring);
    q->ring = r;
    q->cap = cap;
    q->first = 0;
    return OIT_OK;
}

oit_status oit_fence_queue_insert(oit_fence_queue *q, oit_error *err)
{
    if (q->count == q->cap) {
        oit_status st = grow(q, err);
        if (st != OIT_OK)
            return st;
    }
    GLsync f = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!f) {
        oit_status st = oit_gl_check("upload: glFenceSync", err);
        return st != OIT_OK ? st : oit_error_set(err, OIT_ERR_GL, "upload: glFenceSync "
                                                 "returned no fence");
    }
    q->ring[(q->first + q->count) % q->cap] = f;
    q->count++;
    q->issued++;
    return OIT_OK;
}

/* Retires the oldest pending fence when it signalled within timeout_ns;
 * returns 1 when it did. */
static int retire_oldest(oit_fence_queue *q, GLuint64 timeout_ns, oit_status *st,
                         oit_error *err)
{
    GLsync f = q->ring[q->first];
    GLenum r = glClientWaitSync(f, GL_SYNC_FLUSH_COMMANDS_BIT, timeout_ns);
    if (r == GL_WAIT_FAILED) {
        *st = oit_gl_check("upload: glClientWaitSync", err);
        if (*st == OIT_OK)
            *st = oit_error_set(err, OIT_ERR_GL, "upload: glClientWaitSync failed");
        return 0;
    }
    if (r == GL_TIMEOUT_EXPIRED)
        return 0;
    glDeleteSync(f);
    q->first = (q->first + 1) % q->cap;
    q->count--;
    q->completed++;
    return 1;
}

uint64_t oit_fence_queue_poll(oit_fence_queue *q)
{
    oit_status st = OIT_OK;
    while (q->count && retire_oldest(q, 0, &st, NULL))
        ;
    return q->completed;
}

oit_status oit_fence_queue_wait(oit_fence_queue *q, uint64_t serial, oit_host_waits *waits,
                                oit_error *err)
{
    if (serial > q->issued) {
        oit_status st = oit_fence_queue_insert(q, err);
        if (st != OIT_OK)
            return st;
    }
    if (oit_fence_queue_poll(q) < serial)
        oit_host_wait_note(waits);
    oit_status st = OIT_OK;
    /* A bounded wait in a loop rather than an infinite one: a context that
     * was lost would otherwise hang the caller forever. */
    const GLuint64 slice = 100000000ull; /* 0.1 s */
    unsigned slices = 0;
    while (q->completed < serial && st == OIT_OK) {
        if (retire_oldest(q, slice, &st, err))
            slices = 0;
        else if (st == OIT_OK && ++slices >= 600)
            st = oit_error_set(err, OIT_ERR_GL, "upload: the GPU did not finish a pack "
                               "within 60 s (fence %llu)", (unsigned long long)serial);
    }
    return st;
}
