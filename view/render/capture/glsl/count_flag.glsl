/* The slot captures' per-pixel counts and totals (overflow, fragments as
 * 64 bits, most layers) and K: every fill counts each fragment exactly,
 * so that its resolve and the frame's end know what a slot array lost. */
layout(std430, binding = OIT_BIND_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = OIT_BIND_TOTALS) buffer Totals { uint overflow; uint f_lo; uint f_hi; uint f_max; };
layout(location = OIT_LOC_K) uniform int u_K;
