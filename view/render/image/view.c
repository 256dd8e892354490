/* Camera helpers and shading defaults shared by every renderer (view.h).
 * Matrices follow GL conventions (column-major, right-handed view space
 * looking down -z) so the GL methods and the Embree reference see the same
 * rays through the same pixel centres. */
#include "view/render/image/view.h"
#include "base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double kPi = 3.14159265358979323846;

void oit_camera_default(oit_camera *cam, const float bmin[3], const float bmax[3],
                        float azimuth_deg, float elevation_deg)
{
    oit_camera_default_up(cam, bmin, bmax, azimuth_deg, elevation_deg, 1);
}

void oit_camera_default_up(oit_camera *cam, const float bmin[3], const float bmax[3],
                           float azimuth_deg, float elevation_deg, int up_axis)
{
    double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    /* An empty mesh has +inf/-inf bounds: fall back to the unit cube so the
     * camera is still usable. */
    if (isfinite(bmin[0]) && isfinite(bmax[0]) && bmin[0] <= bmax[0])
        for (int k = 0; k < 3; k++) {
            lo[k] = bmin[k];
            hi[k] = bmax[k];
        }
    double c[3], r2 = 0.0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        r2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    double r = sqrt(r2) > 0.0 ? sqrt(r2) : 1.0;
    memset(cam, 0, sizeof *cam);
    cam->fovy_deg = 45.0f;
    /* The bounding sphere fits the vertical field of view. */
    double dist = r / sin(0.5 * cam->fovy_deg * kPi / 180.0);
    double az = azimuth_deg * kPi / 180.0, el = elevation_deg * kPi / 180.0;
    /* up U, front F (the eye's side at azimuth 0), side S = U x F (azimuth
     * 90): y up looks from +z with x to the right; z up (CAD) from -y with x
     * to the right; x up from +z with -y to the right. */
    static const double U[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const double F[3][3] = {{0, 0, 1}, {0, 0, 1}, {0, -1, 0}};
    int a = up_axis >= 0 && up_axis <= 2 ? up_axis : 1;
    double S[3];
    oit_cross3d(U[a], F[a], S);
    double dir[3];
    for (int k = 0; k < 3; k++)
        dir[k] = cos(el) * (sin(az) * S[k] + cos(az) * F[a][k]) + sin(el) * U[a][k];
    for (int k = 0; k < 3; k++) {
        cam->target[k] = (float)c[k];
        cam->eye[k] = (float)(c[k] + dist * dir[k]);
    }
    /* Looking straight up or down: the up axis cannot be the up vector. */
    int polar = fabs(cos(el)) < 1e-6;
    for (int k = 0; k < 3; k++)
        cam->up[k] = (float)(polar ? 0.0 - F[a][k] : U[a][k]); /* +0, not -0 */
    /* The sphere lies within [dist - r, dist + r]; margins keep silhouettes
     * away from the clip planes. */
    cam->znear = (float)fmax(dist - 1.05 * r, 1e-4 * dist);
    cam->zfar = (float)(dist + 1.05 * r);
}

void oit_camera_view_matrix(const oit_camera *cam, float m[16])
{
    double f[3], up[3], s[3], u[3], e[3];
    for (int k = 0; k < 3; k++) {
        f[k] = (double)cam->target[k] - cam->eye[k];
        up[k] = cam->up[k];
        e[k] = cam->eye[k];
    }
    oit_normalize3d(f);
    oit_cross3d(f, up, s);
    oit_normalize3d(s);
    oit_cross3d(s, f, u);
    const double rows[3][3] = {{s[0], s[1], s[2]}, {u[0], u[1], u[2]}, {-f[0], -f[1], -f[2]}};
    memset(m, 0, 16 * sizeof *m);
    for (int r = 0; r < 3; r++) {
        for (int col = 0; col < 3; col++)
            m[col * 4 + r] = (float)rows[r][col];
        m[12 + r] = (float)-(rows[r][0] * e[0] + rows[r][1] * e[1] + rows[r][2] * e[2]);
    }
    m[15] = 1.0f;
}

static int window_is_zero(const oit_camera *cam)
{
    return cam->window[0] == 0.0f && cam->window[1] == 0.0f && cam->window[2] == 0.0f &&
           cam->window[3] == 0.0f;
}

void oit_camera_window(const oit_camera *cam, double aspect, double w[4])
{
    if (!window_is_zero(cam)) {
        for (int k = 0; k < 4; k++)
            w[k] = cam->window[k];
        return;
    }
    double hy;
    if (cam->projection == OIT_PROJ_ORTHOGRAPHIC) {
        hy = 0.5 * (cam->ortho_height > 0.0f ? cam->ortho_height : 1.0);
    } else {
        double fovy = cam->fovy_deg > 0.0f ? cam->fovy_deg : 45.0;
        hy = tan(0.5 * fovy * kPi / 180.0);
    }
    w[0] = -hy * aspect;
    w[1] = hy * aspect;
    w[2] = -hy;
    w[3] = hy;
}

void oit_camera_proj_matrix(const oit_camera *cam, float aspect, float m[16])
{
    double n = cam->znear, fa = cam->zfar;
    memset(m, 0, 16 * sizeof *m);
    if (cam->projection == OIT_PROJ_ORTHOGRAPHIC) {
        double w[4];
        oit_camera_window(cam, aspect, w);
        m[0] = (float)(2.0 / (w[1] - w[0]));
        m[5] = (float)(2.0 / (w[3] - w[2]));
        m[10] = (float)(-2.0 / (fa - n));
        m[12] = (float)(-(w[1] + w[0]) / (w[1] - w[0]));
        m[13] = (float)(-(w[3] + w[2]) / (w[3] - w[2]));
        m[14] = (float)(-(fa + n) / (fa - n));
        m[15] = 1.0f;
        return;
    }
    if (window_is_zero(cam)) {
        /* The symmetric perspective: the arithmetic every pinned image was
         * made with. */
        double fovy = cam->fovy_deg > 0.0f ? cam->fovy_deg : 45.0;
        double f = 1.0 / tan(0.5 * fovy * kPi / 180.0);
        m[0] = (float)(f / aspect);
        m[5] = (float)f;
    } else {
        double w[4];
        oit_camera_window(cam, aspect, w);
        m[0] = (float)(2.0 / (w[1] - w[0]));
        m[5] = (float)(2.0 / (w[3] - w[2]));
        m[8] = (float)((w[1] + w[0]) / (w[1] - w[0]));
        m[9] = (float)((w[3] + w[2]) / (w[3] - w[2]));
    }
    m[11] = -1.0f;
    if (isinf(fa)) {
        m[10] = -1.0f;
        m[14] = (float)(-2.0 * n);
    } else {
        m[10] = (float)((fa + n) / (n - fa));
        m[14] = (float)(2.0 * fa * n / (n - fa));
    }
}

void oit_view_ray_map(const oit_view *view, float ray[4])
{
    const oit_camera *cam = &view->camera;
    if (cam->projection == OIT_PROJ_ORTHOGRAPHIC) {
        ray[0] = ray[1] = ray[2] = ray[3] = 0.0f;
        return;
    }
    if (!window_is_zero(cam)) {
        ray[0] = (float)(((double)cam->window[1] - cam->window[0]) / view->width);
        ray[1] = (float)(((double)cam->window[3] - cam->window[2]) / view->height);
        ray[2] = cam->window[0];
        ray[3] = cam->window[2];
        return;
    }
    double fovy = view->camera.fovy_deg > 0.0f ? view->camera.fovy_deg : 45.0;
    double ty = tan(0.5 * fovy * kPi / 180.0);
    double tx = ty * (double)view->width / (double)view->height;
    ray[0] = (float)(2.0 * tx / view->width);
    ray[1] = (float)(2.0 * ty / view->height);
    ray[2] = (float)-tx;
    ray[3] = (float)-ty;
}

void oit_view_origin_map(const oit_view *view, float org[4], float *org_z)
{
    const oit_camera *cam = &view->camera;
    org[0] = org[1] = org[2] = org[3] = 0.0f;
    *org_z = 0.0f;
    if (cam->projection != OIT_PROJ_ORTHOGRAPHIC)
        return;
    double w[4];
    oit_camera_window(cam, (double)view->width / (double)view->height, w);
    org[0] = (float)((w[1] - w[0]) / view->width);
    org[1] = (float)((w[3] - w[2]) / view->height);
    org[2] = (float)w[0];
    org[3] = (float)w[2];
    *org_z = -cam->znear;
}

void oit_view_pixel_origin(const float org[4], float org_z, int x, int y, int height,
                           float o[3])
{
    float fx = (float)x + 0.5f, fy = (float)(height - 1 - y) + 0.5f;
    o[0] = fx * org[0] + org[2];
    o[1] = fy * org[1] + org[3];
    o[2] = org_z;
}

void oit_view_pixel_ray(const float ray[4], int x, int y, int height, float dir[3])
{
    float fx = (float)x + 0.5f, fy = (float)(height - 1 - y) + 0.5f;
    dir[0] = fx * ray[0] + ray[2];
    dir[1] = fy * ray[1] + ray[3];
    dir[2] = -1.0f;
    float inv = 1.0f / sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (int k = 0; k < 3; k++)
        dir[k] *= inv;
}

void oit_camera_frustum(const oit_camera *cam, float aspect, float planes[6][4])
{
    double slack = 1.001;
    double ep[6][4];
    if (cam->projection == OIT_PROJ_ORTHOGRAPHIC) {
        /* Eye space: l <= x <= r, b <= y <= t, znear <= d <= zfar, each
         * grown by 0.1% of the volume's size. */
        double w[4];
        oit_camera_window(cam, aspect, w);
        double gx = 1e-3 * (w[1] - w[0]), gy = 1e-3 * (w[3] - w[2]);
        double gz = 1e-3 * ((double)cam->zfar - cam->znear);
        const double o[6][4] = {{1, 0, 0, -(w[0] - gx)},  {-1, 0, 0, w[1] + gx},
                                {0, 1, 0, -(w[2] - gy)},  {0, -1, 0, w[3] + gy},
                                {0, 0, -1, -(cam->znear - gz)},
                                {0, 0, 1, (double)cam->zfar + gz}};
        memcpy(ep, o, sizeof ep);
    } else if (window_is_zero(cam)) {
        double fovy = cam->fovy_deg > 0.0f ? cam->fovy_deg : 45.0;
        double f = 1.0 / tan(0.5 * fovy * kPi / 180.0);
        double a = aspect / f * slack, b = 1.0 / f * slack;
        /* Eye space (looking down -z, depth d = -z): |x| <= a d, |y| <= b d,
         * znear / 2 <= d <= zfar * slack. */
        const double o[6][4] = {{1, 0, -a, 0},  {-1, 0, -a, 0},
                                {0, 1, -b, 0},  {0, -1, -b, 0},
                                {0, 0, -1, -0.5 * cam->znear},
                                {0, 0, 1, (double)cam->zfar * slack}};
        memcpy(ep, o, sizeof ep);
    } else {
        /* l d <= x <= r d, b d <= y <= t d, each side turned out by 0.1% of
         * the window's size. */
        double w[4];
        oit_camera_window(cam, aspect, w);
        double gx = 1e-3 * (w[1] - w[0]), gy = 1e-3 * (w[3] - w[2]);
        const double o[6][4] = {{1, 0, w[0] - gx, 0},  {-1, 0, -(w[1] + gx), 0},
                                {0, 1, w[2] - gy, 0},  {0, -1, -(w[3] + gy), 0},
                                {0, 0, -1, -0.5 * cam->znear},
                                {0, 0, 1, (double)cam->zfar * slack}};
        memcpy(ep, o, sizeof ep);
    }
    float m[16];
    oit_camera_view_matrix(cam, m);
    /* A plane p on eye coordinates M x is the plane M^T p on x. An infinite
     * far plane culls nothing: (0, 0, 0, 1). */
    for (int i = 0; i < 6; i++) {
        if (isinf(ep[i][3])) {
            planes[i][0] = planes[i][1] = planes[i][2] = 0.0f;
            planes[i][3] = 1.0f;
            continue;
        }
        for (int j = 0; j < 4; j++) {
            double v = 0;
            for (int r = 0; r < 4; r++)
                v += ep[i][r] * m[j * 4 + r];
            planes[i][j] = (float)v;
        }
    }
}

int oit_view_model(const oit_view *view, double m[16])
{
    int any = 0;
    for (int i = 0; i < 16; i++) {
        m[i] = view->model[i];
        any |= view->model[i] != 0.0f;
    }
    if (!any) {
        memset(m, 0, 16 * sizeof *m);
        m[0] = m[5] = m[10] = m[15] = 1.0;
        return 0;
    }
    return 1;
}

void oit_view_model_view_matrix(const oit_view *view, float m[16])
{
    oit_camera_view_matrix(&view->camera, m);
    double mm[16];
    if (!oit_view_model(view, mm))
        return;
    float v[16];
    memcpy(v, m, sizeof v);
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double acc = 0.0;
            for (int k = 0; k < 4; k++)
                acc += (double)v[k * 4 + r] * mm[c * 4 + k];
            m[c * 4 + r] = (float)acc;
        }
}

int oit_view_model_eye(const oit_view *view, double eye[3], double dir[3])
{
    double m[16];
    oit_view_model(view, m);
    /* The linear part L (m[col * 4 + row]) and its inverse by cofactors. */
    double a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6],
           i = m[10];
    double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    if (!(fabs(det) > 0.0) || !isfinite(det))
        return 0;
    double inv[3][3] = {{(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det},
                        {(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det},
                        {(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det}};
    double pe[3], pd[3];
    for (int k = 0; k < 3; k++) {
        pe[k] = (double)view->camera.eye[k] - m[12 + k];
        pd[k] = (double)view->camera.target[k] - view->camera.eye[k];
    }
    for (int r = 0; r < 3; r++) {
        eye[r] = inv[r][0] * pe[0] + inv[r][1] * pe[1] + inv[r][2] * pe[2];
        dir[r] = inv[r][0] * pd[0] + inv[r][1] * pd[1] + inv[r][2] * pd[2];
    }
    return 1;
}

/* Reads up to max comma-separated finite numbers; returns how many. */
static int parse_numbers(const char *text, double *v, int max)
{
    int n = 0;
    const char *p = text;
    while (n < max) {
        char *end;
        double x = strtod(p, &end);
        if (end == p || !isfinite(x))
            return -1;
        v[n++] = x;
        if (*end == '\0')
            return n;
        if (*end != ',')
            return -1;
        p = end + 1;
    }
    return -1; /* more numbers than allowed */
}

const char *oit_camera_parse_error(int code)
{
    switch (code) {
    case -2: return "the eye and the target are the same point (no direction to look in)";
    case -3: return "the up vector is zero or parallel to the viewing direction";
    case -4: return "fovy must lie in (0, 180) degrees";
    case -5: return "znear must be > 0 and zfar > znear";
    case -6: return "bad projection field: expected :ortho=H (H > 0), :window=l,r,b,t (l < r, "
                    "b < t) or :far=inf (perspective only)";
    default: return "expected ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy[,znear,zfar]"
                    "[:ortho=H][:window=l,r,b,t][:far=inf]";
    }
}

/* The projection fields after the numbers (oit_camera_parse). */
static int parse_projection(oit_camera *cam, const char *p)
{
    int ortho = 0, far_inf = 0, have_window = 0;
    double h = 0.0, w[4] = {0, 0, 0, 0};
    while (*p == ':') {
        p++;
        const char *end = strchr(p, ':');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char field[256];
        if (len >= sizeof field)
            return -6;
        memcpy(field, p, len);
        field[len] = '\0';
        if (!strncmp(field, "ortho=", 6)) {
            if (parse_numbers(field + 6, &h, 1) != 1 || !(h > 0.0))
                return -6;
            ortho = 1;
        } else if (!strncmp(field, "window=", 7)) {
            if (parse_numbers(field + 7, w, 4) != 4 || !(w[0] < w[1]) || !(w[2] < w[3]))
                return -6;
            have_window = 1;
        } else if (!strcmp(field, "far=inf")) {
            far_inf = 1;
        } else {
            return -6;
        }
        p += len;
    }
    if (*p != '\0' || (ortho && far_inf))
        return -6;
    cam->projection = ortho ? OIT_PROJ_ORTHOGRAPHIC : OIT_PROJ_PERSPECTIVE;
    cam->ortho_height = (float)h;
    for (int k = 0; k < 4; k++)
        cam->window[k] = (float)w[k];
    (void)have_window;
    return 0;
}

int oit_camera_parse(oit_camera *cam, const char *text, const double origin[3])
{
    double v[12];
    /* The numbers end at the first ':' (projection fields follow). */
    char numbers[1024];
    const char *colon = text ? strchr(text, ':') : NULL;
    size_t len = text ? (colon ? (size_t)(colon - text) : strlen(text)) : 0;
    if (!text || len >= sizeof numbers)
        return -1;
    memcpy(numbers, text, len);
    numbers[len] = '\0';
    int n = parse_numbers(numbers, v, 12);
    /* Ten numbers, or twelve with znear,zfar appended; without them the
     * caller's clip planes are kept. */
    if (n != 10 && n != 12)
        return -1;
    double f[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, up[3] = {v[6], v[7], v[8]}, s[3];
    oit_cross3d(f, up, s);
    if (!(oit_dot3d(f, f) > 0.0))
        return -2;
    if (!(oit_dot3d(s, s) > 0.0))
        return -3;
    if (!(v[9] > 0.0 && v[9] < 180.0))
        return -4;
    oit_camera c = *cam;
    if (parse_projection(&c, colon ? colon : "") != 0)
        return -6;
    int ortho = c.projection == OIT_PROJ_ORTHOGRAPHIC;
    if (n == 12 && !((ortho || v[10] > 0.0) && v[11] > v[10]))
        return -5;
    for (int k = 0; k < 3; k++) {
        double o = origin ? origin[k] : 0.0;
        c.eye[k] = (float)(v[k] - o);
        c.target[k] = (float)(v[3 + k] - o);
        c.up[k] = (float)v[6 + k];
    }
    c.fovy_deg = (float)v[9];
    if (n == 12) {
        c.znear = (float)v[10];
        c.zfar = (float)v[11];
    }
    if (colon && strstr(colon, ":far=inf"))
        c.zfar = INFINITY;
    *cam = c;
    return 0;
}

void oit_shading_resolve_defaults(oit_shading *s)
{
    if (s->alpha == 0.0f)
        s->alpha = 0.35f;
    if (s->default_rgb[0] == 0.0f && s->default_rgb[1] == 0.0f && s->default_rgb[2] == 0.0f) {
        s->default_rgb[0] = 0.85f;
        s->default_rgb[1] = 0.55f;
        s->default_rgb[2] = 0.2f;
    }
    /* All zero means default white; negative values (black) are kept and
     * read as 0 by the compositor. */
    if (s->background[0] == 0.0f && s->background[1] == 0.0f && s->background[2] == 0.0f)
        s->background[0] = s->background[1] = s->background[2] = 1.0f;
    if (s->absorption == 0.0f)
        s->absorption = 4.0f;
}

uint32_t oit_shading_attrs(const oit_shading *s)
{
    return s->see_through ? s->attributes & ~(uint32_t)OIT_ATTR_ALPHA : s->attributes;
}

int oit_shading_opaque(const oit_shading *s)
{
    uint32_t both = OIT_ATTR_ALPHA | OIT_ATTR_OPAQUE;
    return s->mode == OIT_SHADING_TRANSPARENT && (oit_shading_attrs(s) & both) == both;
}

float oit_scene_scale(const float bmin[3], const float bmax[3])
{
    double d2 = 0.0;
    for (int k = 0; k < 3; k++)
        d2 += ((double)bmax[k] - bmin[k]) * ((double)bmax[k] - bmin[k]);
    return d2 > 0.0 && isfinite(d2) ? (float)sqrt(d2) : 1.0f;
}

/* FNV-1a over n bytes. */
static uint64_t mix(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

uint64_t oit_view_key(const oit_view *view)
{
    /* Field by field: no padding bytes enter the key. */
    const oit_camera *cam = &view->camera;
    uint64_t h = 14695981039346656037ull;
    h = mix(h, cam->eye, sizeof cam->eye);
    h = mix(h, cam->target, sizeof cam->target);
    h = mix(h, cam->up, sizeof cam->up);
    h = mix(h, &cam->fovy_deg, sizeof cam->fovy_deg);
    h = mix(h, &cam->znear, sizeof cam->znear);
    h = mix(h, &cam->zfar, sizeof cam->zfar);
    h = mix(h, &cam->projection, sizeof cam->projection);
    h = mix(h, &cam->ortho_height, sizeof cam->ortho_height);
    h = mix(h, cam->window, sizeof cam->window);
    h = mix(h, &view->width, sizeof view->width);
    h = mix(h, &view->height, sizeof view->height);
    h = mix(h, &view->shading.mode, sizeof view->shading.mode);
    h = mix(h, view->model, sizeof view->model);
    h = mix(h, &view->clip.count, sizeof view->clip.count);
    for (int i = 0; i >= 0 && i < view->clip.count && i < OIT_CLIP_MAX; i++)
        h = mix(h, view->clip.plane[i], sizeof view->clip.plane[i]);
    return h;
}
