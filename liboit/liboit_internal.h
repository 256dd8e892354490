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
#include "render/gl/band.h"
#include "render/capture/blend_into.h"
#include "render/capture/dfb.h"
#include "render/gl/frag_glsl.h"
#include "render/gl/gpu_timer.h"
#include "render/image/image.h"
#include "render/image/shade.h"
#include "stream/streamer.h"
#include "liboit/desc_ranges.h"

struct oit_scene {
    oit_partfile *pf; /* a part file, or NULL: in core */
    oit_mesh mesh;    /* in core: the triangles */
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

struct oit_renderer {
    oit_renderer_desc desc;
    oit_streamer_desc stream;    /* desc spelt for the streamer (stream_desc); K per scene */
    oit_scene *scene;            /* the scene the streamer or gpu_mesh holds: a share */
    oit_streamer *streamer;      /* part files */
    oit_dfb *dfb;                /* in-core scenes; kept across scenes */
    oit_gpu_mesh *gpu_mesh;      /* the in-core scene's triangles */
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

/* liboit_renderer.c */
oit_status oit_lib_bind_scene(oit_renderer *r, oit_scene *scene, oit_error *err);
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
