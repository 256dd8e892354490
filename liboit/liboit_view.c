/* The caller's view (liboit_internal.h): its matrices turned into a
 * camera, and a frame's camera, model matrix and section planes into the
 * view the methods render. */
#include "liboit/liboit_internal.h"

/* ---- caller matrices -> camera ------------------------------------------ */

/* A rigid view matrix: rows of its rotation are the camera's right, up and
 * backward axes; the eye is -R^T t. */
static oit_status camera_from_view(const float *m, oit_camera *cam, oit_error *err)
{
    double r[3][3], t[3] = {m[12], m[13], m[14]};
    for (int row = 0; row < 3; row++)
        for (int col = 0; col < 3; col++)
            r[row][col] = m[col * 4 + row];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double d = r[a][0] * r[b][0] + r[a][1] * r[b][1] + r[a][2] * r[b][2];
            if (fabs(d - (a == b)) > 1e-3)
                return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                     "oit_frame.view: not a rigid "
                                     "transform (rows %d,%d dot %.4g); scale belongs in the "
                                     "model, not the view",
                                     a, b, d);
        }
    if (m[3] != 0.0f || m[7] != 0.0f || m[11] != 0.0f || m[15] != 1.0f)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "oit_frame.view: last row is not "
                             "(0, 0, 0, 1)");
    for (int k = 0; k < 3; k++) {
        double eye = -(r[0][k] * t[0] + r[1][k] * t[1] + r[2][k] * t[2]);
        cam->eye[k] = (float)eye;
        cam->target[k] = (float)(eye - r[2][k]);
        cam->up[k] = (float)r[1][k];
    }
    return OIT_OK;
}

/* The projections a viewer uses, classified from the matrix (liboit.h,
 * oit_frame): a perspective (m[11] = -1, m[15] = 0), symmetric or
 * off-centre (m[8], m[9]), with a finite or an infinite far plane
 * (m[10] = -1, m[14] = -2 near); or an orthographic one (m[11] = 0,
 * m[15] = 1). A symmetric perspective whose aspect is the viewport's keeps
 * the fovy form, as before the others were accepted. */
static oit_status camera_from_projection(const float *m, double aspect, oit_camera *cam,
                                         oit_error *err)
{
    static const int zeros[] = {1, 2, 3, 4, 6, 7};
    for (size_t i = 0; i < sizeof zeros / sizeof *zeros; i++)
        if (m[zeros[i]] != 0.0f)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "oit_frame.projection[%d] = %g: "
                                 "not a perspective or orthographic projection (a skewed or "
                                 "rotated one)",
                                 zeros[i], m[zeros[i]]);
    if (!(m[0] > 0.0f) || !(m[5] > 0.0f))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "oit_frame.projection: m[0] = %g and "
                             "m[5] = %g must be > 0 (a mirrored projection)",
                             m[0], m[5]);
    double w[4] = {(m[8] - 1.0) / m[0], (m[8] + 1.0) / m[0], (m[9] - 1.0) / m[5],
                   (m[9] + 1.0) / m[5]};
    if (m[11] == -1.0f && m[15] == 0.0f) {
        if (m[12] != 0.0f || m[13] != 0.0f)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "oit_frame.projection: a perspective "
                                 "with m[12] = %g, m[13] = %g (must be 0)",
                                 m[12], m[13]);
        int infinite = m[10] == -1.0f;
        double n = infinite ? -0.5 * m[14] : m[14] / (m[10] - 1.0);
        double fa = infinite ? INFINITY : m[14] / (m[10] + 1.0);
        if (!(n > 0.0) || !(fa > n) || !(infinite || isfinite(fa)))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "oit_frame.projection: a "
                                 "perspective with near %g, far %g (m[10] = %g, m[14] = %g): "
                                 "need 0 < near < far <= inf",
                                 n, fa, m[10], m[14]);
        cam->projection = OIT_PROJ_PERSPECTIVE;
        cam->znear = (float)n;
        cam->zfar = infinite ? INFINITY : (float)fa;
        double f = m[5], a = f / m[0];
        if (m[8] == 0.0f && m[9] == 0.0f && fabs(a - aspect) <= 1e-3 * aspect) {
            cam->fovy_deg = (float)(2.0 * atan(1.0 / f) * 180.0 / 3.14159265358979323846);
            return OIT_OK;
        }
        cam->fovy_deg = (float)(2.0 * atan((w[3] - w[2]) / 2.0) * 180.0 / 3.14159265358979323846);
        for (int k = 0; k < 4; k++)
            cam->window[k] = (float)w[k];
        return OIT_OK;
    }
    if (m[11] == 0.0f && m[15] == 1.0f) {
        if (m[8] != 0.0f || m[9] != 0.0f)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "oit_frame.projection: an "
                                 "orthographic projection with m[8] = %g, m[9] = %g (an "
                                 "oblique one)",
                                 m[8], m[9]);
        double depth = -2.0 / m[10]; /* far - near */
        double n = -0.5 * depth * (m[14] + 1.0), fa = 0.5 * depth * (1.0 - m[14]);
        if (!(m[10] < 0.0f) || !isfinite(n) || !isfinite(fa) || !(fa > n))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "oit_frame.projection: an "
                                 "orthographic projection with near %g, far %g (m[10] = %g, "
                                 "m[14] = %g): need near < far, both finite",
                                 n, fa, m[10], m[14]);
        double ow[4] = {(-1.0 - m[12]) / m[0], (1.0 - m[12]) / m[0], (-1.0 - m[13]) / m[5],
                        (1.0 - m[13]) / m[5]};
        cam->projection = OIT_PROJ_ORTHOGRAPHIC;
        cam->fovy_deg = 45.0f; /* unused */
        cam->znear = (float)n;
        cam->zfar = (float)fa;
        cam->ortho_height = (float)(ow[3] - ow[2]);
        for (int k = 0; k < 4; k++)
            cam->window[k] = (float)ow[k];
        return OIT_OK;
    }
    return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                         "oit_frame.projection: m[11] = %g, m[15] = "
                         "%g: neither a perspective (-1, 0) nor an orthographic projection "
                         "(0, 1)",
                         m[11], m[15]);
}

/* oit_frame.model (liboit.h): all 0 the identity, else affine, finite and
 * invertible. */
static oit_status model_from_frame(const float *m, oit_view *v, oit_error *err)
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(m[i]))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                                 "oit_frame.model[%d] = %g is not "
                                 "finite",
                                 i, m[i]);
    memcpy(v->model, m, sizeof v->model);
    double d[16], eye[3], dir[3];
    if (!oit_view_model(v, d))
        return OIT_OK;
    if (m[3] != 0.0f || m[7] != 0.0f || m[11] != 0.0f || m[15] != 1.0f)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "oit_frame.model: last row (%g, %g, %g, "
                             "%g) is not (0, 0, 0, 1): not affine",
                             m[3], m[7], m[11], m[15]);
    if (!oit_view_model_eye(v, eye, dir))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED,
                             "oit_frame.model: the linear part is "
                             "singular");
    return OIT_OK;
}

/* oit_frame.clip: checked once, by its owner (view/render/image/clip.h). */
_Static_assert(OIT_FRAME_CLIP_MAX == OIT_CLIP_MAX, "oit_frame.clip holds OIT_CLIP_MAX planes");
static oit_status clip_from_frame(const oit_frame *f, oit_view *v, oit_error *err)
{
    v->clip.count = f->clip_count > OIT_CLIP_MAX ? OIT_CLIP_MAX + 1 : (int)f->clip_count;
    for (int i = 0; i < OIT_CLIP_MAX && i < v->clip.count; i++)
        memcpy(v->clip.plane[i], f->clip[i], sizeof v->clip.plane[i]);
    if (f->clip_count > OIT_CLIP_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "oit_frame.clip_count = %u: at most %d "
                             "planes",
                             f->clip_count, OIT_CLIP_MAX);
    return oit_clip_check(&v->clip, "oit_frame.clip", err);
}

static int all_finite(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* oit_frame.camera (liboit.h) copied as it is, so that no rounding stands
 * between the caller's camera and the one the capture builds its matrices
 * from; checked here, its one reader. */
static oit_status camera_given(const oit_frame_camera *c, oit_camera *cam, oit_error *err)
{
    const char *F = "oit_frame.camera";
    double d[3], u[3];
    for (int k = 0; k < 3; k++) {
        d[k] = (double)c->target[k] - c->eye[k];
        u[k] = c->up[k];
    }
    double cx = d[1] * u[2] - d[2] * u[1], cy = d[2] * u[0] - d[0] * u[2],
           cz = d[0] * u[1] - d[1] * u[0];
    if (!all_finite(c->eye, 3) || !all_finite(c->target, 3) || !all_finite(c->up, 3) ||
        !all_finite(c->window, 4) || !isfinite(c->ortho_height) || !isfinite(c->znear))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: a number that is not finite", F);
    if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 0.0) || !(cx * cx + cy * cy + cz * cz > 0.0))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: eye (%g, %g, %g) and target give no "
                             "view direction, or up (%g, %g, %g) is parallel to it",
                             F, c->eye[0], c->eye[1], c->eye[2], c->up[0], c->up[1], c->up[2]);
    int ortho = c->ortho_height != 0.0f;
    if (ortho ? !(c->ortho_height > 0.0f && c->zfar > c->znear && isfinite(c->zfar))
              : !(c->fovy_deg > 0.0f && c->fovy_deg < 180.0f && c->znear > 0.0f &&
                  c->zfar > c->znear))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s, fovy %g, near %g, far %g: need %s", F,
                             ortho ? "orthographic" : "perspective", c->fovy_deg, c->znear, c->zfar,
                             ortho ? "ortho_height > 0, znear < zfar < inf"
                                   : "fovy_deg in (0, 180), 0 < znear < zfar");
    memset(cam, 0, sizeof *cam);
    memcpy(cam->eye, c->eye, sizeof cam->eye);
    memcpy(cam->target, c->target, sizeof cam->target);
    memcpy(cam->up, c->up, sizeof cam->up);
    cam->fovy_deg = c->fovy_deg;
    cam->znear = c->znear;
    cam->zfar = c->zfar;
    cam->projection = ortho ? OIT_PROJ_ORTHOGRAPHIC : OIT_PROJ_PERSPECTIVE;
    cam->ortho_height = c->ortho_height;
    memcpy(cam->window, c->window, sizeof cam->window);
    return OIT_OK;
}

/* The view's size, camera and model from f (no shading). */
oit_status oit_lib_frame_camera(const oit_frame *f, oit_view *v, oit_error *err)
{
    if (f->viewport_width <= 0 || f->viewport_height <= 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_frame: viewport %dx%d is empty",
                             f->viewport_width, f->viewport_height);
    memset(v, 0, sizeof *v);
    v->width = f->viewport_width;
    v->height = f->viewport_height;
    oit_status st = OIT_OK;
    if (f->camera)
        st = camera_given(f->camera, &v->camera, err);
    if (st == OIT_OK && !f->camera)
        st = camera_from_view(f->view, &v->camera, err);
    if (st == OIT_OK && !f->camera)
        st = camera_from_projection(f->projection, (double)v->width / v->height, &v->camera, err);
    if (st == OIT_OK)
        st = model_from_frame(f->model, v, err);
    if (st == OIT_OK)
        st = clip_from_frame(f, v, err);
    return st;
}

oit_status oit_lib_frame_view(const oit_renderer *r, const oit_scene *scene, const oit_frame *f,
                              const float *bg, oit_view *v, oit_error *err)
{
    oit_status st = oit_lib_frame_camera(f, v, err);
    if (st == OIT_OK)
        oit_lib_make_shading(r, scene, bg, &v->shading);
    return st;
}
