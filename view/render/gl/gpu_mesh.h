/* Triangles resident on the GPU, drawn by every GL method with the same
 * vertex layout and the same fragment-generation shader (frag_glsl.h), so
 * that all methods produce bit-identical fragments. */
#ifndef OIT_RENDER_GPU_MESH_H
#define OIT_RENDER_GPU_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_gpu_mesh oit_gpu_mesh;

/* Uploads count triangles. Their primitive indices (the tie-break key) are
 * first_prim + i. Requires a current GL context. */
oit_status oit_gpu_mesh_create(const oit_triangle *tris, size_t count,
                               uint32_t first_prim, oit_gpu_mesh **out,
                               oit_error *err);
/* A mesh over triangles the caller places in its own GL buffer (a streaming
 * ring): it does not own the buffer, and oit_gpu_mesh_set_range re-points it
 * without allocating or calling GL. Empty until set. */
oit_status oit_gpu_mesh_create_view(unsigned buffer, oit_gpu_mesh **out, oit_error *err);
/* count oit_triangle records at byte offset (a multiple of
 * GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT) of a view's buffer; their
 * prims are first_prim + i. Only for views (an owned mesh keeps its
 * range), as is oit_gpu_mesh_set_range_sourced. */
void oit_gpu_mesh_set_range(oit_gpu_mesh *m, uint64_t offset, size_t count, uint32_t first_prim);
/* The same for a sourced range (partfile/triangles.h
 * oit_part_expand_sourced): count triangles at offset, then count u32 at
 * offset + 48 count, the triangles' prims (source indices, < 2^31): drawn
 * with those as the fragments' prims (frag_glsl.h, "Sourced draws"). */
void oit_gpu_mesh_set_range_sourced(oit_gpu_mesh *m, uint64_t offset, size_t count);
/* 1 with the byte offset of the prims when m is a sourced range, else 0. */
int oit_gpu_mesh_sourced(const oit_gpu_mesh *m, uint64_t *prims_offset);
/* Re-points a view at another buffer of the caller's (a streamer draws a part
 * from its upload ring or from its residency cache). Only for views. */
void oit_gpu_mesh_set_buffer(oit_gpu_mesh *m, unsigned buffer);
void oit_gpu_mesh_destroy(oit_gpu_mesh *m);
size_t oit_gpu_mesh_triangles(const oit_gpu_mesh *m);
/* The GPU bytes m holds, as every method's memory figure counts a mesh
 * (oit_frame_stats.gpu_mesh_bytes): its triangle buffer when it owns one
 * (48 bytes a triangle, 16 for an empty mesh) and its draw-record buffer
 * (one oit_draw_rec a draw window; a view's one). A view's triangles are in
 * its owner's buffer (a ring, a cache), which its owner counts. */
uint64_t oit_gpu_mesh_bytes(const oit_gpu_mesh *m);
uint32_t oit_gpu_mesh_first_prim(const oit_gpu_mesh *m);
/* The GL buffer the triangles live in, and the byte offset of the first. */
unsigned oit_gpu_mesh_buffer(const oit_gpu_mesh *m);
uint64_t oit_gpu_mesh_offset(const oit_gpu_mesh *m);

/* For the GL methods: draws the triangles with the bound program built from
 * frag_glsl.h, binding them for vertex pulling (OIT_BIND_VERTS, and
 * OIT_BIND_PRIMS always) and giving the per-draw input OIT_IN_DRAW
 * (frag_glsl.h) from m's record buffer through m's own vertex array, which
 * it binds; no current attribute value is read. Large meshes are drawn in
 * windows that fit the SSBO limit, one glDrawArraysInstancedBaseInstance
 * each; a view writes its record before each window. program is not read
 * (the first prim used to be its uniform); kept so callers need not
 * change. */
void oit_gpu_mesh_draw(const oit_gpu_mesh *m, unsigned program);
/* For tests: binds a sourced view's prims as if
 * GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT were bytes (a multiple of the
 * driver's; anything else restores the driver's), so that a driver's larger
 * alignment, and the prim index it moves into the record, can be tried. */
void oit_gpu_mesh_set_align(oit_gpu_mesh *m, uint64_t bytes);

/* Scratch for oit_gpu_mesh_draw_many: the indirect commands and per-draw
 * records it uploads (grown geometrically, never shrunk), the vertex array
 * that reads the records, and a count of the draw calls made through it.
 * One per owner (a capture); requires a current GL context, which destroy
 * needs too. */
typedef struct oit_gpu_draws oit_gpu_draws;
oit_status oit_gpu_draws_create(oit_gpu_draws **out, oit_error *err);
void oit_gpu_draws_destroy(oit_gpu_draws *d);
/* GL draw commands issued through d since its creation (a multi-draw
 * counts 1). */
uint64_t oit_gpu_draws_calls(const oit_gpu_draws *d);
/* GPU bytes its command and record buffers hold (its owner's footprint). */
uint64_t oit_gpu_draws_bytes(const oit_gpu_draws *d);
/* For tests: the triangles one group may span, rounded down to keep window
 * offsets aligned (at least the alignment's step); 0 restores the driver's
 * window (oit_gpu_triangle_window). Lets a test split groups and window
 * large meshes without buffers of GL_MAX_SHADER_STORAGE_BLOCK_SIZE. */
void oit_gpu_draws_set_window(oit_gpu_draws *d, size_t triangles);
/* For tests: groups are bound as if GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT
 * were bytes (a multiple of the driver's; anything else restores the
 * driver's), as on drivers where it is 32, 64 or 256; the window is
 * recomputed to keep its starts aligned. Mesh offsets must keep it. */
void oit_gpu_draws_set_align(oit_gpu_draws *d, uint64_t bytes);

/* Draws meshes[0..n), in that order, with the bound program built from
 * frag_glsl.h, in few draw calls: consecutive meshes in one GL buffer whose
 * bytes, from the lowest offset rounded down to a multiple of 16 and of
 * GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT to the furthest end, fit one
 * window (oit_gpu_triangle_window) form a group, bound once at
 * OIT_BIND_VERTS and drawn by one glMultiDrawArraysIndirect. A streamer's
 * pack drawn from one ring region, or from its cache, is one group; parts
 * alternating between two buffers make one group per run. A mesh larger
 * than a window is cut into windows that join groups like meshes. A
 * sourced mesh's prims join the group's binding at OIT_BIND_PRIMS under the
 * same window rule; a group without one binds its triangles' range there,
 * so that the binding is never absent or stale. Fragments and primitive
 * ids are those of oit_gpu_mesh_draw on each mesh in turn.
 * Empty meshes draw nothing. Mesh offsets must keep the alignment (as
 * oit_gpu_mesh_set_range requires). Leaves d's vertex array and indirect
 * buffer bound.
 * Never an error: should d's scratch not grow to the call's commands, it
 * draws them in runs that fit (more calls, same fragments). */
void oit_gpu_mesh_draw_many(oit_gpu_draws *d, const oit_gpu_mesh *const *meshes, int n);
/* The same, each command drawn only when uint `word` of the GL buffer
 * gate is nonzero when the GPU reaches it (its instance count set on the
 * GPU: the host never reads the word); the draw calls count as issued
 * either way. The caller's program and storage bindings are kept. */
void oit_gpu_mesh_draw_many_gated(oit_gpu_draws *d, const oit_gpu_mesh *const *meshes, int n,
                                  unsigned gate, unsigned word);

/* For compute passes with one invocation per triangle: binds each of those
 * windows at OIT_BIND_VERTS, sets the uints u_window_first (the window's
 * first triangle, counted within the mesh) and u_window_count, and
 * dispatches groups of 'local' invocations over it, in rows of at most
 * 65535 groups: invocation i = gl_GlobalInvocationID.y * 65535 * local +
 * gl_GlobalInvocationID.x handles triangle i of the window (skip
 * i >= u_window_count). */
void oit_gpu_mesh_dispatch(const oit_gpu_mesh *m, unsigned program, unsigned local);

/* Triangles one storage binding holds with its offset aligned: the window
 * of oit_gpu_mesh_draw, oit_gpu_mesh_dispatch and (unless a test set
 * another) oit_gpu_mesh_draw_many, for buffers laid out like a mesh's. */
size_t oit_gpu_triangle_window(void);
/* The fewest triangles whose bytes are a multiple of `align`: windows,
 * chunks and groups that start that many triangles apart keep a binding
 * offset aligned. */
size_t oit_gpu_triangle_step(uint64_t align);

/* oit_glsl_raster_begin, then draws meshes[0..n) with prog clipped to the
 * GL rect r (bottom rows first, exclusive ends), in as few draw calls as
 * oit_gpu_mesh_draw_many makes of them with the scratch of draws. */
void oit_glsl_draw_scissored(unsigned fbo, int w, int h, unsigned prog, oit_gpu_draws *draws,
                             const oit_gpu_mesh *const *meshes, int n, const int r[4]);
/* The same, drawn only where the uint `word` of the buffer `gate` is
 * nonzero when the GPU reaches it (oit_gpu_mesh_draw_many_gated). */
void oit_glsl_draw_scissored_gated(unsigned fbo, int w, int h, unsigned prog,
                                   oit_gpu_draws *draws,
                                   const oit_gpu_mesh *const *meshes, int n,
                                   const int r[4], unsigned gate, unsigned word);

#ifdef __cplusplus
}
#endif
#endif
