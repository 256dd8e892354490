/* The viewer's orbit camera (viewer_internal.h): orbit, zoom and fly about
 * the target, with clip planes fitted to the scene's bounding sphere. */
#include "tools/oitstream/viewer_internal.h"

/* ---- camera ---- */

/* Rotates v by angle (radians) about the unit axis (Rodrigues). */
static void rotate3(float v[3], const float axis[3], float angle)
{
    float c = cosf(angle), s = sinf(angle), kxv[3];
    float kdv = oit_dot3f(axis, v);
    oit_cross3f(axis, v, kxv);
    for (int k = 0; k < 3; k++)
        v[k] = v[k] * c + kxv[k] * s + axis[k] * kdv * (1.0f - c);
}

/* Clip planes around the bounding sphere as seen from the current eye, so
 * that orbiting, zooming and flying never cut the model. */
void viewer_fit_clip(viewer *v)
{
    oit_camera *c = &v->view.camera;
    float f[3], to_c[3];
    oit_sub3f(c->target, c->eye, f);
    oit_normalize3f(f);
    oit_sub3f(v->centre, c->eye, to_c);
    float dc = oit_dot3f(f, to_c);
    float r = 1.05f * v->radius;
    c->zfar = dc + r > 0.0f ? dc + r : r;
    c->znear = fmaxf(dc - r, 1e-4f * c->zfar);
    if (c->projection == OIT_PROJ_ORTHOGRAPHIC) /* parallel rays: behind the eye too */
        c->znear = dc - r;
}

/* V: orthographic as high as the perspective frustum at the target, so
 * that what lies there keeps its size on screen; V again: perspective. */
void viewer_toggle_ortho(viewer *v)
{
    oit_camera *c = &v->view.camera;
    if (c->projection == OIT_PROJ_ORTHOGRAPHIC) {
        c->projection = OIT_PROJ_PERSPECTIVE;
        printf("viewer: projection perspective\n");
        return;
    }
    float d[3];
    oit_sub3f(c->target, c->eye, d);
    double fovy = c->fovy_deg > 0.0f ? c->fovy_deg : 45.0;
    c->projection = OIT_PROJ_ORTHOGRAPHIC;
    c->ortho_height = (float)(2.0 * sqrt((double)oit_dot3f(d, d)) *
                              tan(0.5 * fovy * 3.14159265358979323846 / 180.0));
    printf("viewer: projection orthographic, %.6g high\n", c->ortho_height);
}

/* Left drag: azimuth about the up axis, elevation about the right axis,
 * kept short of the poles where the view would flip. */
void viewer_orbit(viewer *v, double dx, double dy)
{
    oit_camera *c = &v->view.camera;
    float off[3], up[3] = {c->up[0], c->up[1], c->up[2]}, right[3];
    oit_sub3f(c->eye, c->target, off);
    oit_normalize3f(up);
    rotate3(off, up, (float)(-dx * 0.01));
    oit_cross3f(off, up, right);
    if (oit_normalize3f(right) > 0.0f) {
        float before[3] = {off[0], off[1], off[2]};
        rotate3(off, right, (float)(dy * 0.01));
        float cosu = oit_dot3f(off, up) / sqrtf(oit_dot3f(off, off));
        if (fabsf(cosu) > 0.995f)
            memcpy(off, before, sizeof off);
    }
    for (int k = 0; k < 3; k++)
        c->eye[k] = c->target[k] + off[k];
}

void viewer_zoom(viewer *v, double factor)
{
    oit_camera *c = &v->view.camera;
    if (c->projection == OIT_PROJ_ORTHOGRAPHIC) /* the distance alone would not show */
        c->ortho_height *= (float)factor;
    for (int k = 0; k < 3; k++)
        c->eye[k] = c->target[k] + (c->eye[k] - c->target[k]) * (float)factor;
}

/* One step of 5% of the eye-target distance along forward, right or up. */
void viewer_fly(viewer *v, int forward, int right, int up_dir)
{
    oit_camera *c = &v->view.camera;
    float f[3], r[3], u[3] = {c->up[0], c->up[1], c->up[2]};
    oit_sub3f(c->target, c->eye, f);
    float step = 0.05f * oit_normalize3f(f);
    oit_normalize3f(u);
    oit_cross3f(f, u, r);
    oit_normalize3f(r);
    for (int k = 0; k < 3; k++) {
        float d = step * ((float)forward * f[k] + (float)right * r[k] + (float)up_dir * u[k]);
        c->eye[k] += d;
        c->target[k] += d;
    }
}
