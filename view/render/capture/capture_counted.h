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
 * Predicted batches. A view drawn again draws the same fragments, so its
 * last frame's counts already say where each pixel's fragments go: batch j
 * of a frame whose view has the key of the frame that counted its batch j
 * (OIT_COUNTED_PREDICTED_BATCHES of them kept, 4 bytes a pixel each) is
 * drawn once a band, each fragment counted and stored in its pixel's
 * segment of those offsets where it falls within it. The resolve
 * composites the pixels the segments held and keeps every count for the
 * next frame; a pixel that got more (the scene or the opaque depth
 * changed under the same view) keeps its count, and those are scanned and
 * stored as an ordinary band of their own, whose judge shuts the store
 * pass where none spilled. Only the same view predicts: a moving one
 * spills throughout and would pay that second pass on top of counting's
 * (the 1M plant at 256x256, 10 degrees a frame: 440-730 ms a frame
 * against 360-375). The first-K backend keeps its pass 1's counts the
 * same way on the first frame of a deep view (oit_counted_predict), for
 * auto's counted try on the next. The 1M plant at 512x512, the same view:
 * 250-310 ms a frame against 440-470 counted first and 430-490 for DFB.
 *
 * Internal to view/render/capture/: the counted backend and first-K's wide packs
 * (capture_backend.h); capture.c owns the frame's counts and state buffers
 * and the framebuffer; the counts are zero between batches (the
 * store pass counts them back down). */
#ifndef OIT_RENDER_CAPTURE_COUNTED_H
#define OIT_RENDER_CAPTURE_COUNTED_H

#include "view/render/gl/gpu_mesh.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/scan_glsl.h"

/* Its programs (prog), whose uniforms its backend sets: the view, the opaque
 * depth after it (frag_glsl.h), and the early-termination threshold in the
 * two geometry passes, first, which drop fragments of saturated pixels
 * alike. */
enum {
    OIT_COUNTED_COUNT,
    OIT_COUNTED_STORE,
    OIT_COUNTED_PREDICTED, /* a predicted band's store (a geometry pass too) */
    OIT_COUNTED_RESOLVE,
    OIT_COUNTED_PREDICTED_RESOLVE,
    OIT_COUNTED_PROGS,
    OIT_COUNTED_GEOMETRY_PROGS = 3 /* the first three: epsilon applies */
};
/* Batches of a frame whose counts predict the next frame's (each holds a
 * frame's offsets: 4 bytes a pixel). */
enum { OIT_COUNTED_PREDICTED_BATCHES = 4 };

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
    /* The offsets of the last frame's batch j (the scan of its counts,
     * frames of predicted_pixels pixels, its view's key) where
     * predicted_ok[j]; next, the
     * counts the predicted batch drawing now keeps for the frame after;
     * the batches this frame drew predicted. */
    GLuint predicted[OIT_COUNTED_PREDICTED_BATCHES], next;
    uint64_t predicted_cap[OIT_COUNTED_PREDICTED_BATCHES], next_cap, predicted_pixels;
    int predicted_ok[OIT_COUNTED_PREDICTED_BATCHES];
    uint64_t predicted_view[OIT_COUNTED_PREDICTED_BATCHES]; /* the key of its frame's view */
    uint32_t predicted_batches;
    oit_program_cache *pc; /* the predicted passes' programs, built on first use */
    int predicted_failed;  /* they could not be: no batch is drawn predicted */
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
/* Every program it can build, each once (glsl_program.h). */
void oit_counted_glsl_variants(oit_glsl_visit *visit, void *user);
uint64_t oit_counted_bytes(const oit_counted *k);

/* The frame's buffers and draw scratch, owned by capture.c. */
typedef struct oit_counted_frame {
    GLuint fbo, counts, state;
    int width, height;
    oit_gpu_draws *draws;
    uint64_t bind; /* the most bytes one storage buffer may span */
    uint64_t view_key;           /* oit_view_key of the frame's view */
    struct oit_gpu_timer *timer; /* phases marked on it (view/render/gl/gpu_timer.h); NULL: none */
    oit_host_waits *waits;       /* the frame's waits on the GPU (view/render/gl/host_wait.h) */
} oit_counted_frame;

/* Captures meshes[0..n) over the GL rect r (bottom rows first, exclusive
 * ends) and composites them behind the state. oit_counted_bytes tells the
 * caller what the module holds afterwards. */
oit_status oit_counted_batch(oit_counted *k, const oit_counted_frame *f,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4],
                             oit_error *err);

/* A prediction from another capture's batch j of the frame (its pass
 * counting every fragment): *copy receives a buffer for that batch's
 * counts (pixels of frame f), into which the caller copies them; 0 where
 * j is past the batches kept or the prediction would not fit `budget`
 * bytes beside what the counted capture holds (the caller's own store
 * taken off; UINT64_MAX: no limit), then nothing is kept. Then
 * oit_counted_predict scans them and keeps them as batch j's prediction
 * for the next frame, nothing read back. */
oit_status oit_counted_predict_target(oit_counted *k, const oit_counted_frame *f, size_t j,
                                      uint64_t budget, GLuint *copy, oit_error *err);
oit_status oit_counted_predict(oit_counted *k, const oit_counted_frame *f, size_t j,
                               oit_error *err);

#endif
