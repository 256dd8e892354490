/* Bounded upload of part data: one GL buffer of a fixed byte budget used as
 * a ring. Parts are expanded on the CPU into the triangle soup that
 * render/gpu_mesh draws (stream/part_triangles.h) and copied in with
 * glNamedBufferSubData; a pack (<= the budget, see pack.h) is placed
 * contiguously, wrapping to the start when the tail is too short. GL orders
 * the copy after the draws that still read the overwritten range, so reuse
 * needs no fence. Requires a current GL context. */
#ifndef OIT_STREAM_UPLOAD_H
#define OIT_STREAM_UPLOAD_H

#include "oit/partfile.h"

typedef struct oit_upload oit_upload;

/* budget: the ring's bytes; max_part_bytes: the largest part expanded (the
 * host staging buffer). */
oit_status oit_upload_create(uint64_t budget, uint64_t max_part_bytes, oit_upload **out,
                             oit_error *err);
void oit_upload_destroy(oit_upload *u);
unsigned oit_upload_buffer(const oit_upload *u);
uint64_t oit_upload_gpu_bytes(const oit_upload *u);

/* Reserves room for a pack of bytes (<= budget, a multiple of OIT_PACK_ALIGN). */
oit_status oit_upload_begin_pack(oit_upload *u, uint64_t bytes, oit_error *err);
/* Expands a validated part into the pack's next slot; *offset receives its
 * byte offset in the buffer. */
oit_status oit_upload_part(oit_upload *u, const oit_partfile *pf, uint32_t part,
                           uint64_t *offset, oit_error *err);

#endif
