/* Guarded OIT (Petrescu et al.): per-pixel linked lists whose
 * append culls fragments that cannot matter. APPROXIMATE for threshold > 0;
 * with threshold 0 nothing is culled and it is PLL, exact.
 *
 * Per fragment S, as the seed's pseudo code: if the pixel has no head, S
 * becomes the head; if S is nearer than the head H (by (t, prim)), S becomes
 * the head and is stored; otherwise S is culled when its importance with H
 * in front, a_S * (1 - a_H), is below the threshold (the 1-guard), or when
 * the pixel's next stored element K lies in front of S too and
 * a_S * (1 - a_H) * (1 - a_K) is below it (the 2-guard); else S is stored.
 * The resolve is PLL's: sort by (t, prim), composite per shade.h.
 *
 * Choices where the seed is open, and why:
 * - Importance is the seed's Contrib = C * A * vis with the colour C taken
 *   at its bound 1. A culled fragment changes its pixel by its own colour
 *   and by the light it would have blocked from behind; both are at most
 *   a_S * vis per channel, so this makes the threshold an error bound: each
 *   culled fragment moves its pixel (transparent shading) by less than the
 *   threshold, and a pixel by less than threshold x its culled fragments.
 *   vis uses only H and K, which are stored and in front of S, so it is
 *   never below S's true visibility among the stored fragments: the test is
 *   conservative. A colour-weighted importance (the seed's remark that
 *   poorly lit fragments matter little) would cull dark but opaque
 *   fragments and lose what they hide, without bound.
 * - The seed keeps the head in a separate buffer under a per-pixel
 *   spinlock. Here every stored fragment goes into the pixel's PLL list
 *   (atomic exchange) and a second head word points at the nearest stored
 *   node, moved by compare-and-swap: lock-free, so no fragment waits on
 *   another (a spinning fragment can starve the one holding the lock on
 *   GPUs without independent thread scheduling). K is the list's newest
 *   node when that is not H (its link may not be written yet, so the guard
 *   never follows links).
 * - Default threshold 0.0025, the seed's "0.25% of the pixel value".
 *
 * Translucent shading: the resolve is exact for what is stored, but the
 * bound above covers colour and transmittance only, not absorption between
 * surfaces (a culled face also changes the nesting).
 *
 * Memory: PLL's, minus the culled fragments, plus one word per pixel.
 * Sizing as PLL (list_store.h), except that a pass which overflowed counts
 * too much (guards whose nodes fell past the pool could not cull), so the
 * pool at most doubles per pass instead of growing to that count: the first
 * deep frame takes a few passes, and the pool ends near the culled need
 * (within 2x) instead of near PLL's.
 *
 * Stats: fragments = fragments stored (generated minus culled), max_layers
 * (longest list), batches = geometry passes, gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_GUARDED_H
#define OIT_RENDER_BASELINES_GUARDED_H

#include "view/render/gl/gpu_mesh.h"

#define OIT_GUARDED_DEFAULT_THRESHOLD 0.0025f

/* A list store (list_store.h) with the guard's shaders. */
typedef struct oit_list_store oit_guarded;

/* Contribution threshold in [0, 1); 0 culls nothing. OIT_ERR_ARGUMENT
 * outside it (NaN included). Holds for the next frames. The method
 * (methods.h) starts at OIT_GUARDED_DEFAULT_THRESHOLD. */
oit_status oit_guarded_set_threshold(oit_guarded *g, float threshold, oit_error *err);

#endif
