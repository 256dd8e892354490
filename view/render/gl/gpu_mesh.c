/* Triangles on the GPU (gpu_mesh.h). The soup is uploaded as is (16-byte
 * vertices) and read by the vertex-pulling shader of frag_glsl.h, whose one
 * vertex input is the per-draw record (gpu_draw_record.h). Each mesh owns a
 * vertex array that reads it from the mesh's record buffer: an owned mesh
 * holds one record per window, written once; a view one, written before
 * each of its windows is drawn, since its range changes between draws
 * without GL calls (the streamer re-points views per pack and never draws
 * them one by one). Multi-draws are in gpu_mesh_many.c. */
#include "view/render/gl/gpu_mesh.h"

#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_draw_record.h"

#include <stdlib.h>

struct oit_gpu_mesh {
    GLuint buffer;
    GLuint vao;
    GLuint records; /* OIT_IN_DRAW's records: a window's each, or a view's one */
    size_t count;
    uint32_t first_prim;
    size_t window; /* triangles per draw: SSBO size limit and alignment */
    uint64_t offset; /* of the first triangle in buffer */
    int owns_buffer;
    int sourced;          /* prims are per-triangle u32 at prims_offset */
    uint64_t prims_offset;
    uint64_t align;       /* GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT */
};

size_t oit_gpu_triangle_step(uint64_t align)
{
    size_t step = 1;
    while ((step * sizeof(oit_triangle)) % align != 0)
        step++;
    return step;
}

/* Triangles per draw window: the SSBO binding limit, rounded down so that
 * window offsets keep the SSBO offset alignment. The limit is a 64-bit
 * figure (glGetInteger64v): a driver may allow more than 2^31 bytes, which
 * glGetIntegerv would clamp or, on some drivers, truncate. */
size_t oit_gpu_triangle_window(void)
{
    size_t step = oit_gpu_triangle_step(oit_gl_ssbo_align());
    uint64_t w = oit_gl_ssbo_max_bytes() / sizeof(oit_triangle);
    /* A window's vertices count in a GLsizei, and in the shader's int
     * gl_VertexID and verts.length(). */
    if (w > (uint64_t)0x7fffffff / 3)
        w = (uint64_t)0x7fffffff / 3;
    return (size_t)w / step * step;
}

static size_t windows_of(size_t count, size_t window)
{
    return count ? (count + window - 1) / window : 1;
}

/* The record of the window that starts at triangle `start`, with the byte
 * offset of the window's prims binding (sourced meshes) in *prims_base. */
static oit_draw_rec window_record(const oit_gpu_mesh *m, size_t start, uint64_t *prims_base)
{
    if (!m->sourced)
        return (oit_draw_rec){0, m->first_prim + (uint32_t)start};
    uint64_t at = m->prims_offset + start * 4;
    *prims_base = at - at % m->align;
    return (oit_draw_rec){0, 0x80000000u | (uint32_t)((at - *prims_base) / 4)};
}

/* The vertex array and record buffer: an owned mesh's records, one a
 * window, go in once (immutable); a view's one record is rewritten. */
static oit_status create_records(oit_gpu_mesh *m, const char *what, oit_error *err)
{
    size_t n = m->owns_buffer ? windows_of(m->count, m->window) : 1;
    oit_draw_rec *recs = calloc(n, sizeof *recs);
    if (!recs)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold %zu draw records", what, n);
    uint64_t unused = 0;
    for (size_t w = 0; m->owns_buffer && w < n; w++)
        recs[w] = window_record(m, w * m->window, &unused);
    glCreateVertexArrays(1, &m->vao);
    glCreateBuffers(1, &m->records);
    glNamedBufferStorage(m->records, (GLsizeiptr)(n * sizeof *recs), recs,
                         m->owns_buffer ? 0 : GL_DYNAMIC_STORAGE_BIT);
    free(recs);
    oit_draw_records_attach(m->vao, m->records);
    return oit_gl_check(what, err);
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
    m->align = oit_gl_ssbo_align();
    m->owns_buffer = 1;
    glCreateBuffers(1, &m->buffer);
    uint64_t bytes = (uint64_t)count * sizeof(oit_triangle);
    glNamedBufferStorage(m->buffer, (GLsizeiptr)(bytes ? bytes : 16), count ? tris : NULL, 0);
    oit_status s = oit_gl_check("GPU mesh: glNamedBufferStorage", err);
    if (s == OIT_ERR_NOMEM)
        oit_error_set(err, s, "GPU mesh: cannot allocate %llu bytes for %zu triangles",
                      (unsigned long long)bytes, count);
    if (s == OIT_OK && m->window == 0)
        s = oit_error_set(err, OIT_ERR_GL, "GPU mesh: GL_MAX_SHADER_STORAGE_BLOCK_SIZE is "
                          "smaller than one triangle");
    if (s == OIT_OK)
        s = create_records(m, "GPU mesh: draw records", err);
    if (s != OIT_OK) {
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
    m->align = oit_gl_ssbo_align();
    oit_status s = m->window ? create_records(m, "GPU mesh view: draw record", err)
                             : oit_error_set(err, OIT_ERR_GL, "GPU mesh view: "
                                             "GL_MAX_SHADER_STORAGE_BLOCK_SIZE is smaller than "
                                             "one triangle");
    if (s != OIT_OK) {
        oit_gpu_mesh_destroy(m);
        return s;
    }
    *out = m;
    return OIT_OK;
}

/* An owned mesh keeps its range: its records were written for it. */
void oit_gpu_mesh_set_range(oit_gpu_mesh *m, uint64_t offset, size_t count, uint32_t first_prim)
{
    if (m->owns_buffer)
        return;
    m->offset = offset;
    m->count = count;
    m->first_prim = first_prim;
    m->sourced = 0;
}

void oit_gpu_mesh_set_range_sourced(oit_gpu_mesh *m, uint64_t offset, size_t count)
{
    if (m->owns_buffer)
        return;
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
    glDeleteBuffers(1, &m->records);
    free(m);
}

size_t oit_gpu_mesh_triangles(const oit_gpu_mesh *m)
{
    return m->count;
}

uint64_t oit_gpu_mesh_bytes(const oit_gpu_mesh *m)
{
    if (!m)
        return 0;
    uint64_t tris = (uint64_t)m->count * sizeof(oit_triangle);
    uint64_t buffer = m->owns_buffer ? (tris ? tris : 16) : 0;
    size_t recs = m->owns_buffer ? windows_of(m->count, m->window) : 1;
    return buffer + (uint64_t)recs * sizeof(oit_draw_rec);
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

void oit_gpu_mesh_set_align(oit_gpu_mesh *m, uint64_t bytes)
{
    uint64_t driver = oit_gl_ssbo_align();
    m->align = bytes && bytes % driver == 0 ? bytes : driver;
}

/* Every storage binding the vertex stage declares is backed on every draw,
 * OIT_BIND_PRIMS too where it reads none (its window's own triangles then):
 * a block left unbound, or bound to a buffer since deleted or too short,
 * is undefined behaviour a compiler may turn into a fault or a dropped
 * draw even on a path that never reads it. */
void oit_gpu_mesh_draw(const oit_gpu_mesh *m, unsigned program)
{
    (void)program;
    glBindVertexArray(m->vao);
    for (size_t start = 0, w = 0; start < m->count; start += m->window, w++) {
        size_t n = m->count - start < m->window ? m->count - start : m->window;
        GLintptr at = (GLintptr)(m->offset + start * sizeof(oit_triangle));
        GLsizeiptr bytes = (GLsizeiptr)(n * sizeof(oit_triangle));
        uint64_t base = 0;
        oit_draw_rec rec = window_record(m, start, &base);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_VERTS, m->buffer, at, bytes);
        uint64_t prims_end = m->prims_offset + (start + n) * 4;
        if (m->sourced)
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, m->buffer,
                              (GLintptr)base, (GLsizeiptr)(prims_end - base));
        else
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, OIT_BIND_PRIMS, m->buffer, at, bytes);
        if (!m->owns_buffer)
            glNamedBufferSubData(m->records, 0, sizeof rec, &rec);
        glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, (GLsizei)(n * 3), 1,
                                          m->owns_buffer ? (GLuint)w : 0);
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
