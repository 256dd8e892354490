/* Section planes (clip.h). */
#include "view/render/image/clip.h"

#include <math.h>
#include <string.h>

#include "base/args.h"

oit_status oit_clip_check(const oit_clip *c, const char *what, oit_error *err)
{
    if (c->count < 0 || c->count > OIT_CLIP_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %d planes; at most %d", what, c->count,
                             OIT_CLIP_MAX);
    for (int i = 0; i < c->count; i++) {
        const float *p = c->plane[i];
        for (int k = 0; k < 4; k++)
            if (!isfinite(p[k]))
                return oit_error_set(err, OIT_ERR_ARGUMENT,
                                     "%s: plane %d (%g,%g,%g,%g): not a finite number", what,
                                     i + 1, p[0], p[1], p[2], p[3]);
        if (p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: plane %d (%g,%g,%g,%g): the normal (a,b,c) is zero", what,
                                 i + 1, p[0], p[1], p[2], p[3]);
    }
    return OIT_OK;
}

/* Splits "a,b,c,d" into four finite numbers; returns how many it read, or
 * -1 on anything else. */
static int parse_four(const char *text, double v[4])
{
    char buf[256];
    size_t len = strlen(text);
    if (len >= sizeof buf)
        return -1;
    memcpy(buf, text, len + 1);
    int n = 0;
    for (char *s = buf;; n++) {
        char *comma = strchr(s, ',');
        if (comma)
            *comma = '\0';
        if (n == 4 || oit_parse_double(s, -1e30, 1e30, &v[n]) != 0)
            return -1;
        if (!comma)
            return n + 1;
        s = comma + 1;
    }
}

/* The plane "a,b,c,d" into v, or OIT_ERR_ARGUMENT naming what and text. */
static oit_status parse_plane(const char *text, int count, const char *what, double v[4],
                              oit_error *err)
{
    if (!text || parse_four(text, v) != 4)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s '%s': expected four numbers nx,ny,nz,d (the plane keeps "
                             "nx*x + ny*y + nz*z + d >= 0)",
                             what, text ? text : "(null)");
    if (count >= OIT_CLIP_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s '%s': at most %d planes", what, text,
                             OIT_CLIP_MAX);
    return OIT_OK;
}

/* Appends v, relative to origin, to c when the result passes the check. */
static oit_status add_plane(oit_clip *c, const double given[4], const double origin[3],
                            const char *what, oit_error *err)
{
    double v[4] = {given[0], given[1], given[2], given[3]};
    /* Positions are relative to origin: n . (p + origin) + d. */
    if (origin)
        v[3] += v[0] * origin[0] + v[1] * origin[1] + v[2] * origin[2];
    oit_clip next = *c;
    for (int k = 0; k < 4; k++)
        next.plane[next.count][k] = (float)v[k];
    next.count++;
    oit_status s = oit_clip_check(&next, what, err);
    if (s == OIT_OK)
        *c = next;
    return s;
}

oit_status oit_clip_add_text(oit_clip *c, const char *text, const double origin[3],
                             const char *what, oit_error *err)
{
    double v[4];
    oit_status s = parse_plane(text, c->count, what, v, err);
    return s == OIT_OK ? add_plane(c, v, origin, what, err) : s;
}

oit_status oit_clip_given_add_text(oit_clip_given *g, const char *text, const char *what,
                                   oit_error *err)
{
    double v[4];
    oit_clip placed;
    oit_status s = parse_plane(text, g->count, what, v, err);
    if (s == OIT_OK)
        s = oit_clip_place(g, NULL, what, &placed, err);
    if (s == OIT_OK)
        s = add_plane(&placed, v, NULL, what, err);
    if (s == OIT_OK)
        memcpy(g->plane[g->count++], v, sizeof v);
    return s;
}

oit_status oit_clip_place(const oit_clip_given *g, const double origin[3], const char *what,
                          oit_clip *out, oit_error *err)
{
    oit_clip c;
    memset(&c, 0, sizeof c);
    oit_status s = OIT_OK;
    for (int i = 0; i < g->count && i < OIT_CLIP_MAX && s == OIT_OK; i++)
        s = add_plane(&c, g->plane[i], origin, what, err);
    if (s == OIT_OK)
        *out = c;
    return s;
}

void oit_clip_eye(const oit_clip *c, const float m[16], float out[OIT_CLIP_MAX][4])
{
    memset(out, 0, OIT_CLIP_MAX * sizeof out[0]);
    for (int i = 0; i < c->count && i < OIT_CLIP_MAX; i++) {
        const float *p = c->plane[i];
        /* q = R p + t, so n . p + d = (R n) . q + d - (R n) . t. */
        double n[3], nt = 0.0;
        for (int r = 0; r < 3; r++) {
            n[r] = (double)m[r] * p[0] + (double)m[4 + r] * p[1] + (double)m[8 + r] * p[2];
            nt += n[r] * m[12 + r];
        }
        for (int r = 0; r < 3; r++)
            out[i][r] = (float)n[r];
        out[i][3] = (float)((double)p[3] - nt);
    }
}

int oit_clip_keeps(int count, const float eye[OIT_CLIP_MAX][4], const float o[3],
                   const float dir[3], float t)
{
    float p[3];
    for (int k = 0; k < 3; k++)
        p[k] = o[k] + dir[k] * t;
    for (int i = 0; i < count && i < OIT_CLIP_MAX; i++) {
        const float *q = eye[i];
        float s = q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3];
        if (s < 0.0f)
            return 0;
    }
    return 1;
}

void oit_clip_model(const oit_clip *c, const double mm[16], double out[OIT_CLIP_MAX][4])
{
    memset(out, 0, OIT_CLIP_MAX * sizeof out[0]);
    for (int i = 0; i < c->count && i < OIT_CLIP_MAX; i++)
        for (int j = 0; j < 4; j++)
            out[i][j] = c->plane[i][0] * mm[j * 4] + c->plane[i][1] * mm[j * 4 + 1] +
                        c->plane[i][2] * mm[j * 4 + 2] + c->plane[i][3] * mm[j * 4 + 3];
}

int oit_clip_box_outside(int count, const double planes[OIT_CLIP_MAX][4], const float lo[3],
                         const float hi[3])
{
    for (int i = 0; i < count && i < OIT_CLIP_MAX; i++) {
        const double *p = planes[i];
        /* The corner farthest on the kept side, and the scale of the sum,
         * for a margin far above float rounding yet below any real gap. */
        double best = p[3], scale = fabs(p[3]);
        for (int k = 0; k < 3; k++) {
            best += fmax(p[k] * lo[k], p[k] * hi[k]);
            scale += fabs(p[k]) * fmax(fabs(lo[k]), fabs(hi[k]));
        }
        if (best < -1e-5 * scale)
            return 1;
    }
    return 0;
}
