/* Triangles on the GPU (gpu_mesh.h). The soup is uploaded as is (16-byte
 * vertices) and read by the vertex-pulling shader of frag_glsl.h, which
 * needs no vertex array attributes (its one input, the per-draw record, is
 * the current attribute value in a single draw): one empty VAO per context
 * suffices, and GL core requires one to be bound, so each mesh owns its own.
 * Multi-draws are in gpu_mesh_many.c. */
#include "render/gpu_mesh.h"

#include "render/frag_glsl.h"

#include <stdlib.h>

struct oit_gpu_mesh {
    GLuint buffer;
    GLuint vao;
    size_t count;
    uint32_t first_prim;
    size_t window; /* triangles per draw: SSBO size limit and alignment */
    uint64_t offset; /* of the first triangle in buffer */
    int owns_buffer;
    int sourced;          /* prims are per-triangle u32 at prims_offset */
    uint64_t prims_offset;
    uint64_t align;       /* GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT */
};

static uint64_t ssbo_align(void)
{
    GLint align = 16;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    return align > 0 ? (uint64_t)align : 16;
}

/* Triangles per draw window: the SSBO binding limit, rounded down so that
 * window offsets keep the SSBO offset alignment. */
size_t oit_gpu_triangle_window(void)
{
    GLint max_block = 0, align = 16;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    size_t tri_bytes = sizeof(oit_triangle);
    size_t step = 1;
    while ((step * tri_bytes) % (size_t)(align > 0 ? align : 16) != 0)
        step++;
    size_t w = (size_t)(max_block > 0 ? max_block : (1 << 27)) / tri_bytes;
    /* glDrawArrays counts vertices in a GLsizei. */
    if (w > (size_t)0x7fffffff / 3)
        w = (size_t)0x7fffffff / 3;
    return w / step * step;
}

oit_status oit_gpu_mesh_create(const oit_triangle *tris, size_t count,
                               uint32_t first_prim, oit_gpu_mesh **out,
                               oit_error *err)
{
    *out = NULL;
    if ((uint64_t)first_prim + count > 0x80000000ull)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "GPU mesh: primitive indices %u..%llu exceed the 31 bits a "
                             "fragment carries", first_prim,
                             (unsigned long long)first_prim + count);
    oit_gpu_mesh *m = calloc(1, sizeof *m);
    if (!m)
        return oit_error_set(err, OIT_ERR_NOMEM, "GPU mesh: out of memory");
    m->count = count;
    m->first_prim = first_prim;
    m->window = oit_gpu_triangle_window();
    m->align = ssbo_align();
    m->owns_buffer = 1;
    glCreateVertexArrays(1, &m->vao);
    glCreateBuffers(1, &m->buffer);
    uint64_t bytes = (uint64_t)count * sizeof(oit_triangle);
    glNamedBufferStorage(m->buffer, (GLsizeiptr)(bytes ? bytes : 16), count ? tris : NULL, 0);
    oit_status s = oit_gl_check("GPU mesh: glNamedBufferStorage", err);
    if (s == OIT_OK && m->window == 0)
        s = oit_error_set(err, OIT_ERR_GL, "GPU mesh: GL_MAX_SHADER_STORAGE_BLOCK_SIZE is "
                          "smaller than one triangle");
    if (s != OIT_OK) {
        if (s == OIT_ERR_NOMEM)
            oit_error_set(err, s, "GPU mesh: cannot allocate %llu bytes for %zu triangles",
                          (unsigned long long)bytes, count);
        oit_gpu_mesh_destroy(m);
        return s;
    }
    *out = m;
    return OIT_OK;
}

oit_status oit_gpu_mesh_create_view(unsigned buffer, oit_gpu_mesh **out, oit_error *err)
{
    oit_gpu_mesh *m = calloc(1, sizeof *m);
    *out = NULL;
    if (!m)
        return oit_error_set(err, OIT_ERR_NOMEM, "GPU mesh view: out of memory");
    m->buffer = buffer;
    m->window = oit_gpu_triangle_window();
    m->align = ssbo_align();
    glCreateVertexArrays(1, &m->vao);
    oit_status s = oit_gl_check("GPU mesh view", err);
    if (s != OIT_OK) {
        oit_gpu_mesh_destroy(m);
        return s;
    }
    *out = m;
    return OIT_OK;
}

void oit_gpu_mesh_set_range(oit_gpu_mesh *m, uint64_t offset, size_t count, uint32_t first_prim)
{
    m->offset = offset;
    m->count = count;
    m->first_prim = first_prim;
    m->sourced = 0;
}

void oit_gpu_mesh_set_range_sourced(oit_gpu_mesh *m, uint64_t offset, size_t count)
{
    m->offset = offset;
    m->count = count;
    m->first_prim = 0;
    m->sourced = 1;
    m->prims_offset = offset + (uint64_t)count * sizeof(oit_triangle);
}

int oit_gpu_mesh_sourced(const oit_gpu_mesh *m, uint64_t *prims_offset)
{
    if (m->sourced)
        *prims_offset = m->prims_offset;
    return m->sourced;
}

void oit_gpu_mesh_set_buffer(oit_gpu_mesh *m, unsigned buffer)
{
    if (!m->owns_buffer)
        m->buffer = buffer;
}

void oit_gpu_mesh_destroy(oit_gpu_mesh *m)
{
    if (!m)
        return;
    if (m->owns_buffer)
        glDeleteBuffers(1, &m->buffer);
    glDeleteVertexArrays(1, &m->vao);
    free(m);
}

size_t oit_gpu_mesh_triangles(const oit_gpu_mesh *m)
{
    return m->count;
}

uint64_t oit_gpu_mesh_bytes(const oit_gpu_mesh *m)
{
    return (uint64_t)m->count * sizeof(oit_triangle);
}

uint32_t oit_gpu_mesh_first_prim(const oit_gpu_mesh *m)
{
    return m->first_prim;
}

unsigned oit_gpu_mesh_buffer(const oit_gpu_mesh *m)
{
    return m->buffer;
}

uint64_t oit_gpu_mesh_offset(const oit_gpu_mesh *m)
{
    return m->offset;
}

void oit_gpu_mesh_draw(const oit_gpu_mesh *m, unsigned program)
{
    (void)program;
    /* The mesh's vertex array enables no attribute, so the shader's
     * per-draw input reads the current value set here. */
    glBindVertexArray(m->vao);
    for (size_t start = 0; start < m->count; start += m->window) {
        size_t n = m->count - start < m->window ? m->count - start : m->window;
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, m->buffer,
                          (GLintptr)(m->offset + start * sizeof(oit_triangle)),
                          (GLsizeiptr)(n * sizeof(oit_triangle)));
        if (m->sourced) {
            /* The window's prims, bound from the alignment below them. */
            uint64_t at = m->prims_offset + start * 4, base = at - at % m->align;
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, m->buffer,
                              (GLintptr)base, (GLsizeiptr)(at + n * 4 - base));
            glVertexAttribI2ui(OIT_IN_DRAW, 0, 0x80000000u | (uint32_t)((at - base) / 4));
        } else
            glVertexAttribI2ui(OIT_IN_DRAW, 0, m->first_prim + (uint32_t)start);
        glDrawArrays(GL_TRIANGLES, 0, (GLsizei)(n * 3));
    }
}

void oit_gpu_mesh_dispatch(const oit_gpu_mesh *m, unsigned program, unsigned local)
{
    GLint first_loc = glGetUniformLocation(program, "u_window_first");
    GLint count_loc = glGetUniformLocation(program, "u_window_count");
    glUseProgram(program);
    for (size_t start = 0; start < m->count; start += m->window) {
        size_t n = m->count - start < m->window ? m->count - start : m->window;
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, m->buffer,
                          (GLintptr)(m->offset + start * sizeof(oit_triangle)),
                          (GLsizeiptr)(n * sizeof(oit_triangle)));
        glProgramUniform1ui(program, first_loc, (GLuint)start);
        glProgramUniform1ui(program, count_loc, (GLuint)n);
        GLuint groups = oit_gl_groups(n, local);
        glDispatchCompute(groups < 65535 ? groups : 65535, oit_gl_groups(groups, 65535), 1);
    }
}
