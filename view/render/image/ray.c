/* A pixel's ray as the CPU casts it (ray.h). */
#include "view/render/image/ray.h"

#include "base/vec.h"
#include "view/render/image/shade.h"

#include <math.h>

/* 1 when v had a finite, non-zero length and is now a unit vector; else 0
 * and v unchanged (an infinite v is refused, not divided into zeros). */
static int unit3(double v[3])
{
    return isfinite(oit_dot3d(v, v)) && oit_normalize3d(v) > 0.0;
}

oit_status oit_ray_basis_make(const oit_view *view, const char *who, oit_ray_basis *b,
                              oit_error *err)
{
    const oit_camera *c = &view->camera;
    int ortho = c->projection == OIT_PROJ_ORTHOGRAPHIC;
    if (!(ortho || (c->fovy_deg > 0.0f && c->fovy_deg < 180.0f)) ||
        !(ortho || c->znear > 0.0f) || !(c->zfar > c->znear) || (ortho && isinf(c->zfar)))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: bad camera (fovy %g, znear %g, zfar %g)",
                             who, c->fovy_deg, c->znear, c->zfar);
    double up[3];
    for (int k = 0; k < 3; k++) {
        b->eye[k] = c->eye[k];
        b->forward[k] = (double)c->target[k] - c->eye[k];
        up[k] = c->up[k];
    }
    oit_cross3d(b->forward, up, b->right);
    if (!unit3(b->forward) || !unit3(b->right))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: camera eye equals target or up is parallel to the view", who);
    oit_cross3d(b->right, b->forward, b->up);
    b->tan_half_y = tan(c->fovy_deg * (3.14159265358979323846 / 360.0));
    b->aspect = (double)view->width / (double)view->height;
    b->ortho = ortho;
    b->windowed = c->window[0] != 0.0f || c->window[1] != 0.0f || c->window[2] != 0.0f ||
                  c->window[3] != 0.0f;
    oit_camera_window(c, b->aspect, b->win);
    b->znear = c->znear;
    b->zfar = c->zfar;
    if (!(b->win[0] < b->win[1] && b->win[2] < b->win[3]))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: empty camera window", who);
    return OIT_OK;
}

void oit_ray_basis_pixel(const oit_ray_basis *b, double px, double py, int w, int h,
                         double org[3], double dir[3])
{
    double sx, sy;
    if (b->windowed || b->ortho) {
        sx = b->win[0] + (b->win[1] - b->win[0]) * (px / w);
        sy = b->win[3] - (b->win[3] - b->win[2]) * (py / h);
    } else {
        sx = (px / w * 2.0 - 1.0) * b->tan_half_y * b->aspect;
        sy = (1.0 - py / h * 2.0) * b->tan_half_y;
    }
    if (b->ortho) {
        for (int k = 0; k < 3; k++) {
            org[k] = b->eye[k] + b->znear * b->forward[k] + sx * b->right[k] + sy * b->up[k];
            dir[k] = b->forward[k];
        }
        return;
    }
    double len2 = 0.0;
    for (int k = 0; k < 3; k++) {
        org[k] = b->eye[k];
        dir[k] = b->forward[k] + sx * b->right[k] + sy * b->up[k];
        len2 += dir[k] * dir[k];
    }
    double inv = 1.0 / sqrt(len2);
    for (int k = 0; k < 3; k++)
        dir[k] *= inv;
}

int oit_ray_depth_kept(const oit_ray_basis *b, double t, const double dir[3])
{
    double depth = t * (dir[0] * b->forward[0] + dir[1] * b->forward[1] + dir[2] * b->forward[2]);
    if (b->ortho)
        depth += b->znear;
    return depth >= (float)b->znear && depth <= (float)b->zfar;
}

void oit_ray_keying_init(const oit_view *view, oit_ray_keying *k)
{
    for (int i = 0; i < 3; i++)
        k->eye[i] = view->camera.eye[i];
    oit_camera_view_matrix(&view->camera, k->view_matrix);
    k->clip_count = view->clip.count;
    oit_clip_eye(&view->clip, k->view_matrix, k->clip_eye);
    oit_view_ray_map(view, k->ray_map);
    oit_view_origin_map(view, k->org_map, &k->org_z);
    k->height = view->height;
}

void oit_ray_pixel_at(const oit_ray_keying *k, int x, int y, oit_ray_pixel *p)
{
    oit_view_pixel_ray(k->ray_map, x, y, k->height, p->dir);
    oit_view_pixel_origin(k->org_map, k->org_z, x, y, k->height, p->o);
}

/* Whether the section planes keep the hit: its point is where the pixel's
 * ray meets the triangle's plane at the t the key is made of (shade.c
 * oit_depth_key, before quantising), as the fragment stage's oit_clipped()
 * finds it, so that both test the same float point. */
static int clip_keeps(const oit_ray_keying *k, const oit_ray_pixel *p, const float n[3],
                      float d, float t_hit)
{
    float nd = n[0] * p->dir[0] + n[1] * p->dir[1] + n[2] * p->dir[2];
    float t = t_hit;
    if (fabsf(nd) >= OIT_DEPTH_GRAZING) {
        float tp = d / nd;
        if (tp > 0.0f && isfinite(tp))
            t = tp;
    }
    return oit_clip_keeps(k->clip_count, k->clip_eye, p->o, p->dir, t);
}

int oit_ray_key_hit(const oit_ray_keying *k, const oit_ray_pixel *p, const oit_triangle *tri,
                    float t, float *key)
{
    const float *m = k->view_matrix;
    float nw[3], nv[3], d;
    oit_depth_plane(tri, k->eye, nw, &d);
    for (int r = 0; r < 3; r++)
        nv[r] = m[r] * nw[0] + m[4 + r] * nw[1] + m[8 + r] * nw[2];
    /* d - n . o as the shaders compute it: d itself for a perspective
     * (o = 0). */
    float no = nv[0] * p->o[0] + nv[1] * p->o[1] + nv[2] * p->o[2];
    *key = oit_depth_key(nv, d - no, p->dir, t);
    return k->clip_count == 0 || clip_keeps(k, p, nv, d - no, t);
}
