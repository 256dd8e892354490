/* Camera helpers and shading defaults shared by every renderer (view.h).
 * Matrices follow GL conventions (column-major, right-handed view space
 * looking down -z) so the GL methods and the Embree reference see the same
 * rays through the same pixel centres. */
#include "render/view.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double kPi = 3.14159265358979323846;

static void normalize3(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0.0)
        for (int k = 0; k < 3; k++)
            v[k] /= len;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

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
    cross3(U[a], F[a], S);
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
    normalize3(f);
    cross3(f, up, s);
    normalize3(s);
    cross3(s, f, u);
    const double rows[3][3] = {{s[0], s[1], s[2]}, {u[0], u[1], u[2]}, {-f[0], -f[1], -f[2]}};
    memset(m, 0, 16 * sizeof *m);
    for (int r = 0; r < 3; r++) {
        for (int col = 0; col < 3; col++)
            m[col * 4 + r] = (float)rows[r][col];
        m[12 + r] = (float)-(rows[r][0] * e[0] + rows[r][1] * e[1] + rows[r][2] * e[2]);
    }
    m[15] = 1.0f;
}

void oit_camera_proj_matrix(const oit_camera *cam, float aspect, float m[16])
{
    double fovy = cam->fovy_deg > 0.0f ? cam->fovy_deg : 45.0;
    double f = 1.0 / tan(0.5 * fovy * kPi / 180.0);
    double n = cam->znear, fa = cam->zfar;
    memset(m, 0, 16 * sizeof *m);
    m[0] = (float)(f / aspect);
    m[5] = (float)f;
    m[10] = (float)((fa + n) / (n - fa));
    m[11] = -1.0f;
    m[14] = (float)(2.0 * fa * n / (n - fa));
}

void oit_view_ray_map(const oit_view *view, float ray[4])
{
    double fovy = view->camera.fovy_deg > 0.0f ? view->camera.fovy_deg : 45.0;
    double ty = tan(0.5 * fovy * kPi / 180.0);
    double tx = ty * (double)view->width / (double)view->height;
    ray[0] = (float)(2.0 * tx / view->width);
    ray[1] = (float)(2.0 * ty / view->height);
    ray[2] = (float)-tx;
    ray[3] = (float)-ty;
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
    double fovy = cam->fovy_deg > 0.0f ? cam->fovy_deg : 45.0;
    double f = 1.0 / tan(0.5 * fovy * kPi / 180.0), slack = 1.001;
    double a = aspect / f * slack, b = 1.0 / f * slack;
    /* Eye space (looking down -z, depth d = -z): |x| <= a d, |y| <= b d,
     * znear / 2 <= d <= zfar * slack. */
    const double eye_planes[6][4] = {{1, 0, -a, 0},  {-1, 0, -a, 0},
                                     {0, 1, -b, 0},  {0, -1, -b, 0},
                                     {0, 0, -1, -0.5 * cam->znear},
                                     {0, 0, 1, (double)cam->zfar * slack}};
    float m[16];
    oit_camera_view_matrix(cam, m);
    /* A plane p on eye coordinates M x is the plane M^T p on x. */
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 4; j++) {
            double v = 0;
            for (int r = 0; r < 4; r++)
                v += eye_planes[i][r] * m[j * 4 + r];
            planes[i][j] = (float)v;
        }
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
    default: return "expected ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy[,znear,zfar]";
    }
}

int oit_camera_parse(oit_camera *cam, const char *text, const double origin[3])
{
    double v[12];
    int n = text ? parse_numbers(text, v, 12) : -1;
    /* Ten numbers, or twelve with znear,zfar appended; without them the
     * caller's clip planes are kept. */
    if (n != 10 && n != 12)
        return -1;
    double f[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, up[3] = {v[6], v[7], v[8]}, s[3];
    cross3(f, up, s);
    if (!(f[0] * f[0] + f[1] * f[1] + f[2] * f[2] > 0.0))
        return -2;
    if (!(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] > 0.0))
        return -3;
    if (!(v[9] > 0.0 && v[9] < 180.0))
        return -4;
    if (n == 12 && !(v[10] > 0.0 && v[11] > v[10]))
        return -5;
    for (int k = 0; k < 3; k++) {
        double o = origin ? origin[k] : 0.0;
        cam->eye[k] = (float)(v[k] - o);
        cam->target[k] = (float)(v[3 + k] - o);
        cam->up[k] = (float)v[6 + k];
    }
    cam->fovy_deg = (float)v[9];
    if (n == 12) {
        cam->znear = (float)v[10];
        cam->zfar = (float)v[11];
    }
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

float oit_scene_scale(const float bmin[3], const float bmax[3])
{
    double d2 = 0.0;
    for (int k = 0; k < 3; k++)
        d2 += ((double)bmax[k] - bmin[k]) * ((double)bmax[k] - bmin[k]);
    return d2 > 0.0 && isfinite(d2) ? (float)sqrt(d2) : 1.0f;
}
