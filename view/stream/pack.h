/* Cutting the per-view part order into packs (Wang & Xie, 5.1): parts of the
 * order drawn as one capture batch, earlier packs in front of later ones
 * along every ray. A K-slot pack is exact when no pixel can receive more
 * than K fragments from it, since the batch's per-pixel sort then orders its
 * fragments as the whole order would.
 *  - OIT_RENDER_PACK_BUDGET: a screen grid of 32x32-pixel tiles holds the sum of the
 *    layer bounds of the pack's parts whose rectangle touches the tile; a
 *    part joins while every tile it touches stays <= K.
 *  - OIT_RENDER_PACK_DISJOINT (the paper's rule, Fig. 6): a part joins while its
 *    rectangle does not overlap the bounding rectangle of the pack so far;
 *    with the wave schedule, packs by level instead (the paper's "pack of
 *    the unoccluded parts among those remaining", 5.1): no two parts of a
 *    pack share a pixel, and of two parts that do, the earlier one in the
 *    order is in the earlier pack (pack.c says why that is exact, and the
 *    image the same byte for byte as one part a pack).
 *  - OIT_RENDER_PACK_COUNTED: no layer rule at all, for the counted capture
 *    (view/render/capture/capture_counted.h), which has no per-pixel limit and measures
 *    each pack's fragments before storing them; wide parts join too.
 *  - OIT_RENDER_PACK_FIRSTK: the same packs, for the first-K capture
 *    (view/render/capture/capture_firstk.h), also without a per-pixel limit.
 * The parts are first culled; see oit_render_schedule for the order the packs
 * are then cut from.
 * Rectangles are the projections of the parts' bounding boxes (a box that
 * reaches in front of the near plane covers the screen); a box wholly outside
 * the view volume yields no fragment and is culled, and so is one wholly on
 * the removed side of a section plane (oit_packing.clipped). A pack is also cut where
 * its expanded triangle data would exceed the upload budget.
 * Under the K-slot rules a wide part (layer bound above K, prepare/partition/kd.h)
 * is a pack of its own, captured with that many slots per pixel
 * (oit_capture_batch_layers). */
#ifndef OIT_STREAM_PACK_H
#define OIT_STREAM_PACK_H

#include "oit/partfile.h"
#include "oit/render_modes.h"
#include "view/render/image/view.h"

/* The pack modes are liboit's (oit/render_modes.h, oit_render_pack):
 * OIT_RENDER_PACK_COUNTED takes the counted capture, OIT_RENDER_PACK_FIRSTK
 * the first-K capture, BUDGET and DISJOINT the K-slot array.
 * OIT_RENDER_PACK_AUTO (0) is for the streamer to resolve (streamer.h); the
 * packer takes only the others. */

/* The order packs are cut from (oit_render_schedule). OIT_RENDER_SCHEDULE_TREE
 * (default): consecutive parts of partfile/order.h's order.
 * OIT_RENDER_SCHEDULE_WAVE: packs filled from a front-to-back wavefront over the screen (view/stream/schedule.h), each tile
 * holding the layers of the rule above (the disjoint rule: by level, as
 * above, a pack per level of the parts that share pixels; the 1M plant's
 * guaranteed scheme at 512x512: 7,380 packs where the tree cuts 61,790);
 * about 40% fewer packs, but their
 * parts are scattered, so each pack's resolve rectangle is larger. On
 * llvmpipe, where resolving a rectangle costs more than a pack's fixed
 * overhead, the tree order is faster (bunny and plant100k at 512x512). */

/* GPU bytes a part takes in the upload ring: its triangles expanded to the
 * 48-byte oit_triangle and their 4-byte source indices after them
 * (oit_part_expand_sourced), rounded up to OIT_PACK_ALIGN. */
#define OIT_PACK_ALIGN 256u
uint64_t oit_pack_part_bytes(const oit_partfile_part *p);

typedef struct oit_packing {
    const uint32_t *parts;      /* the parts to draw, in order (culled ones left out) */
    uint32_t part_count;
    const uint32_t *pack_first; /* pack i: parts[pack_first[i] .. pack_first[i+1]) */
    const int (*rects)[4];      /* pack i's screen rectangle, as oit_capture_batch reads */
    const int (*part_rects)[4]; /* parts[j]'s own screen rectangle */
    const uint64_t *bytes;      /* pack i's upload bytes */
    const uint32_t *layers;     /* pack i's fragments per pixel at most: K, or a wide part's */
    uint32_t pack_count;
    uint32_t culled;            /* boxes outside the view volume */
    /* Boxes in the view volume but wholly on the removed side of a section
     * plane (oit_view.clip, view/render/image/clip.h), and the bytes they would have
     * written into the upload ring (as bytes_uploaded counts them, without
     * the ring's alignment): neither uploaded nor drawn. */
    uint32_t clipped;
    uint64_t clipped_bytes;
} oit_packing;

typedef struct oit_packer oit_packer;

#define OIT_PACK_MAX_LAYERS 64u /* = OIT_CAPTURE_MAX_LAYERS */

/* Fails (OIT_ERR_UNSUPPORTED) when a part's layer bound exceeds
 * OIT_PACK_MAX_LAYERS or a part alone exceeds byte_budget, naming the part. */
oit_status oit_packer_create(const oit_partfile *pf, oit_render_pack mode, int K,
                             uint64_t byte_budget, oit_packer **out, oit_error *err);
void oit_packer_destroy(oit_packer *pk);
void oit_packer_set_schedule(oit_packer *pk, oit_render_schedule schedule);
/* Front first, for early termination with the unbounded modes (COUNTED,
 * FIRSTK; the tree schedule): packs are also cut by depth, pack i taking at
 * most K * 2^i layer bounds on any 32x32 tile (the budget rule's sums; a
 * pack's first part always joins). The first packs of a frame then lay the
 * front layers over the whole screen, so pixels saturate (view/render/
 * saturation.h) before the parts behind them are read, while a pixel of
 * depth D is spread over about log2(D / K) packs, not D / K. */
void oit_packer_set_front_first(oit_packer *pk, int on);

/* Packs order[0..n) for view. The arrays in out belong to the packer and
 * stay valid until the next call. */
oit_status oit_packer_run(oit_packer *pk, const oit_view *view, const uint32_t *order,
                          uint32_t n, oit_packing *out, oit_error *err);

#endif
