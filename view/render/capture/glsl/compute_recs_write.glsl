/* compute_recs.glsl's record blocks, writable: the set-up's cs_put(r, w, v)
 * sets word w of record r. */
#define CS_RECS_WRITE_BLOCK(bind, block, recs) \
    layout(std430, binding = bind) writeonly buffer block { uvec4 recs[]; };
#define CS_RECS_WRITE_STEP(bind, block, recs) \
    if (r < u_block_recs) { recs[r * CS_REC + w] = v; return; } \
    r -= u_block_recs;
CS_RECS_EACH(CS_RECS_WRITE_BLOCK)
void cs_put(uint r, uint w, uvec4 v) {
    CS_RECS_EACH(CS_RECS_WRITE_STEP)
}
