/* The compute capture's records across several storage bindings
 * (capture_compute.h): a batch is one sweep over all its triangles, which
 * are not in visibility order, so it cannot be cut where its records
 * outgrow one binding (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, or a store limit).
 * One buffer holds them; block j, bound at OIT_BIND_FRAGS (j = 0) or
 * OIT_BIND_RECS<j>, spans records [j, j + 1) * per of it, and the shaders
 * pick a record's block with an if-chain (compute_glsl.c). Internal to
 * view/render/capture/. */
#ifndef OIT_RENDER_CAPTURE_COMPUTE_BLOCKS_H
#define OIT_RENDER_CAPTURE_COMPUTE_BLOCKS_H

#include "view/render/gl/gl_util.h"

#include <stdint.h>

/* As many blocks as the driver lets the sweep declare and bind, at most
 * OIT_COMPUTE_BLOCKS, at least 1. */
int oit_compute_record_blocks(void);

/* Records one block holds within bind bytes: whole records, each block's
 * offset a multiple of align (GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT),
 * a block's word indices within a uint. 0 where not one record fits. */
uint64_t oit_compute_block_records(uint64_t align, uint64_t bind);

/* Binds the blocks of the records of tris triangles in buffer recs, per
 * a block; the blocks past the batch's get the first one's range again
 * (never read; a binding is not left absent). */
void oit_compute_bind_records(GLuint recs, int blocks, uint64_t tris, uint64_t per);

/* OIT_ERR_UNSUPPORTED naming the batch's records against what blocks of
 * bind bytes (per records each) hold. */
oit_status oit_compute_too_many(int blocks, uint64_t tris, uint64_t per, uint64_t bind,
                                oit_error *err);

#endif
