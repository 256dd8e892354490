/* GLSL of the capture backends (capture.h): the fragment stages that fill
 * the K-fragment A-buffer (array slots or routed MSAA samples), the per-batch
 * resolve that sorts and composites into the carried per-pixel state, and
 * the begin/end passes over that state. Each is the text of files of
 * glsl/, embedded at build time (CMakeLists.txt: which files, in which
 * order), the programs' own comments in those files. */
#ifndef OIT_RENDER_CAPTURE_GLSL_H
#define OIT_RENDER_CAPTURE_GLSL_H

#ifdef __cplusplus
extern "C" {
#endif

/* Fragment stage, with the per-pixel state struct: bool oit_saturated(uint
 * p), the early-termination test against uniform float u_epsilon (true
 * only when u_epsilon > 0 and pixel p's carried transmittance is below it
 * in every channel); reads the state at OIT_BIND_STATE. */
extern const char oit_capture_saturated[];
/* `uniform int u_mode` at OIT_LOC_MODE, for a compute stage that reads the
 * state (oit_glsl_state_io) without oit_glsl_composite. */
extern const char oit_capture_mode[];
/* Array backend: slot by atomic counter, overflow counted once per pixel. */
extern const char oit_capture_array_fs[];
/* Wide batches: u_W slots per pixel of the tile u_tile (capture.h). */
extern const char oit_capture_wide_fs[];
/* Stencil backend: the fragment is the colour output; counts as above.
 * Prefix "#define OIT_FIRSTK_PASS 1" for first-K's pass 1 (no overflow
 * flag), "#define OIT_ROUTE_BY_COPY 1" for routing by copies (testing,
 * capture_stencil.h): oit_capture_routed_fill. */
extern const char oit_capture_stencil_fs[];
/* Routing by copies: one sample's copy from the fill's slots. */
extern const char oit_capture_route_copy_fs[];
/* The routing set-up's fragment stage, which writes nothing. */
extern const char oit_capture_route_setup_fs[];
/* Resolve over the batch rect; prefix "#define OIT_STENCIL 1" for samples,
 * "#define OIT_WIDE N" for a wide tile (u_rect is the tile, N >= u_W). */
extern const char oit_capture_resolve_cs[];
extern const char oit_capture_end_cs[];
/* Full-screen triangle for the stencil initialisation. */
extern const char oit_capture_fullscreen_vs[];
/* The counted capture (capture_counted.h): count and store fragment stages
 * (after oit_glsl_fragment_gen), and the resolve in two halves around
 * oit_glsl_segment_composite (after oit_glsl_composite). */
extern const char oit_capture_counted_count_fs[];
extern const char oit_capture_counted_store_fs[];
extern const char oit_capture_counted_resolve_cs[];
extern const char oit_capture_counted_resolve_main[];
/* Its predicted bands: the store fragment stage (after
 * oit_glsl_fragment_gen) and the resolve in two halves around
 * oit_glsl_segment_composite (after oit_glsl_composite and
 * oit_glsl_state_io). */
extern const char oit_capture_counted_predicted_fs[];
extern const char oit_capture_counted_predicted_cs[];
extern const char oit_capture_counted_predicted_main[];

#ifdef __cplusplus
}
#endif
#endif
