/* The driver's free GPU memory (gpu_memory.h). */
#include "view/render/gl/gpu_memory.h"

#include <string.h>

#include "view/render/gl/gl_util.h"

/* Not in glcorearb.h: the extensions' own enums. */
#define GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX 0x9049
#define VBO_FREE_MEMORY_ATI 0x87FB

static int has_extension(const char *name)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && !strcmp(e, name))
            return 1;
    }
    return 0;
}

uint64_t oit_gpu_free_bytes(void *ctx, const char **source)
{
    (void)ctx;
    GLint kib[4] = {0, 0, 0, 0};
    if (has_extension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, kib);
        *source = "GL_NVX_gpu_memory_info";
    } else if (has_extension("GL_ATI_meminfo")) {
        /* [0]: the pool's total free memory, in KiB */
        glGetIntegerv(VBO_FREE_MEMORY_ATI, kib);
        *source = "GL_ATI_meminfo";
    } else {
        *source = "no driver figure (neither GL_NVX_gpu_memory_info nor GL_ATI_meminfo)";
        return 0;
    }
    if (glGetError() != GL_NO_ERROR || kib[0] <= 0) {
        *source = "the driver's free-memory query failed";
        return 0;
    }
    return (uint64_t)kib[0] << 10;
}
