/* Persistently mapped upload ring (upload.h). */
#include "view/stream/upload.h"

#include <stdlib.h>

#include "view/render/gl/gl_util.h"
#include "view/stream/pack.h"

typedef struct region {
    uint64_t start, end;
    uint64_t serial; /* fence tag of its draws; 0 while undrawn */
} region;

/* Live regions in reservation order, a growable circular array. They lie in
 * the ring in the same order, so the free space is the arc from the newest
 * region's end (head) round to the oldest one's start. */
struct oit_upload {
    GLuint buffer;
    unsigned char *map;
    uint64_t budget;
    uint64_t head;
    region *live;
    uint32_t cap, first, count;
    uint32_t drawn; /* live[first .. first+drawn) carry their serial */
};

oit_status oit_upload_create(uint64_t budget, oit_upload **out, oit_error *err)
{
    *out = NULL;
    oit_upload *u = calloc(1, sizeof *u);
    if (!u)
        return oit_error_set(err, OIT_ERR_NOMEM, "upload: out of memory");
    u->budget = budget;
    const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glCreateBuffers(1, &u->buffer);
    glNamedBufferStorage(u->buffer, (GLsizeiptr)budget, NULL, flags);
    oit_gl_poison_buffer(u->buffer);
    oit_status s = oit_gl_check("upload ring: glNamedBufferStorage", err);
    if (s == OIT_OK) {
        u->map = glMapNamedBufferRange(u->buffer, 0, (GLsizeiptr)budget, flags);
        s = oit_gl_check("upload ring: glMapNamedBufferRange", err);
        if (s == OIT_OK && !u->map)
            s = oit_error_set(err, OIT_ERR_GL, "upload ring: cannot map %llu bytes "
                              "persistently", (unsigned long long)budget);
    }
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
    if (u->map)
        glUnmapNamedBuffer(u->buffer);
    if (u->buffer)
        glDeleteBuffers(1, &u->buffer);
    free(u->live);
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

unsigned char *oit_upload_map(const oit_upload *u)
{
    return u->map;
}

static region *at(const oit_upload *u, uint32_t i)
{
    return &u->live[(u->first + i) % u->cap];
}

/* Drops the oldest drawn regions whose work completed. */
static void reclaim(oit_upload *u, uint64_t completed)
{
    while (u->drawn && at(u, 0)->serial <= completed) {
        u->first = (u->first + 1) % u->cap;
        u->count--;
        u->drawn--;
    }
    if (!u->count)
        u->head = 0; /* an empty ring starts over: the longest run */
}

/* Where `bytes` fit in the free arc, or UINT64_MAX. */
static uint64_t place(const oit_upload *u, uint64_t bytes)
{
    if (!u->count)
        return 0;
    uint64_t tail = at(u, 0)->start;
    if (tail < u->head) { /* live data in [tail, head): free after head, then before tail */
        if (u->budget - u->head >= bytes)
            return u->head;
        return bytes <= tail ? 0 : UINT64_MAX;
    }
    return tail - u->head >= bytes ? u->head : UINT64_MAX; /* live data wraps */
}

static oit_status push(oit_upload *u, uint64_t start, uint64_t bytes, oit_error *err)
{
    if (u->count == u->cap) {
        uint32_t cap = u->cap ? 2 * u->cap : 64;
        region *r = malloc((size_t)cap * sizeof *r);
        if (!r)
            return oit_error_set(err, OIT_ERR_NOMEM, "upload: cannot track %u regions", cap);
        for (uint32_t i = 0; i < u->count; i++)
            r[i] = *at(u, i);
        free(u->live);
        u->live = r;
        u->cap = cap;
        u->first = 0;
    }
    u->live[(u->first + u->count) % u->cap] = (region){start, start + bytes, 0};
    u->count++;
    u->head = start + bytes;
    return OIT_OK;
}

oit_status oit_upload_reserve(oit_upload *u, oit_fence_queue *f, uint64_t bytes, int wait,
                              uint64_t *offset, int *got, oit_host_waits *waits,
                              oit_error *err)
{
    *got = 0;
    if (bytes == 0 || bytes > u->budget || bytes % OIT_PACK_ALIGN)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "upload: cannot reserve %llu bytes of a "
                             "%llu-byte ring", (unsigned long long)bytes,
                             (unsigned long long)u->budget);
    for (;;) {
        reclaim(u, oit_fence_queue_poll(f));
        uint64_t o = place(u, bytes);
        if (o != UINT64_MAX) {
            oit_status s = push(u, o, bytes, err);
            *offset = o;
            *got = s == OIT_OK;
            return s;
        }
        /* Not empty, or it would have fitted: the oldest region is in the way. */
        if (!wait || !u->drawn)
            return OIT_OK;
        oit_status s = oit_fence_queue_wait(f, at(u, 0)->serial, waits, err);
        if (s != OIT_OK)
            return s;
    }
}

void oit_upload_drawn(oit_upload *u, uint64_t serial)
{
    if (u->drawn < u->count)
        at(u, u->drawn++)->serial = serial;
}

void oit_upload_release_undrawn(oit_upload *u)
{
    u->count = u->drawn;
    u->head = u->count ? at(u, u->count - 1)->end : 0;
}
