/* Which K-slot fill a capture gets (auto, stencil or array): the
 * stencil-routed A-buffer where its self-test passes on this driver,
 * array slots otherwise. Decided without GL: the self-test comes in as a
 * function, so that tests can inject its verdicts (capture.h's
 * oit_capture_create runs it with the real one).
 *
 * The tries: K first; where the capture may route fewer samples than K
 * (first-K's pass 1: pixels of more take the second pass, exact either
 * way) each power of two below K down to 2, the first that passes taken.
 * K-slot packs may not (a part of K layers would lose fragments), so they
 * try K alone. */
#ifndef OIT_RENDER_CAPTURE_CHOICE_H
#define OIT_RENDER_CAPTURE_CHOICE_H

#include "oit/render_modes.h"
#include "oit/status.h"

/* The capture's K, fragments a pixel a batch: the one range, and its one
 * check, which liboit runs on the value it was given, named in its
 * spelling (what: "oit_renderer_desc.K", a tool's flag; NULL:
 * "capture: K"). */
#define OIT_CAPTURE_K_MIN OIT_RENDER_K_MIN
#define OIT_CAPTURE_K_MAX OIT_RENDER_K_MAX
oit_status oit_capture_k_check(long long K, const char *what, oit_error *err);

/* The self-test at stencil_k samples: OIT_OK when it passes (the try may
 * keep what it built), else the reason in err. */
typedef oit_status (*oit_capture_try)(void *ctx, int stencil_k, oit_error *err);

typedef struct oit_capture_choice {
    oit_render_capture asked; /* AUTO, ARRAY or STENCIL (COMPUTE: no choice) */
    oit_render_capture slots; /* what runs: ARRAY or STENCIL */
    int stencil_k;          /* STENCIL: the samples routed a pixel; else 0 */
    /* the self-test's reason at K where auto fell back to array slots or
     * took fewer samples than K; "" where it did not */
    char reason[512];
} oit_capture_choice;

/* asked: OIT_RENDER_CAPTURE_AUTO, _ARRAY or _STENCIL (else OIT_ERR_ARGUMENT).
 * ARRAY tries nothing. STENCIL where no try passes: OIT_ERR_GL (the driver
 * lacks the routing; each try's refusal is OIT_ERR_UNSUPPORTED) whose
 * message gives the self-test's reason at K (no fallback: the caller asked
 * for it). what: the setting in the caller's spelling, for the
 * errors ("oit_renderer_desc.capture"; NULL: "capture"). */
oit_status oit_capture_choose(oit_render_capture asked, const char *what, int K, int fewer_ok,
                              oit_capture_try try_stencil, void *ctx, oit_capture_choice *out,
                              oit_error *err);

/* "auto", "array", "stencil", "compute": the figures' names of what was
 * asked (oit_stream_frame_stats.capture_asked); NULL for no such value. */
const char *oit_capture_asked_name(oit_render_capture asked);

#endif
