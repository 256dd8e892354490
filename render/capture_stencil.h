/* The render target of the stencil-routed capture (Wang & Xie): K MSAA
 * samples of packed fragments (rgba32ui) with a per-sample stencil that
 * routes the i-th fragment of a pixel into sample i. Internal to capture.c. */
#ifndef OIT_RENDER_CAPTURE_STENCIL_H
#define OIT_RENDER_CAPTURE_STENCIL_H

#include "render/gl_util.h"

typedef struct oit_stencil_target {
    GLuint fbo, colour, depth_stencil, init_prog;
    GLuint vao; /* empty: core GL draws need one bound */
    int width, height, samples;
} oit_stencil_target;

/* OIT_ERR_UNSUPPORTED when K samples exceed what integer colour and
 * depth-stencil multisample targets allow here; the message gives limits. */
oit_status oit_stencil_check_limits(int K, oit_error *err);
oit_status oit_stencil_target_init(oit_stencil_target *t, int K, oit_error *err);
void oit_stencil_target_release(oit_stencil_target *t);
/* (Re)allocates for a w x h frame when the size changed. */
oit_status oit_stencil_target_resize(oit_stencil_target *t, int w, int h, oit_error *err);
/* Sets sample i's stencil to i + 1 inside rect (GL rows) so that, drawing
 * with EQUAL 1 and DECR, each fragment lands in the next free sample. */
void oit_stencil_target_route(oit_stencil_target *t, const int rect[4]);
/* Binds the target and the routing state for a capture draw in rect. */
void oit_stencil_target_begin_draw(oit_stencil_target *t, const int rect[4]);
void oit_stencil_target_end_draw(void);
uint64_t oit_stencil_target_bytes(const oit_stencil_target *t);

#endif
