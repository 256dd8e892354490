/* What every renderer agrees on: the camera, the shading parameters, the
 * output image and the per-frame figures.
 *
 * Conventions shared by all methods (DFB, capture backends, streaming and the
 * Embree reference), so that their images can be compared pixel by pixel:
 * - Perspective camera, vertical field of view fovy_deg, aspect width/height,
 *   or an off-centre frustum, or an orthographic view volume (oit_camera).
 *   Pixel (x, y), y = 0 the TOP row, is sampled at its centre: NDC
 *   ((x + 0.5) / w * 2 - 1, 1 - (y + 0.5) / h * 2).
 * - A fragment is kept when its view-space depth (distance along the view
 *   direction) lies in [znear, zfar], as GL clipping does.
 * - Fragments sort by the tie rule (shade.h): the key, the distance from the
 *   pixel centre's ray origin (the eye; orthographic: the point of the near
 *   plane) along its unit ray to the triangle's plane with its low bits
 *   cleared, then the source triangle's index, ascending.
 * - Shading and compositing are defined once in shade.h.
 */
#ifndef OIT_RENDER_VIEW_H
#define OIT_RENDER_VIEW_H

#include <stddef.h>
#include <stdint.h>

#include "oit/mesh.h"
#include "view/render/image/clip.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum oit_projection {
    OIT_PROJ_PERSPECTIVE = 0,
    OIT_PROJ_ORTHOGRAPHIC = 1
} oit_projection;

/* Zero means default for the fields after zfar: a symmetric perspective of
 * fovy_deg, as before they existed (the same matrices bit for bit).
 * - projection OIT_PROJ_PERSPECTIVE: rays from the eye. window all 0: the
 *   symmetric frustum of fovy_deg at the view's aspect; else the frustum's
 *   sides at distance 1 along the view direction (glFrustum's l, r, b, t
 *   divided by its near), l < r, b < t: off-centre (stereo, tiles).
 *   zfar = +INFINITY: an infinite far plane.
 * - OIT_PROJ_ORTHOGRAPHIC: parallel rays along the view direction, from the
 *   near plane. window all 0: the volume ortho_height high (> 0) and
 *   ortho_height * aspect wide, centred on the view axis; else its sides in
 *   view-space units (glOrtho's l, r, b, t). znear may be <= 0 (behind the
 *   eye); zfar > znear, finite. fovy_deg is not used. */
typedef struct oit_camera {
    float eye[3];
    float target[3];
    float up[3];
    float fovy_deg; /* default 45 */
    float znear;    /* > 0 (orthographic: any, < zfar) */
    float zfar;     /* > znear; +INFINITY: infinite far (perspective) */
    int projection; /* oit_projection */
    float ortho_height;
    float window[4]; /* l, r, b, t; all 0: symmetric */
} oit_camera;

typedef enum oit_shading_mode {
    OIT_SHADING_TRANSPARENT = 0,
    OIT_SHADING_TRANSLUCENT = 1
} oit_shading_mode;

/* Where compositing happens (shade.h, "Colour space"). Zero is the space the
 * OIT papers and most viewers use. */
typedef enum oit_colour_space {
    OIT_COLOUR_SRGB = 0,  /* on the sRGB-encoded values, as given             */
    OIT_COLOUR_LINEAR = 1 /* in linear light, the result encoded back to sRGB */
} oit_colour_space;

/* Zero means default for every field but mode. */
typedef struct oit_shading {
    oit_shading_mode mode;
    float alpha;          /* alpha for inputs without one; default 0.35      */
    float default_rgb[3]; /* colour for inputs without one; default .85,.55,.2 */
    float background[3];  /* default 1,1,1 (white), set all <0 for black     */
    float absorption;     /* translucent: optical depth across scene_scale;
                             default 4                                        */
    float scene_scale;    /* length that absorption refers to (the model's
                             bounding-box diagonal); must be > 0 for
                             translucent shading                              */
    uint32_t attributes;  /* OIT_ATTR_* of the mesh: which vertex data is real */
    oit_colour_space colour_space; /* default OIT_COLOUR_SRGB (shade.h)        */
    int see_through;      /* 1: alpha on every triangle, the file's alpha and
                             opaque materials ignored; default 0 (shade.h,
                             "Opaque triangles")                             */
} oit_shading;

typedef struct oit_view {
    oit_camera camera;
    int width, height;
    oit_shading shading;
    /* Model to world, column-major, affine (last row 0, 0, 0, 1), any
     * invertible linear part (non-uniform scale included); all 0: identity.
     * The GL methods apply it to the vertices before anything else, so the
     * tie rule sees the world-space float vertices, as if pre-transformed;
     * the streamer culls and orders parts through it. */
    float model[16];
    /* Section planes in world space (clip.h); count 0: none. A method
     * without OIT_RENDER_METHOD_CLIP refuses a view with planes (method.h). */
    oit_clip clip;
} oit_view;

/* A view's key: the camera, the size, the shading mode, the model matrix
 * and the section planes, field by field (no padding bytes); views with
 * equal keys see the scene alike. */
uint64_t oit_view_key(const oit_view *view);

/* RGBA float image, row 0 at the top, values in [0,1] (alpha is 1 for a
 * composited frame). Colour is sRGB-encoded in both colour spaces (the
 * linear result is encoded by oit_pixel_end / oit_state_final), as PNG
 * stores it; PFM files hold linear light (image.h). */
typedef struct oit_image {
    int width, height;
    float *rgba;
} oit_image;

typedef struct oit_frame_stats {
    double ms;                /* wall time of the frame, GPU work included     */
    uint64_t fragments;       /* fragments generated (all layers)              */
    uint32_t max_layers;      /* most fragments on one pixel                   */
    uint64_t overflow_pixels; /* pixels that got more than K in one batch      */
    /* Every GPU buffer and texture the method held at its peak in the frame:
     * its own working memory, and (oit_method_render adds it) the mesh an
     * in-core method holds for as long as it is open, gpu_mesh_bytes. The
     * stream's is its whole footprint: upload ring, residency cache,
     * capture buffers and textures, per-pixel state, tiles (streamer.h). A
     * method's render operation called directly fills its own part only. */
    uint64_t gpu_bytes_peak;
    /* Of gpu_bytes_peak, the uploaded mesh's (oit_gpu_mesh_bytes: its
     * triangle and draw-record buffers); 0 for the stream (its parts are in
     * its ring and cache) and for methods without GL. */
    uint64_t gpu_mesh_bytes;
    uint32_t batches;         /* capture batches (packs) drawn                 */
    /* The first-K capture (view/render/capture/capture_firstk.h): pixels that got more
     * fragments in one pack than its slots hold, summed over the packs, and
     * the packs that had any, so took the second geometry pass; 0 for every
     * other method and capture. */
    uint64_t second_pass_pixels;
    uint32_t second_pass_packs;
    /* The first-K and counted captures: pixels that got more than
     * capture_k fragments in one batch (first-K: more than its pack's
     * slots), summed over the batches. First-K's second pass took exactly
     * these (second_pass_pixels); the counted capture counts them in its
     * scan. 0 for every other method and capture. */
    uint64_t deep_pixels;
    /* The counted capture's batches drawn at the offsets its last frame
     * of the same view counted (capture_counted.h, "Predicted batches"),
     * not counted first; 0 for every other method and capture. */
    uint32_t predicted_batches;
    /* The reference with a saturation threshold (reference.h): fragments
     * behind pixels already saturated; 0 for every other method. */
    uint64_t fragments_saturated;
    /* The capture backends (view/render/capture/capture.h): the one that ran
     * ("array", "stencil", "counted", "first-k") and its K; NULL and 0
     * for every other method. */
    const char *capture;
    uint32_t capture_k;
    /* How the capture's K-slot fills were made: "stencil" (routed MSAA
     * samples, capture_slots_k of them a pixel) or "array" (slots through
     * an atomic counter; capture_slots_k 0); NULL where it has none (the
     * counted capture, every other method). */
    const char *capture_slots;
    uint32_t capture_slots_k;
    /* The GPU timer's number of this frame (view/render/gl/gpu_timer.h), whose
     * gpu_ms comes later (oit_method_gpu_poll); 0: not timed on the GPU. */
    uint64_t gpu_frame;
    /* The exact capture's frames (the stream): the host's waits on the GPU
     * between the frame's first command and its final read-back
     * (view/render/gl/host_wait.h), and the times the frame was drawn again
     * because a store sized ahead of the GPU's need proved short (its
     * image is the redrawn one); 0 for other methods, whose waits are not
     * counted. */
    uint32_t host_waits;
    uint32_t redraws;
} oit_frame_stats;

/* Camera helpers. */
void oit_camera_default(oit_camera *cam, const float bmin[3], const float bmax[3],
                        float azimuth_deg, float elevation_deg);
/* The same about another up axis (0 x, 1 y, 2 z; oit_camera_default is y):
 * z up, as CAD models are, looks from -y at azimuth 0 with x to the right
 * and z up; x up looks from +z with -y to the right. */
void oit_camera_default_up(oit_camera *cam, const float bmin[3], const float bmax[3],
                           float azimuth_deg, float elevation_deg, int up_axis);
/* 4x4 column-major matrices, as GL expects. */
void oit_camera_view_matrix(const oit_camera *cam, float m[16]);
void oit_camera_proj_matrix(const oit_camera *cam, float aspect, float m[16]);
/* The pixel ray map of a view (the tie rule, shade.h): the view-space ray
 * through window point (x, y), GL orientation (y = 0 the BOTTOM row, pixel
 * centres at +0.5), is (x * ray[0] + ray[2], y * ray[1] + ray[3], -1), so a
 * pixel centre's ray is the same for every triangle drawn there. */
void oit_view_ray_map(const oit_view *view, float ray[4]);
/* The ray origin map: the view-space origin of window point (x, y)'s ray is
 * (x * org[0] + org[2], y * org[1] + org[3], org_z). Perspective: all 0 (the
 * eye), and ray[] is the direction map. Orthographic: the point on the near
 * plane (org_z = -znear), and ray[] is (0, 0, 0, 0): direction (0, 0, -1).
 * The tie rule's t is then (d - n . o) / (n . dir), d = n . (p0 - eye). */
void oit_view_origin_map(const oit_view *view, float org[4], float *org_z);
/* The view-space origin of pixel (x, y)'s ray, y = 0 the TOP row, as the GL
 * methods compute it. */
void oit_view_pixel_origin(const float org[4], float org_z, int x, int y, int height,
                           float o[3]);
/* The window (l, r, b, t) of cam at this aspect: perspective, the frustum's
 * sides at distance 1; orthographic, the volume's sides (oit_camera). */
void oit_camera_window(const oit_camera *cam, double aspect, double w[4]);
/* The tie rule's unit view-space ray of pixel (x, y), y = 0 the TOP row, as
 * the GL methods compute it from gl_FragCoord and the ray map. */
void oit_view_pixel_ray(const float ray[4], int x, int y, int height, float dir[3]);
/* World-space planes bounding what the camera sees at this aspect: a point x
 * can be visible only if p[0] x + p[1] y + p[2] z + p[3] >= 0 for all six
 * (left, right, bottom, top, near, far). Deliberately a little wider than
 * the view volume (0.1% in angle and depth, near plane at znear / 2), so
 * that rounding never culls what the rasterizer would draw. */
void oit_camera_frustum(const oit_camera *cam, float aspect, float planes[6][4]);
/* The view's model matrix in double (identity for all 0); returns 0 for the
 * identity, 1 otherwise. */
int oit_view_model(const oit_view *view, double m[16]);
/* Model to eye: the camera's view matrix times the model matrix, in double,
 * rounded; exactly oit_camera_view_matrix for the identity. */
void oit_view_model_view_matrix(const oit_view *view, float m[16]);
/* The model-space eye (the affine inverse of the model applied to the eye)
 * and the model-space view direction (the inverse linear part applied to
 * target - eye), in double. Returns 0 when the model is singular. */
int oit_view_model_eye(const oit_view *view, double eye[3], double dir[3]);

/* Parses "ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy"; returns 0 on success. Two more
 * numbers ",znear,zfar" may follow; without them cam's clip planes are kept.
 * Projection fields may follow, each
 * after a ':': "ortho=H" (orthographic, H high), "window=l,r,b,t"
 * (oit_camera.window), "far=inf"; without them the camera's projection is
 * a symmetric perspective.
 * Eye and target are in the file's coordinates: origin (NULL: 0), the one
 * the model's positions are relative to (oit_mesh_info), is subtracted in
 * double before they become floats. */
int oit_camera_parse(oit_camera *cam, const char *text, const double origin[3]);
/* Why oit_camera_parse returned code (< 0): the syntax, or which value of a
 * well-formed view cannot make a camera, for the user's message. */
const char *oit_camera_parse_error(int code);

/* The length translucent absorption refers to: the bounds' diagonal, or 1
 * for empty or non-finite bounds. */
float oit_scene_scale(const float bmin[3], const float bmax[3]);

/* Fills defaults for zero fields of the shading descriptor. */
void oit_shading_resolve_defaults(oit_shading *s);
/* The OIT_ATTR_* bits shading uses: attributes without OIT_ATTR_ALPHA when
 * see_through is set. */
uint32_t oit_shading_attrs(const oit_shading *s);
/* 1 when the methods run the opaque pre-pass (opaque_keys.h): transparent
 * shading, not see-through, of a mesh with alpha some of whose triangles
 * are opaque (OIT_ATTR_ALPHA and OIT_ATTR_OPAQUE; shade.h, "Opaque
 * triangles"). Without OIT_ATTR_OPAQUE an opaque triangle still
 * composites with a = 1: the image is the same, only nothing is culled. */
int oit_shading_opaque(const oit_shading *s);

#ifdef __cplusplus
}
#endif
#endif
