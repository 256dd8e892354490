/* compute_recs_read.glsl's record blocks (it says why there are several),
 * writable: the set-up's cs_put(r, w, v) sets word w of record r. */
uniform uint u_block_recs;
#if CS_BLOCKS > 0
layout(std430, binding = OIT_BIND_FRAGS) writeonly buffer Recs0 { uvec4 recs0[]; };
#endif
#if CS_BLOCKS > 1
layout(std430, binding = OIT_BIND_RECS1) writeonly buffer Recs1 { uvec4 recs1[]; };
#endif
#if CS_BLOCKS > 2
layout(std430, binding = OIT_BIND_RECS2) writeonly buffer Recs2 { uvec4 recs2[]; };
#endif
#if CS_BLOCKS > 3
layout(std430, binding = OIT_BIND_RECS3) writeonly buffer Recs3 { uvec4 recs3[]; };
#endif
#if CS_BLOCKS > 4
layout(std430, binding = OIT_BIND_RECS4) writeonly buffer Recs4 { uvec4 recs4[]; };
#endif
#if CS_BLOCKS > 5
layout(std430, binding = OIT_BIND_RECS5) writeonly buffer Recs5 { uvec4 recs5[]; };
#endif
#if CS_BLOCKS > 6
layout(std430, binding = OIT_BIND_RECS6) writeonly buffer Recs6 { uvec4 recs6[]; };
#endif
#if CS_BLOCKS > 7
layout(std430, binding = OIT_BIND_RECS7) writeonly buffer Recs7 { uvec4 recs7[]; };
#endif
void cs_put(uint r, uint w, uvec4 v) {
#if CS_BLOCKS > 0
    if (r < u_block_recs) { recs0[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 1
    if (r < u_block_recs) { recs1[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 2
    if (r < u_block_recs) { recs2[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 3
    if (r < u_block_recs) { recs3[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 4
    if (r < u_block_recs) { recs4[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 5
    if (r < u_block_recs) { recs5[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 6
    if (r < u_block_recs) { recs6[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
#if CS_BLOCKS > 7
    if (r < u_block_recs) { recs7[r * CS_REC + w] = v; return; }
    r -= u_block_recs;
#endif
}
