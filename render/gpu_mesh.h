/* Triangles resident on the GPU, drawn by every GL method with the same
 * vertex layout and the same fragment-generation shader (frag_glsl.h), so
 * that all methods produce bit-identical fragments. */
#ifndef OIT_RENDER_GPU_MESH_H
#define OIT_RENDER_GPU_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "view.h"

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
 * without allocating. Empty until set. */
oit_status oit_gpu_mesh_create_view(unsigned buffer, oit_gpu_mesh **out, oit_error *err);
/* count oit_triangle records at byte offset (a multiple of
 * GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT) of a view's buffer. */
void oit_gpu_mesh_set_range(oit_gpu_mesh *m, uint64_t offset, size_t count, uint32_t first_prim);
/* Re-points a view at another buffer of the caller's (a streamer draws a part
 * from its upload ring or from its residency cache). Only for views. */
void oit_gpu_mesh_set_buffer(oit_gpu_mesh *m, unsigned buffer);
void oit_gpu_mesh_destroy(oit_gpu_mesh *m);
size_t oit_gpu_mesh_triangles(const oit_gpu_mesh *m);
uint64_t oit_gpu_mesh_bytes(const oit_gpu_mesh *m);
uint32_t oit_gpu_mesh_first_prim(const oit_gpu_mesh *m);

/* For the GL methods: draws the triangles with the bound program built from
 * frag_glsl.h, binding them for vertex pulling and setting the first-prim
 * uniform; large meshes are drawn in windows that fit the SSBO limit. */
void oit_gpu_mesh_draw(const oit_gpu_mesh *m, unsigned program);

/* For compute passes with one invocation per triangle: binds each of those
 * windows at OIT_BIND_VERTS, sets the uints u_window_first (the window's
 * first triangle, counted within the mesh) and u_window_count, and
 * dispatches groups of 'local' invocations over it, in rows of at most
 * 65535 groups: invocation i = gl_GlobalInvocationID.y * 65535 * local +
 * gl_GlobalInvocationID.x handles triangle i of the window (skip
 * i >= u_window_count). */
void oit_gpu_mesh_dispatch(const oit_gpu_mesh *m, unsigned program, unsigned local);

/* Triangles one storage binding holds with its offset aligned: the window
 * size of the two calls above, for buffers laid out like a mesh's. */
size_t oit_gpu_triangle_window(void);

#ifdef __cplusplus
}
#endif
#endif
