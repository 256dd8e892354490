/* Saturated screen tiles (saturation.h). */
#include "view/render/capture/saturation.h"

#include "view/render/capture/capture_glsl.h"
#include "view/render/gl/frag_glsl.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

struct oit_saturation {
    GLuint prog;
    GLuint tiles;         /* GPU: float bits of each tile's largest T */
    uint64_t tiles_cap;
    GLuint readback;      /* persistently mapped copy of tiles */
    uint64_t readback_cap;
    const uint32_t *mapped;
    GLsync fence;         /* the read-back in flight, 0 when none */
    uint32_t *cpu;        /* the newest read-back that landed */
    size_t cpu_cap;
    int w, h, tx, ty;
};
_Static_assert(offsetof(struct oit_saturation, prog) == 0,
               "oit_glsl_module_create builds the first member");

extern const char oit_saturation_cs[]; /* glsl/saturation.glsl */
static const oit_glsl_program program = {
    "saturation tiles",
    .cs = {"#define OIT_SATURATION_TILE " OIT_GLSL_STR(OIT_SATURATION_TILE) "\n", oit_capture_mode,
           oit_glsl_state_io, oit_saturation_cs}};

void oit_saturation_glsl_variants(oit_glsl_visit *visit, void *user)
{
    visit(user, &program);
}

oit_status oit_saturation_create(oit_saturation **out, oit_error *err)
{
    oit_status st;
    *out = oit_glsl_module_create(sizeof **out, &program, "saturation tiles", &st, err);
    return st;
}

static void drop_readback(oit_saturation *s)
{
    if (s->fence)
        glDeleteSync(s->fence);
    s->fence = 0;
    if (s->readback) {
        glUnmapNamedBuffer(s->readback);
        glDeleteBuffers(1, &s->readback);
    }
    s->readback = 0;
    s->readback_cap = 0;
    s->mapped = NULL;
}

void oit_saturation_destroy(oit_saturation *s)
{
    if (!s)
        return;
    drop_readback(s);
    glDeleteBuffers(1, &s->tiles);
    glDeleteProgram(s->prog);
    free(s->cpu);
    free(s);
}

/* Immutable storage, mapped once for the buffer's life. */
static oit_status make_readback(oit_saturation *s, uint64_t bytes, oit_error *err)
{
    if (bytes <= s->readback_cap)
        return OIT_OK;
    drop_readback(s);
    const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glCreateBuffers(1, &s->readback);
    glNamedBufferStorage(s->readback, (GLsizeiptr)bytes, NULL, flags);
    oit_gl_poison_buffer(s->readback);
    s->mapped = glMapNamedBufferRange(s->readback, 0, (GLsizeiptr)bytes, flags);
    if (!s->mapped) {
        oit_gl_check("saturation tiles: glMapNamedBufferRange", err);
        return oit_error_set(err, OIT_ERR_GL, "saturation tiles: cannot map %llu bytes",
                             (unsigned long long)bytes);
    }
    s->readback_cap = bytes;
    return OIT_OK;
}

oit_status oit_saturation_begin(oit_saturation *s, int w, int h, int translucent,
                                 oit_error *err)
{
    glProgramUniform1i(s->prog, glGetUniformLocation(s->prog, "u_mode"), translucent ? 1 : 0);
    int T = OIT_SATURATION_TILE;
    s->w = w, s->h = h, s->tx = (w + T - 1) / T, s->ty = (h + T - 1) / T;
    size_t n = (size_t)s->tx * s->ty;
    uint64_t bytes = n * sizeof(uint32_t);
    if (n > s->cpu_cap) {
        uint32_t *c = realloc(s->cpu, bytes);
        if (!c)
            return oit_error_set(err, OIT_ERR_NOMEM, "saturation tiles: out of memory");
        s->cpu = c, s->cpu_cap = n;
    }
    if (s->fence)
        glDeleteSync(s->fence); /* a read-back of the last frame: not ours */
    s->fence = 0;
    oit_status st = oit_gl_buffer_reserve(&s->tiles, &s->tiles_cap, bytes, "saturation tiles", err);
    if (st == OIT_OK)
        st = make_readback(s, bytes, err);
    if (st != OIT_OK)
        return st;
    const float one = 1.0f;
    uint32_t one_bits;
    memcpy(&one_bits, &one, sizeof one_bits);
    for (size_t i = 0; i < n; i++)
        s->cpu[i] = one_bits;
    glClearNamedBufferData(s->tiles, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &one_bits);
    return oit_gl_check("saturation tiles: frame start", err);
}

/* Takes the read-back in flight when it has landed; never waits. */
static void poll(oit_saturation *s)
{
    if (!s->fence)
        return;
    GLenum r = glClientWaitSync(s->fence, 0, 0);
    if (r != GL_ALREADY_SIGNALED && r != GL_CONDITION_SATISFIED)
        return;
    memcpy(s->cpu, s->mapped, (size_t)s->tx * s->ty * sizeof *s->cpu);
    glDeleteSync(s->fence);
    s->fence = 0;
}

oit_status oit_saturation_wait(oit_saturation *s, oit_host_waits *waits, oit_error *err)
{
    poll(s);
    if (!s->fence)
        return OIT_OK;
    oit_host_wait_note(waits);
    GLenum r = glClientWaitSync(s->fence, GL_SYNC_FLUSH_COMMANDS_BIT, 10000000000ull);
    if (r == GL_WAIT_FAILED || r == GL_TIMEOUT_EXPIRED)
        return oit_error_set(err, OIT_ERR_GL, "saturation tiles: the read-back %s",
                             r == GL_WAIT_FAILED ? "wait failed" : "took over 10 s");
    poll(s);
    return OIT_OK;
}

/* rect (row 0 at the top) to the tiles it touches, GL rows. */
static int tile_range(const oit_saturation *s, const int rect[4], int t[4])
{
    int T = OIT_SATURATION_TILE;
    int x0 = rect ? rect[0] : 0, x1 = rect ? rect[2] : s->w;
    int gy0 = rect ? s->h - rect[3] : 0, gy1 = rect ? s->h - rect[1] : s->h;
    x0 = x0 < 0 ? 0 : x0, gy0 = gy0 < 0 ? 0 : gy0;
    x1 = x1 > s->w ? s->w : x1, gy1 = gy1 > s->h ? s->h : gy1;
    if (x1 <= x0 || gy1 <= gy0)
        return 0;
    t[0] = x0 / T, t[1] = gy0 / T, t[2] = (x1 - 1) / T, t[3] = (gy1 - 1) / T;
    return 1;
}

oit_status oit_saturation_update(oit_saturation *s, unsigned state, const int rect[4],
                                 oit_error *err)
{
    int t[4];
    if (!tile_range(s, rect, t))
        return OIT_OK;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(s->prog);
    glProgramUniform2i(s->prog, OIT_LOC_TILES_SIZE, s->w, s->h);
    glProgramUniform3i(s->prog, OIT_LOC_TILE0, t[0], t[1], s->tx);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_SUMS, s->tiles);
    glDispatchCompute((GLuint)(t[2] - t[0] + 1), (GLuint)(t[3] - t[1] + 1), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    poll(s);
    if (!s->fence) {
        glCopyNamedBufferSubData(s->tiles, s->readback, 0, 0,
                                 (GLsizeiptr)((size_t)s->tx * s->ty * sizeof(uint32_t)));
        s->fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        glFlush(); /* so the fence can signal without anyone waiting on it */
    }
    return oit_gl_check("saturation tiles: update", err);
}

int oit_saturation_covered(oit_saturation *s, const int rect[4], float epsilon)
{
    int t[4];
    if (!(epsilon > 0.0f) || !tile_range(s, rect, t))
        return 0;
    poll(s);
    uint32_t limit;
    memcpy(&limit, &epsilon, sizeof limit);
    for (int y = t[1]; y <= t[3]; y++)
        for (int x = t[0]; x <= t[2]; x++)
            if (s->cpu[(size_t)y * s->tx + x] >= limit)
                return 0;
    return 1;
}

uint64_t oit_saturation_gpu_bytes(const oit_saturation *s)
{
    return s->tiles_cap + s->readback_cap;
}
