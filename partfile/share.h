/* Shares of a part file for sort-last rendering over several processes
 * (oitstream-mpi, liboit's oit_scene_desc.share_*): each of N shares is one
 * whole subtree of the management tree, and a view orders the shares
 * without looking at a triangle.
 *
 * The tree is order.h's: each grid an implicit kd-tree over its cell index
 * ranges (oit_order_split_range), a leaf cell with a subgrid continuing into
 * that subgrid's tree. Shares are cut from the root down: a node given r
 * shares passes them to its two halves in proportion to their triangles
 * (the split that makes the larger of triangles / shares least), one share
 * to a node ends the descent, and a node that cannot be split (a leaf cell:
 * one part, or the two of a slab) gives its parts to its first share and
 * leaves the rest empty. So every share is one node of the tree: a cell
 * range, a box bounded by the tree's planes.
 *
 * Why that orders the shares for any view: order.c emits a node's parts
 * contiguously (the near half, then the far half, recursively), so in the
 * part order of ANY eye or direction each share's parts form one run, and
 * the runs' order is a visibility order of the shares: a ray meets the
 * shares' content in that order, because it meets the parts in the part
 * order. A share made of two nodes that are not siblings would not do: with
 * leaves ((1,2),(3,4)), a share {1,2,3} is interleaved with {4} by any view
 * whose root puts (3,4) first (3, 4, 1, 2). oit_shares_order reads the
 * shares' order off a part order by first appearance; empty shares (and
 * shares no part of the order reached) follow, in index order, where they
 * change nothing in a blend.
 *
 * Contract: as order.h, every part in exactly one leaf cell; a part listed
 * by cells of two shares is refused. */
#ifndef OIT_PARTFILE_SHARE_H
#define OIT_PARTFILE_SHARE_H

#include <stdint.h>

#include "oit/partfile.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 4096: far beyond the 16-node runs the design is for, small enough that a
 * per-view order of the shares is a trivial cost. */
#define OIT_SHARES_MAX 4096u
/* Part index of no share: a part no cell lists (never drawn). */
#define OIT_SHARE_NONE UINT32_MAX

typedef struct oit_shares oit_shares;

/* The one check of a share's numbers (the streamer's desc, liboit's
 * oit_scene_desc): count 0 or 1 (no shares) with index 0, or count
 * 2..OIT_SHARES_MAX with index below it. The message names pf and both. */
oit_status oit_shares_check(const oit_partfile *pf, uint32_t count, uint32_t index,
                            oit_error *err);

/* count 1..OIT_SHARES_MAX; pf must outlive the shares only for the call. */
oit_status oit_shares_create(const oit_partfile *pf, uint32_t count, oit_shares **out,
                             oit_error *err);
void oit_shares_destroy(oit_shares *s);

uint32_t oit_shares_count(const oit_shares *s);
/* The share of part p (< the file's part count), or OIT_SHARE_NONE. */
uint32_t oit_shares_of_part(const oit_shares *s, uint32_t part);
/* Parts and triangles of share i. */
uint32_t oit_shares_parts(const oit_shares *s, uint32_t share);
uint64_t oit_shares_triangles(const oit_shares *s, uint32_t share);

/* The shares front to back for the view whose part order (oit_order_compute
 * or _parallel, front to back; culled orders work too, with the shares
 * they leave out following) is parts[0..n): writes oit_shares_count(s)
 * share indices into out. */
void oit_shares_order(oit_shares *s, const uint32_t *parts, uint32_t n, uint32_t *out);

#ifdef __cplusplus
}
#endif
#endif
