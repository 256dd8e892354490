/* The host's waits on the GPU within a frame, counted where they happen:
 * every read-back of GPU-written data, every fence or query wait that
 * blocked, every glFinish between a frame's first command and its final
 * read-back (which is not counted: a frame must end in one). A frame that
 * waits stalls the pipeline it feeds, so the figure is reported per frame
 * (oit_frame_stats.host_waits) and the default paths are held to 0 on
 * warm frames. The counter lives in the frame's owner (the capture's
 * frame); NULL counts nothing (work outside a frame: set-up, self-tests). */
#ifndef OIT_RENDER_GL_HOST_WAIT_H
#define OIT_RENDER_GL_HOST_WAIT_H

#include "view/render/gl/gl_util.h"

#include <stdint.h>

typedef struct oit_host_waits {
    uint32_t count;
} oit_host_waits;

/* A wait of another kind (a fence that blocked, a blocking query result,
 * glFinish) on w. */
void oit_host_wait_note(oit_host_waits *w);

/* glGetNamedBufferSubData of bytes at offset of buf into dst, counted on
 * w: the call waits until the GPU has written them. */
void oit_host_read(oit_host_waits *w, GLuint buf, uint64_t offset, uint64_t bytes, void *dst);

#endif
