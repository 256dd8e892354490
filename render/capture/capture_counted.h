/* The counted capture (OIT_CAPTURE_COUNTED, capture.h): a batch is captured
 * as DFB captures a frame (Maule et al.: count fragments per pixel, prefix-sum,
 * store each at its pixel's offset, sort per pixel) and composited into the
 * state the frame carries across batches. No per-pixel layer limit: a batch
 * is bounded by its fragments instead, which a count pass measures before
 * anything is stored. A batch whose fragments outgrow the fragment budget
 * is stored and composited in bands of rows from that one count, each band
 * a store pass scissored to its rows (so the bands together rasterize what
 * one store pass would), within what one storage buffer binds. Long lists
 * are sorted in memory past OIT_GLSL_SEGMENT_LOCAL fragments, as DFB sorts them:
 * splitting a batch by its meshes to shorten them drew it again at every
 * halving (a 300-layer stack of 22 parts at 1024x1024: 43 count passes,
 * 3.8 s a frame against 2.1-2.7 s in bands).
 *
 * Bands are cut on the GPU from the count (an eighth under the store), and
 * every band goes through a judge on the GPU that opens its store pass and
 * resolve where its fragments fit the store, at the offset it read there.
 * On the host (the first frame, or a need past one store), the host reads
 * the batch's bands back (one wait a batch) and sizes the store for each.
 * Ahead (oit_counted_begin with no_wait, once a frame measured the need):
 * the host reads nothing. The store is sized for the most fragments a band
 * of earlier frames took (an eighth more), and batch j is drawn in the
 * bands the last frame cut its batch j in; where a band does not fit, the
 * judge flags the frame short, as first-K's pass 2 does: a short frame's
 * image is not exact and is drawn again (oit_counted_ended), with the need
 * and the bands it measured.
 *
 * Internal to render/capture/: the counted backend and first-K's wide packs
 * (capture_backend.h); capture.c owns the frame's counts and state buffers
 * and the framebuffer; the counts are zero between batches (the
 * store pass counts them back down). */
#ifndef OIT_RENDER_CAPTURE_COUNTED_H
#define OIT_RENDER_CAPTURE_COUNTED_H

#include "render/gl/gpu_mesh.h"
#include "render/gl/frag_glsl.h"
#include "render/gl/scan_glsl.h"

/* Its programs (prog), whose uniforms its backend sets: the view, the opaque
 * depth after it (frag_glsl.h), and the early-termination threshold in the
 * two geometry passes, first, which drop fragments of saturated pixels
 * alike. */
enum { OIT_COUNTED_COUNT, OIT_COUNTED_STORE, OIT_COUNTED_RESOLVE, OIT_COUNTED_PROGS };

typedef struct oit_counted {
    GLuint prog[OIT_COUNTED_PROGS];
    GLuint offsets, frags;
    uint64_t offsets_cap, frags_cap;
    oit_scan scan;
    uint64_t budget;   /* fragment store bytes a batch may take before it splits */
    uint32_t splits;   /* batches split this frame (the caller resets it) */
    /* this frame's pixels of more than deep_over fragments in a batch,
     * summed over its batches (oit_capture_counted_batch sets deep_over to
     * the capture's K; the caller resets deep_pixels): those a first-K
     * pack would send through its second pass */
    uint32_t deep_over;
    uint64_t deep_pixels;
    /* The judge's program and words (gate, short, this frame's deep
     * pixels, the resolve's groups, the band's base and the store's
     * capacity); the program that cuts bands and its table (SLOT words a
     * batch of the frame); this frame's mode and batch; the need (the last
     * frame's largest band, an eighth more); the last frame's table (pred_n
     * batches), and whether a batch of it needed more bands than a slot
     * holds. */
    GLuint judge, words, split, table;
    size_t table_slots, batch;
    int ahead, measured, ended_short, unbanded;
    uint64_t need, fit; /* fit: the fragments one store holds (the last batch's) */
    uint32_t *pred;
    size_t pred_n, pred_cap;
} oit_counted;

oit_status oit_counted_init(oit_counted *k, oit_program_cache *pc, oit_error *err);
/* A frame's begin: its figures reset; ahead when no_wait is set, a frame
 * has measured the need and `fit` fragments (one store) hold it. */
void oit_counted_begin(oit_counted *k, int no_wait, uint64_t fit);
/* After the frame's final read-back (the GPU is done: nothing waits): the
 * figures the GPU kept, the need, the bands for the next frame; 1 when the
 * frame ended short. */
int oit_counted_ended(oit_counted *k);
/* Measured from elsewhere (another capture's frame of `fragments`): the
 * need set, the store reserved where `fit` holds it. */
void oit_counted_seed(oit_counted *k, uint64_t fragments, uint64_t fit);
void oit_counted_release(oit_counted *k);
uint64_t oit_counted_bytes(const oit_counted *k);

/* The frame's buffers and draw scratch, owned by capture.c. */
typedef struct oit_counted_frame {
    GLuint fbo, counts, state;
    int width, height;
    oit_gpu_draws *draws;
    uint64_t bind; /* the most bytes one storage buffer may span */
    struct oit_gpu_timer *timer; /* phases marked on it (render/gl/gpu_timer.h); NULL: none */
    oit_host_waits *waits;       /* the frame's waits on the GPU (render/gl/host_wait.h) */
} oit_counted_frame;

/* Captures meshes[0..n) over the GL rect r (bottom rows first, exclusive
 * ends) and composites them behind the state. oit_counted_bytes tells the
 * caller what the module holds afterwards. */
oit_status oit_counted_batch(oit_counted *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4],
                             oit_error *err);

#endif
