/* Binding points: every storage-buffer binding, texture unit and image unit
 * that a GLSL program shares with the C code that binds its resources, in
 * one list, so that the two sides cannot drift apart. The C side gets each
 * entry as an enumerator; every program gets the same entries as GLSL
 * #defines (OIT_GLSL_BINDINGS, which oit_glsl_version carries right after
 * its #version line, so they precede every other line of every program).
 * Shaders write layout(std430, binding = OIT_BIND_FRAGS) and the driver's
 * preprocessor puts in the number that glBindBufferBase(...,
 * OIT_BIND_FRAGS, ...) binds. Neither side spells a binding as a number:
 * tests/view/render/test_glsl_bindings.sh fails on one, naming file and line.
 *
 * GL numbers three kinds of binding point separately; the prefix tells the
 * kind: OIT_BIND_ storage buffers, OIT_TEX_ texture units (sampler
 * bindings), OIT_IMG_ image units. A storage binding is named for what most programs
 * keep there; the others reuse the slot for a buffer of the same kind under
 * a block name of their own, listed below, and bind it under the same
 * enumerator. Texture and image units are named for what they hold; names
 * that share a number are never used by the same program.
 *
 * The contract, entry by entry (which stage reads or writes it):
 *
 * OIT_BIND_VERTS    the triangle soup, 16-byte vertices (gpu_mesh.h): the
 *                   vertex stage of every raster pass (oit_glsl_vertex);
 *                   F2B's key and gather compute passes.
 * OIT_BIND_COUNTS   per-pixel fragment counts: the count and store fragment
 *                   stages and resolves of DFB, B3D and the captures (GLSL,
 *                   counted, first-k). Also list heads (PPLL, PPLL4,
 *                   guarded: append fragment stage, resolve walk), the data
 *                   a prefix sum scans in place (scan_glsl.c), the
 *                   fragment counters of depth and dual peeling (merge,
 *                   final), and F2B's sort keys (key pass).
 * OIT_BIND_OFFSETS  per-pixel offsets into OIT_BIND_FRAGS (DFB and capture
 *                   store and resolve); first-k's segment table
 *                   (allocation, store, segment resolve); F2B's ranks
 *                   (gather).
 * OIT_BIND_FRAGS    the stored fragments: DFB's and the captures' store
 *                   fragment stages and resolves, list nodes and slots
 *                   (PPLL, PPLL4, guarded), F2B's sorted triangles (gather).
 * OIT_BIND_OUT      the frame's rgba, written by every resolve or final
 *                   compute pass; the stencil self-test's prims
 *                   (capture.c); test_gpu_draws' accumulation.
 * OIT_BIND_TOTALS   the capture's totals and overflow flag, the prefix
 *                   sum's totals (scan_glsl.c); the links of PPLL, PPLL4
 *                   and guarded (append, resolve walk); the counted
 *                   capture's next counts (its predicted resolve).
 * OIT_BIND_STATE    the per-pixel compositing state (oit_glsl_state_io:
 *                   the captures' and DFB's resolves to state, saturation,
 *                   liboit's blend into the caller's framebuffer; depth and
 *                   dual peeling's merge and final passes); the list
 *                   methods' and B3D's statistics (counter, longest list,
 *                   total).
 * OIT_BIND_SUMS     the prefix sum's block sums (scan_glsl.c); first-k's
 *                   spill counters; dual peeling's back accumulators (merge,
 *                   final); saturation's tile maxima (saturation.c).
 * OIT_BIND_PRIMS    the source index of each triangle of a sourced draw:
 *                   the vertex stage (frag_glsl.h, "Primitive id").
 * OIT_BIND_OPAQUE_TILES  the opaque depth's tile maxima (opaque_tiles.c,
 *                   compute): a slot no other program uses, so that it
 *                   needs none of the caller's bindings (opaque_tiles.h).
 * OIT_BIND_RECS1..7 the compute capture's triangle records past the first
 *                   binding's (which is OIT_BIND_FRAGS): blocks 1..7 of a
 *                   batch too large for one binding (glsl/compute_recs_*.glsl,
 *                   set-up, scatter and sweep). Consecutive numbers.
 *
 * OIT_TEX_ACCUM     F2B's accumulation (final pass) and its copy after the
 *                   last chunk (blend fragment stage); WBOIT's
 *                   accumulation (resolve).
 * OIT_TEX_REVEAL    WBOIT's revealage (resolve).
 * OIT_TEX_LAYER     depth peeling's layers (peel fragment stage: the last
 *                   layer; merge: the new one); dual peeling's (-near, far)
 *                   pairs (peel fragment stage, merge).
 * OIT_TEX_SAMPLES   the stencil-routed capture's multisampled fragments
 *                   (resolve, stencil self-test).
 * OIT_TEX_OPAQUE_DEPTH  the caller's opaque depth: every fragment stage
 *                   built on oit_glsl_fragment_gen (oit_behind_opaque) and
 *                   the opaque tiles' compute pass. Apart from the units
 *                   above, which passes that read it also bind; liboit
 *                   gives the caller's binding of this unit back, and
 *                   liboit.h tells callers its number.
 * OIT_TEX_OPAQUE_KEYS  the least key of the opaque triangles' fragments
 *                   per pixel (opaque_keys.h): every fragment stage built
 *                   on oit_glsl_fragment_gen (oit_behind_opaque) where
 *                   the shading has opaque triangles; liboit gives the
 *                   caller's binding of this unit back too.
 *
 * OIT_IMG_OUT       the rgba32f result of F2B's final pass and WBOIT's
 *                   resolve.
 * OIT_IMG_SLOTS     B3D's slot array (store fragment stage, resolve).
 * OIT_IMG_FRONT     dual peeling's front layer (peel fragment stage writes,
 *                   merge reads).
 * OIT_IMG_BACK      dual peeling's back layer (the same).
 */
#ifndef OIT_RENDER_GLSL_BINDINGS_H
#define OIT_RENDER_GLSL_BINDINGS_H

/* X(name, number): the number must be a decimal literal, since the GLSL
 * side is its spelling (#number), not its value. */
#define OIT_GLSL_BINDING_LIST(X) \
    X(OIT_BIND_VERTS, 0)         \
    X(OIT_BIND_COUNTS, 1)        \
    X(OIT_BIND_OFFSETS, 2)       \
    X(OIT_BIND_FRAGS, 3)         \
    X(OIT_BIND_OUT, 4)           \
    X(OIT_BIND_TOTALS, 5)        \
    X(OIT_BIND_STATE, 6)         \
    X(OIT_BIND_SUMS, 7)          \
    X(OIT_BIND_PRIMS, 8)         \
    X(OIT_BIND_OPAQUE_TILES, 9)  \
    X(OIT_BIND_RECS1, 10)        \
    X(OIT_BIND_RECS2, 11)        \
    X(OIT_BIND_RECS3, 12)        \
    X(OIT_BIND_RECS4, 13)        \
    X(OIT_BIND_RECS5, 14)        \
    X(OIT_BIND_RECS6, 15)        \
    X(OIT_BIND_RECS7, 16)        \
    X(OIT_TEX_ACCUM, 0)          \
    X(OIT_TEX_REVEAL, 1)         \
    X(OIT_TEX_LAYER, 0)          \
    X(OIT_TEX_SAMPLES, 0)        \
    X(OIT_TEX_OPAQUE_DEPTH, 7)   \
    X(OIT_TEX_OPAQUE_KEYS, 6)    \
    X(OIT_IMG_OUT, 0)            \
    X(OIT_IMG_SLOTS, 0)          \
    X(OIT_IMG_FRONT, 0)          \
    X(OIT_IMG_BACK, 1)

#define OIT_GLSL_BINDING_ENUM_(name, n) name = n,
enum { OIT_GLSL_BINDING_LIST(OIT_GLSL_BINDING_ENUM_) };

/* "#define OIT_BIND_VERTS 0\n..." for the GLSL preprocessor. */
#define OIT_GLSL_BINDING_DEFINE_(name, n) "#define " #name " " #n "\n"
#define OIT_GLSL_BINDINGS OIT_GLSL_BINDING_LIST(OIT_GLSL_BINDING_DEFINE_)

#endif
