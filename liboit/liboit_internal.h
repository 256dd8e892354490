/* liboit's state and what its files share (include/oit/liboit.h is the
 * interface). liboit.c: drawing, into the caller's framebuffer or an
 * image; liboit_scene.c: scenes, opened or made from arrays;
 * liboit_view.c: the caller's matrices and frame turned into a view;
 * liboit_renderer.c: the renderer's lifetime, descriptor and scene;
 * liboit_gl_state.c: the caller's GL state kept, the blend into its
 * framebuffer and its depth texture. Each function is documented at its
 * definition. Internal to liboit/. */
#ifndef OIT_LIBOIT_INTERNAL_H
#define OIT_LIBOIT_INTERNAL_H

#include "oit/liboit.h"

#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "formats/readers_internal.h"
#include "view/render/gl/band.h"
#include "view/render/capture/blend_into.h"
#include "view/render/capture/dfb.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "view/render/image/shade.h"
#include "view/render/gl/gl_context.h"
#include "view/render/method.h"
#include "formats/plugin_load.h"
#include "view/stream/streamer.h"
#include "liboit/desc_ranges.h"

struct oit_scene {
    oit_partfile *pf; /* a part file, or NULL: in core */
    oit_mesh mesh;    /* in core: the triangles */
    int mesh_borrowed; /* mesh is the caller's (oit_scene_borrow_mesh): not freed here */
    char *name;       /* in core: the file or the descriptor's name */
    oit_scene_info info;
    /* oit_scene_desc.share_*: the shares of the file and the order that
     * oit_scene_share_order reads them from (NULL for a whole scene). */
    oit_shares *share_set;
    oit_order *order;
    uint32_t *ordered; /* the part order of a view, a part count long */
    /* The caller's handle is one share and each renderer that drew the
     * scene last holds one: the scene is freed with the last share, so a
     * renderer never meets a freed scene, nor another scene at its address
     * (allocators hand freed blocks back), when the caller closes it first. */
    atomic_uint shares;
};

enum { GPU_QUEUE = 64 };

/* A method of liboit's table (liboit_methods.c), as oit_render_methods
 * lists it. */
typedef oit_render_method_info oit_lib_method;

/* K of the in-core methods where oit_renderer_desc.K is 0, as the tools'. */
#define OIT_LIB_IN_CORE_K 16

struct oit_renderer {
    oit_renderer_desc desc;
    oit_streamer_desc stream;    /* desc spelt for the streamer (stream_desc); K per scene */
    oit_scene *scene;            /* the scene the streamer or gpu_mesh holds: a share */
    oit_streamer *streamer;      /* part files */
    oit_dfb *dfb;                /* in-core scenes; kept across scenes */
    oit_gpu_mesh *gpu_mesh;      /* the in-core scene's triangles (oit_renderer_draw) */
    /* An in-core scene's image path (oit_renderer_draw_pixels): the method
     * drawing it (`method`, resolved at the draw), opened in the caller's
     * context (run_gl), with the reference's plugin where it is the one. */
    const oit_lib_method *method;
    oit_method_state *run;
    struct oit_gl *run_gl;
    oit_plugin reference_plugin;
    const oit_method *reference;
    char device[256];            /* oit_draw_stats.device: the GL renderer's */
    uint64_t pending_upload;     /* bytes uploaded by bind_scene, for the stats */
    GLuint blend_prog, vao;      /* blend_prog: made at the first oit_renderer_draw */
    oit_program_cache *programs; /* desc.program_cache's, NULL: none */
    GLuint depth_sampler;        /* reads oit_frame.depth_texture: no compare, nearest */
    oit_gpu_timer *timer;        /* made at the first draw (GL current) */
    oit_gpu_times gpu;           /* the newest figures polled; frame 0: none yet */
    /* Figures polled but not yet taken by oit_renderer_gpu_poll, oldest
     * first at gpu_head; the oldest go when it is full. */
    oit_gpu_times gpu_queue[GPU_QUEUE];
    unsigned gpu_head, gpu_count;
    uint64_t draws; /* oit_draw_stats.draw of the last draw */
    unsigned bands; /* streamer frames of the draw under way (render_state) */
};

_Static_assert(OIT_DRAW_GPU_PHASES == OIT_GPU_PHASES, "one list of GPU phases");

static inline const char *scene_name(const oit_scene *s)
{
    return s->pf ? oit_partfile_name(s->pf) : s->name;
}

/* The state oit_renderer_draw promises to give back (liboit.h). */
typedef struct gl_saved {
    GLint draw_fb, read_fb, viewport[4], program, vao, indirect;
    GLint src_rgb, dst_rgb, src_a, dst_a, eq_rgb, eq_a;
    GLboolean colour_mask[4], depth_mask;
    GLboolean enabled[7];
} gl_saved;

typedef struct depth_unit {
    GLint active, tex, sampler;
} depth_unit;

/* liboit_scene.c */
void oit_lib_scene_unshare(oit_scene *s);

/* liboit_view.c */
oit_status oit_lib_frame_camera(const oit_frame *f, oit_view *v, oit_error *err);
oit_status oit_lib_frame_view(const oit_renderer *r, const oit_scene *scene, const oit_frame *f,
                              const float *bg, oit_view *v, oit_error *err);

/* liboit_methods.c */
const oit_lib_method *oit_lib_method_find(const char *name);
oit_status oit_lib_method_check(const char *name, oit_error *err);
oit_status oit_lib_method_for(const oit_renderer *r, const oit_scene *scene,
                              const oit_lib_method **out, oit_error *err);
oit_status oit_lib_method_open(oit_renderer *r, const oit_lib_method *m, const oit_scene *scene,
                               oit_error *err);
oit_status oit_lib_method_table(oit_renderer *r, const oit_lib_method *m,
                                const oit_method **out, oit_error *err);

/* liboit_renderer.c */
oit_status oit_lib_bind_scene(oit_renderer *r, oit_scene *scene, int image, oit_error *err);
oit_status oit_lib_gl_ready(oit_renderer *r, oit_error *err);
void oit_lib_make_shading(const oit_renderer *r, const oit_scene *scene, const float *bg,
                          oit_shading *s);

/* liboit_gl_state.c */
GLint oit_lib_keys_unit_save(void);
oit_status oit_lib_blend_ready(oit_renderer *r, oit_error *err);
oit_status oit_lib_check_depth_texture(const oit_frame *f, oit_error *err);
void oit_lib_blend_over(const oit_renderer *r, const oit_frame *f, const oit_view *v, int x, int y,
                        GLuint state);
void oit_lib_depth_unit_bind(const oit_renderer *r, GLuint tex, depth_unit *u);
void oit_lib_depth_unit_restore(const depth_unit *u);
void oit_lib_gl_restore(const gl_saved *g);
void oit_lib_gl_save(gl_saved *g);

#endif
