/* GPU exclusive scan (scan_glsl.h). */
#include "view/render/gl/scan_glsl.h"

#include "view/render/gl/frag_glsl.h"

#include <string.h>

#define BLOCK 1024u

extern const char oit_glsl_scan_block[], oit_glsl_scan_add[]; /* glsl/scan_*.glsl */
static const oit_glsl_program programs[2] = {
    {"prefix sum (block)", .cs = {oit_glsl_scan_block}},
    {"prefix sum (add)", .cs = {oit_glsl_scan_add}},
};

void oit_scan_glsl_variants(oit_glsl_visit *visit, void *user)
{
    for (int i = 0; i < 2; i++)
        visit(user, &programs[i]);
}

oit_status oit_scan_init(oit_scan *s, oit_program_cache *pc, oit_error *err)
{
    memset(s, 0, sizeof *s);
    GLuint progs[2] = {0, 0};
    oit_status st = oit_glsl_programs_build(pc, programs, 2, progs, err);
    s->block = progs[0];
    s->add = progs[1];
    if (st == OIT_OK) {
        s->max_groups = oit_gl_max_groups_x();
        glCreateBuffers(1, &s->totals);
        glNamedBufferStorage(s->totals, 16, NULL, GL_DYNAMIC_STORAGE_BIT);
        oit_gl_poison_buffer(s->totals);
    }
    return st;
}

void oit_scan_release(oit_scan *s)
{
    glDeleteProgram(s->block);
    glDeleteProgram(s->add);
    glDeleteBuffers(OIT_SCAN_LEVELS, s->sums);
    glDeleteBuffers(1, &s->totals);
    memset(s, 0, sizeof *s);
}

uint64_t oit_scan_bytes(const oit_scan *s)
{
    uint64_t b = 16;
    for (int i = 0; i < OIT_SCAN_LEVELS; i++)
        b += s->sums_cap[i];
    return b;
}

static void dispatch_block(oit_scan *s, GLuint data, GLuint sums, uint64_t n, int first)
{
    glUseProgram(s->block);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, data);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, sums);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_TOTALS, s->totals);
    glProgramUniform1ui(s->block, OIT_LOC_COUNT, (GLuint)n);
    glProgramUniform1i(s->block, OIT_LOC_FIRST_LEVEL, first);
    glProgramUniform1ui(s->block, glGetUniformLocation(s->block, "u_over"), s->over);
    oit_gl_dispatch_x(s->block, glGetUniformLocation(s->block, "u_group0"),
                      oit_gl_groups(n, BLOCK), s->max_groups);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

static void dispatch_add(oit_scan *s, GLuint data, GLuint sums, uint64_t n)
{
    glUseProgram(s->add);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, data);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, sums);
    glProgramUniform1ui(s->add, OIT_LOC_COUNT, (GLuint)n);
    oit_gl_dispatch_x(s->add, glGetUniformLocation(s->add, "u_group0"), oit_gl_groups(n, 256),
                      s->max_groups);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

oit_status oit_scan_run(oit_scan *s, GLuint buf, uint64_t n, oit_scan_result *res,
                        oit_host_waits *waits, oit_error *err)
{
    uint64_t size[OIT_SCAN_LEVELS + 1];
    size[0] = n;
    int levels = 0;
    /* Level i scans size[i] elements into size[i+1] block sums; recursion
     * stops when one block covers everything. */
    do {
        if (levels == OIT_SCAN_LEVELS)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "prefix sum: %llu elements exceed "
                                 "the scan's %d levels", (unsigned long long)n, OIT_SCAN_LEVELS);
        size[levels + 1] = (size[levels] + BLOCK - 1) / BLOCK;
        oit_status st = oit_gl_buffer_reserve(&s->sums[levels], &s->sums_cap[levels],
                                              size[levels + 1] * 4, "prefix sum", err);
        if (st != OIT_OK)
            return st;
        levels++;
    } while (size[levels] > 1);
    static const GLuint zero[4];
    glNamedBufferSubData(s->totals, 0, sizeof zero, zero);
    for (int i = 0; i < levels; i++)
        dispatch_block(s, i == 0 ? buf : s->sums[i - 1], s->sums[i], size[i], i == 0);
    for (int i = levels - 2; i >= 0; i--)
        dispatch_add(s, i == 0 ? buf : s->sums[i - 1], s->sums[i], size[i]);
    if (!res)
        return oit_gl_check("prefix sum", err);
    GLuint t[4];
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    oit_host_read(waits, s->totals, 0, sizeof t, t);
    res->total = (uint64_t)t[1] << 32 | t[0];
    res->max = t[2];
    res->over = t[3];
    return oit_gl_check("prefix sum", err);
}
