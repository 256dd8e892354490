/* The host's waits on the GPU, counted (host_wait.h). */
#include "view/render/gl/host_wait.h"

void oit_host_wait_note(oit_host_waits *w)
{
    if (w)
        w->count++;
}

void oit_host_read(oit_host_waits *w, GLuint buf, uint64_t offset, uint64_t bytes, void *dst)
{
    oit_host_wait_note(w);
    glGetNamedBufferSubData(buf, (GLintptr)offset, (GLsizeiptr)bytes, dst);
}
