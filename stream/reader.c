/* The read-ahead thread (reader.h). */
#include "stream/reader.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "oit/mesh.h"
#include "partfile/triangles.h"

typedef struct job {
    const oit_read_item *items;
    uint32_t count;
    oit_status status;
    oit_error err;
} job;

/* Jobs are numbered from 0 in submission order: job n lives in
 * jobs[n % OIT_READER_QUEUE]. collected <= finished <= submitted; the render
 * thread writes a slot only while it is free (n >= collected +
 * OIT_READER_QUEUE is never submitted), the reader reads it only after
 * taking the lock that the submit released. */
struct oit_reader {
    oit_partfile *pf;
    unsigned char *dst;
    /* Where the reader thread decodes parts (only it touches it; the
     * synchronous mode runs jobs on the submitting thread, one at a time). */
    oit_partfile_buffer decoded;
    int threaded, started;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t work, done;
    job jobs[OIT_READER_QUEUE];
    uint64_t submitted, finished, collected; /* under lock */
    /* Read between parts without the lock: jobs numbered below drop_below
     * stop (cancel); stop ends the thread (destroy). */
    atomic_uint_fast64_t drop_below;
    atomic_int stop;
};

static int dropped(oit_reader *r, uint64_t n)
{
    return n < atomic_load_explicit(&r->drop_below, memory_order_relaxed) ||
           atomic_load_explicit(&r->stop, memory_order_relaxed);
}

static oit_status run_job(oit_reader *r, job *j, uint64_t n)
{
    for (uint32_t i = 0; i < j->count && !dropped(r, n); i++) {
        const oit_read_item *it = &j->items[i];
        /* One decode a use: validated on the part's first (part_load). */
        oit_status s = oit_part_expand_sourced(r->pf, it->part, &r->decoded,
                                               r->dst + it->offset, &j->err);
        if (s != OIT_OK)
            return s;
    }
    return OIT_OK;
}

static void *thread_main(void *arg)
{
    oit_reader *r = arg;
    pthread_mutex_lock(&r->lock);
    for (;;) {
        while (!atomic_load(&r->stop) && r->finished == r->submitted)
            pthread_cond_wait(&r->work, &r->lock);
        if (atomic_load(&r->stop))
            break;
        uint64_t n = r->finished;
        job *j = &r->jobs[n % OIT_READER_QUEUE];
        pthread_mutex_unlock(&r->lock);
        oit_status s = run_job(r, j, n);
        pthread_mutex_lock(&r->lock);
        j->status = s;
        r->finished++;
        pthread_cond_broadcast(&r->done);
    }
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

oit_status oit_reader_create(oit_partfile *pf, unsigned char *dst, int threaded,
                             oit_reader **out, oit_error *err)
{
    *out = NULL;
    oit_reader *r = calloc(1, sizeof *r);
    if (!r)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the part reader",
                             oit_partfile_name(pf));
    r->pf = pf;
    r->dst = dst;
    r->threaded = threaded;
    atomic_init(&r->drop_below, 0);
    atomic_init(&r->stop, 0);
    pthread_mutex_init(&r->lock, NULL);
    pthread_cond_init(&r->work, NULL);
    pthread_cond_init(&r->done, NULL);
    if (threaded) {
        int e = pthread_create(&r->thread, NULL, thread_main, r);
        if (e != 0) {
            oit_reader_destroy(r);
            return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot start the part reader "
                                 "thread: %s", oit_partfile_name(pf), strerror(e));
        }
        r->started = 1;
    }
    *out = r;
    return OIT_OK;
}

void oit_reader_destroy(oit_reader *r)
{
    if (!r)
        return;
    if (r->started) {
        pthread_mutex_lock(&r->lock);
        atomic_store(&r->stop, 1);
        pthread_cond_signal(&r->work);
        pthread_mutex_unlock(&r->lock);
        pthread_join(r->thread, NULL);
    }
    pthread_cond_destroy(&r->done);
    pthread_cond_destroy(&r->work);
    pthread_mutex_destroy(&r->lock);
    oit_partfile_buffer_free(&r->decoded);
    free(r);
}

oit_status oit_reader_submit(oit_reader *r, const oit_read_item *items, uint32_t count,
                             oit_error *err)
{
    pthread_mutex_lock(&r->lock);
    uint64_t n = r->submitted;
    if (n - r->collected >= OIT_READER_QUEUE) {
        pthread_mutex_unlock(&r->lock);
        return oit_error_set(err, OIT_ERR_ARGUMENT, "part reader: %u jobs outstanding already",
                             OIT_READER_QUEUE);
    }
    job *j = &r->jobs[n % OIT_READER_QUEUE];
    *j = (job){.items = items, .count = count};
    r->submitted++;
    if (r->threaded)
        pthread_cond_signal(&r->work);
    pthread_mutex_unlock(&r->lock);
    if (!r->threaded) { /* only this thread touches the queue: no lock needed */
        j->status = run_job(r, j, n);
        r->finished++;
    }
    return OIT_OK;
}

oit_status oit_reader_collect(oit_reader *r, oit_error *err)
{
    pthread_mutex_lock(&r->lock);
    if (r->collected == r->submitted) {
        pthread_mutex_unlock(&r->lock);
        return oit_error_set(err, OIT_ERR_ARGUMENT, "part reader: no job to collect");
    }
    uint64_t n = r->collected;
    while (r->finished <= n)
        pthread_cond_wait(&r->done, &r->lock);
    job *j = &r->jobs[n % OIT_READER_QUEUE];
    oit_status s = j->status;
    if (s != OIT_OK && err)
        *err = j->err;
    r->collected++;
    pthread_mutex_unlock(&r->lock);
    return s;
}

uint32_t oit_reader_outstanding(const oit_reader *r)
{
    return (uint32_t)(r->submitted - r->collected);
}

void oit_reader_cancel(oit_reader *r)
{
    pthread_mutex_lock(&r->lock);
    atomic_store(&r->drop_below, r->submitted);
    while (r->finished < r->submitted)
        pthread_cond_wait(&r->done, &r->lock);
    r->collected = r->submitted;
    pthread_mutex_unlock(&r->lock);
}
