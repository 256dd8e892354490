/* Reading parts ahead of the GPU: a thread that validates parts of a part
 * file and expands them (partfile/triangles.h) into memory the render thread
 * made available, in the order they were asked for.
 *
 * Ownership. The render thread owns the GL context, the upload ring and the
 * decision of where each part goes; it hands the reader a job (an array of
 * {part, byte offset}) whose target bytes it has reserved (upload.h), and
 * collects jobs in submission order. The reader never calls GL: it touches
 * only the part file (the mapping's pages fault in here, off the render
 * thread) and the target bytes of the job it runs. A job's items array
 * belongs to the caller and must stay untouched until the job is collected.
 *
 * Queue: at most OIT_READER_QUEUE jobs submitted and not yet collected,
 * guarded by one mutex with two condition variables (work to do, job done).
 * Errors (a part that fails oit_partfile_validate_part, a read fault surfaced
 * as a format error) end that job with an oit_status whose message names the
 * file and the part; later jobs still run, and the caller usually cancels
 * them. Cancel and destroy never wait for more than the part in progress.
 *
 * Without a thread (threaded = 0) every job runs inside oit_reader_submit on
 * the caller's thread: the same results, no overlap; for comparison and
 * debugging. */
#ifndef OIT_STREAM_READER_H
#define OIT_STREAM_READER_H

#include <stdint.h>

#include "oit/partfile.h"

#define OIT_READER_QUEUE 16u

typedef struct oit_read_item {
    uint32_t part;
    uint64_t offset; /* of its oit_triangle records from the target's first byte */
} oit_read_item;

typedef struct oit_reader oit_reader;

/* dst: the target (oit_upload_map); pf and dst must outlive the reader. The
 * reader validates parts (oit_partfile_validate_part), so pf may be opened
 * with defer_part_data; no one else may validate parts of pf while a job
 * runs. */
oit_status oit_reader_create(oit_partfile *pf, unsigned char *dst, int threaded,
                             oit_reader **out, oit_error *err);
/* Stops the thread after the part in progress and joins it; jobs not
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
 * more (the one in progress stops between two parts). */
void oit_reader_cancel(oit_reader *r);

#endif
