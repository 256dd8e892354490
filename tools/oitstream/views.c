/* oitstream's views, shading, output names and stream settings (views.h). */
#include "tools/oitstream/views.h"

#include "formats/up_axis.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* Clip planes that enclose the model's bounding sphere, for a --view given
 * without them. */
static void fit_clip_planes(oit_camera *cam, const oit_mesh_info *info)
{
    double c[3], r2 = 0.0, f[3], flen = 0.0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * ((double)info->bounds_min[k] + info->bounds_max[k]);
        r2 += 0.25 * pow((double)info->bounds_max[k] - info->bounds_min[k], 2.0);
        f[k] = (double)cam->target[k] - cam->eye[k];
        flen += f[k] * f[k];
    }
    double r = sqrt(r2) > 0.0 && isfinite(r2) ? sqrt(r2) : 1.0, dc = 0.0;
    for (int k = 0; k < 3; k++)
        dc += (c[k] - cam->eye[k]) * f[k] / sqrt(flen);
    double far = dc + 1.05 * r;
    cam->zfar = (float)(far > 0.0 ? far : r);
    cam->znear = (float)fmax(dc - 1.05 * r, 1e-4 * cam->zfar);
    if (cam->projection == OIT_PROJ_ORTHOGRAPHIC) /* parallel rays: behind the eye too */
        cam->znear = (float)(dc - 1.05 * r);
}

/* --ortho H|fit on a camera made by any other option. */
static void apply_ortho(oit_camera *cam, float ortho)
{
    if (ortho == 0.0f)
        return;
    double d2 = 0.0;
    for (int k = 0; k < 3; k++)
        d2 += ((double)cam->target[k] - cam->eye[k]) * ((double)cam->target[k] - cam->eye[k]);
    double fovy = cam->fovy_deg > 0.0f ? cam->fovy_deg : 45.0;
    cam->projection = OIT_PROJ_ORTHOGRAPHIC;
    cam->ortho_height = ortho > 0.0f ? ortho
                                     : (float)(2.0 * sqrt(d2) *
                                               tan(0.5 * fovy * 3.14159265358979323846 / 180.0));
    if (isinf(cam->zfar))
        cam->zfar = 2.0f * cam->znear + 1.0f;
}

/* --walk FILE: one camera a line; a bad line is bad input naming it. */
static oit_status read_walk(const char *path, const oit_mesh_info *info, oit_camera **out,
                            int *count, oit_error *err)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    oit_camera *cams = NULL;
    int n = 0, cap = 0, line_no = 0;
    char line[1024];
    oit_status s = OIT_OK;
    while (s == OIT_OK && fgets(line, sizeof line, f)) {
        line_no++;
        char *t = line + strspn(line, " \t");
        size_t len = strcspn(t, "#\r\n");
        while (len > 0 && (t[len - 1] == ' ' || t[len - 1] == '\t'))
            len--;
        t[len] = '\0';
        if (!*t)
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 16;
            oit_camera *c = realloc(cams, (size_t)cap * sizeof *c);
            if (!c) {
                s = oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot hold %d views", path, cap);
                break;
            }
            cams = c;
        }
        memset(&cams[n], 0, sizeof cams[n]);
        int code = oit_camera_parse(&cams[n], t, info->origin);
        if (code != 0)
            s = oit_error_set(err, OIT_ERR_FORMAT, "%s: line %d: not a view (%s): '%.60s'",
                              path, line_no, oit_camera_parse_error(code), t);
        else if (!(cams[n].znear > 0.0f && cams[n].zfar > cams[n].znear))
            fit_clip_planes(&cams[n], info);
        n += s == OIT_OK;
    }
    if (s == OIT_OK && ferror(f))
        s = oit_error_set(err, OIT_ERR_IO, "%s: read error", path);
    if (s == OIT_OK && n == 0)
        s = oit_error_set(err, OIT_ERR_FORMAT, "%s: no views", path);
    fclose(f);
    if (s != OIT_OK) {
        free(cams);
        return s;
    }
    *out = cams;
    *count = n;
    return OIT_OK;
}

static oit_status make_views_of(const oit_stream_args *a, const oit_mesh_info *info,
                                oit_camera **out, int *count, oit_error *err);

oit_status make_views(const oit_stream_args *a, const oit_mesh_info *info,
                      oit_camera **out, int *count, oit_error *err)
{
    oit_status s = make_views_of(a, info, out, count, err);
    if (s == OIT_OK)
        for (int i = 0; i < *count; i++)
            apply_ortho(&(*out)[i], a->ortho);
    return s;
}

static oit_status make_views_of(const oit_stream_args *a, const oit_mesh_info *info,
                                oit_camera **out, int *count, oit_error *err)
{
    if (a->walk)
        return read_walk(a->walk, info, out, count, err);
    int n = a->orbit > 0 ? a->orbit : 1;
    oit_camera *cams = calloc((size_t)n, sizeof *cams);
    if (!cams)
        return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate %d views", n);
    for (int i = 0; i < n; i++) {
        if (a->have_view) {
            cams[i] = a->view;
            oit_camera_parse(&cams[i], a->view_text, info->origin);
            int ortho = cams[i].projection == OIT_PROJ_ORTHOGRAPHIC;
            if (!((ortho || cams[i].znear > 0.0f) && cams[i].zfar > cams[i].znear))
                fit_clip_planes(&cams[i], info);
        } else if (a->orbit > 0) {
            oit_camera_default_up(&cams[i], info->bounds_min, info->bounds_max,
                                  (float)(i * 360.0 / n), 20.0f, a->up_axis);
        } else {
            oit_camera_default_up(&cams[i], info->bounds_min, info->bounds_max, a->azimuth,
                                  a->elevation, a->up_axis);
        }
    }
    *out = cams;
    *count = n;
    return OIT_OK;
}

oit_shading make_shading(const oit_stream_args *a, const oit_mesh_info *info)
{
    oit_shading s = a->shading;
    s.attributes = info->attributes;
    s.scene_scale = oit_scene_scale(info->bounds_min, info->bounds_max);
    oit_shading_resolve_defaults(&s);
    return s;
}

static int has_image_ext(const char *p)
{
    size_t n = strlen(p);
    return n > 4 && (!strcasecmp(p + n - 4, ".png") || !strcasecmp(p + n - 4, ".pfm"));
}

/* FILE.png for one view, FILE_007.png for several, DIR/frame_007.png for a
 * folder (created when missing). */
oit_status output_path(const char *out, int index, int views, char *buf, size_t cap,
                              oit_error *err)
{
    if (has_image_ext(out)) {
        size_t n = strlen(out);
        if (views == 1)
            snprintf(buf, cap, "%s", out);
        else
            snprintf(buf, cap, "%.*s_%03d%s", (int)(n - 4), out, index, out + n - 4);
        return OIT_OK;
    }
    if (mkdir(out, 0777) != 0 && errno != EEXIST)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot create folder: %s", out, strerror(errno));
    snprintf(buf, cap, "%s/frame_%03d.png", out, index);
    return OIT_OK;
}

int stream_max_layers(const oit_stream_args *a, oit_partfile *pf)
{
    if (a->max_layers)
        return a->max_layers;
    oit_partfile_summary sum = {0};
    if (pf)
        oit_partfile_get_summary(pf, &sum);
    /* A file cut for more than the K-slot capture holds streams as parts
     * wider than K: captured alone over tiles (oit_capture_batch_layers). */
    return pf && sum.K < 16 ? (int)sum.K : 16;
}

/* One image: the default cache would only hold a second copy of what the
 * ring uploaded (on the 2M plant at 1024x1024, 104 of its 240 MB GPU
 * peak), and auto packs start counted (oit_renderer_desc.frames). */
oit_renderer_desc stream_renderer_desc(const oit_stream_args *a, int views)
{
    oit_renderer_desc d = a->stream;
    if (views == 1 && !a->window && d.cache_budget == 0)
        d.cache_budget = OIT_RENDER_CACHE_OFF;
    if (views == 1 && !a->window)
        d.frames = 1;
    return d;
}

/* --up auto: the model's up axis (formats/up_axis.h), said where it is not
 * y and the default views use it. */
int stream_up_axis(const oit_stream_args *a, oit_partfile *pf, const oit_mesh_info *info)
{
    const char *why = NULL;
    const char *name = pf ? oit_partfile_source_name(pf) : a->model;
    int axis = oit_up_axis_guess(name, info->bounds_min, info->bounds_max, &why);
    if (axis != 1 && !a->quiet && !a->have_view && !a->walk)
        fprintf(stderr, "oitstream: %s: up axis %c (%s; --up overrides)\n", a->model,
                "xyz"[axis], why);
    return axis;
}
