/* What a capture (capture.h) is made of: the part every backend shares
 * (the frame's view, counts, state and totals, the settings, the opaque
 * pre-pass, the draws, this frame's figures), owned by capture.c, and one
 * table of operations per backend (OIT_CAPTURE_OPS, designated
 * initialisers) beside the backend's own state in its own file:
 *   array    capture_array.c           K slots a pixel (and the tiles of wide batches)
 *   stencil  capture_stencil.c         the stencil-routed target, its self-test
 *   counted  capture_counted.c         count, store, sort per batch
 *   first-k  capture_firstk_backend.c  K slots, and a second pass where they
 *                                      overflow (capture_firstk.c)
 *   compute  capture_compute.c         binning, coverage, order and compositing
 *                                      in compute shaders
 * capture_create.c picks the table once, at creation; nothing else asks which
 * backend runs (tests/view/render/test_render_layout.sh). Internal to
 * view/render/capture/. */
#ifndef OIT_RENDER_CAPTURE_BACKEND_H
#define OIT_RENDER_CAPTURE_BACKEND_H

#include "view/render/capture/capture.h"
#include "view/render/capture/capture_choice.h"
#include "view/render/capture/capture_counted.h"
#include "view/render/capture/capture_stencil.h"
#include "view/render/capture/opaque_keys.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/gl/host_wait.h"

/* The frame's buffers every backend uses. */
enum { OIT_CAPTURE_COUNTS, OIT_CAPTURE_STATE, OIT_CAPTURE_TOTALS, OIT_CAPTURE_BUFS };

/* This frame's, set by oit_capture_begin. */
typedef struct oit_capture_frame {
    double t0;
    uint64_t bind;       /* the most one storage binding spans: store_limit or the driver's */
    uint64_t view_key;   /* oit_view_key of the frame's view (predicted batches') */
    float applied;       /* the threshold the programs test now: epsilon, or 0 (gate_epsilon) */
    int touched[4];      /* GL box of the frame's batches so far; empty: x0 >= x1 */
    int in_frame;
    uint32_t batches;
    uint64_t calls0;     /* the draws' calls at the frame's begin */
    uint64_t bytes_peak;
    oit_host_waits waits; /* the host's waits on the GPU so far (host_wait.h) */
    uint64_t fragments;   /* the frame's, once ended (oit_capture_ready_counted) */
} oit_capture_frame;

/* The buffer a frame's output passes through at its end (idle by then). */
typedef struct oit_capture_out {
    GLuint buf;
    uint64_t cap;
} oit_capture_out;

typedef struct oit_capture_ops oit_capture_ops;

struct oit_capture {
    const oit_capture_ops *ops;
    void *be;     /* the backend's own state (ops->create) */
    oit_program_cache *programs; /* where its programs are built through; NULL: none */
    int K;
    int routed_k; /* samples a pixel of the routed fills; 0: none */
    oit_capture_choice choice; /* the fill creation chose (oit_capture_get_choice) */
    unsigned faults;
    oit_capture_settings set; /* oit_capture_desc.settings, or as applied */
    oit_opaque_depth opaque; /* the caller's depth; keyed: this frame's opaque triangles */
    oit_opaque_keys *keys;   /* the opaque pre-pass, made on first need */
    GLuint fbo;              /* attachment-less: the fills write buffers */
    GLuint buf[OIT_CAPTURE_BUFS];
    uint64_t cap[OIT_CAPTURE_BUFS];
    GLuint end_prog;      /* final colours and totals (oit_capture_end_program) */
    GLuint max_groups;    /* GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] */
    oit_gpu_draws *draws; /* every geometry draw goes through it */
    oit_view view;
    oit_capture_frame frame;
    int ended_short; /* oit_capture_short */
};

/* A backend (OIT_CAPTURE_OPS writes its table). r: a batch's rect in GL
 * rows (batch_start's); rect: the caller's, top rows first. */
struct oit_capture_ops {
    oit_capture_kind kind;
    const char *name; /* oit_capture_kind_name */
    size_t size;      /* of its state, which capture_create.c allocates zeroed as c->be */
    /* Sets c->be up; stencil_k: the samples of routed fills (0: none). */
    oit_status (*create)(oit_capture *c, int stencil_k, oit_error *err);
    /* Releases what c->be holds, however far create got. */
    void (*destroy)(void *be);
    /* The frame's own buffers for c->view; this frame's figures reset. */
    oit_status (*begin)(oit_capture *c, oit_error *err);
    /* The view, the opaque depth and K into its programs. */
    void (*uniforms)(oit_capture *c);
    /* The early-termination threshold into the programs that test it. */
    void (*epsilon)(oit_capture *c, float e);
    /* Its buffers at their bindings (OIT_BIND_OUT, OIT_BIND_FRAGS). */
    void (*bind)(const oit_capture *c);
    /* A batch that may give up to `layers` fragments a pixel
     * (oit_capture_batch_layers; oit_capture_batch passes K). */
    oit_status (*batch)(oit_capture *c, const oit_gpu_mesh *const *meshes, int n,
                        const int rect[4], int layers, oit_error *err);
    /* The buffer the frame's output passes through, reserved for `want`
     * bytes where the backend sizes it (rows of `row` bytes). */
    oit_status (*end)(oit_capture *c, uint64_t want, uint64_t row, oit_capture_out *out,
                      oit_error *err);
    uint64_t (*bytes)(const void *be); /* GPU bytes held */
    /* Its part of the frame's stats: capture, capture_slots(_k), batches
     * past c->frame.batches, second-pass figures. */
    void (*stats)(const oit_capture *c, oit_frame_stats *stats);
    /* first-k only (NULL elsewhere): oit_capture_set_first_k,
     * oit_capture_ready_counted */
    void (*first_k)(oit_capture *c, int on);
    void (*ready_counted)(oit_capture *c);
    /* After the frame's final read-back (NULL: nothing to do): reads what
     * the backend measured on the GPU (no wait: it is done); returns 1
     * when the frame ended short (oit_capture_short). */
    int (*ended)(oit_capture *c);
};

/* The table of backend P (its functions P_create, P_destroy, ... and its
 * state type T) as oit_capture_P_ops; FIRST_K, READY, ENDED: its first_k,
 * ready_counted and ended, or NULL. */
#define OIT_CAPTURE_OPS(P, KIND, NAME, T, FIRST_K, READY, ENDED)                              \
    const oit_capture_ops oit_capture_##P##_ops = {                                           \
        .kind = KIND, .name = NAME, .size = sizeof(T), .create = P##_create,                  \
        .destroy = P##_destroy, .begin = P##_begin, .uniforms = P##_uniforms,                 \
        .epsilon = P##_epsilon, .bind = P##_bind, .batch = P##_batch, .end = P##_end,         \
        .bytes = P##_bytes, .stats = P##_stats, .first_k = FIRST_K, .ready_counted = READY,  \
        .ended = ENDED}

extern const oit_capture_ops oit_capture_array_ops, oit_capture_stencil_ops,
    oit_capture_counted_ops, oit_capture_firstk_ops, oit_capture_compute_ops;

/* ---- what capture.c lends its backends ----------------------------------- */

/* The frame's end (glsl/end.glsl): final colours and totals, built at
 * creation into end_prog. */
extern const oit_glsl_program oit_capture_end_program;

void oit_capture_note_peak(oit_capture *c);
/* A buffer of the capture grown to bytes, the peak noted. */
oit_status oit_capture_reserve(oit_capture *c, GLuint *buf, uint64_t *cap, uint64_t bytes,
                               const char *name, oit_error *err);
/* bytes, or less where one storage binding (at least one row) spans less. */
uint64_t oit_capture_within_binding(const oit_capture *c, uint64_t bytes, uint64_t row);
/* buf (cap bytes) at binding, no more of it than one binding spans. */
void oit_capture_bind_within(const oit_capture *c, GLuint binding, GLuint buf, uint64_t cap);
/* The frame's buffers and the backend's at their bindings. */
void oit_capture_bind_buffers(const oit_capture *c);
/* The start every batch shares: inside a frame, counted, rect clamped into
 * GL rows in r; *empty when nothing is drawn. Draws the batch's opaque
 * triangles into the keys first. */
oit_status oit_capture_batch_start(oit_capture *c, const oit_gpu_mesh *const *meshes,
                                   const int rect[4], int n, int r[4], int *empty,
                                   oit_error *err);
/* Sorts and composites the GL rect r with a resolve program. */
void oit_capture_resolve(GLuint prog, const int r[4]);
/* The meshes drawn with prog into the attachment-less framebuffer, clipped
 * to the GL rect r. */
void oit_capture_draw_scissored(oit_capture *c, GLuint prog, const oit_gpu_mesh *const *meshes,
                                int n, const int r[4]);
/* What the counted and first-K batches share of the frame. */
oit_counted_frame oit_capture_counted_frame(oit_capture *c);
/* The view, the opaque depth, K and the pixel count in progs[0..n). */
void oit_capture_set_frame_uniforms(const oit_capture *c, GLuint *progs, int n);
/* c->set.epsilon into every program that tests it, from the next batch on
 * (oit_capture_apply). */
void oit_capture_apply_epsilon(oit_capture *c);

/* ---- the counted capture (capture_counted.c), first-K's too ---------------- */

/* The batch over the GL rect r (batch_start's) counted, stored, sorted. */
oit_status oit_capture_counted_batch(oit_capture *c, oit_counted *k,
                                     const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                     oit_error *err);
/* The fragment stores' bytes: the store budget, else the slot budget; 0:
 * no limit but one binding's. */
uint64_t oit_capture_store_budget(const oit_capture *c);
/* Fragments one counted store may hold: the store budget where set, within
 * one storage binding (the frame's; oit_counted_begin's fit). */
uint64_t oit_capture_counted_fit(const oit_capture *c);
/* The output through a fragment store (buf, cap), idle at the frame's end:
 * `want` bytes, within the store budget and one binding (rows of `row`). */
oit_status oit_capture_store_out(oit_capture *c, GLuint *buf, uint64_t *cap, const char *name,
                                 uint64_t want, uint64_t row, oit_capture_out *out,
                                 oit_error *err);

/* ---- the stencil-routed fills (capture_stencil.c) ------------------------- */

/* A routed fill (glsl/stencil_fill.glsl): the stencil backend's
 * (firstk_pass 0) or first-K's pass 1 (1); by_copy: routing by copies
 * (testing, capture_stencil.h). */
oit_glsl_program oit_capture_routed_fill(int firstk_pass, int by_copy);
/* t made for stencil_k samples a pixel, with c's faults. */
oit_status oit_capture_route_init(const oit_capture *c, oit_stencil_target *t, int stencil_k,
                                  oit_error *err);
/* The self-test (capture_stencil.h) in a frame of the probe's view,
 * through the fill program fill and c's counts. */
oit_status oit_capture_stencil_self_test(oit_capture *c, oit_stencil_target *t, GLuint fill,
                                         oit_error *err);

/* ---- K slots a pixel (capture_array.c), the stencil's wide batches too --- */

typedef struct oit_capture_slots {
    GLuint fill, resolve; /* the K-slot fill and its resolve */
    /* Tiled batches (tile-local slots: wide parts, or a slot budget below
     * the full frame), built on first use: [0] sorts up to 16, [1] up to
     * OIT_CAPTURE_MAX_LAYERS; each its fill, then its resolve. */
    GLuint tile_prog[2][2];
    GLuint buf;
    uint64_t cap;
    int tiled; /* this frame: every batch goes through tiles */
} oit_capture_slots;

/* Builds the backend's K-slot fill (programs[0]) and its resolve
 * (programs[1]) into s. */
oit_status oit_capture_slots_init(oit_capture_slots *s, oit_program_cache *pc,
                                  const oit_glsl_program programs[2], oit_error *err);
void oit_capture_slots_release(oit_capture_slots *s);
void oit_capture_slots_uniforms(const oit_capture *c, oit_capture_slots *s);
void oit_capture_slots_epsilon(oit_capture_slots *s, float e);
/* A batch in tiles of array slots small enough that `layers` (at least K)
 * slots a pixel fit: what a batch of more than K layers takes, and every
 * batch of a tiled frame. */
oit_status oit_capture_slots_tiled(oit_capture *c, oit_capture_slots *s,
                                   const oit_gpu_mesh *const *meshes, int n, const int rect[4],
                                   int layers, oit_error *err);
/* The array backend's programs and the tiled batches' (both backends'),
 * each once (glsl_program.h). */
void oit_capture_array_glsl_variants(oit_glsl_visit *visit, void *user);

#endif
