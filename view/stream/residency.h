/* The residency cache's bookkeeping: which parts hold which bytes of a cache
 * buffer of `capacity` bytes, and which to evict for a new one. No GL and no
 * threads: the streamer owns the buffer, copies a part's triangles in on the
 * GPU after its upload, and draws cached parts from it in later frames
 * without reading or uploading them again.
 *
 * Placement is log-structured: a cursor sweeps the buffer in address order
 * and a new part goes at the first run of free bytes long enough for it,
 * evicting on the way parts idle for two frames or more (not used in this
 * frame nor the one before). Keeping the previous frame's parts is what
 * makes the cache useful when a frame's working set exceeds it: plain LRU
 * would evict, for each miss, a part this very frame needs further down its
 * order (the LRU loop pathology), while this keeps a stable subset and lets
 * newcomers in as parts leave the view. A sweep that finds no room marks the
 * cache full for the rest of the frame, so a frame costs at most one failed
 * sweep; parts that find no room are drawn from the upload ring and not
 * kept. Frame numbers start at 1 with the first oit_residency_begin_frame.
 *
 * Hazards are GL's: the streamer writes the buffer only with GL copies,
 * which GL orders after the draws that read the evicted bytes. */
#ifndef OIT_STREAM_RESIDENCY_H
#define OIT_STREAM_RESIDENCY_H

#include <stdint.h>

#include "oit/status.h"

typedef struct oit_residency oit_residency;

oit_status oit_residency_create(uint64_t capacity, uint32_t part_count, oit_residency **out,
                                oit_error *err);
void oit_residency_destroy(oit_residency *r);

void oit_residency_begin_frame(oit_residency *r);
/* 1 with *offset when part is resident (and marks it used in this frame);
 * 0 otherwise. */
int oit_residency_lookup(oit_residency *r, uint32_t part, uint64_t *offset);
/* The same without marking it used (for checks and figures). */
int oit_residency_peek(const oit_residency *r, uint32_t part, uint64_t *offset);
/* Makes a non-resident part of `bytes` (a multiple of the caller's
 * alignment, offsets keep it) resident, used in this frame; 1 with *offset
 * where it goes, 0 when there is no room this frame (see above). */
int oit_residency_insert(oit_residency *r, uint32_t part, uint64_t bytes, uint64_t *offset);
/* Bytes and parts resident now. */
uint64_t oit_residency_bytes(const oit_residency *r);
uint32_t oit_residency_parts(const oit_residency *r);
uint64_t oit_residency_capacity(const oit_residency *r);

#endif
