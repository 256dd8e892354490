/* GPU time per frame and per phase, from GL timestamp queries, read without
 * stalling the frames that make them.
 *
 * A frame is a run of timestamps (glQueryCounter, GL_TIMESTAMP): each mark
 * ends the phase before it and starts its own, so the phases of a frame add
 * up to its gpu_ms exactly (the time from the frame's first timestamp to its
 * last, on the GPU's clock). GL_TIME_ELAPSED queries cannot nest or
 * interleave, and a frame's phases interleave pack by pack; timestamps at
 * the boundaries can. A phase's time is the GPU time between its marks,
 * idle gaps included (a GPU waiting for the CPU in the middle of a phase
 * charges the wait to it).
 *
 * The queries of a frame live in one slot of a small ring; they are read
 * when GL says they are available (GL_QUERY_RESULT_AVAILABLE, no wait), at
 * the latest when their slot is needed again `frames` frames later (then it
 * waits for that old frame, which the GPU has long finished in any renderer
 * that reads its images back) or when the caller asks with wait
 * (oit_gpu_timer_poll, at close). Figures come out oldest first, tagged
 * with the frame number oit_gpu_timer_end_frame returned.
 *
 * Where the driver has no timestamps (GL_QUERY_COUNTER_BITS of GL_TIMESTAMP
 * is 0) the timer is absent: every call is a no-op, frame numbers are 0,
 * nothing is ever polled, and oit_gpu_timer_absent says why. No figure is
 * ever made up. A NULL timer is absent too, so callers mark unconditionally.
 * Needs the GL context current on the calling thread for its whole life. */
#ifndef OIT_RENDER_GPU_TIMER_H
#define OIT_RENDER_GPU_TIMER_H

#include <stdint.h>

#include "oit/status.h"

typedef enum oit_gpu_phase {
    OIT_GPU_OTHER = 0, /* the rest: clears, state, saturation tiles, set-up */
    OIT_GPU_UPLOAD,    /* copies into GPU buffers (the ring into the residency cache) */
    OIT_GPU_PASS1,     /* a capture's first geometry pass (DFB: counting) */
    OIT_GPU_PASS2,     /* the second geometry pass (first-K's overflow, DFB's store) */
    OIT_GPU_RESOLVE,   /* sorting and compositing (per batch and the frame's end) */
    OIT_GPU_READBACK,  /* the image and totals back to the host */
    /* the compute capture (capture_compute.h): triangle set-up, tile
     * counts, their prefix sum and the tile lists */
    OIT_GPU_BINNING,
    /* the compute capture's per-tile pass: coverage, order and compositing
     * of every pixel in one dispatch, so one phase */
    OIT_GPU_SWEEP,
    OIT_GPU_PHASES
} oit_gpu_phase;

/* "other", "upload", "pass1", "pass2", "resolve", "readback", "binning",
 * "sweep". */
const char *oit_gpu_phase_name(oit_gpu_phase p);

typedef struct oit_gpu_times {
    uint64_t frame; /* oit_gpu_timer_end_frame's number */
    double ms;      /* first to last timestamp of the frame */
    double phase_ms[OIT_GPU_PHASES];
} oit_gpu_times;

typedef struct oit_gpu_timer_desc {
    int frames; /* ring slots (frames in flight before one is waited for); 0: 4 */
    /* Testing: behave as a driver without timestamps (absent). */
    int no_queries;
} oit_gpu_timer_desc;

typedef struct oit_gpu_timer oit_gpu_timer;

/* desc may be NULL. An absent timer is still made (OIT_OK): see above. */
oit_status oit_gpu_timer_create(const oit_gpu_timer_desc *desc, oit_gpu_timer **out,
                                oit_error *err);
void oit_gpu_timer_destroy(oit_gpu_timer *t);
/* NULL when timestamps are there, else why not ("the driver reports 0
 * timestamp bits", "no timer"). */
const char *oit_gpu_timer_absent(const oit_gpu_timer *t);

/* Starts a frame in phase OIT_GPU_OTHER. A frame still open is ended first. */
void oit_gpu_timer_begin_frame(oit_gpu_timer *t);
/* From here on the frame's GPU work is phase p's (outside a frame: nothing). */
void oit_gpu_timer_mark(oit_gpu_timer *t, oit_gpu_phase p);
/* Ends the frame; returns its number (1, 2, ...; 0: absent or no frame). */
uint64_t oit_gpu_timer_end_frame(oit_gpu_timer *t);
/* The oldest frame whose figures are not yet taken: 1 and *out when they
 * are ready (wait: waits for them), 0 when none is (or none is left). */
int oit_gpu_timer_poll(oit_gpu_timer *t, oit_gpu_times *out, int wait);
/* Frames whose figures were dropped because nobody polled them in time
 * (the ring of results holds `frames` of them). */
uint64_t oit_gpu_timer_dropped(const oit_gpu_timer *t);

#endif
