/* Paged per-pixel linked lists (Crassin 2010), exact: pages of
 * four fragment slots instead of single nodes, so one link and one atomic
 * allocation serve four fragments and a pixel's fragments sit together.
 *
 * Per pixel one head word packs the newest page and how many of its slots
 * are taken: word = page * 4 + (taken - 1), which is also the node index of
 * the newest fragment; 0xffffffff (no page) reads as a full page. A fragment
 * claims the next slot with a compare-and-swap of that word; when the page
 * is full it first takes a new page from the global atomic page counter and
 * swaps in page * 4 + 0, linking the new page to the old one (pages are
 * chained newest first). Crassin guards this with a per-pixel critical
 * section; the swap is our choice instead because it is lock-free (no
 * fragment waits on another, which GPUs without independent thread
 * scheduling cannot promise) and gives the same layout. Its price: when two
 * fragments of one pixel find a page full at once, both take a page and the
 * loser's stays unused (counted, never linked).
 *
 * Sizing and resolve are PLL's (list_store.h): the page pool starts at one
 * page per four pixels, an overflowing frame (the page counter keeps counting
 * past the pool) grows the pool to the frame's need and is drawn again, so
 * no fragment is dropped; the resolve sorts by (t, prim) and composites
 * exactly like PLL. Memory: 68 bytes per page (4 x 16-byte slots + a link),
 * at most three slots per pixel over PLL's need, plus unused pages.
 *
 * Stats: fragments (stored: all of them), max_layers (longest list),
 * batches = geometry passes drawn, gpu_bytes_peak. */
#ifndef OIT_RENDER_BASELINES_PPLL4_H
#define OIT_RENDER_BASELINES_PPLL4_H

#include "view/render/gl/gpu_mesh.h"

/* A list store (list_store.h) with this method's shaders. */
typedef struct oit_list_store oit_ppll4;

/* Fragment slots the page pool holds now (4 per page; grows with the frames
 * seen). */
uint64_t oit_ppll4_capacity(const oit_ppll4 *p);

#endif
