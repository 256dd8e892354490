/* The read-ahead threads (reader.h). */
#include "view/stream/reader.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "oit/mesh.h"
#include "partfile/triangles.h"

/* A job's items are claimed in order (next), so every item before the
 * first failing one was run: the error kept is the lowest failing item's,
 * whatever order the threads finish in. */
typedef struct job {
    const oit_read_item *items;
    uint32_t count;
    uint32_t next;    /* items claimed; count once failed or dropped */
    uint32_t running; /* claimed and not finished */
    uint32_t failed;  /* the lowest failing item; UINT32_MAX: none */
    oit_status status;
    oit_error err;
} job;

typedef struct worker {
    struct oit_reader *r;
    int index;
} worker;

/* Jobs are numbered from 0 in submission order: job n lives in
 * jobs[n % OIT_READER_QUEUE]; collected <= submitted. Everything below is
 * under lock but the fields set at create. */
struct oit_reader {
    oit_partfile *pf;
    unsigned char *dst;
    oit_reader_expand_fn expand;
    void *ctx;
    int threads, started;
    pthread_t *thread;
    worker *workers; /* each thread's argument */
    /* Where each thread decodes parts ([0] also for jobs run in submit). */
    oit_partfile_buffer *decoded;
    pthread_mutex_t lock;
    pthread_cond_t work, done;
    job jobs[OIT_READER_QUEUE];
    uint64_t submitted, collected;
    int stop;
};


static oit_status expand_sourced(void *ctx, oit_partfile *pf, uint32_t part,
                                 oit_partfile_buffer *buf, unsigned char *dst, oit_error *err)
{
    (void)ctx;
    /* One decode a use: validated on the part's first (part_load). */
    return oit_part_expand_sourced(pf, part, buf, dst, err);
}

static int job_done(const job *j)
{
    return j->next == j->count && j->running == 0;
}

/* The oldest outstanding job with an item to claim, or NULL. */
static job *claimable(oit_reader *r)
{
    for (uint64_t n = r->collected; n < r->submitted; n++) {
        job *j = &r->jobs[n % OIT_READER_QUEUE];
        if (j->next < j->count)
            return j;
    }
    return NULL;
}

/* Runs item i of j outside the lock, then records it under the lock. */
static void run_item(oit_reader *r, job *j, uint32_t i, oit_partfile_buffer *buf)
{
    const oit_read_item it = j->items[i];
    oit_error e = {0};
    pthread_mutex_unlock(&r->lock);
    oit_status s = r->expand(r->ctx, r->pf, it.part, buf, r->dst + it.offset, &e);
    pthread_mutex_lock(&r->lock);
    j->running--;
    if (s != OIT_OK && i < j->failed) {
        j->failed = i;
        j->status = s;
        j->err = e;
        j->next = j->count; /* the items after it are not run */
    }
}

static void *thread_main(void *arg)
{
    const worker *w = arg;
    oit_reader *r = w->r;
    oit_partfile_buffer *buf = &r->decoded[w->index];
    pthread_mutex_lock(&r->lock);
    while (!r->stop) {
        job *j = claimable(r);
        if (!j) {
            pthread_cond_wait(&r->work, &r->lock);
            continue;
        }
        uint32_t i = j->next++;
        j->running++;
        run_item(r, j, i, buf);
        if (job_done(j))
            pthread_cond_broadcast(&r->done);
    }
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

oit_status oit_reader_create(oit_partfile *pf, unsigned char *dst, int threads,
                             oit_reader **out, oit_error *err)
{
    return oit_reader_create_with(pf, dst, threads, expand_sourced, NULL, out, err);
}

static oit_status start_threads(oit_reader *r, oit_error *err)
{
    worker *w = r->workers;
    for (int i = 0; i < r->threads; i++) {
        w[i] = (worker){r, i};
        int e = pthread_create(&r->thread[i], NULL, thread_main, &w[i]);
        if (e != 0)
            return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot start part reader thread %d "
                                 "of %d: %s", oit_partfile_name(r->pf), i + 1, r->threads,
                                 strerror(e));
        r->started++;
    }
    return OIT_OK;
}

oit_status oit_reader_create_with(oit_partfile *pf, unsigned char *dst, int threads,
                                  oit_reader_expand_fn expand, void *ctx, oit_reader **out,
                                  oit_error *err)
{
    *out = NULL;
    if (threads < 0 || threads > OIT_READER_MAX_THREADS)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %d part reader threads: expected "
                             "0..%d", oit_partfile_name(pf), threads, OIT_READER_MAX_THREADS);
    oit_reader *r = calloc(1, sizeof *r);
    size_t slots = threads ? (size_t)threads : 1;
    if (r) {
        r->decoded = calloc(slots, sizeof *r->decoded);
        r->thread = calloc(slots, sizeof *r->thread);
        r->workers = calloc(slots, sizeof *r->workers);
    }
    if (!r || !r->decoded || !r->thread || !r->workers) {
        if (r) {
            free(r->decoded);
            free(r->thread);
            free(r->workers);
        }
        free(r);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the part reader",
                             oit_partfile_name(pf));
    }
    r->pf = pf;
    r->dst = dst;
    r->expand = expand;
    r->ctx = ctx;
    r->threads = threads;
    pthread_mutex_init(&r->lock, NULL);
    pthread_cond_init(&r->work, NULL);
    pthread_cond_init(&r->done, NULL);
    oit_status s = start_threads(r, err);
    if (s != OIT_OK) {
        oit_reader_destroy(r);
        return s;
    }
    *out = r;
    return OIT_OK;
}

int oit_reader_threads(const oit_reader *r)
{
    return r->threads;
}

void oit_reader_destroy(oit_reader *r)
{
    if (!r)
        return;
    pthread_mutex_lock(&r->lock);
    r->stop = 1;
    pthread_cond_broadcast(&r->work);
    pthread_mutex_unlock(&r->lock);
    for (int i = 0; i < r->started; i++)
        pthread_join(r->thread[i], NULL);
    pthread_cond_destroy(&r->done);
    pthread_cond_destroy(&r->work);
    pthread_mutex_destroy(&r->lock);
    for (int i = 0; i < (r->threads ? r->threads : 1); i++)
        oit_partfile_buffer_free(&r->decoded[i]);
    free(r->decoded);
    free(r->thread);
    free(r->workers);
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
    *j = (job){.items = items, .count = count, .failed = UINT32_MAX};
    r->submitted++;
    if (r->threads)
        pthread_cond_broadcast(&r->work);
    else /* no thread: this one runs the job, in order */
        while (j->next < j->count) {
            uint32_t i = j->next++;
            j->running++;
            run_item(r, j, i, &r->decoded[0]);
        }
    pthread_mutex_unlock(&r->lock);
    return OIT_OK;
}

oit_status oit_reader_collect(oit_reader *r, oit_error *err)
{
    pthread_mutex_lock(&r->lock);
    if (r->collected == r->submitted) {
        pthread_mutex_unlock(&r->lock);
        return oit_error_set(err, OIT_ERR_ARGUMENT, "part reader: no job to collect");
    }
    job *j = &r->jobs[r->collected % OIT_READER_QUEUE];
    while (!job_done(j))
        pthread_cond_wait(&r->done, &r->lock);
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
    for (uint64_t n = r->collected; n < r->submitted; n++)
        r->jobs[n % OIT_READER_QUEUE].next = r->jobs[n % OIT_READER_QUEUE].count;
    for (uint64_t n = r->collected; n < r->submitted; n++)
        while (!job_done(&r->jobs[n % OIT_READER_QUEUE]))
            pthread_cond_wait(&r->done, &r->lock);
    r->collected = r->submitted;
    pthread_mutex_unlock(&r->lock);
}
