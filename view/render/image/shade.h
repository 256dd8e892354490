/* The one definition of shading and compositing. The GLSL in every GL method
 * mirrors these functions line for line; the Embree reference calls them.
 *
 * Per fragment (triangle prim hit at point p, seen from eye e):
 *   n     = normalize(cross(p1 - p0, p2 - p0))      geometric normal
 *   v     = normalize(e - p)
 *   ndv   = |dot(n, v)|,  front = dot(n, v) > 0    (counter-clockwise faces
 *                                                    the viewer)
 *   base  = barycentric interpolation of vertex rgba / 255 (perspective
 *           correct); rgb := default_rgb without OIT_ATTR_COLOUR, a := alpha
 *           without OIT_ATTR_ALPHA (or with see_through); a := 1 exactly
 *           on an opaque triangle (below).
 * transparent:  colour = base.rgb * (0.3 + 0.7 * ndv),  a = base.a
 * translucent:  colour = (1,1,1) * (0.3 + 0.7 * ndv) (a specular white),
 *               a = F0 + (1 - F0) * (1 - ndv)^5 with F0 = 0.04 (Schlick);
 *               the medium behind a front face absorbs with
 *               sigma_c = absorption / scene_scale * (1 - base_c), c in rgb.
 *
 * Per pixel, fragments sorted by (key, prim) ascending (the tie rule below;
 * prim is the SOURCE triangle's index, its position in the input file, kept
 * through conversion), with state
 * C = 0, T = (1,1,1), nest = 0:
 *   translucent and nest > 0:  T *= exp(-sigma(medium) * (t - t_prev))
 *   C += T * a * colour;   T *= (1 - a)
 *   translucent: front ? (nest += 1, medium = base.rgb) : nest = max(nest-1, 0);
 *                t_prev = t
 *   final = C + T * background
 * The state (C, T, nest, medium, t_prev) is what crosses batch boundaries
 * when a frame is captured in several batches.
 *
 * Opaque triangles. With transparent shading of a mesh that has alpha
 * (OIT_ATTR_ALPHA, not see_through), a triangle whose three vertices have
 * alpha 255 is opaque (glTF OPAQUE and MASK materials, MTL d 1, a PLY's
 * alpha 255): its a is 1, so T = 0 behind its nearest fragment and nothing
 * there shows. The definition above needs nothing else; the GL methods
 * also avoid storing what cannot show: a pre-pass writes per pixel the
 * least key of the opaque fragments (opaque_keys.h), and every fragment
 * with a greater key is discarded before it is counted or stored. Those
 * at the least key (the opaque one, coplanar ones) are kept and sorted by
 * the tie rule like any other, so the image is the one defined above. A
 * triangle with some vertices at 255 and some below is not opaque.
 * Translucent shading ignores it (alpha there is Fresnel's).
 *
 * Colour space (oit_shading.colour_space). Vertex colours, default_rgb and
 * background are sRGB-encoded (mesh.h: 8-bit sRGB, straight alpha).
 *   OIT_COLOUR_SRGB (0, the default): everything above runs on the encoded
 *     values as given, as the OIT papers and most viewers do; final is the
 *     encoded result. 50% red (255,0,0,128) over white gives 255,127,127.
 *   OIT_COLOUR_LINEAR: each vertex's rgb (decoded before the barycentric
 *     interpolation, in the vertex shader on GL), default_rgb (so also the
 *     translucent medium) and background are decoded with the exact sRGB
 *     EOTF (oit_srgb_decode: c/12.92 up to 0.04045, else
 *     ((c+0.055)/1.055)^2.4, not a 2.2 gamma) before shading; C, T and the
 *     background term are linear light; final = oit_srgb_encode(C + T * bg)
 *     per channel. Alpha is coverage and is never converted. 50% red over
 *     white gives 255,187,187 (encode(127/255) = 187.19).
 * The state that crosses batches is in the compositing space; only final
 * encodes. liboit, which blends C and T into the caller's framebuffer,
 * documents what it writes (liboit.h, Result).
 */
/* The tie rule (docs/ties.md), used by every exact method: DFB, the stream,
 * the exact baselines and the Embree reference.
 *
 * Depth. A fragment's t is taken from its triangle's PLANE, not from
 * interpolation: the plane's unit normal n and its signed distance from the
 * eye d = n . (p0 - eye) are computed in double from the float vertices and
 * then rounded to float, and t = d / (n . dir) in float along the pixel's
 * unit ray dir (from the eye; an orthographic view's rays start at the
 * pixel's point o of the near plane: t = (d - n . o) / (n . dir), view.h,
 * oit_view_origin_map). Two triangles of one plane (a face exported twice, the
 * same face wound the other way, coplanar decals and CAD faces built on one
 * plane) get the same float n and d up to the sign, because the double
 * computation is within 1e-15 of the exact plane and the rounding to float
 * then lands on the same value; a sign flip changes no bit of t. So they
 * get the same t at every pixel, whichever way each method rasterizes or
 * casts rays. Interpolated depth differs between such triangles by a few
 * float ulps, which is what made the order of coincident faces change with
 * the method, the conversion and the view. Where the plane gives no usable t
 * (a degenerate triangle, or a ray within 2^-12 of grazing it, where
 * d / (n . dir) amplifies rounding) the interpolated t is used.
 *
 * Key. The key is t with its OIT_DEPTH_KEY_DROP_BITS lowest mantissa bits
 * cleared: a grid of 2^-19 of t's binade (16 float ulps), so depths within
 * about 1e-6 of t of each other usually share a key (faces that are
 * coplanar only up to the rounding of their float vertices, clipped pieces
 * whose new vertices were rounded, the last-bit differences between two
 * drivers), while faces further apart than 2^-19 of their distance never
 * do: a decal 1e-5 of a unit model in front of its surface stays in front
 * seen from up to 8 model sizes away. (key, prim) is a strict weak order,
 * as sorting needs; a tolerance compare would not be one. The Embree
 * reference computes the key with the same float operations as the GL
 * shaders (normal rotated by the float view matrix, the ray from the ray
 * map, view.h), so that near ties round alike where the hardware lets
 * them. Compositing uses the key as the fragment's t (translucent
 * absorption): an error of at most 2e-6 t in path length. */
#define OIT_DEPTH_KEY_DROP_BITS 4
#define OIT_DEPTH_KEY_MASK 15 /* (1 << OIT_DEPTH_KEY_DROP_BITS) - 1, spelled for GLSL */
#define OIT_DEPTH_GRAZING 2.44140625e-4f /* 2^-12 */

#ifndef OIT_RENDER_SHADE_H
#define OIT_RENDER_SHADE_H

#include <math.h>

#include "view/render/image/view.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_SHADE_AMBIENT 0.3f
#define OIT_SHADE_DIFFUSE 0.7f
#define OIT_SHADE_F0 0.04f

typedef struct oit_shaded_fragment {
    double t;        /* sort key: distance from the eye, quantised (above) */
    uint32_t prim;   /* source triangle index */
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

/* The triangle's plane as the tie rule defines it: unit normal n and signed
 * distance d of the plane from eye along n, both rounded from double.
 * Returns 0 (n = 0, d = 0) for a degenerate triangle. */
int oit_depth_plane(const oit_triangle *tri, const float eye[3], float n[3], float *d);
/* The sort key of a fragment on that plane seen along the unit ray dir
 * (world space), or of t_interp where the plane gives no usable t. d is the
 * plane's distance from the ray's origin: oit_depth_plane's d, less n . o
 * for an orthographic ray from o. */
float oit_depth_key(const float n[3], float d, const float dir[3], float t_interp);
/* t with its low OIT_DEPTH_KEY_DROP_BITS mantissa bits cleared (t > 0). */
float oit_depth_quantise(float t);

/* Shades one hit: p0..p2 the triangle, bary (w0,w1,w2) the barycentric
 * weights of the hit, eye the camera position, t the hit distance. */
/* 1 when tri is opaque under s (above, "Opaque triangles"). */
int oit_triangle_opaque(const oit_shading *s, const oit_triangle *tri);

void oit_shade_fragment(const oit_shading *s, const oit_triangle *tri,
                        uint32_t prim, const float bary[3], const float eye[3],
                        double t, oit_shaded_fragment *out);

void oit_pixel_begin(oit_pixel_state *st);
/* Adds one fragment; fragments must arrive in (t, prim) order, t the key. */
void oit_pixel_add(oit_pixel_state *st, const oit_shading *s,
                   const oit_shaded_fragment *f);
void oit_pixel_end(const oit_pixel_state *st, const oit_shading *s, float rgb[3]);

/* The exact sRGB transfer functions (IEC 61966-2-1), in double, for c in
 * [0, 1] (negative input gives 0). decode: encoded -> linear light;
 * encode: linear light -> encoded. */
double oit_srgb_decode(double c);
double oit_srgb_encode(double c);

/* Sort comparator for oit_shaded_fragment by (t, prim). */
int oit_shaded_fragment_cmp(const void *a, const void *b);

#ifdef __cplusplus
}
#endif
#endif
