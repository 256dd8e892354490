/* How much GPU memory the driver says is free, where it says so:
 * GL_NVX_gpu_memory_info (NVIDIA: GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM)
 * or GL_ATI_meminfo (AMD: VBO_FREE_MEMORY's total free). Other drivers
 * (llvmpipe, Intel, ...) say nothing: 0. Needs a current GL context. */
#ifndef OIT_RENDER_GPU_MEMORY_H
#define OIT_RENDER_GPU_MEMORY_H

#include <stdint.h>

/* Free bytes, 0 when unknown; *source names the extension that told, or
 * why none did. The signature is the one callers take as an injectable
 * query (oit_streamer_desc.free_query), so tests can fake a driver. */
typedef uint64_t (*oit_gpu_free_query)(void *ctx, const char **source);
uint64_t oit_gpu_free_bytes(void *ctx, const char **source);

#endif
