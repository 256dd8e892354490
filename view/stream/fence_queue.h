/* GPU progress as serial numbers, for reusing memory that draws read.
 *
 * Work issued to GL is tagged with oit_fence_queue_tag(): the serial of the
 * next fence, which will follow that work in the command stream. Fences are
 * inserted in order (serials 1, 2, ...), and a fence that signalled implies
 * every earlier one did, so "serial s completed" covers all work tagged
 * <= s. Inserting is cheap but not free on every driver (llvmpipe ends its
 * binned scene at a fence), so the caller inserts where it pays (after a
 * pack that used a fair share of the ring), and a wait on a tag that has no
 * fence yet inserts one. Requires a current GL context (render thread
 * only). */
#ifndef OIT_STREAM_FENCE_QUEUE_H
#define OIT_STREAM_FENCE_QUEUE_H

#include <stdint.h>

#include "oit/status.h"
#include "view/render/gl/host_wait.h"

typedef struct oit_fence_queue oit_fence_queue;

oit_status oit_fence_queue_create(oit_fence_queue **out, oit_error *err);
/* Deletes the sync objects still held (without waiting for them). */
void oit_fence_queue_destroy(oit_fence_queue *q);

/* The serial that work issued from now until the next insert will carry. */
uint64_t oit_fence_queue_tag(const oit_fence_queue *q);
/* Inserts a fence after everything issued so far. */
oit_status oit_fence_queue_insert(oit_fence_queue *q, oit_error *err);
/* The newest serial known complete, after checking pending fences without
 * waiting. */
uint64_t oit_fence_queue_poll(oit_fence_queue *q);
/* Blocks until work tagged `serial` completed (inserting its fence first
 * when it has none yet); one wait counted on waits (NULL: none) when it
 * had to block, none when the fences polled had already signalled. */
oit_status oit_fence_queue_wait(oit_fence_queue *q, uint64_t serial, oit_host_waits *waits,
                                oit_error *err);

#endif
