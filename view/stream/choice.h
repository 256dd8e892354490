/* The automatic pack mode's judge: which capture path a view's next frame
 * takes, from the costs this process measured for that view (no GL here).
 *
 * A view (oit_view_key: the camera, the size, the model matrix and
 * the section planes) keeps, per path, the least wall time of its frames on
 * the host and the least GPU time of those whose timer figures came in
 * (gpu_timer.h: they arrive frames later, never waited for). The least,
 * because a still view's frames do the same work and a shared machine's
 * noise only ever adds to it.
 *
 * A path's cost is its least wall time or, where every measured path has
 * GPU figures, its least frame time over the frames that have one, each
 * the larger of the frame's wall and GPU time (a frame ends when both the
 * host and the GPU are done; a path with no GPU figure is compared on wall
 * time alone, never against a guess).
 *
 * The rule: a new view starts on the path the last view held (the first
 * view: the seed), with no figures. After each frame the caller says which
 * other path a fixed rule suggests (first-K's second-pass share, or the
 * share a counted frame's counts say first-K would send there; a long
 * period's re-check), and that path is probed for one frame unless it is
 * barred. A probe is kept only if its measured cost is lower than the held
 * path's; otherwise the view goes back and the probed path is barred for a
 * number of frames that doubles with each failed probe
 * (OIT_CHOICE_BAR_FIRST up to OIT_CHOICE_BAR_MOST). Bars are the
 * process's, not a view's: the views a session moves between are alike,
 * and a path that lost on one would otherwise be probed again on every new
 * view, a slow frame each. The very first frame carries the process's
 * start-up (programs built, parts read and uploaded): a path measured only
 * there that loses to a probe is not barred, so it is measured again warm
 * at the next suggestion. A held path whose cost rises above another's
 * measured one (late GPU figures, a slower frame) gives way to it. Ties
 * keep the held path. */
#ifndef OIT_STREAM_CHOICE_H
#define OIT_STREAM_CHOICE_H

#include <stddef.h>
#include <stdint.h>

#include "view/render/image/view.h"

typedef enum oit_path {
    OIT_PATH_FIRSTK = 0, /* first-K packs (view/render/capture/capture_firstk.h) */
    OIT_PATH_COUNTED,    /* counted packs (capture_counted.h) */
    OIT_PATHS
} oit_path;

/* "first-k", "counted"; "?" out of range. */
const char *oit_path_name(oit_path p);

#define OIT_CHOICE_VIEWS 4    /* views remembered (bands, stereo, a few) */
#define OIT_CHOICE_PENDING 16 /* frames awaiting their GPU figures */
#define OIT_CHOICE_BAR_FIRST 8u
#define OIT_CHOICE_BAR_MOST 256u

typedef struct oit_path_cost {
    uint32_t frames;     /* frames of the view drawn with the path */
    double wall_ms;      /* their least wall time (frames > 0) */
    uint32_t gpu_frames; /* of those, frames whose GPU figure came in */
    double gpu_ms;       /* their least frame time, each the larger of its
                            wall and GPU time (gpu_frames > 0) */
    int cold;            /* its only frame was the judge's first (start-up) */
} oit_path_cost;

typedef struct oit_choice_view {
    uint64_t key;
    uint64_t used; /* the oit_choice clock at its last frame; 0: free */
    oit_path held; /* the path the view keeps */
    oit_path next; /* the path its next frame takes (held, or a probe) */
    const char *why; /* why next is its path (oit_choice.why) */
    oit_path_cost cost[OIT_PATHS];
} oit_choice_view;

typedef struct oit_choice {
    unsigned candidates; /* 1u << path for each path the capture can take */
    oit_path held;       /* the last view's: where a new view starts */
    uint32_t bar[OIT_PATHS];     /* frames before the path may be probed again */
    uint32_t backoff[OIT_PATHS]; /* the next bar's length */
    oit_choice_view views[OIT_CHOICE_VIEWS];
    uint64_t clock;
    int cur;     /* the view of the frame begun last; -1: none */
    oit_path path; /* the frame's path */
    double wall_ms; /* the wall time of the frame ended last */
    struct {
        uint64_t tag, key;
        oit_path path;
        double wall_ms;
    } pending[OIT_CHOICE_PENDING];
    unsigned pending_next;
    /* Why the frame begun last took its path: "seed" (the first frame),
     * "new view" (the last view's path), "held", "probe" (the fixed rule
     * suggested it and the view had not measured it, or its bar ran out),
     * "kept: measured faster" (the probe before it), "back: measured
     * slower" (the probe before it), "measured faster". */
    const char *why;
} oit_choice;

/* candidates: at least the seed's bit; paths outside it are never taken. */
void oit_choice_init(oit_choice *c, unsigned candidates, oit_path seed);
/* The path of the frame of view key that starts now (c->why says why). */
oit_path oit_choice_begin(oit_choice *c, uint64_t key);
/* The frame begun last ended after wall_ms on the host; suggest: the path
 * the fixed rule would try next (OIT_PATHS: none). Decides the view's
 * next frame. */
void oit_choice_end(oit_choice *c, double wall_ms, oit_path suggest);
/* The frame ended last will have its GPU figure under tag (gpu_timer's
 * frame number; 0: none will come). */
void oit_choice_tag_gpu(oit_choice *c, uint64_t tag);
/* The GPU figure of tag: its view and path take it (unknown tags are
 * dropped). */
void oit_choice_gpu(oit_choice *c, uint64_t tag, double gpu_ms);
/* The measured cost of path p for the frame begun last's view, as the rule
 * compares it against the held path's; < 0: not measured. */
double oit_choice_cost(const oit_choice *c, oit_path p);
/* "first-k 812.0 ms, counted 1650.0 ms" (unmeasured: "-") for the frame
 * begun last's view, in out (always terminated). */
void oit_choice_describe(const oit_choice *c, char *out, size_t n);

#endif
