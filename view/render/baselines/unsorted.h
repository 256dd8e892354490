/* Unsorted alpha blending: one geometry pass, depth test off, each fragment
 * blended "over" the target in submission (rasterization) order, starting
 * from the background. NOT exact: the image equals DFB's only where the
 * fragments of a pixel happen to arrive back to front (or there is at most
 * one); translucent absorption, which needs the order, is left out. It is
 * the cost floor of OIT: fragment generation with the same shading as every
 * other method, and nothing else. fragments is counted with an occlusion
 * query; max_layers is not known (0). */
#ifndef OIT_RENDER_BASELINES_UNSORTED_H
#define OIT_RENDER_BASELINES_UNSORTED_H

#include "view/render/gl/gpu_mesh.h"

typedef struct oit_unsorted oit_unsorted;

#endif
