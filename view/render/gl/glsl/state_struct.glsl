/* The per-pixel state carried across batches, in registers; guarded,
 * since the state's I/O and compositing both declare it. */
#ifndef OIT_STATE_STRUCT
#define OIT_STATE_STRUCT 1
struct oit_state { vec3 C; float t_prev; vec3 T; int nest; vec3 medium; uint nfrag; };
#endif
