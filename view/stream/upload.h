/* Bounded upload of part data: one GL buffer of a fixed byte budget,
 * persistently and coherently mapped (glNamedBufferStorage with
 * MAP_WRITE | MAP_PERSISTENT | MAP_COHERENT), used as a ring of pack
 * regions. Each pack's parts take one contiguous region (<= the budget, see
 * pack.h), placed after the previous one or wrapped to the start when the
 * tail is too short; the CPU writes the parts' triangles and their source
 * indices (partfile/triangles.h oit_part_expand_sourced) straight into the
 * mapping (view/stream/reader.h, possibly from another thread), and the render
 * thread draws them in place.
 *
 * Correctness rests on one rule: a region is handed out again only after the
 * fence that follows its draws signalled (fence_queue.h). Regions are drawn
 * in the order they were reserved; a region reserved but not yet drawn is
 * never reclaimed, and is never waited for (its fence does not exist yet).
 * Coherent mapping: writes finished before a draw is issued are visible to
 * it, with no flush or barrier.
 *
 * Everything here runs on the render thread (it owns the GL context); only
 * the bytes of the mapping are shared, one region with one writer at a
 * time. */
#ifndef OIT_STREAM_UPLOAD_H
#define OIT_STREAM_UPLOAD_H

#include "oit/partfile.h"
#include "view/stream/fence_queue.h"

typedef struct oit_upload oit_upload;

/* budget: the ring's bytes (regions start at multiples of OIT_PACK_ALIGN). */
oit_status oit_upload_create(uint64_t budget, oit_upload **out, oit_error *err);
/* Unmaps and deletes the buffer: nothing may write the mapping any more. */
void oit_upload_destroy(oit_upload *u);
unsigned oit_upload_buffer(const oit_upload *u);
uint64_t oit_upload_gpu_bytes(const oit_upload *u);
/* The mapping's first byte: a region at offset o is map + o. */
unsigned char *oit_upload_map(const oit_upload *u);

/* Reserves `bytes` (1..budget, a multiple of OIT_PACK_ALIGN) for the next
 * pack and sets *offset, reclaiming first every drawn region whose fence
 * signalled. When it does not fit yet: with `wait`, blocks on the fences of
 * drawn regions until it does; without, or when an undrawn region is in the
 * way, returns OIT_OK with *got = 0 and reserves nothing. A fence it
 * blocked on counts on waits (oit_fence_queue_wait). */
oit_status oit_upload_reserve(oit_upload *u, oit_fence_queue *f, uint64_t bytes, int wait,
                              uint64_t *offset, int *got, oit_host_waits *waits,
                              oit_error *err);
/* The oldest undrawn region was drawn by work tagged `serial`
 * (oit_fence_queue_tag). */
void oit_upload_drawn(oit_upload *u, uint64_t serial);
/* Forgets the regions reserved but not drawn (a frame that failed): the
 * caller guarantees nothing writes them any more and no draw reads them. */
void oit_upload_release_undrawn(oit_upload *u);

#endif
