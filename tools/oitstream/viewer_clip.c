/* The viewer's section-plane keys (viewer_clip.h). */
#include "tools/oitstream/viewer_clip.h"

#include <math.h>
#include <stdio.h>

#define STEPS_PER_RADIUS 25.0

/* A plane through centre whose normal is the view direction: it keeps
 * what lies beyond the centre as seen from the eye. */
static void make_facing(oit_viewer_clip *c, const oit_camera *cam, const float centre[3])
{
    double f[3], len = 0.0;
    for (int k = 0; k < 3; k++) {
        f[k] = (double)cam->target[k] - cam->eye[k];
        len += f[k] * f[k];
    }
    len = sqrt(len);
    if (!(len > 0.0))
        f[0] = f[1] = 0.0, f[2] = -1.0, len = 1.0;
    double d = 0.0;
    for (int k = 0; k < 3; k++) {
        c->planes.plane[0][k] = (float)(f[k] / len);
        d -= f[k] / len * centre[k];
    }
    c->planes.plane[0][3] = (float)d;
    c->planes.count = 1;
    c->off = 0;
}

int oit_viewer_clip_key(oit_viewer_clip *c, char key, const oit_camera *cam,
                        const float centre[3], float radius, const double origin[3],
                        char *note, size_t cap)
{
    float *p = c->planes.plane[0];
    if (key == 'X') {
        if (c->planes.count == 0)
            make_facing(c, cam, centre);
        else
            c->off = !c->off;
    } else if (key == '[' || key == ']') {
        if (c->planes.count == 0) {
            snprintf(note, cap, "no section plane to move: X makes one");
            return -1;
        }
        double n = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
        double step = radius / STEPS_PER_RADIUS * n;
        p[3] = (float)(p[3] + (key == ']' ? -step : step));
        c->off = 0;
    } else {
        return 0;
    }
    double d = p[3] - (p[0] * origin[0] + p[1] * origin[1] + p[2] * origin[2]);
    if (c->off)
        snprintf(note, cap, "section planes off (X turns them on)");
    else
        snprintf(note, cap, "section plane 1 of %d: %.9g,%.9g,%.9g,%.17g keeps ax+by+cz+d >= 0",
                 c->planes.count, p[0], p[1], p[2], d);
    return 1;
}

oit_clip oit_viewer_clip_shown(const oit_viewer_clip *c)
{
    oit_clip none = {0};
    return c->off ? none : c->planes;
}
