/* GL helpers (gl_util.h). */
#include "view/render/gl/gl_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "unknown GL error";
    }
}

oit_status oit_gl_check(const char *call, oit_error *err)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR)
        return OIT_OK;
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; i++)
        ;
    oit_status s = e == GL_OUT_OF_MEMORY ? OIT_ERR_NOMEM : OIT_ERR_GL;
    return oit_error_set(err, s, "%s: %s (0x%04x)", call, gl_error_name(e), e);
}

/* Joins the log's lines so the error stays one line. */
static void one_line(char *log)
{
    for (char *p = log; *p; p++)
        if (*p == '\n' || *p == '\r')
            *p = ' ';
}

static oit_status compile(const char *what, GLenum stage, const char *const *src,
                          GLuint *out, oit_error *err)
{
    GLsizei n = 0;
    while (src[n])
        n++;
    GLuint sh = glCreateShader(stage);
    glShaderSource(sh, n, (const GLchar *const *)src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[440] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        glDeleteShader(sh);
        one_line(log);
        const char *kind = stage == GL_VERTEX_SHADER ? "vertex"
                         : stage == GL_FRAGMENT_SHADER ? "fragment" : "compute";
        return oit_error_set(err, OIT_ERR_GL, "%s: %s shader does not compile: %s",
                             what, kind, log);
    }
    *out = sh;
    return OIT_OK;
}

static oit_status link(const char *what, GLuint prog, oit_error *err)
{
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (ok)
        return OIT_OK;
    char log[440] = "";
    glGetProgramInfoLog(prog, sizeof log, NULL, log);
    one_line(log);
    return oit_error_set(err, OIT_ERR_GL, "%s: program does not link: %s", what, log);
}

oit_status oit_gl_program_build(const char *what, const char *const *vs,
                               const char *const *fs, const char *const *cs, int retrievable,
                               GLuint *out, oit_error *err)
{
    GLuint sh[2] = {0, 0};
    oit_status s = cs ? compile(what, GL_COMPUTE_SHADER, cs, &sh[0], err)
                      : compile(what, GL_VERTEX_SHADER, vs, &sh[0], err);
    if (s == OIT_OK && !cs && fs)
        s = compile(what, GL_FRAGMENT_SHADER, fs, &sh[1], err);
    GLuint prog = 0;
    if (s == OIT_OK) {
        prog = glCreateProgram();
        if (retrievable)
            glProgramParameteri(prog, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
        for (int i = 0; i < 2; i++)
            if (sh[i])
                glAttachShader(prog, sh[i]);
        s = link(what, prog, err);
    }
    glDeleteShader(sh[0]);
    glDeleteShader(sh[1]);
    if (s != OIT_OK) {
        glDeleteProgram(prog);
        return s;
    }
    *out = prog;
    return OIT_OK;
}

oit_status oit_gl_program_graphics(const char *what, const char *const *vs,
                                   const char *const *fs, GLuint *out, oit_error *err)
{
    return oit_gl_program_build(what, vs, fs, NULL, 0, out, err);
}

oit_status oit_gl_program_compute(const char *what, const char *const *cs, GLuint *out,
                                  oit_error *err)
{
    return oit_gl_program_build(what, NULL, NULL, cs, 0, out, err);
}

oit_status oit_gl_framebuffer_create(GLuint *fbo, GLuint *samples_query, const char *what,
                                     oit_error *err)
{
    glCreateFramebuffers(1, fbo);
    if (samples_query)
        glCreateQueries(GL_SAMPLES_PASSED, 1, samples_query);
    return oit_gl_check(what, err);
}

void oit_gl_buffer_release(GLuint *buf, uint64_t *cap)
{
    glDeleteBuffers(1, buf);
    *buf = 0;
    *cap = 0;
}

static int poison_wanted(void)
{
    const char *env = getenv("OIT_GL_POISON");
    return env && strcmp(env, "1") == 0;
}

#define POISON_WORD 0xffc00001u

void oit_gl_poison_buffer(GLuint buf)
{
    static const GLuint word = POISON_WORD;
    if (!buf || !poison_wanted())
        return;
    /* Whole words only: a clear in R32UI needs a size that is a multiple
     * of 4, which a buffer grown by half need not have. */
    GLint64 size = 0;
    glGetNamedBufferParameteri64v(buf, GL_BUFFER_SIZE, &size);
    if (size >= 4)
        glClearNamedBufferSubData(buf, GL_R32UI, 0, (GLsizeiptr)(size - size % 4), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &word);
}

void oit_gl_poison_texture(GLuint tex, GLenum format)
{
    static const GLuint words[4] = {POISON_WORD, POISON_WORD, POISON_WORD, POISON_WORD};
    if (!tex || !poison_wanted())
        return;
    switch (format) {
    case GL_RGBA32UI: case GL_RG32UI: case GL_R32UI:
        glClearTexImage(tex, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, words);
        break;
    case GL_DEPTH_COMPONENT32F: case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT16:
        glClearTexImage(tex, 0, GL_DEPTH_COMPONENT, GL_FLOAT, words);
        break;
    case GL_DEPTH24_STENCIL8: case GL_DEPTH32F_STENCIL8:
        break; /* cleared before every use by the depth and stencil tests' owners */
    default:
        glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, words);
    }
}

oit_status oit_gl_buffer_reserve(GLuint *buf, uint64_t *cap, uint64_t bytes,
                                 const char *what, oit_error *err)
{
    if (*buf && *cap >= bytes)
        return OIT_OK;
    /* Grown by half, kept a multiple of 16 bytes: a whole-buffer clear
     * (glClearNamedBufferData, R32UI or RGBA32UI) needs its size a
     * multiple of the format's, and 1.5x of 4 * odd is not. */
    uint64_t grown = (*cap + *cap / 2 + 15) / 16 * 16;
    uint64_t want = bytes > grown ? bytes : grown;
    if (want == 0)
        want = 16;
    if (!*buf)
        glCreateBuffers(1, buf);
    /* The geometric margin is a convenience: without room for it, the
     * exact size still serves this frame. So an out-of-memory here is
     * expected: a debug group that mutes error messages keeps it from
     * failing a debug context's frame (gl_context.h), and restores the
     * caller's message settings when popped. */
    int probe = want > bytes;
    if (probe) {
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "oit: allocation probe");
        glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, NULL, GL_FALSE);
    }
    glNamedBufferData(*buf, (GLsizeiptr)want, NULL, GL_DYNAMIC_COPY);
    GLenum e = glGetError();
    if (probe)
        glPopDebugGroup();
    if (e != GL_NO_ERROR && want > bytes) {
        want = bytes;
        glNamedBufferData(*buf, (GLsizeiptr)want, NULL, GL_DYNAMIC_COPY);
        e = glGetError();
    }
    if (e != GL_NO_ERROR) {
        *cap = 0;
        return oit_error_set(err, OIT_ERR_NOMEM,
                             "%s: cannot allocate a GPU buffer of %llu bytes", what,
                             (unsigned long long)want);
    }
    *cap = want;
    oit_gl_poison_buffer(*buf);
    return OIT_OK;
}

oit_status oit_gl_read_rows(GLuint obj, int is_texture, int w, int h, size_t item, void *dst,
                            const char *what, oit_error *err)
{
    size_t row = (size_t)w * item, bytes = row * (size_t)h;
    char *tmp = malloc(bytes);
    if (!tmp)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate %zu bytes for the "
                             "readback", what, bytes);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    if (is_texture)
        glGetTextureImage(obj, 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, tmp);
    else
        glGetNamedBufferSubData(obj, 0, (GLsizeiptr)bytes, tmp);
    char call[96];
    snprintf(call, sizeof call, "%s: %s", what,
             is_texture ? "glGetTextureImage" : "glGetNamedBufferSubData");
    oit_status s = oit_gl_check(call, err);
    for (int y = 0; s == OIT_OK && y < h; y++)
        memcpy((char *)dst + (size_t)y * row, tmp + (size_t)(h - 1 - y) * row, row);
    free(tmp);
    return s;
}

uint64_t oit_gl_ssbo_max_bytes(void)
{
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    return max_block > 0 ? (uint64_t)max_block : 0;
}

uint64_t oit_gl_ssbo_align(void)
{
    GLint align = 16;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    return align > 0 ? (uint64_t)align : 16;
}

oit_status oit_gl_check_ssbo_size(uint64_t bytes, const char *what, oit_error *err)
{
    uint64_t max_block = oit_gl_ssbo_max_bytes();
    if (bytes > max_block)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: needs %llu bytes in one storage buffer, "
                             "more than this driver binds (%llu)", what,
                             (unsigned long long)bytes, (unsigned long long)max_block);
    return OIT_OK;
}

GLuint oit_gl_groups(uint64_t n, GLuint local)
{
    return (GLuint)((n + local - 1) / local);
}

GLuint oit_gl_max_groups_x(void)
{
    GLint n = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &n);
    return n > 0 ? (GLuint)n : 65535u;
}

void oit_gl_dispatch_x(GLuint prog, GLint group0_loc, uint64_t groups, GLuint max_x)
{
    max_x = max_x ? max_x : 1u;
    for (uint64_t first = 0; first < groups; first += max_x) {
        uint64_t left = groups - first;
        glProgramUniform1ui(prog, group0_loc, (GLuint)first);
        glDispatchCompute(left < max_x ? (GLuint)left : max_x, 1, 1);
    }
}

