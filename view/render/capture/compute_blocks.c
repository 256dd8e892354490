/* The compute capture's record blocks (compute_blocks.h). */
#include "view/render/capture/compute_blocks.h"

#include "view/render/capture/compute_glsl.h"
#include "view/render/gl/glsl_bindings.h"

/* The sweep's storage blocks besides the records: tile ends, tile list,
 * resume cursors, pending counts, two work lists, the per-pixel state. */
#define SWEEP_OTHER_BLOCKS 7

#define RECORD_BYTES ((uint64_t)OIT_COMPUTE_RECORD_WORDS * 16)

/* GL 4.5 promises 8 blocks a compute shader, which the sweep's others
 * and one record block take already: more only where the driver says. */
int oit_compute_record_blocks(void)
{
    GLint stage = 0, bindings = 0;
    glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &stage);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &bindings);
    int n = OIT_COMPUTE_BLOCKS;
    n = stage - SWEEP_OTHER_BLOCKS < n ? stage - SWEEP_OTHER_BLOCKS : n;
    n = bindings - OIT_BIND_RECS1 + 1 < n ? bindings - OIT_BIND_RECS1 + 1 : n;
    return n > 1 ? n : 1;
}

uint64_t oit_compute_block_records(uint64_t align, uint64_t bind)
{
    uint64_t g = RECORD_BYTES;
    for (uint64_t t = align ? align : 1; t;) { /* gcd(record, align) */
        uint64_t m = g % t;
        g = t;
        t = m;
    }
    uint64_t step = (align ? align : 1) / g, n = bind / RECORD_BYTES;
    n -= n % step;
    uint64_t most = UINT32_MAX / OIT_COMPUTE_RECORD_WORDS;
    return n < most ? n : most;
}

void oit_compute_bind_records(GLuint recs, int blocks, uint64_t tris, uint64_t per)
{
    for (int j = 0; j < blocks; j++) {
        uint64_t first = (uint64_t)j * per, count = tris > first ? tris - first : 0;
        count = count < per ? count : per;
        if (count == 0) {
            first = 0;
            count = tris < per ? tris : per;
        }
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, j ? OIT_BIND_RECS1 + j - 1 : OIT_BIND_FRAGS,
                          recs, (GLintptr)(first * RECORD_BYTES),
                          (GLsizeiptr)(count * RECORD_BYTES));
    }
}

oit_status oit_compute_too_many(int blocks, uint64_t tris, uint64_t per, uint64_t bind,
                                oit_error *err)
{
    return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                         "compute capture: the batch's %llu triangles take %llu bytes of "
                         "records, more than the %d storage bindings of %llu bytes it may "
                         "span hold (%llu triangles); capture it in smaller packs",
                         (unsigned long long)tris, (unsigned long long)(tris * RECORD_BYTES),
                         blocks, (unsigned long long)bind, (unsigned long long)(per * blocks));
}
