/* The one definition of shading and compositing. The GLSL in every GL method
 * mirrors these functions line for line; the Embree reference calls them.
 *
 * Per fragment (triangle prim hit at point p, seen from eye e):
 *   n     = normalize(cross(p1 - p0, p2 - p0))      geometric normal
 *   v     = normalize(e - p)
 *   ndv   = |dot(n, v)|,  front = dot(n, v) > 0    (counter-clockwise faces
 *                                                    the viewer)
 *   base  = barycentric interpolation of vertex rgba / 255 (perspective
 *           correct); rgb := default_rgb without OIT_ATTR_COLOR, a := alpha
 *           without OIT_ATTR_ALPHA.
 * transparent:  colour = base.rgb * (0.3 + 0.7 * ndv),  a = base.a
 * translucent:  colour = (1,1,1) * (0.3 + 0.7 * ndv) (a specular white),
 *               a = F0 + (1 - F0) * (1 - ndv)^5 with F0 = 0.04 (Schlick);
 *               the medium behind a front face absorbs with
 *               sigma_c = absorption / scene_scale * (1 - base_c), c in rgb.
 *
 * Per pixel, fragments sorted by (t, prim) ascending, with state
 * C = 0, T = (1,1,1), nest = 0:
 *   translucent and nest > 0:  T *= exp(-sigma(medium) * (t - t_prev))
 *   C += T * a * colour;   T *= (1 - a)
 *   translucent: front ? (nest += 1, medium = base.rgb) : nest = max(nest-1, 0);
 *                t_prev = t
 *   final = C + T * background
 * The state (C, T, nest, medium, t_prev) is what crosses batch boundaries
 * when a frame is captured in several batches.
 */
#ifndef OIT_RENDER_SHADE_H
#define OIT_RENDER_SHADE_H

#include <math.h>

#include "view.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_SHADE_AMBIENT 0.3f
#define OIT_SHADE_DIFFUSE 0.7f
#define OIT_SHADE_F0 0.04f

typedef struct oit_shaded_fragment {
    double t;        /* distance from the eye */
    uint32_t prim;   /* triangle index        */
    int front;       /* 1 when front-facing   */
    float colour[3]; /* shaded colour         */
    float alpha;     /* coverage / Fresnel    */
    float base[3];   /* medium colour (translucent) */
} oit_shaded_fragment;

typedef struct oit_pixel_state {
    double C[3], T[3];
    double t_prev;
    float medium[3];
    int nest;
} oit_pixel_state;

/* Shades one hit: p0..p2 the triangle, bary (w0,w1,w2) the barycentric
 * weights of the hit, eye the camera position, t the hit distance. */
void oit_shade_fragment(const oit_shading *s, const oit_triangle *tri,
                        uint32_t prim, const float bary[3], const float eye[3],
                        double t, oit_shaded_fragment *out);

void oit_pixel_begin(oit_pixel_state *st);
/* Adds one fragment; fragments must arrive in (t, prim) order. */
void oit_pixel_add(oit_pixel_state *st, const oit_shading *s,
                   const oit_shaded_fragment *f);
void oit_pixel_end(const oit_pixel_state *st, const oit_shading *s, float rgb[3]);

/* Sort comparator for oit_shaded_fragment by (t, prim). */
int oit_shaded_fragment_cmp(const void *a, const void *b);

#ifdef __cplusplus
}
#endif
#endif
