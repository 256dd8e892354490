/* Fixed per-pixel arrays (b3d.h). Counts and output are buffers in GL row
 * order; slot s of pixel (x, y) is texel (x, y, s) of the layer array. */
#include "view/render/baselines/b3d.h"
#include "view/render/baselines/methods.h"

#include "view/render/baselines/baseline_common.h"
#include "view/render/baselines/baseline_glsl.h"
#include "view/render/image/image.h"

#include <stdlib.h>

enum { BUF_COUNTS, BUF_STATS, BUF_OUT, BUF_N };
enum { PROG_COUNT, PROG_STORE, PROG_MAX, PROG_RESOLVE, PROG_N };

struct oit_b3d {
    GLuint prog[PROG_N], fbo;
    GLuint slots;     /* RGBA32UI 2D array, w x h x layers */
    int w, h, layers; /* its size */
    oit_gpu_buffers b;
};

static const char *const buffer_names[BUF_N] = {"counts", "counters", "output"};

/* glsl/b3d_*.glsl: the count and store fragment stages, the deepest
 * pixel's compute pass, and the walk of the slots for the sorted resolve. */
extern const char oit_b3d_count_fs[], oit_b3d_store_fs[], oit_b3d_max_cs[], oit_b3d_walk[];

static const oit_glsl_program programs[PROG_N] = {
    [PROG_COUNT] = {"B3D count pass", .fs = {oit_b3d_count_fs}},
    [PROG_STORE] = {"B3D store pass", .fs = {oit_b3d_store_fs}},
    [PROG_MAX] = {"B3D layer maximum", .cs = {oit_b3d_max_cs}},
    [PROG_RESOLVE] = {"B3D resolve",
                      .cs = {oit_glsl_composite, oit_glsl_sorted_resolve, oit_b3d_walk}},
};

void oit_b3d_glsl_variants(oit_glsl_visit *visit, void *user)
{
    oit_baseline_visit_table(programs, PROG_N, visit, user);
}

static oit_status oit_b3d_init(oit_b3d *b, oit_error *err)
{
    b->b.method = "B3D";
    b->b.names = buffer_names;
    oit_status s = oit_glsl_programs_build(NULL, programs, PROG_N, b->prog, err);
    if (s == OIT_OK)
        s = oit_gl_framebuffer_create(&b->fbo, NULL, "B3D: glCreateFramebuffers", err);
    return s;
}

static void oit_b3d_release(oit_b3d *b)
{
    oit_glsl_programs_delete(b->prog, PROG_N);
    glDeleteFramebuffers(1, &b->fbo);
    glDeleteTextures(1, &b->slots);
    oit_gpu_buffers_release(&b->b);
}

/* Slots for 'layers' per pixel, grown only. */
static oit_status reserve_slots(oit_b3d *b, int w, int h, uint32_t layers, oit_error *err)
{
    if (layers < 1)
        layers = 1;
    if (b->slots && b->w == w && b->h == h && (uint32_t)b->layers >= layers)
        return OIT_OK;
    GLint max_layers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    uint64_t positions = (uint64_t)w * h * layers;
    if (layers > (uint32_t)max_layers || positions >= 0xffffffffull)
        return oit_error_set(err, OIT_ERR_NOMEM, "B3D: %u layers of %dx%d slots exceed this "
                             "driver's %d array layers or 2^32 slots", layers, w, h, max_layers);
    glDeleteTextures(1, &b->slots);
    b->layers = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &b->slots);
    glTextureStorage3D(b->slots, 1, GL_RGBA32UI, w, h, (GLsizei)layers);
    oit_gl_poison_texture(b->slots, GL_RGBA32UI);
    if (glGetError() != GL_NO_ERROR)
        return oit_error_set(err, OIT_ERR_NOMEM, "B3D: cannot allocate %u layers of %dx%d "
                             "slots (%llu bytes)", layers, w, h,
                             (unsigned long long)positions * 16);
    b->w = w;
    b->h = h;
    b->layers = (int)layers;
    b->b.texture_bytes = positions * 16;
    oit_gpu_buffers_note(&b->b);
    return OIT_OK;
}

static oit_status prepare(oit_b3d *b, const oit_view *v, oit_error *err)
{
    uint64_t pixels = (uint64_t)v->width * v->height;
    oit_status s = oit_gl_check_ssbo_size(pixels * 16, "B3D: the frame's output", err);
    if (s == OIT_OK)
        s = oit_gpu_buffers_reserve_all(&b->b, BUF_N,
                                        (const uint64_t[BUF_N]){pixels * 4, 16, pixels * 16},
                                        err);
    if (s != OIT_OK)
        return s;
    oit_glsl_raster_begin_sized(b->fbo, v->width, v->height);
    oit_glsl_set_view_all(b->prog, PROG_N, v);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_COUNTS, b->b.buf[BUF_COUNTS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, b->b.buf[BUF_STATS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_OUT, b->b.buf[BUF_OUT]);
    return oit_gl_check("B3D: frame set-up", err);
}

static void clear_u32(GLuint buf)
{
    static const GLuint zero = 0;
    glClearNamedBufferData(buf, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

/* A geometry pass of program 'geometry' on cleared counts and counters,
 * then program 'frame' over the frame; reads n_words counters from word
 * 'first' into words. */
static oit_status pass(oit_b3d *b, int geometry, int frame, const oit_gpu_mesh *const *meshes,
                       int n, const oit_view *v, int first, int n_words, GLuint *words,
                       const char *what, oit_error *err)
{
    clear_u32(b->b.buf[BUF_COUNTS]);
    clear_u32(b->b.buf[BUF_STATS]);
    oit_baseline_draw(b->prog[geometry], 0, 0, meshes, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
    oit_baseline_dispatch_frame(b->prog[frame], v->width, v->height);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(b->b.buf[BUF_STATS], (GLintptr)first * 4, (GLsizeiptr)n_words * 4,
                            words);
    return oit_gl_check(what, err);
}

/* Count pass and its maximum: the layers the slot array needs. */
static oit_status count(oit_b3d *b, const oit_gpu_mesh *const *meshes, int n,
                        const oit_view *v, GLuint *layers, oit_error *err)
{
    return pass(b, PROG_COUNT, PROG_MAX, meshes, n, v, 1, 1, layers, "B3D: count pass", err);
}

static oit_status store_and_resolve(oit_b3d *b, const oit_gpu_mesh *const *meshes, int n,
                                    const oit_view *v, GLuint figures[3], oit_error *err)
{
    glProgramUniform1i(b->prog[PROG_STORE], OIT_LOC_K, b->layers);
    glProgramUniform1i(b->prog[PROG_RESOLVE], OIT_LOC_K, b->layers);
    glBindImageTexture(OIT_IMG_SLOTS, b->slots, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32UI);
    return pass(b, PROG_STORE, PROG_RESOLVE, meshes, n, v, 0, 3, figures,
                "B3D: store pass and resolve", err);
}

static oit_status oit_b3d_render(oit_b3d *b, const oit_gpu_mesh *const *meshes, int n,
                                 const oit_view *v, oit_image *out, oit_frame_stats *stats,
                                 oit_error *err)
{
    GLuint layers = 0, figures[3] = {0, 0, 0}; /* counter, max_len, total */
    oit_status s = prepare(b, v, err);
    if (s == OIT_OK)
        s = count(b, meshes, n, v, &layers, err);
    if (s == OIT_OK)
        s = reserve_slots(b, v->width, v->height, layers, err);
    if (s == OIT_OK)
        s = store_and_resolve(b, meshes, n, v, figures, err);
    if (s == OIT_OK)
        s = oit_baseline_read_buffer("B3D", b->b.buf[BUF_OUT], v->width, v->height, out, err);
    *stats = (oit_frame_stats){.fragments = figures[2], .max_layers = figures[1],
                               .gpu_bytes_peak = b->b.peak, .batches = 2};
    return s;
}

OIT_BASELINE_METHOD(b3d, oit_b3d, "B3D", 0, OIT_NO_THRESHOLD);
