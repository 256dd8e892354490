/* The records in up to OIT_COMPUTE_BLOCKS (8) storage blocks, CS_BLOCKS of
 * them (the program's first lines define it: as many as the driver lets a
 * stage bind), u_block_recs records each, so that a batch is not limited
 * to what one binding spans. Block i holds records [i, i + 1) *
 * u_block_recs. GLSL 4.5 indexes an array of blocks only with a
 * dynamically uniform index, and a tile's records may lie in any block, so
 * the block is picked by an if-chain on the record's index; a batch within
 * one binding takes its first branch. cs_rec(r, w): word w of record r
 * (past every block: zeros, never asked for). */
uniform uint u_block_recs;
#if CS_BLOCKS > 0
layout(std430, binding = OIT_BIND_FRAGS) readonly buffer Recs0 { uvec4 recs0[]; };
#endif
#if CS_BLOCKS > 1
layout(std430, binding = OIT_BIND_RECS1) readonly buffer Recs1 { uvec4 recs1[]; };
#endif
#if CS_BLOCKS > 2
layout(std430, binding = OIT_BIND_RECS2) readonly buffer Recs2 { uvec4 recs2[]; };
#endif
#if CS_BLOCKS > 3
layout(std430, binding = OIT_BIND_RECS3) readonly buffer Recs3 { uvec4 recs3[]; };
#endif
#if CS_BLOCKS > 4
layout(std430, binding = OIT_BIND_RECS4) readonly buffer Recs4 { uvec4 recs4[]; };
#endif
#if CS_BLOCKS > 5
layout(std430, binding = OIT_BIND_RECS5) readonly buffer Recs5 { uvec4 recs5[]; };
#endif
#if CS_BLOCKS > 6
layout(std430, binding = OIT_BIND_RECS6) readonly buffer Recs6 { uvec4 recs6[]; };
#endif
#if CS_BLOCKS > 7
layout(std430, binding = OIT_BIND_RECS7) readonly buffer Recs7 { uvec4 recs7[]; };
#endif
uvec4 cs_rec(uint r, uint w) {
#if CS_BLOCKS > 0
    if (r < u_block_recs) return recs0[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 1
    if (r < u_block_recs) return recs1[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 2
    if (r < u_block_recs) return recs2[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 3
    if (r < u_block_recs) return recs3[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 4
    if (r < u_block_recs) return recs4[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 5
    if (r < u_block_recs) return recs5[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 6
    if (r < u_block_recs) return recs6[r * CS_REC + w];
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 7
    if (r < u_block_recs) return recs7[r * CS_REC + w];
    r -= u_block_recs;
#endif
    return uvec4(0u);
}
