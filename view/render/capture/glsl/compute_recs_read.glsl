/* compute_recs.glsl's record blocks, read: cs_rec(r, w) is word w of
 * record r (past every block: zeros, never asked for). */
#define CS_RECS_READ_BLOCK(bind, block, recs) \
    layout(std430, binding = bind) readonly buffer block { uvec4 recs[]; };
#define CS_RECS_READ_STEP(bind, block, recs) \
    if (r < u_block_recs) return recs[r * CS_REC + w]; \
    r -= u_block_recs;
CS_RECS_EACH(CS_RECS_READ_BLOCK)
uvec4 cs_rec(uint r, uint w) {
    CS_RECS_EACH(CS_RECS_READ_STEP)
    return uvec4(0u);
}
