/* Where to split a kd node (kd.h): the choice of axis and position.
 *
 * Candidates on each axis are the 15 positions lo + (hi - lo) * j / 16 that
 * are exact floats, and every start and end of a piece's box: a plane there
 * cuts nothing that starts or ends on it, so in models of beams, pipes and
 * boxes it slips between objects. A candidate counts only when it leaves a
 * subgrid record whose plane origin + cell_size is exactly the position
 * (docs/part-file.md: a two-cell subgrid may be larger than its parent cell,
 * so an off-centre plane is still one cell boundary).
 *
 * A plane where one piece has a triangle in its upper face and another one
 * in its lower face does not qualify: the two may coincide, and as two
 * parts their tie would be resolved by pack order rather than by primitive
 * id as in every other exact method.
 *
 * Each piece is summarised by its box and weight (its layers in the node);
 * a candidate sends a piece below when it starts below the plane or ends on
 * it, above when it ends above it, both when it straddles. The cost of a
 * candidate is the least number of parts its halves could become,
 * ceil(below / K) + ceil(above / K): it rewards splits that leave full parts
 * (a piece peeled off alone would be a part of its own) and, at equal count,
 * cutting less weight (every cut piece is clipped and counted twice), then
 * balance. Only candidates that lower the larger half's weight below the
 * node's qualify, and in a node heavier than 4K only those whose larger half
 * keeps at most 3/4 of the weight (so the depth stays logarithmic). When
 * none qualifies the caller falls back to the midplane.
 */
#ifndef OIT_PARTITION_KD_SPLIT_H
#define OIT_PARTITION_KD_SPLIT_H

#include <stdint.h>

typedef struct oit_kd_piece_box {
    float lo[3], hi[3];
    uint32_t weight; /* 1 (planar in the node) or 2 */
    /* bit a: a triangle of the piece lies in its box's lower (upper) face
     * on axis a */
    uint8_t face_lo, face_hi;
} oit_kd_piece_box;

/* Returns 1 and sets *axis, *pos when a candidate qualifies, 0 when none
 * does, -1 when memory runs out. O(count log count) per axis. */
int oit_kd_choose_split(const oit_kd_piece_box *pieces, uint32_t count, const float lo[3],
                        const float hi[3], uint32_t max_layers, int *axis, float *pos);

/* The subgrid record of a split: a two-cell grid along axis whose inner
 * boundary is pos and which contains [lo, hi]: the half-width is the larger
 * side widened by up to 31 ulps until origin + cell_size rounds to exactly
 * pos. Returns 0 when none does. */
int oit_kd_split_cells(const float lo[3], const float hi[3], int axis, float pos,
                       float origin[3], float cell_size[3]);

#endif
