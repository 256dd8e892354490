/* The render target of the stencil-routed capture (Wang & Xie): K MSAA
 * samples of packed fragments (rgba32ui) with a per-sample stencil that
 * routes the i-th fragment of a pixel into sample i, and the start-up
 * self-test that decides whether this driver does route so; the stencil
 * backend (capture_backend.h) is in capture_stencil.c too. Internal to
 * view/render/capture/. */
#ifndef OIT_RENDER_CAPTURE_STENCIL_H
#define OIT_RENDER_CAPTURE_STENCIL_H

#include "view/render/capture/capture_stencil_probe.h"
#include "view/render/gl/gl_util.h"
#include "view/render/gl/gpu_mesh.h"
#include "view/render/gl/glsl_program.h"
#include "view/render/gl/program_cache.h"

typedef struct oit_stencil_target {
    GLuint fbo, colour, depth_stencil, init_prog;
    oit_program_cache *pc; /* its programs' and its self-test's (NULL: compiled) */
    GLuint vao; /* empty: core GL draws need one bound */
    int width, height;
    int K;       /* fragments routed a pixel: samples 0..K-1 */
    int samples; /* what the target holds: K, or the next count GL has */
    /* Testing (oit_capture_desc.faults): the fill shaded once per sample,
     * as a driver that supersamples runs it more than once a pixel. */
    int sample_shading;
    /* Testing (OIT_CAPTURE_TEST_ROUTE_BY_COPY): no stencil routing; the
     * fill (built with OIT_ROUTE_BY_COPY) puts a pixel's c-th fragment in
     * slot c of routed, and K full-screen draws, each masked to one sample
     * with multisampling on, copy slot i into sample i: the samples routing
     * gives, on a driver that does not route (llvmpipe), so that all but
     * the routing draw is tested there. */
    int by_copy;
    GLuint copy_prog, routed;
    uint64_t routed_cap;
} oit_stencil_target;

/* The sample count for K in *samples: OIT_ERR_UNSUPPORTED when K exceeds
 * what integer colour and depth-stencil multisample targets allow here, or
 * when GL_NV_internalformat_sample_query says K samples are not K true
 * multisamples (oit_stencil_pick_samples); the message gives the numbers.
 * Without that extension the self-test is the judge. */
oit_status oit_stencil_choose_samples(int K, int *samples, oit_error *err);
oit_status oit_stencil_target_init(oit_stencil_target *t, int K, int samples,
                                   oit_program_cache *pc, oit_error *err);
void oit_stencil_target_release(oit_stencil_target *t);
/* Routing by copies from now on (by_copy above); its program. */
oit_status oit_stencil_target_by_copy(oit_stencil_target *t, oit_error *err);
/* (Re)allocates for a w x h frame when the size changed. */
oit_status oit_stencil_target_resize(oit_stencil_target *t, int w, int h, oit_error *err);
/* Routes and draws meshes[0..n) with the fill program prog (its frame's
 * uniforms and buffers set) into the GL rect rect: sample i of a pixel
 * takes its (i+1)-th fragment. */
void oit_stencil_target_fill(oit_stencil_target *t, const int rect[4], GLuint prog,
                             oit_gpu_draws *draws, const oit_gpu_mesh *const *meshes, int n);
uint64_t oit_stencil_target_bytes(const oit_stencil_target *t);

/* What the self-test fills with: the capture's fill program and the buffer
 * its fill shader counts fragments in, for a frame begun with the probe's
 * view (so its counts are zero and the target has the probe's size). */
typedef struct oit_stencil_fill {
    GLuint prog, counts;
    oit_gpu_draws *draws;
} oit_stencil_fill;

/* The self-test: fills the probe (capture_stencil_probe.h) into t and reads
 * every pixel's count and samples back for the verdict. OIT_OK when the
 * driver routes; OIT_ERR_UNSUPPORTED saying how it does not. */
oit_status oit_stencil_self_test(oit_stencil_target *t, const oit_stencil_probe *p,
                                 const oit_stencil_fill *f, oit_error *err);

/* Every program of the target and the stencil backend, and every routed
 * fill (oit_capture_routed_fill: the stencil backend's and first-K's pass
 * 1, routed or by copies), each once (glsl_program.h). */
void oit_capture_stencil_glsl_variants(oit_glsl_visit *visit, void *user);

#endif
