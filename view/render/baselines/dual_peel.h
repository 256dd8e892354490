/* Dual depth peeling (Bavoil & Myers 2008): each geometry pass peels the
 * nearest and the farthest layer that are left, so L layers take
 * 1 + max(1, ceil(L / 2)) passes where front-to-back peeling (depth_peel.h)
 * takes L + 1.
 *
 * A first pass writes (-t, t) of every fragment into an RG32F target with
 * MAX blending, giving (-nearest, farthest) per pixel. Each peel pass reads
 * the previous pass's pair: a fragment outside [nearest, farthest] was
 * peeled already and is discarded; one at exactly the nearest (farthest) t
 * is this pass's front (back) layer and stores its packed fragment into a
 * front (back) image; one strictly inside writes its (-t, t) for the next
 * pass. A compute pass then composites the front layer behind the front
 * state, front to back per shade.h, and the back layer in front of a back
 * accumulation, back to front (C = a c + (1 - a) C, T *= 1 - a); the frame
 * is C_front + T_front * (C_back + T_back * background). Peeling stops
 * when an occlusion query says no fragment was left inside. t is the same
 * float the other methods sort by (no depth-buffer quantization), so the
 * peeled order is t's order exactly.
 *
 * Exact, equal to DFB's (t, prim) order within float rounding of the two
 * association orders, whenever no pixel has two fragments at bitwise-equal
 * t. Where it has (coplanar or shared-edge fragments), the tied fragments
 * all store into the same layer image, one of them wins (the last one
 * written, not the lowest prim as DFB's order would put first) and the next
 * pass discards the rest because their t is no longer inside: those
 * fragments are LOST, as with depth peeling.
 *
 * Transparent shading only: translucent absorption between layers needs the
 * nest and medium of everything in front, which the back-to-front half does
 * not know, so a translucent frame fails with OIT_ERR_UNSUPPORTED.
 *
 * Memory does not grow with depth: per pixel two RG32F targets, two
 * RGBA32UI layer images, the front state (48 bytes), the back accumulation
 * (32) and the output (16).
 *
 * Stats: fragments = fragments composited (lost ties not counted),
 * max_layers = most composited on one pixel, batches = geometry passes,
 * gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_DUAL_PEEL_H
#define OIT_RENDER_BASELINES_DUAL_PEEL_H

#include "view/render/gl/gpu_mesh.h"

typedef struct oit_dual_peel oit_dual_peel;

#endif
