/* Upload ring (upload.h). */
#include "stream/upload.h"

#include <stdlib.h>

#include "render/gl_util.h"
#include "stream/pack.h"
#include "stream/part_triangles.h"

struct oit_upload {
    GLuint buffer;
    uint64_t budget;
    uint64_t head;      /* next free byte */
    uint64_t pack_end;  /* end of the space reserved for the current pack */
    oit_triangle *staging;
};

oit_status oit_upload_create(uint64_t budget, uint64_t max_part_bytes, oit_upload **out,
                             oit_error *err)
{
    *out = NULL;
    oit_upload *u = calloc(1, sizeof *u);
    if (u)
        u->staging = malloc(max_part_bytes ? (size_t)max_part_bytes : 1);
    if (!u || !u->staging) {
        oit_upload_destroy(u);
        return oit_error_set(err, OIT_ERR_NOMEM, "upload: cannot allocate %llu staging bytes",
                             (unsigned long long)max_part_bytes);
    }
    u->budget = budget;
    glCreateBuffers(1, &u->buffer);
    glNamedBufferStorage(u->buffer, (GLsizeiptr)budget, NULL, GL_DYNAMIC_STORAGE_BIT);
    oit_status s = oit_gl_check("upload ring: glNamedBufferStorage", err);
    if (s != OIT_OK) {
        oit_upload_destroy(u);
        return s;
    }
    *out = u;
    return OIT_OK;
}

void oit_upload_destroy(oit_upload *u)
{
    if (!u)
        return;
    if (u->buffer)
        glDeleteBuffers(1, &u->buffer);
    free(u->staging);
    free(u);
}

unsigned oit_upload_buffer(const oit_upload *u)
{
    return u->buffer;
}

uint64_t oit_upload_gpu_bytes(const oit_upload *u)
{
    return u->budget;
}

oit_status oit_upload_begin_pack(oit_upload *u, uint64_t bytes, oit_error *err)
{
    if (bytes > u->budget)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "upload: a pack of %llu bytes exceeds the "
                             "ring's %llu", (unsigned long long)bytes,
                             (unsigned long long)u->budget);
    if (u->budget - u->head < bytes)
        u->head = 0;
    u->pack_end = u->head + bytes;
    return OIT_OK;
}

oit_status oit_upload_part(oit_upload *u, const oit_partfile *pf, uint32_t part,
                           uint64_t *offset, oit_error *err)
{
    const oit_partfile_part *p = &oit_partfile_parts(pf)[part];
    uint64_t slot = oit_pack_part_bytes(p), bytes = p->index_count / 3 * sizeof(oit_triangle);
    if (u->head + slot > u->pack_end)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "upload: part %u overruns its pack", part);
    oit_status s = oit_part_expand(pf, part, u->staging, err);
    if (s != OIT_OK)
        return s;
    glNamedBufferSubData(u->buffer, (GLintptr)u->head, (GLsizeiptr)bytes, u->staging);
    *offset = u->head;
    u->head += slot;
    return OIT_OK;
}
