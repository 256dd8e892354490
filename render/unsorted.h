/* Unsorted alpha blending: one geometry pass, depth test off, each fragment
 * blended "over" the target in submission (rasterization) order, starting
 * from the background. NOT exact: the image equals DFB's only where the
 * fragments of a pixel happen to arrive back to front (or there is at most
 * one); translucent absorption, which needs the order, is left out. It is
 * the cost floor of OIT: fragment generation with the same shading as every
 * other method, and nothing else. fragments is counted with an occlusion
 * query; max_layers is not known (0). */
#ifndef OIT_RENDER_UNSORTED_H
#define OIT_RENDER_UNSORTED_H

#include "render/gpu_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oit_unsorted oit_unsorted;

oit_status oit_unsorted_create(oit_unsorted **out, oit_error *err);
void oit_unsorted_destroy(oit_unsorted *u);

/* Renders meshes[0..n) in order; out is allocated by the call. */
oit_status oit_unsorted_render(oit_unsorted *u, const oit_gpu_mesh *const *meshes, int n,
                               const oit_view *view, oit_image *out,
                               oit_frame_stats *stats, oit_error *err);

#ifdef __cplusplus
}
#endif
#endif
