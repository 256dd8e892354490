/* The first-K capture (OIT_CAPTURE_FIRSTK, capture.h): exact like the
 * counted capture, but a pack usually costs one geometry pass instead of
 * two and a scan.
 *
 * Pass 1 draws the pack once into W slots per pixel of the pack's
 * rectangle (rectangle-local, so a small pack gets many slots) while an
 * atomic counter counts every fragment of every pixel, beyond W too; a
 * resolve then sorts and composites the pixels that got at most W, from
 * their slots, and leaves the others (their counts) alone. W is the
 * largest number of slots, at most the capture's K, that keeps
 * W x 16 bytes x the rectangle's pixels within the slot budget.
 *
 * Only when some pixel got more than W, pass 2 draws the pack again: an
 * allocation pass gives each such pixel a segment of its measured count in
 * a compact store (the counts are pass 1's; no count pass), the draw stores
 * those pixels' fragments only, and a resolve sorts each segment as DFB
 * does (registers up to 32, heap beyond) and composites it. Every pixel is
 * thus composited exactly once per pack, behind the packs before it, and
 * nothing is lost. Pass 2 covers only the box of the overflowed pixels,
 * which pass 1 measures. Its store reuses the slots' buffer (idle by
 * then); where the box's overflowed pixels need more than the slot budget,
 * pass 2 runs over bands of rows that fit (one draw each), and a single row
 * that needs more grows the store to what it needs.
 *
 * Early termination: both passes drop the fragments of a pixel whose
 * carried transmittance is below epsilon, and pass 2 only visits pixels
 * that pass 1's resolve left untouched, so both passes see the same state
 * and agree on every pixel.
 *
 * Internal to view/render/capture/ (the first-K backend,
 * capture_firstk_backend.c); capture.c owns the frame's counts and state
 * buffers and the framebuffer. Contract: the counts are zero between
 * batches; the pass-1 resolve zeroes the pixels it composites, the pass-2
 * store counts the others back down to zero. */
#ifndef OIT_RENDER_CAPTURE_FIRSTK_H
#define OIT_RENDER_CAPTURE_FIRSTK_H

#include "view/render/capture/capture_counted.h"
#include "view/render/gl/frag_glsl.h"
#include "view/render/gl/gpu_mesh.h"

/* Its programs (prog), set up by its backend as the counted capture's
 * (capture_counted.h): the two geometry passes first. */
enum {
    OIT_FIRSTK_FILL,
    OIT_FIRSTK_STORE,
    OIT_FIRSTK_RESOLVE,
    OIT_FIRSTK_ALLOC,
    OIT_FIRSTK_SEGMENT,
    OIT_FIRSTK_ROUTED_RESOLVE,
    OIT_FIRSTK_JUDGE, /* ahead mode: pass 2's dispatch, gate and verdict on the GPU */
    OIT_FIRSTK_PROGS
};

struct oit_stencil_target;

typedef struct oit_firstk {
    GLuint prog[OIT_FIRSTK_PROGS];
    GLuint store;   /* pass 1: the W slots; pass 2: the overflowed pixels' fragments */
    GLuint table;   /* pass 2: per pixel of the band, (offset, count); count 0: not its */
    /* a pack's words: uint overflowed pixels, fragments lo, fragments hi,
     * the gate of pass 2's draw, the overflow box; then the frame's
     * (oit_firstk_begin): short, the most fragments a pack's pass 2
     * needed, pixels and packs that took pass 2 */
    GLuint totals;
    uint64_t store_cap, table_cap;
    int K;          /* the most slots a pixel gets */
    uint64_t budget; /* slot bytes a pack may take; UINT64_MAX: no limit */
    uint64_t store_budget; /* pass 2's store bytes before it bands; UINT64_MAX: no limit */
    /* this frame (the caller resets them): pixels and packs that took pass 2,
     * and the draws pass 2 made */
    uint64_t second_pixels;
    uint32_t second_packs, second_draws;
    /* Pass 1 routed by the stencil (oit_firstk_route), else NULL: array
     * slots. */
    struct oit_stencil_target *routed;
    GLuint routed_fill;
    /* Programs are built at their first use (a routed pass 1 needs none
     * of the array pass's, a pack without overflow none of pass 2's),
     * through pc; then built(built_ctx) gives them the frame's uniforms. */
    oit_program_cache *pc;
    void (*built)(void *built_ctx);
    void *built_ctx;
    /* Pass 2 driven by the GPU (oit_capture_settings.no_wait; its backend sets
     * ahead a frame, from the first on, and off while the measured `need`
     * passes the store budget or one binding: the host then splits pass 2
     * in bands): the store sized ahead for `need` fragments (the most an
     * earlier frame's pack needed; before any, what the slots hold); a
     * pack that needs more flags the frame short. */
    int ahead;
    uint64_t need;
    int measured;    /* a frame has ended: need holds what it saw */
    uint64_t seen;   /* this frame's most fragments a band's pass 2 took (host mode) */
    int ended_short; /* the last frame (oit_firstk_ended) */
    /* Where pass 1's counts go (every pixel's fragments, before its
     * resolve takes them back to 0) for a counted frame to predict by
     * (capture_counted.h); 0: nowhere. Set by the caller per batch. */
    GLuint counts_copy;
} oit_firstk;

/* The frame's words of the totals cleared: at a frame's begin. */
void oit_firstk_begin(oit_firstk *k);
/* After the frame's final read-back (the GPU is done: no wait): in ahead
 * mode, the frame's pass-2 figures, whether it ended short and the need
 * the next frames size the store for. */
void oit_firstk_ended(oit_firstk *k);

/* built(built_ctx): after programs were built mid-frame (may be NULL). */
oit_status oit_firstk_init(oit_firstk *k, int K, oit_program_cache *pc,
                           void (*built)(void *built_ctx), void *built_ctx, oit_error *err);
void oit_firstk_release(oit_firstk *k);
/* Every program it can build, each once (glsl_program.h). */
void oit_firstk_glsl_variants(oit_glsl_visit *visit, void *user);
uint64_t oit_firstk_bytes(const oit_firstk *k);

/* Pass 1 from now on through the stencil target t (its K samples a pixel
 * of the whole frame, whatever the budget), filled with fill (the stencil
 * fill shader built with OIT_FIRSTK_PASS, capture_glsl.h): the fill counts
 * every fragment exactly with the atomic counter, so a pixel that got more
 * than the samples hold is found from its count (not from the stencil,
 * which stops at the last sample), and its fragments are all taken by pass
 * 2. Pass 1's resolve reads the samples of the pixels of at most K. */
void oit_firstk_route(oit_firstk *k, struct oit_stencil_target *t, GLuint fill);

/* The slots a pack over the GL rect r gets: 0 when fewer than 2 fit the
 * budget, where pass 1 would settle too few pixels to pay for itself (the
 * caller then captures the pack counted). */
int oit_firstk_slots(const oit_firstk *k, const int r[4]);

/* Captures meshes[0..n) over the GL rect r (bottom rows first, exclusive
 * ends) with W = oit_firstk_slots(k, r) >= 2 slots a pixel and composites
 * them behind the state f carries. The frame's buffers are those of the
 * counted capture (capture_counted.h). */
oit_status oit_firstk_batch(oit_firstk *k, const oit_counted_frame *f,
                            const oit_gpu_mesh *const *meshes, int n, const int r[4],
                            oit_error *err);

#endif
