/* What the baseline methods (unsorted.h, wboit.h, ppll.h, ppll4.h, b3d.h,
 * guarded.h, depth_peel.h, dual_peel.h, f2b.h) share beyond frag_glsl.h: the
 * premultiplied colour of a packed fragment, the sort-and-composite resolve
 * of the methods that store every fragment, their GPU buffers, the passes
 * of the peeling and of the blending methods, a frame's start (size
 * validation) and end (figures), and readback of a GL-ordered (bottom row
 * first) RGBA float result into a top-first oit_image. Only the buffer and
 * pass structs keep state, their owner's. */
#ifndef OIT_RENDER_BASELINES_BASELINE_COMMON_H
#define OIT_RENDER_BASELINES_BASELINE_COMMON_H

#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_mesh.h"
#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fragment-stage GLSL (glsl/premultiplied.glsl), placed after
 * oit_glsl_fragment_gen or oit_glsl_composite (it uses u_mode):
 * vec4 oit_premultiplied(uvec4 f) returns (a * colour, a) of a packed
 * fragment, the terms oit_composite adds for one fragment on a clear state.
 * Translucent absorption needs the order and is not part of it. */
extern const char oit_glsl_premultiplied[];

/* Compute-stage GLSL (glsl/sorted_resolve.glsl; 8x8 groups), placed after
 * oit_glsl_composite: per
 * pixel, sorts the stored fragments by (t, prim) and composites them per
 * shade.h into out_rgba[p] (binding OIT_BIND_OUT, GL rows), and adds the
 * pixel's count to max_len (atomicMax) and total (atomicAdd) of the block
 * Stats { uint counter; uint max_len; uint total; } at OIT_BIND_STATE. The
 * method's GLSL follows it and defines how a pixel's fragments are walked
 * (any order; OIT_LIST_END ends a walk):
 *   uint oit_list_first(uint p)  the first of pixel p (GL-row linear index)
 *   uint oit_list_next(uint it)  the one after it
 *   uvec4 oit_list_load(uint it) its packed fragment (frag_glsl.h)
 *   bool oit_list_can_relink()   whether every fragment has its own link
 *   void oit_list_relink(uint it, uint next)  sets it (when it can)
 *   bool oit_list_index(uint first, uint n)  prepares direct access to the
 *                                 k-th of the walk; false when it cannot
 *   uint oit_list_at(uint k)     that position
 *   void oit_list_store(uint it, uvec4 f)    writes a fragment there
 * Up to 32 fragments sort in registers. Longer lists are merge-sorted by
 * relinking (PLL, guarded) or heap-sorted in place through direct access
 * (paged lists up to 1024 fragments, B3D), both O(n log n); otherwise
 * composited by walking again for the successor of the last (t, prim) key,
 * O(n^2) ((t, prim) is unique per pixel: a triangle covers a pixel centre
 * once). llvmpipe stops a shader's loops after 65535 iterations in all,
 * silently: the quadratic walk is right there only up to about 256
 * fragments a pixel, the sorts to about 2500. */
extern const char oit_glsl_sorted_resolve[];

/* A method's GPU buffers and its footprint at peak (gpu_bytes_peak): every
 * buffer's capacity plus the texture bytes it declares. Buffers grow by
 * oit_gl_buffer_reserve; errors name "method names[which]". */
#define OIT_GPU_BUFFERS_MAX 6
typedef struct oit_gpu_buffers {
    const char *method;
    const char *const *names;
    GLuint buf[OIT_GPU_BUFFERS_MAX];
    uint64_t cap[OIT_GPU_BUFFERS_MAX];
    uint64_t texture_bytes;
    uint64_t peak;
} oit_gpu_buffers;

oit_status oit_gpu_buffers_reserve(oit_gpu_buffers *b, int which, uint64_t bytes,
                                   oit_error *err);
/* Buffers 0..n-1 to at least bytes[i] each (0: leave that one as it is),
 * up to the first failure. */
oit_status oit_gpu_buffers_reserve_all(oit_gpu_buffers *b, int n, const uint64_t *bytes,
                                       oit_error *err);
/* Takes a new texture_bytes into the peak. */
void oit_gpu_buffers_note(oit_gpu_buffers *b);
void oit_gpu_buffers_release(oit_gpu_buffers *b);

/* What both peeling methods (depth_peel.h, dual_peel.h) hold besides
 * their targets: the geometry pass, the merge and final compute passes
 * (programs[OIT_PEEL_PROG_PASS, _MERGE, _FINAL], the method's table, which
 * its oit_*_glsl_variants visits too), two framebuffers to ping-pong and
 * the any-samples query that ends the peeling loop. Errors name 'method'. */
enum { OIT_PEEL_PROG_PASS, OIT_PEEL_PROG_MERGE, OIT_PEEL_PROG_FINAL, OIT_PEEL_PROG_N };
typedef struct oit_peel_passes {
    GLuint peel, merge, final, fbo[2], query;
} oit_peel_passes;

oit_status oit_peel_passes_create(oit_peel_passes *p, const char *method,
                                  const oit_glsl_program programs[OIT_PEEL_PROG_N], oit_error *err);
void oit_peel_passes_release(oit_peel_passes *p);
/* oit_glsl_set_view on the three programs. */
void oit_peel_passes_set_view(const oit_peel_passes *p, const oit_view *v);
/* One geometry pass (bound target and state are the caller's); returns
 * whether any fragment passed, waiting for the query. */
int oit_peel_passes_draw(const oit_peel_passes *p, const oit_gpu_mesh *const *meshes, int n);
/* The merge pass over a w x h frame, its uniform u_first set to first. */
void oit_peel_passes_merge(const oit_peel_passes *p, int first, int w, int h);

/* Draws meshes[0..n) with prog; a non-zero query (of query_target,
 * GL_SAMPLES_PASSED or GL_ANY_SAMPLES_PASSED) counts the draws' samples. */
void oit_baseline_draw(GLuint prog, GLenum query_target, GLuint query,
                       const oit_gpu_mesh *const *meshes, int n);

/* Runs compute prog over a w x h frame in 8x8 groups. */
void oit_baseline_dispatch_frame(GLuint prog, int w, int h);
/* The same, writing the RGBA32F texture out (image unit OIT_IMG_OUT), and
 * the barrier before it is read back. */
void oit_baseline_dispatch_to_texture(GLuint prog, GLuint out, int w, int h);
/* Compute-stage GLSL of a pass that writes a frame's colour into an
 * RGBA32F texture (8x8 groups; glsl/to_texture.glsl, with view/render/gl's
 * srgb.glsl and output.glsl): u_size, u_background, u_colour_space and the
 * image u_out at OIT_IMG_OUT, and oit_background() and oit_output(). The
 * method's GLSL follows it with its samplers and main, which stores each
 * pixel's colour in u_out through oit_output (over oit_background()). */
extern const char oit_glsl_to_texture[];

/* A frame of a baseline (methods.h): the view it renders, the figures its
 * passes fill and the time it started (oit_time_ms). */
typedef struct oit_baseline_frame {
    oit_view view;
    oit_frame_stats stats;
    double t0;
} oit_baseline_frame;

/* The most bytes a pixel takes in any baseline's largest per-pixel storage
 * buffer, which holds the whole frame in one binding: the peelers' state
 * (oit_state, 48 bytes in std430). The others' (16, the output) are
 * smaller, so their frames are banded a little sooner than they need. */
#define OIT_BASELINE_PIXEL_BYTES 48u
/* OIT_BASELINE_PIXEL_BYTES, as view/render/method.h's pixel_bytes. */
uint64_t oit_baseline_pixel_bytes(const void *impl, const oit_view *view);

/* Starts a frame: OIT_ERR_ARGUMENT naming 'method' when it cannot be
 * rendered here (non-positive or larger than GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT,
 * n < 0); else fr->view is view with its shading defaults filled in, the
 * figures are 0 and the clock runs. */
oit_status oit_baseline_begin(const char *method, const oit_view *view, int n,
                              oit_baseline_frame *fr, oit_error *err);
/* Ends it with the passes' status s: when s is OIT_OK and stats is set,
 * *stats = the figures with the wall time since the start (overflow_pixels
 * stays 0: no baseline has a per-batch K). Returns s. */
oit_status oit_baseline_end(oit_baseline_frame *fr, oit_frame_stats *stats, oit_status s);

/* An immutable 2D texture of w x h texels of 'format' with nearest
 * filtering (an integer texture with a linear filter would read 0). */
GLuint oit_baseline_texture(GLenum format, int w, int h);

/* Allocates out and fills it from an RGBA32F texture or from a buffer of
 * w*h vec4, both bottom row first; alpha is set to 1 (a composited frame). */
oit_status oit_baseline_read_texture(const char *method, GLuint tex, int w, int h,
                                     oit_image *out, oit_error *err);
oit_status oit_baseline_read_buffer(const char *method, GLuint buf, int w, int h,
                                    oit_image *out, oit_error *err);

/* What the blending baselines (unsorted.h, wboit.h, f2b.h) hold besides
 * their own: their programs (a table of frag_glsl.h), a framebuffer, a
 * GL_SAMPLES_PASSED query that counts what their geometry pass blends, and
 * float targets (RGBA32F or R32F) of the frame's size, the first 'attached'
 * of them the framebuffer's colour attachments 0, 1, ... Errors name
 * 'method'. */
#define OIT_BLEND_PROGS_MAX   4
#define OIT_BLEND_TARGETS_MAX 3
typedef struct oit_blend_passes {
    const char *method;
    GLuint prog[OIT_BLEND_PROGS_MAX], fbo, query;
    GLuint tex[OIT_BLEND_TARGETS_MAX];
    GLenum format[OIT_BLEND_TARGETS_MAX];
    int n_prog, n_tex, attached;
    int w, h;       /* the targets' size */
    uint64_t bytes; /* the targets' bytes */
    uint64_t peak;  /* the most bytes they took */
} oit_blend_passes;

oit_status oit_blend_passes_init(oit_blend_passes *p, const char *method,
                                 const oit_glsl_program *programs, int n_prog,
                                 const GLenum *formats, int n_tex, int attached, oit_error *err);
void oit_blend_passes_release(oit_blend_passes *p);
/* A frame of v: the targets of its size (made again when it changes) and
 * the view set on every program. */
oit_status oit_blend_passes_begin(oit_blend_passes *p, const oit_view *v, oit_error *err);
/* Its end after the passes: their GL check, out read from target 'result'
 * and the figures: the samples counted (fragments), bytes_peak and one
 * batch. */
oit_status oit_blend_passes_end(oit_blend_passes *p, int result, uint64_t bytes_peak,
                                oit_image *out, oit_frame_stats *stats, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
