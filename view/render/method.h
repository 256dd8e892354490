/* A rendering method behind one interface: DFB, the capture backends, the
 * baselines, the Embree reference and (tools/common/method_stream.h) liboit
 * streaming a part file each describe themselves with one `oit_method` table of operations
 * (designated initialisers; an operation a method lacks is NULL), and the
 * tools drive any of them through oit_method_open / _render / _close.
 *
 * What the interface does for every method, so no method repeats it: a GL
 * method (OIT_RENDER_METHOD_GL) gets the caller's context or a headless one of its
 * own, and an in-core GL method gets the mesh uploaded once at open; GL
 * objects are released before the context that owns them.
 *
 * Adding a method: its own file with its table, one line in the registry
 * (tools/common/methods.c), one line in CMake. */
#ifndef OIT_RENDER_METHOD_H
#define OIT_RENDER_METHOD_H

#include <stdint.h>

#include "oit/mesh.h"
#include "oit/render_modes.h"
#include "view/render/gl/gpu_mesh.h"
#include "view/render/image/view.h"

struct oit_gl;
struct oit_gpu_timer;
struct oit_gpu_times;
struct oit_pick_ray;
struct oit_pick_hits;

/* A method's flags are the public oit_render_method_flag (oit/render_modes.h),
 * which liboit's list of methods gives its callers as they are. Beside
 * what the public header says: a PART_FILE method renders what
 * options.source names, not the mesh; oit_method_render refuses section
 * planes to a method without CLIP. */

typedef struct oit_method_options {
    int max_layers; /* K of the capture backends and the streamer */
    /* NULL: GL methods make their own headless context. Else they render in
     * this one, current on the calling thread (the viewer's window), and do
     * not destroy it. */
    struct oit_gl *gl;
    /* The threshold of a method flagged OIT_RENDER_METHOD_EPSILON, in [0, 1); its
     * table's file says what it means (the streamer's early termination,
     * f2b's alpha, guarded's contribution, what the reference counts as
     * saturated). NULL: the method's own default. Other methods ignore it. */
    const float *threshold;
    float ambiguity_px; /* the reference's ambiguity radius, pixels; 0: 1/64 */
    /* OIT_RENDER_METHOD_PART_FILE methods: what they render and how, in the
     * method's own type (liboit's: tools/common/method_stream.h), which
     * this floor does not name; NULL for the others. */
    const void *source;
    /* The most bytes a frame puts in one storage buffer (view/render/gl/band.h):
     * 0, what the driver binds (GL_MAX_SHADER_STORAGE_BLOCK_SIZE); lower
     * only to test the bands. The image is the same either way. */
    uint64_t store_limit;
    /* NULL: a GL method's frames are timed by a GPU timer of the
     * interface's own. Else by this one (the caller's, which outlives the
     * method; liboit's renderer, whose draws of every path it numbers). */
    struct oit_gpu_timer *timer;
    /* Testing: the GPU timer behaves as on a driver without timestamp
     * queries (view/render/gl/gpu_timer.h): no gpu_ms, and it says why. */
    int no_gpu_timer;
} oit_method_options;

/* One frame's inputs and outputs, as a method's render operation sees them. */
typedef struct oit_method_frame {
    const oit_mesh *mesh;     /* the scene in host memory (empty for part files) */
    const oit_gpu_mesh *gpu;  /* the same on the GPU (in-core GL methods) */
    const oit_view *view;
    oit_image *out;           /* allocated by the method */
    uint32_t *counts;         /* width*height, or NULL; only with OIT_RENDER_METHOD_COUNTS */
    uint8_t *ambiguous;       /* width*height, or NULL; only with OIT_RENDER_METHOD_AMBIGUITY */
    oit_frame_stats *stats;
    /* A frame too large for one storage binding is rendered as bands of
     * rows (view/render/gl/band.h), each a frame of its own: band is its index in
     * the frame, 0 for the first (or the only one), for a method that
     * keeps figures across them (figures). */
    int band;
    /* The most bytes one storage buffer binding may take in this frame:
     * the driver's, or less (oit_method_options.store_limit). */
    uint64_t store_limit;
    /* A method whose store grows with the frame's depth (a fragment pool)
     * and cannot hold it within store_limit sets *split to the bands of
     * rows that would each fit, at least 2, and fails: oit_method_render
     * then renders the frame in that many bands. */
    int *split;
    /* GPU time per phase (view/render/gl/gpu_timer.h): the frame is begun and
     * ended around the method; the method marks its phases (NULL-safe). */
    struct oit_gpu_timer *timer;
} oit_method_frame;

typedef struct oit_method {
    const char *name;
    unsigned flags; /* OIT_METHOD_* */
    /* Makes the method's object; a GL context is current (GL methods). */
    oit_status (*create)(const oit_mesh *mesh, const oit_method_options *opt, void **impl,
                         oit_error *err);
    oit_status (*render)(void *impl, const oit_method_frame *frame, oit_error *err);
    void (*destroy)(void *impl);
    /* "Embree 3.13.5 (CPU reference)"; NULL: the GL context's renderer. */
    const char *(*renderer)(const void *impl);
    /* The method's own figures of the last frame beside oit_frame_stats, in
     * its own type (the stream method's: tools/common/method_stream.h reads them
     * typed); NULL for a method with none. */
    const void *(*figures)(const void *impl);
    /* Bytes a pixel of view takes in the method's largest per-pixel
     * storage buffer, which must hold the whole frame in one binding;
     * oit_method_render renders frames past it in bands (view/render/gl/band.h).
     * NULL: no per-pixel storage (not GL). */
    uint64_t (*pixel_bytes)(const void *impl, const oit_view *view);
    /* A method that times its frames on the GPU itself (a library with a
     * timer of its own): oit_method_gpu_poll and _absent ask it, the
     * interface makes no timer for it, and its render sets
     * oit_frame_stats.gpu_frame. NULL: the interface's timer. */
    int (*gpu_poll)(void *impl, struct oit_gpu_times *out, int wait);
    const char *(*gpu_absent)(const void *impl);
    /* Appends to hits what the pixel ray (view/render/pick/pick.h) meets
     * in mesh, found the method's own way: the Embree reference's, so
     * that a pick of the reference is its hits. NULL: the pick's walk. */
    oit_status (*pick)(const oit_mesh *mesh, const struct oit_pick_ray *ray,
                       struct oit_pick_hits *hits, oit_error *err);
} oit_method;

typedef struct oit_method_state oit_method_state;

/* Opens m for mesh (empty for OIT_RENDER_METHOD_PART_FILE methods, whose part file
 * comes in opt->source). opt may be NULL for methods that need none. */
oit_status oit_method_open(const oit_method *m, const oit_mesh *mesh,
                           const oit_method_options *opt, oit_method_state **out,
                           oit_error *err);
/* out is allocated by the call; counts and ambiguous (width*height) may be
 * NULL, and are used only where the method's flags say it fills them. A
 * frame whose per-pixel state does not fit one storage binding (pixel_bytes)
 * is rendered in bands of rows, each band copied into out; stats add up
 * over them (oit_frame_stats_add), ms is the whole frame's. gpu_bytes_peak
 * is the method's own peak plus the mesh uploaded at open (gpu_mesh_bytes),
 * so that every method's figure counts all it holds on the GPU. */
oit_status oit_method_render(oit_method_state *st, const oit_view *view, oit_image *out,
                             uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                             oit_error *err);
/* "llvmpipe (LLVM 15.0.6, 256 bits)", "Embree 3.13.5 (CPU reference)", ... */
const char *oit_method_renderer(const oit_method_state *st);
const oit_method *oit_method_of(const oit_method_state *st);
/* The method's own figures of the last frame (oit_method.figures); NULL
 * for a method with none. */
const void *oit_method_figures(const oit_method_state *st);
/* GPU time of earlier frames, oldest first, matched to a frame by
 * oit_frame_stats.gpu_frame (view/render/gl/gpu_timer.h): 1 and *out when the next
 * one is in (wait: waits for it; at the end of a run), 0 when none is.
 * Never for a method without GL or a driver without timestamps. */
int oit_method_gpu_poll(oit_method_state *st, struct oit_gpu_times *out, int wait);
/* NULL when the method's frames are timed on the GPU, else why not. */
const char *oit_method_gpu_absent(const oit_method_state *st);
void oit_method_close(oit_method_state *st);

/* The in-core exact methods of view/render/: DFB, and the two capture backends
 * drawing the whole mesh as one batch (which is where their overflow count
 * means something). */
extern const oit_method oit_method_dfb;
extern const oit_method oit_method_array;
extern const oit_method oit_method_stencil;
extern const oit_method oit_method_compute;

#endif
