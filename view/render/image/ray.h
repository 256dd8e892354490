/* A pixel's ray as the CPU casts it: the Embree reference (every pixel) and
 * the pick (one pixel, view/render/pick/) trace the same ray and key its
 * hits with the same float operations as the GL methods' shaders, so that
 * the reference's image, the pick's layers and the GL methods' fragments
 * agree wherever rasterization and rays do (off the ambiguity mask). */
#ifndef OIT_RENDER_IMAGE_RAY_H
#define OIT_RENDER_IMAGE_RAY_H

#include "oit/status.h"
#include "view/render/image/clip.h"
#include "view/render/image/view.h"

/* The camera's frame in double, as a GL look-at: right = forward x up,
 * up' = right x forward. */
typedef struct oit_ray_basis {
    double eye[3], forward[3], right[3], up[3];
    double tan_half_y, aspect;
    /* Off-centre or orthographic (oit_camera_window): the window; ortho:
     * rays along forward from the near plane (znear from the eye). */
    int windowed, ortho;
    double win[4], znear, zfar;
} oit_ray_basis;

/* The basis of view's camera; a camera no ray can be cast from is
 * OIT_ERR_ARGUMENT, the message opening with who ("reference", "pick"). */
oit_status oit_ray_basis_make(const oit_view *view, const char *who, oit_ray_basis *b,
                              oit_error *err);
/* The ray through image point (px, py) in pixels of a w x h view, the
 * centre of pixel (x, y) being (x + 0.5, y + 0.5), y = 0 the TOP row: its
 * origin (the eye; orthographic: the point of the near plane) and unit
 * direction. */
void oit_ray_basis_pixel(const oit_ray_basis *b, double px, double py, int w, int h,
                         double org[3], double dir[3]);
/* 1 when the hit at t along dir lies in [znear, zfar] in view depth, as GL
 * clips. */
int oit_ray_depth_kept(const oit_ray_basis *b, double t, const double dir[3]);

/* What keying a hit needs of the view (shade.h, the tie rule): the float
 * view matrix, ray and origin maps, and the section planes in view space. */
typedef struct oit_ray_keying {
    float eye[3];
    float view_matrix[16], ray_map[4], org_map[4], org_z;
    float clip_eye[OIT_CLIP_MAX][4];
    int clip_count, height;
} oit_ray_keying;

void oit_ray_keying_init(const oit_view *view, oit_ray_keying *k);

/* Pixel (x, y)'s view-space ray (dir) and origin (o), as the GL methods
 * compute them. */
typedef struct oit_ray_pixel {
    float dir[3], o[3];
} oit_ray_pixel;

void oit_ray_pixel_at(const oit_ray_keying *k, int x, int y, oit_ray_pixel *p);
/* The tie rule's key of tri's hit at t on the pixel, from the triangle's
 * plane (normal rotated into view space by the float view matrix); returns
 * 0 when a section plane removes the hit, else 1. */
int oit_ray_key_hit(const oit_ray_keying *k, const oit_ray_pixel *p, const oit_triangle *tri,
                    float t, float *key);

#endif
