/* Dual peeling's back half (dual_peel.h), composited back to front apart
 * from the front state; its merge and final passes share the layout of
 * the buffer that carries it across passes. */
struct back_acc { vec3 C; float T; uint n; };
