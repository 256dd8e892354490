/* The first-K capture's pass-2 totals (capture_firstk.c's TOTALS_BYTES and
 * W_* name its words) at a binding no other program of a pack uses while
 * they are live: overflowed pixels, their fragments as 64 bits, the gate
 * of pass 2's draw (ahead mode), the GL rect that holds them (x0, y0, x1,
 * y1; exclusive ends), so that pass 2 works only there; then the frame's
 * words (oit_firstk_begin) and pass 2's dispatch (ahead mode). */
layout(std430, binding = OIT_BIND_SUMS) buffer Spill { uint spill_pixels; uint spill_lo; uint spill_hi; uint gate; uint box[4]; uint frame_short; uint need; uint second_pixels; uint second_packs; uvec4 groups; };
ivec4 oit_box() { return ivec4(box[0], box[1], box[2], box[3]); }
void oit_spill(uvec2 px) {
    atomicAdd(spill_pixels, 1u);
    atomicMin(box[0], px.x); atomicMin(box[1], px.y);
    atomicMax(box[2], px.x + 1u); atomicMax(box[3], px.y + 1u);
}
