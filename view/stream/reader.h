/* Reading parts ahead of the GPU: threads that validate parts of a part
 * file and expand them (partfile/triangles.h) into memory the render thread
 * made available, delivered in the order they were asked for.
 *
 * Ownership. The render thread owns the GL context, the upload ring and the
 * decision of where each part goes; it hands the reader a job (an array of
 * {part, byte offset}) whose target bytes it has reserved (upload.h), and
 * collects jobs in submission order. The reader never calls GL: it touches
 * only the part file (the mapping's pages fault in here, off the render
 * thread) and the target bytes of the job it runs. A job's items array
 * belongs to the caller and must stay untouched until the job is collected.
 *
 * Threads. Every thread takes the next unclaimed item of the oldest job
 * that has one, so the items of one job, and of the jobs behind it, are
 * decoded at once, each into its own bytes; items finish in any order, but
 * a job is collected only once all of its items are done, and jobs are
 * collected in submission order. Each thread decodes in a buffer of its
 * own. A part may appear in at most one item of the jobs outstanding (the
 * streamer reads a part once a frame and collects the frame's jobs before
 * the next): two threads must not validate one part at once.
 *
 * Queue: at most OIT_READER_QUEUE jobs submitted and not yet collected,
 * guarded by one mutex with two condition variables (work to do, item
 * done). Errors (a part that fails oit_partfile_validate_part, a read fault
 * surfaced as a format error) end that job with an oit_status whose message
 * names the file and the part (the first failing item's, in the job's
 * order); its items not yet started are not run; later jobs still run, and
 * the caller usually cancels them. Cancel and destroy never wait for more
 * than the items in progress.
 *
 * Without a thread (threads = 0) every job runs inside oit_reader_submit on
 * the caller's thread: the same results, no overlap; for comparison and
 * debugging. */
#ifndef OIT_STREAM_READER_H
#define OIT_STREAM_READER_H

#include <stdint.h>

#include "oit/partfile.h"
#include "oit/render_modes.h"

#define OIT_READER_QUEUE 16u
/* The most threads a reader starts (oit_renderer_desc.reader_threads). */
#define OIT_READER_MAX_THREADS OIT_RENDER_READER_THREADS_MAX

typedef struct oit_read_item {
    uint32_t part;
    uint64_t offset; /* of its oit_triangle records from the target's first byte */
} oit_read_item;

typedef struct oit_reader oit_reader;

/* Expands part into dst, decoding in buf (the calling thread's own):
 * oit_part_expand_sourced unless a test injects another. */
typedef oit_status (*oit_reader_expand_fn)(void *ctx, oit_partfile *pf, uint32_t part,
                                           oit_partfile_buffer *buf, unsigned char *dst,
                                           oit_error *err);

/* dst: the target (oit_upload_map); pf and dst must outlive the reader.
 * threads: 0..OIT_READER_MAX_THREADS (0: none, jobs run in submit). The
 * reader validates parts (oit_partfile_validate_part), so pf may be opened
 * with defer_part_data; no one else may validate parts of pf while a job
 * runs. */
oit_status oit_reader_create(oit_partfile *pf, unsigned char *dst, int threads,
                             oit_reader **out, oit_error *err);
/* The same with expand in place of oit_part_expand_sourced (ctx passed
 * through): for tests that delay or fail items. */
oit_status oit_reader_create_with(oit_partfile *pf, unsigned char *dst, int threads,
                                  oit_reader_expand_fn expand, void *ctx, oit_reader **out,
                                  oit_error *err);
/* Threads it runs (0: none). */
int oit_reader_threads(const oit_reader *r);
/* Stops the threads after the items in progress and joins them; jobs not
 * collected are dropped. NULL is allowed. */
void oit_reader_destroy(oit_reader *r);

/* Queues count items (count may be 0). OIT_ERR_ARGUMENT when
 * OIT_READER_QUEUE jobs are outstanding already. */
oit_status oit_reader_submit(oit_reader *r, const oit_read_item *items, uint32_t count,
                             oit_error *err);
/* Waits for the oldest outstanding job and returns its status (err filled
 * from the reader's message on failure). OIT_ERR_ARGUMENT when none is
 * outstanding. */
oit_status oit_reader_collect(oit_reader *r, oit_error *err);
/* Jobs submitted and not yet collected. */
uint32_t oit_reader_outstanding(const oit_reader *r);
/* Drops every outstanding job: returns once nothing writes for them any
 * more (the items in progress finish, no other starts). */
void oit_reader_cancel(oit_reader *r);

#endif
