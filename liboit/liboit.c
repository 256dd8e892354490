/* The public embedding API (include/oit/liboit.h) over the streamer and
 * DFB: the caller's matrices become an oit_camera, the streamer (a part
 * file) or DFB (an in-core mesh) leaves the frame's per-pixel (C, T) state
 * in a GPU buffer, and one fullscreen pass blends it over the caller's
 * framebuffer. */
#include "oit/liboit.h"

#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "formats/readers_internal.h"
#include "render/gl/band.h"
#include "render/capture/blend_into.h"
#include "render/capture/dfb.h"
#include "render/gl/frag_glsl.h"
#include "render/gl/gpu_timer.h"
#include "render/image/image.h"
#include "render/image/shade.h"
#include "stream/streamer.h"
#include "liboit/desc_ranges.h"

struct oit_scene {
    oit_partfile *pf; /* a part file, or NULL: in core */
    oit_mesh mesh;    /* in core: the triangles */
    char *name;       /* in core: the file or the descriptor's name */
    oit_scene_info info;
    /* oit_scene_desc.share_*: the shares of the file and the order that
     * oit_scene_share_order reads them from (NULL for a whole scene). */
    oit_shares *share_set;
    oit_order *order;
    uint32_t *ordered; /* the part order of a view, a part count long */
    /* The caller's handle is one share and each renderer that drew the
     * scene last holds one: the scene is freed with the last share, so a
     * renderer never meets a freed scene, nor another scene at its address
     * (allocators hand freed blocks back), when the caller closes it first. */
    atomic_uint shares;
};

enum { GPU_QUEUE = 64 };

struct oit_renderer {
    oit_renderer_desc desc;
    oit_streamer_desc stream; /* desc spelt for the streamer (stream_desc); K per scene */
    oit_scene *scene;       /* the scene the streamer or gpu_mesh holds: a share */
    oit_streamer *streamer; /* part files */
    oit_dfb *dfb;           /* in-core scenes; kept across scenes */
    oit_gpu_mesh *gpu_mesh; /* the in-core scene's triangles */
    uint64_t pending_upload; /* bytes uploaded by bind_scene, for the stats */
    GLuint blend_prog, vao; /* blend_prog: made at the first oit_renderer_draw */
    oit_program_cache *programs; /* desc.program_cache's, NULL: none */
    GLuint depth_sampler; /* reads oit_frame.depth_texture: no compare, nearest */
    oit_gpu_timer *timer; /* made at the first draw (GL current) */
    oit_gpu_times gpu;    /* the newest figures polled; frame 0: none yet */
    /* Figures polled but not yet taken by oit_renderer_gpu_poll, oldest
     * first at gpu_head; the oldest go when it is full. */
    oit_gpu_times gpu_queue[GPU_QUEUE];
    unsigned gpu_head, gpu_count;
    uint64_t draws; /* oit_draw_stats.draw of the last draw */
    unsigned bands; /* streamer frames of the draw under way (render_state) */
};

_Static_assert(OIT_DRAW_GPU_PHASES == OIT_GPU_PHASES, "one list of GPU phases");

static const char *scene_name(const oit_scene *s)
{
    return s->pf ? oit_partfile_name(s->pf) : s->name;
}

/* ---- scene ------------------------------------------------------------- */

/* 1 when path names a part file: its first bytes are the part-file magic,
 * or (missing, unreadable, too short) its name ends in .oitp, so that the
 * part-file reader names what is wrong with it. */
static int is_part_file(const char *path)
{
    static const char magic[8] = "OITPART"; /* partfile/layout.h */
    char head[8];
    FILE *f = fopen(path, "rb");
    size_t got = f ? fread(head, 1, sizeof head, f) : 0;
    if (f)
        fclose(f);
    if (got == sizeof head && memcmp(head, magic, sizeof head) == 0)
        return 1;
    size_t n = strlen(path);
    return n >= 5 && strcmp(path + n - 5, ".oitp") == 0;
}

/* A scene of one share, the caller's. */
static oit_scene *scene_new(void)
{
    oit_scene *s = calloc(1, sizeof *s);
    if (s)
        atomic_init(&s->shares, 1u);
    return s;
}

/* Ends one share; the last one frees the scene. */
static void scene_unshare(oit_scene *s)
{
    if (!s || atomic_fetch_sub(&s->shares, 1u) != 1u)
        return;
    oit_shares_destroy(s->share_set);
    oit_order_destroy(s->order);
    free(s->ordered);
    oit_partfile_close(s->pf);
    oit_mesh_free(&s->mesh);
    free(s->name);
    free(s);
}

static oit_status mesh_scene(oit_mesh *mesh, const char *name, oit_scene **out,
                             oit_error *err)
{
    oit_scene *s = scene_new();
    char *copy = s ? malloc(strlen(name) + 1) : NULL;
    if (!copy) {
        free(s);
        oit_mesh_free(mesh);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the scene", name);
    }
    strcpy(copy, name);
    s->name = copy;
    s->mesh = *mesh;
    const oit_mesh_info *mi = &mesh->info;
    s->info.triangles = mesh->count;
    memcpy(s->info.bounds_min, mi->bounds_min, sizeof mi->bounds_min);
    memcpy(s->info.bounds_max, mi->bounds_max, sizeof mi->bounds_max);
    s->info.attributes = mi->attributes;
    memcpy(s->info.origin, mi->origin, sizeof s->info.origin);
    s->info.in_core = 1;
    s->info.share_count = 1;
    s->info.share_parts = 0;
    s->info.share_triangles = mesh->count;
    *out = s;
    return OIT_OK;
}

/* oit_scene_desc.share_*, checked by the shares' owner (partfile/share.h);
 * the shares and an order object kept for oit_scene_share_order. */
static oit_status open_share(oit_scene *s, const oit_scene_desc *desc, oit_error *err)
{
    uint32_t count = desc ? desc->share_count : 0, index = desc ? desc->share_index : 0;
    oit_status st = oit_shares_check(s->pf, count, index, err);
    if (st != OIT_OK) {
        oit_error_prefix(err, "oit_scene_desc");
        return st;
    }
    s->info.share_count = count > 1 ? count : 1;
    s->info.share_index = index;
    s->info.share_parts = s->info.parts;
    s->info.share_triangles = s->info.triangles;
    if (count <= 1)
        return OIT_OK;
    uint32_t parts = oit_partfile_part_count(s->pf);
    st = oit_shares_create(s->pf, count, &s->share_set, err);
    if (st == OIT_OK)
        st = oit_order_create(s->pf, &s->order, err);
    if (st == OIT_OK && !(s->ordered = malloc((parts ? parts : 1) * sizeof *s->ordered)))
        st = oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the order of %u parts",
                           oit_partfile_name(s->pf), parts);
    if (st == OIT_OK) {
        s->info.share_parts = oit_shares_parts(s->share_set, index);
        s->info.share_triangles = oit_shares_triangles(s->share_set, index);
    }
    return st;
}

oit_status oit_scene_open(const char *path, const oit_scene_desc *desc, oit_scene **out,
                          oit_error *err)
{
    if (!out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_open: out is NULL");
    *out = NULL;
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_open: path is NULL");
    if (!is_part_file(path)) {
        /* Shares cut a part file's management tree; a mesh has none. */
        if (desc && (desc->share_count > 1 || desc->share_index != 0))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: oit_scene_desc share %u of %u: "
                                 "shares are of part files (oitprep), this is a mesh", path,
                                 desc->share_index, desc->share_count);
        oit_mesh mesh;
        oit_status st = oit_mesh_load(path, NULL, &mesh, err);
        return st == OIT_OK ? mesh_scene(&mesh, path, out, err) : st;
    }
    oit_scene *s = scene_new();
    if (!s)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate the scene", path);
    oit_partfile_open_desc od = {.defer_part_data = desc && desc->defer_validation};
    oit_status st = oit_partfile_open(path, &od, &s->pf, err);
    if (st != OIT_OK) {
        free(s);
        return st;
    }
    oit_partfile_summary sum;
    oit_partfile_get_summary(s->pf, &sum);
    s->info.triangles = sum.triangles;
    s->info.parts = sum.parts;
    memcpy(s->info.bounds_min, sum.bounds_min, sizeof sum.bounds_min);
    memcpy(s->info.bounds_max, sum.bounds_max, sizeof sum.bounds_max);
    s->info.K = sum.K;
    s->info.attributes = sum.attributes;
    memcpy(s->info.origin, sum.origin, sizeof s->info.origin);
    st = open_share(s, desc, err);
    if (st != OIT_OK) {
        scene_unshare(s);
        return st;
    }
    *out = s;
    return OIT_OK;
}

oit_status oit_scene_get_info(const oit_scene *scene, oit_scene_info *info, oit_error *err)
{
    if (!scene || !info)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_get_info: NULL argument");
    *info = scene->info;
    return OIT_OK;
}

void oit_scene_close(oit_scene *scene)
{
    scene_unshare(scene);
}

/* Colour i of the descriptor's array as 8-bit RGBA. */
static void desc_colour(const oit_scene_mesh_desc *d, uint64_t i, uint8_t rgba[4])
{
    if (d->colour_type == OIT_COLOUR_FLOAT) {
        const float *c = (const float *)d->colours + 4 * i;
        for (int k = 0; k < 4; k++)
            rgba[k] = oit_rd_unit_to_u8(c[k]);
    } else {
        memcpy(rgba, (const uint8_t *)d->colours + 4 * i, 4);
    }
}

static oit_status check_mesh_desc(const oit_scene_mesh_desc *d, const char *name,
                                  uint64_t *triangles, oit_error *err)
{
    const char *D = "oit_scene_mesh_desc";
    if (!d->positions)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.positions is NULL", name, D);
    if (d->vertex_count < 3)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.vertex_count = %llu: fewer than "
                             "one triangle's 3", name, D, (unsigned long long)d->vertex_count);
    if (d->colour_type != OIT_COLOUR_UINT8 && d->colour_type != OIT_COLOUR_FLOAT)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.colour_type = %d is not an "
                             "oit_colour_type", name, D, (int)d->colour_type);
    if (d->colour_rate != OIT_COLOUR_PER_VERTEX && d->colour_rate != OIT_COLOUR_PER_TRIANGLE)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.colour_rate = %d is not an "
                             "oit_colour_rate", name, D, (int)d->colour_rate);
    if (d->indices) {
        if (d->index_count == 0 || d->index_count % 3)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.index_count = %llu is not a "
                                 "positive multiple of 3", name, D,
                                 (unsigned long long)d->index_count);
        for (uint64_t i = 0; i < d->index_count; i++)
            if (d->indices[i] >= d->vertex_count)
                return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.indices[%llu] = %u: not "
                                     "below vertex_count %llu", name, D,
                                     (unsigned long long)i, d->indices[i],
                                     (unsigned long long)d->vertex_count);
        *triangles = d->index_count / 3;
    } else {
        if (d->index_count != 0)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.index_count = %llu without "
                                 "indices", name, D, (unsigned long long)d->index_count);
        if (d->vertex_count % 3)
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.vertex_count = %llu: a soup "
                                 "(indices NULL) needs a multiple of 3", name, D,
                                 (unsigned long long)d->vertex_count);
        *triangles = d->vertex_count / 3;
    }
    for (uint64_t i = 0; i < 3 * d->vertex_count; i++)
        if (!isfinite(d->positions[i]))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s.positions[%llu] (vertex "
                                 "%llu) is not finite", name, D, (unsigned long long)i,
                                 (unsigned long long)(i / 3));
    if ((uint64_t)SIZE_MAX / sizeof(oit_triangle) < *triangles)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: %llu triangles do not fit in memory",
                             name, (unsigned long long)*triangles);
    return OIT_OK;
}

oit_status oit_scene_create_mesh(const oit_scene_mesh_desc *d, oit_scene **out,
                                 oit_error *err)
{
    if (!out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_create_mesh: out is NULL");
    *out = NULL;
    if (!d)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_create_mesh: desc is NULL");
    const char *name = d->name && d->name[0] ? d->name : "mesh";
    uint64_t n = 0;
    oit_status st = check_mesh_desc(d, name, &n, err);
    if (st != OIT_OK)
        return st;
    oit_mesh mesh = {0};
    mesh.tris = malloc((size_t)n * sizeof *mesh.tris);
    if (!mesh.tris)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: cannot allocate %llu triangles", name,
                             (unsigned long long)n);
    mesh.count = mesh.capacity = (size_t)n;
    for (uint64_t t = 0; t < n; t++)
        for (int c = 0; c < 3; c++) {
            uint64_t v = d->indices ? d->indices[3 * t + c] : 3 * t + c;
            oit_vertex *out_v = &mesh.tris[t].v[c];
            memcpy(out_v->pos, d->positions + 3 * v, sizeof out_v->pos);
            if (d->colours)
                desc_colour(d, d->colour_rate == OIT_COLOUR_PER_TRIANGLE ? t : v, out_v->rgba);
            else
                memset(out_v->rgba, 255, sizeof out_v->rgba);
        }
    oit_mesh_info_init(&mesh.info);
    oit_mesh_info_add(&mesh.info, mesh.tris, mesh.count);
    mesh.info.vertices_in = d->vertex_count;
    mesh.info.faces_in = n;
    mesh.info.attributes = d->colours ? OIT_ATTR_COLOUR | OIT_ATTR_ALPHA : 0;
    oit_mesh_info_opaque(&mesh.info, mesh.tris, mesh.count);
    return mesh_scene(&mesh, name, out, err);
}

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
                return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.view: not a rigid "
                                     "transform (rows %d,%d dot %.4g); scale belongs in the "
                                     "model, not the view", a, b, d);
        }
    if (m[3] != 0.0f || m[7] != 0.0f || m[11] != 0.0f || m[15] != 1.0f)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.view: last row is not "
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
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection[%d] = %g: "
                                 "not a perspective or orthographic projection (a skewed or "
                                 "rotated one)", zeros[i], m[zeros[i]]);
    if (!(m[0] > 0.0f) || !(m[5] > 0.0f))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection: m[0] = %g and "
                             "m[5] = %g must be > 0 (a mirrored projection)", m[0], m[5]);
    double w[4] = {(m[8] - 1.0) / m[0], (m[8] + 1.0) / m[0], (m[9] - 1.0) / m[5],
                   (m[9] + 1.0) / m[5]};
    if (m[11] == -1.0f && m[15] == 0.0f) {
        if (m[12] != 0.0f || m[13] != 0.0f)
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection: a perspective "
                                 "with m[12] = %g, m[13] = %g (must be 0)", m[12], m[13]);
        int infinite = m[10] == -1.0f;
        double n = infinite ? -0.5 * m[14] : m[14] / (m[10] - 1.0);
        double fa = infinite ? INFINITY : m[14] / (m[10] + 1.0);
        if (!(n > 0.0) || !(fa > n) || !(infinite || isfinite(fa)))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection: a "
                                 "perspective with near %g, far %g (m[10] = %g, m[14] = %g): "
                                 "need 0 < near < far <= inf", n, fa, m[10], m[14]);
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
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection: an "
                                 "orthographic projection with m[8] = %g, m[9] = %g (an "
                                 "oblique one)", m[8], m[9]);
        double depth = -2.0 / m[10]; /* far - near */
        double n = -0.5 * depth * (m[14] + 1.0), fa = 0.5 * depth * (1.0 - m[14]);
        if (!(m[10] < 0.0f) || !isfinite(n) || !isfinite(fa) || !(fa > n))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection: an "
                                 "orthographic projection with near %g, far %g (m[10] = %g, "
                                 "m[14] = %g): need near < far, both finite", n, fa, m[10],
                                 m[14]);
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
    return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.projection: m[11] = %g, m[15] = "
                         "%g: neither a perspective (-1, 0) nor an orthographic projection "
                         "(0, 1)", m[11], m[15]);
}

/* ---- renderer ---------------------------------------------------------- */

/* Frees r's GPU state for its scene and lets the scene go (the streamer
 * reads the scene's part file until it is destroyed). */
static void drop_scene(oit_renderer *r)
{
    oit_streamer_destroy(r->streamer);
    r->streamer = NULL;
    oit_gpu_mesh_destroy(r->gpu_mesh);
    r->gpu_mesh = NULL;
    scene_unshare(r->scene);
    r->scene = NULL;
}

void oit_renderer_destroy(oit_renderer *r)
{
    if (!r)
        return;
    drop_scene(r);
    oit_dfb_destroy(r->dfb);
    oit_gpu_timer_destroy(r->timer);
    glDeleteProgram(r->blend_prog);
    oit_program_cache_close(r->programs);
    glDeleteVertexArrays(1, &r->vao);
    glDeleteSamplers(1, &r->depth_sampler);
    free(r);
}

/* liboit's spelling of the streamer's settings onto oit_streamer_desc, the
 * one place it is built: the streamer checks the values
 * (oit_streamer_desc_check) and each scene adds its K and share. */
static void stream_desc(const oit_renderer_desc *d, oit_streamer_desc *sd)
{
    memset(sd, 0, sizeof *sd);
    _Static_assert((int)OIT_RENDER_CAPTURE_ARRAY == (int)OIT_CAPTURE_ARRAY &&
                       (int)OIT_RENDER_CAPTURE_STENCIL == (int)OIT_CAPTURE_STENCIL &&
                       (int)OIT_RENDER_CAPTURE_AUTO == (int)OIT_CAPTURE_AUTO &&
                       (int)OIT_RENDER_CAPTURE_COMPUTE == (int)OIT_CAPTURE_COMPUTE,
                   "liboit's capture values are the streamer's");
    sd->capture = (oit_capture_kind)d->capture;
    sd->pack = d->pack == OIT_RENDER_PACK_FIRSTK     ? OIT_PACK_FIRSTK
               : d->pack == OIT_RENDER_PACK_DISJOINT ? OIT_PACK_DISJOINT
               : d->pack == OIT_RENDER_PACK_BUDGET   ? OIT_PACK_BUDGET
               : d->pack == OIT_RENDER_PACK_COUNTED  ? OIT_PACK_COUNTED
                                                     : OIT_PACK_AUTO;
    sd->upload_budget = d->upload_budget;
    sd->epsilon = d->epsilon;
    _Static_assert(OIT_RENDER_CACHE_OFF == OIT_STREAM_CACHE_OFF, "one spelling of 'no cache'");
    sd->cache_budget = d->cache_budget;
    sd->reader_threads = d->read_on_draw_thread ? OIT_STREAM_READ_INLINE
                                                : (int)(d->reader_threads > INT_MAX
                                                            ? INT_MAX : d->reader_threads);
    sd->gpu_budget = d->gpu_budget;
    _Static_assert((int)OIT_RENDER_SCHEDULE_WAVE == (int)OIT_SCHEDULE_WAVE &&
                       (int)OIT_RENDER_SCHEDULE_TREE == (int)OIT_SCHEDULE_TREE,
                   "liboit's schedule values are the packer's");
    sd->schedule = (oit_pack_schedule)d->schedule;
    sd->slot_budget = d->slot_budget;
    sd->store_budget = d->store_budget;
    sd->store_limit = d->binding_limit;
    sd->frames = d->frames;
}

static const char *spelt(const char *given, const char *field)
{
    return given ? given : field;
}

/* One row of desc_ranges.h that liboit checks, on an integer field. */
static oit_status check_row(const oit_renderer_desc *d, const oit_desc_range *row,
                            const oit_renderer_desc_names *n, oit_error *err)
{
    const char *p = (const char *)d + row->offset;
    long long v;
    if (row->type == OIT_DESC_U32) {
        uint32_t u;
        memcpy(&u, p, sizeof u);
        v = u;
    } else {
        int i;
        memcpy(&i, p, sizeof i);
        v = i;
    }
    if ((v == 0 && row->zero_default) || (v >= (long long)row->lo && v <= (long long)row->hi))
        return OIT_OK;
    const char *given;
    memcpy(&given, (const char *)n + row->name_offset, sizeof given);
    char own[64];
    snprintf(own, sizeof own, "oit_renderer_desc.%s", row->field);
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s = %lld: expected %s", spelt(given, own), v,
                         row->expect);
}

/* liboit's own checks (the rows of desc_ranges.h it owns), then the
 * streamer's (oit_streamer_desc_check) on the descriptor stream_desc
 * spells, under the caller's names. */
oit_status oit_renderer_desc_check(const oit_renderer_desc *d, const oit_renderer_desc_names *names,
                                   oit_error *err)
{
    static const oit_renderer_desc_names none = {0};
    const oit_renderer_desc_names *n = names ? names : &none;
    for (size_t i = 0; i < OIT_DESC_RANGES; i++)
        if (oit_desc_ranges[i].liboit_checks &&
            check_row(d, &oit_desc_ranges[i], n, err) != OIT_OK)
            return OIT_ERR_ARGUMENT;
    oit_streamer_desc sd;
    stream_desc(d, &sd);
    const oit_streamer_names sn = {
        .upload_budget = spelt(n->upload_budget, "oit_renderer_desc.upload_budget"),
        .cache_budget = spelt(n->cache_budget, "oit_renderer_desc.cache_budget"),
        .gpu_budget = spelt(n->gpu_budget, "oit_renderer_desc.gpu_budget"),
        .epsilon = spelt(n->epsilon, "oit_renderer_desc.epsilon"),
        .slot_budget = spelt(n->slot_budget, "oit_renderer_desc.slot_budget"),
        .store_budget = spelt(n->store_budget, "oit_renderer_desc.store_budget"),
        .schedule = spelt(n->schedule, "oit_renderer_desc.schedule"),
        .cache_off = spelt(n->cache_off, "OIT_RENDER_CACHE_OFF")};
    return oit_streamer_desc_check(&sd, &sn, err);
}

oit_status oit_renderer_create(const oit_renderer_desc *desc, oit_renderer **out,
                               oit_error *err)
{
    *out = NULL;
    oit_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return oit_error_set(err, OIT_ERR_NOMEM, "oit_renderer_create: out of memory");
    if (desc)
        r->desc = *desc;
    oit_status bad = oit_renderer_desc_check(&r->desc, NULL, err);
    if (bad != OIT_OK) {
        free(r);
        return bad;
    }
    stream_desc(&r->desc, &r->stream);
    oit_status st = oit_program_cache_open(r->desc.program_cache, &r->programs, err);
    /* the caller's string is not kept: the folder in use is read back */
    r->desc.program_cache = r->programs ? oit_program_cache_dir(r->programs) : "off";
    r->stream.programs = r->programs;
    if (st == OIT_OK) {
        glCreateVertexArrays(1, &r->vao);
        glCreateSamplers(1, &r->depth_sampler);
        glSamplerParameteri(r->depth_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
        glSamplerParameteri(r->depth_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(r->depth_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        st = oit_gl_check("oit_renderer_create", err);
    }
    if (st != OIT_OK) {
        oit_renderer_destroy(r);
        return st;
    }
    *out = r;
    return OIT_OK;
}

void oit_renderer_release_scene(oit_renderer *r, const oit_scene *scene)
{
    if (!r || !scene || r->scene != scene)
        return;
    drop_scene(r);
}

/* r takes a share of scene, whose GPU state it now holds. */
static void hold_scene(oit_renderer *r, oit_scene *scene)
{
    atomic_fetch_add(&scene->shares, 1u);
    r->scene = scene;
}

/* (Re)builds the streamer when r draws a scene it was not built for. r's
 * share keeps the scene it holds alive, so the address names one scene. */
static oit_status bind_scene(oit_renderer *r, oit_scene *scene, oit_error *err)
{
    if (r->scene == scene && (r->streamer || r->gpu_mesh))
        return OIT_OK;
    drop_scene(r);
    if (!scene->pf) {
        oit_status st = r->dfb ? OIT_OK : oit_dfb_create(&r->dfb, err);
        if (st == OIT_OK)
            st = oit_gpu_mesh_create(scene->mesh.tris, scene->mesh.count, 0, &r->gpu_mesh, err);
        if (st == OIT_OK) {
            hold_scene(r, scene);
            r->pending_upload = (uint64_t)scene->mesh.count * sizeof(oit_triangle);
        }
        return st;
    }
    oit_streamer_desc sd = r->stream;
    /* A file cut for more than the K-slot capture holds streams its parts as
     * wider than K, captured alone over tiles, as oitstream does. */
    sd.K = r->desc.K ? (int)r->desc.K : scene->info.K < 16 ? (int)scene->info.K : 16;
    sd.share_count = scene->info.share_count;
    sd.share_index = scene->info.share_index;
    oit_status st = oit_streamer_create(scene->pf, &sd, &r->streamer, err);
    if (st == OIT_OK)
        hold_scene(r, scene);
    return st;
}

/* bg: the background of a resolved image (oit_renderer_draw_image), NULL
 * for the default (white), which a blend over a framebuffer does not read. */
static void make_shading(const oit_renderer *r, const oit_scene *scene, const float *bg,
                         oit_shading *s)
{
    const oit_render_shading *in = &r->desc.shading;
    memset(s, 0, sizeof *s);
    if (bg)
        memcpy(s->background, bg, sizeof s->background);
    s->mode = in->mode == OIT_RENDER_TRANSLUCENT ? OIT_SHADING_TRANSLUCENT
                                                  : OIT_SHADING_TRANSPARENT;
    s->alpha = in->alpha;
    memcpy(s->default_rgb, in->default_rgb, sizeof s->default_rgb);
    s->absorption = in->absorption;
    s->colour_space = in->colour_space == OIT_RENDER_COLOUR_LINEAR ? OIT_COLOUR_LINEAR
                                                                   : OIT_COLOUR_SRGB;
    s->attributes = scene->info.attributes;
    s->see_through = r->desc.see_through;
    s->scene_scale = in->scene_scale > 0.0f
                         ? in->scene_scale
                         : oit_scene_scale(scene->info.bounds_min, scene->info.bounds_max);
    oit_shading_resolve_defaults(s);
}

void oit_renderer_get_desc(const oit_renderer *r, oit_renderer_desc *out)
{
    *out = r->desc;
    if (r->scene) {
        oit_shading s;
        make_shading(r, r->scene, NULL, &s);
        out->shading.alpha = s.alpha;
        memcpy(out->shading.default_rgb, s.default_rgb, sizeof out->shading.default_rgb);
        out->shading.absorption = s.absorption;
        out->shading.scene_scale = s.scene_scale;
        out->shading.colour_space = s.colour_space == OIT_COLOUR_LINEAR
                                        ? OIT_RENDER_COLOUR_LINEAR : OIT_RENDER_COLOUR_SRGB;
    }
    if (!r->streamer)
        return;
    oit_streamer_desc sd;
    oit_streamer_resolved_desc(r->streamer, &sd);
    out->K = (uint32_t)sd.K;
    out->upload_budget = sd.upload_budget;
    out->cache_budget = sd.cache_budget;
    out->gpu_budget = sd.gpu_budget;
    out->capture = (oit_render_capture)sd.capture;
    out->read_on_draw_thread = sd.reader_threads == OIT_STREAM_READ_INLINE;
}

/* The state oit_renderer_draw promises to give back (liboit.h). */
typedef struct gl_saved {
    GLint draw_fb, read_fb, viewport[4], program, vao, indirect;
    GLint src_rgb, dst_rgb, src_a, dst_a, eq_rgb, eq_a;
    GLboolean colour_mask[4], depth_mask;
    GLboolean enabled[7];
} gl_saved;

static const GLenum kToggles[7] = {GL_BLEND, GL_DEPTH_TEST, GL_STENCIL_TEST, GL_CULL_FACE,
                                   GL_SCISSOR_TEST, GL_MULTISAMPLE, GL_FRAMEBUFFER_SRGB};

static void gl_save(gl_saved *g)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &g->draw_fb);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &g->read_fb);
    glGetIntegerv(GL_VIEWPORT, g->viewport);
    glGetIntegerv(GL_CURRENT_PROGRAM, &g->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &g->vao);
    glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &g->indirect);
    glGetIntegerv(GL_BLEND_SRC_RGB, &g->src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &g->dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &g->src_a);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &g->dst_a);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &g->eq_rgb);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &g->eq_a);
    glGetBooleanv(GL_COLOR_WRITEMASK, g->colour_mask);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &g->depth_mask);
    for (int i = 0; i < 7; i++)
        g->enabled[i] = glIsEnabled(kToggles[i]);
}

static void gl_restore(const gl_saved *g)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)g->draw_fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)g->read_fb);
    glViewport(g->viewport[0], g->viewport[1], g->viewport[2], g->viewport[3]);
    /* A program the caller deleted while it was current lived only as long
     * as it stayed current (GL 4.5, 7.3): once liboit's own replaced it,
     * it is gone, and binding its name again would fail; the caller then
     * gets none, as after any glUseProgram of another. */
    glUseProgram(glIsProgram((GLuint)g->program) ? (GLuint)g->program : 0);
    glBindVertexArray((GLuint)g->vao);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, (GLuint)g->indirect);
    glBlendFuncSeparate((GLenum)g->src_rgb, (GLenum)g->dst_rgb, (GLenum)g->src_a,
                        (GLenum)g->dst_a);
    glBlendEquationSeparate((GLenum)g->eq_rgb, (GLenum)g->eq_a);
    glColorMask(g->colour_mask[0], g->colour_mask[1], g->colour_mask[2], g->colour_mask[3]);
    glDepthMask(g->depth_mask);
    for (int i = 0; i < 7; i++)
        (g->enabled[i] ? glEnable : glDisable)(kToggles[i]);
}

/* dst = C + T * dst through dual-source blending, one fragment per pixel,
 * over the target's rect at (x, y) of v's size, the state's pixels. */
/* The blend program, built at the first draw over a framebuffer (a run
 * that only reads images back never needs it). */
static oit_status blend_ready(oit_renderer *r, oit_error *err)
{
    if (r->blend_prog)
        return OIT_OK;
    return oit_blend_into_build(r->programs, &r->blend_prog, err);
}

static void blend_over(const oit_renderer *r, const oit_frame *f, const oit_view *v, int x,
                       int y, GLuint state)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, f->framebuffer);
    glViewport(x, y, v->width, v->height);
    for (int i = 1; i < 5; i++)
        glDisable(kToggles[i]);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_SRC1_COLOR);
    /* Linear light: C and T are linear, so the blend must read and write
     * linear values; GL decodes and encodes an sRGB target's values only
     * with GL_FRAMEBUFFER_SRGB (liboit.h, Result). */
    if (v->shading.colour_space == OIT_COLOUR_LINEAR)
        glEnable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(r->blend_prog);
    glProgramUniform2i(r->blend_prog, OIT_LOC_SIZE, v->width, v->height);
    glProgramUniform2i(r->blend_prog, OIT_LOC_ORIGIN, x, y);
    /* The state buffer's layout follows the shading (frag_glsl.h). */
    glProgramUniform1i(r->blend_prog, glGetUniformLocation(r->blend_prog, "u_mode"),
                       v->shading.mode == OIT_SHADING_TRANSLUCENT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_BIND_STATE, state);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindVertexArray(r->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

/* oit_frame.model (liboit.h): all 0 the identity, else affine, finite and
 * invertible. */
static oit_status model_from_frame(const float *m, oit_view *v, oit_error *err)
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(m[i]))
            return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.model[%d] = %g is not "
                                 "finite", i, m[i]);
    memcpy(v->model, m, sizeof v->model);
    double d[16], eye[3], dir[3];
    if (!oit_view_model(v, d))
        return OIT_OK;
    if (m[3] != 0.0f || m[7] != 0.0f || m[11] != 0.0f || m[15] != 1.0f)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.model: last row (%g, %g, %g, "
                             "%g) is not (0, 0, 0, 1): not affine", m[3], m[7], m[11], m[15]);
    if (!oit_view_model_eye(v, eye, dir))
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_frame.model: the linear part is "
                             "singular");
    return OIT_OK;
}

/* oit_frame.clip: checked once, by its owner (render/image/clip.h). */
_Static_assert(OIT_FRAME_CLIP_MAX == OIT_CLIP_MAX, "oit_frame.clip holds OIT_CLIP_MAX planes");
static oit_status clip_from_frame(const oit_frame *f, oit_view *v, oit_error *err)
{
    v->clip.count = f->clip_count > OIT_CLIP_MAX ? OIT_CLIP_MAX + 1 : (int)f->clip_count;
    for (int i = 0; i < OIT_CLIP_MAX && i < v->clip.count; i++)
        memcpy(v->clip.plane[i], f->clip[i], sizeof v->clip.plane[i]);
    if (f->clip_count > OIT_CLIP_MAX)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_frame.clip_count = %u: at most %d "
                             "planes", f->clip_count, OIT_CLIP_MAX);
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
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: eye (%g, %g, %g) and target give no "
                             "view direction, or up (%g, %g, %g) is parallel to it", F,
                             c->eye[0], c->eye[1], c->eye[2], c->up[0], c->up[1], c->up[2]);
    int ortho = c->ortho_height != 0.0f;
    if (ortho ? !(c->ortho_height > 0.0f && c->zfar > c->znear && isfinite(c->zfar))
              : !(c->fovy_deg > 0.0f && c->fovy_deg < 180.0f && c->znear > 0.0f &&
                  c->zfar > c->znear))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s, fovy %g, near %g, far %g: need %s",
                             F, ortho ? "orthographic" : "perspective", c->fovy_deg, c->znear,
                             c->zfar, ortho ? "ortho_height > 0, znear < zfar < inf"
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
static oit_status frame_camera(const oit_frame *f, oit_view *v, oit_error *err)
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
        st = camera_from_projection(f->projection, (double)v->width / v->height, &v->camera,
                                    err);
    if (st == OIT_OK)
        st = model_from_frame(f->model, v, err);
    if (st == OIT_OK)
        st = clip_from_frame(f, v, err);
    return st;
}

static oit_status frame_view(const oit_renderer *r, const oit_scene *scene,
                             const oit_frame *f, const float *bg, oit_view *v, oit_error *err)
{
    oit_status st = frame_camera(f, v, err);
    if (st == OIT_OK)
        make_shading(r, scene, bg, &v->shading);
    return st;
}

/* oit_frame.depth_texture: a single-sample 2D depth texture covering the
 * viewport, texel (x, y) the target's pixel (x, y). */
static oit_status check_depth_texture(const oit_frame *f, oit_error *err)
{
    GLuint tex = f->depth_texture;
    if (!glIsTexture(tex))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_frame.depth_texture = %u is not a "
                             "texture", tex);
    GLint target = 0, bits = 0, w = 0, h = 0, mode = GL_DEPTH_COMPONENT;
    glGetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_frame.depth_texture = %u: target "
                             "0x%x is not GL_TEXTURE_2D", tex, (unsigned)target);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_DEPTH_SIZE, &bits);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureParameteriv(tex, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    if (bits <= 0 || mode != GL_DEPTH_COMPONENT)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_frame.depth_texture = %u: level 0 "
                             "holds no depth%s", tex,
                             bits > 0 ? " (GL_DEPTH_STENCIL_TEXTURE_MODE reads stencil)" : "");
    if (f->viewport_x < 0 || f->viewport_y < 0 || w < f->viewport_x + f->viewport_width ||
        h < f->viewport_y + f->viewport_height)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_frame.depth_texture = %u: %dx%d does "
                             "not cover the viewport %d,%d %dx%d (it is of the target's size)",
                             tex, w, h, f->viewport_x, f->viewport_y, f->viewport_width,
                             f->viewport_height);
    return oit_gl_check("oit_frame.depth_texture", err);
}

/* The texture unit and sampler binding oit_renderer_draw takes for the
 * depth texture, given back after the capture. liboit.h tells callers the
 * unit by number. */
_Static_assert(OIT_TEX_OPAQUE_DEPTH == 7, "liboit.h documents texture unit 7");
typedef struct depth_unit {
    GLint active, tex, sampler;
} depth_unit;

static void depth_unit_bind(const oit_renderer *r, GLuint tex, depth_unit *u)
{
    glGetIntegerv(GL_ACTIVE_TEXTURE, &u->active);
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_DEPTH);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &u->tex);
    glGetIntegerv(GL_SAMPLER_BINDING, &u->sampler);
    glBindTexture(GL_TEXTURE_2D, tex);
    glBindSampler(OIT_TEX_OPAQUE_DEPTH, r->depth_sampler);
    glActiveTexture((GLenum)u->active);
}

/* Texture unit 6 (OIT_TEX_OPAQUE_KEYS), which the opaque pre-pass binds
 * (render/capture/opaque_keys.h): liboit.h promises it back. */
_Static_assert(OIT_TEX_OPAQUE_KEYS == 6, "liboit.h documents texture unit 6");
static GLint keys_unit_save(void)
{
    GLint active = 0, tex = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_KEYS);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex);
    glActiveTexture((GLenum)active);
    return tex;
}

static void depth_unit_restore(const depth_unit *u)
{
    glActiveTexture(GL_TEXTURE0 + OIT_TEX_OPAQUE_DEPTH);
    glBindTexture(GL_TEXTURE_2D, (GLuint)u->tex);
    glBindSampler(OIT_TEX_OPAQUE_DEPTH, (GLuint)u->sampler);
    glActiveTexture((GLenum)u->active);
}

/* One band's (or the whole frame's) state: the scene through the streamer
 * or DFB into *state, its figures in *fs and *ss. */
static oit_status render_state(oit_renderer *r, const oit_scene *scene, const oit_view *v,
                               const oit_opaque_depth *opaque, GLuint *state,
                               oit_frame_stats *fs, oit_stream_frame_stats *ss, oit_error *err)
{
    if (scene->pf) {
        r->bands++;
        oit_streamer_set_gpu_timer(r->streamer, r->timer);
        oit_streamer_set_opaque(r->streamer, opaque);
        return oit_streamer_render_gpu(r->streamer, v, state, fs, ss, err);
    }
    const oit_gpu_mesh *list[1] = {r->gpu_mesh};
    oit_dfb_set_opaque(r->dfb, opaque);
    oit_dfb_set_gpu_timer(r->dfb, r->timer);
    oit_status st = oit_dfb_render_state(r->dfb, list, 1, v, state, fs, err);
    ss->packs = fs->batches;
    ss->draw_calls = 1 + (uint64_t)fs->batches; /* the count pass; a store a band */
    ss->bytes_uploaded = r->pending_upload;
    ss->gpu_bytes_peak = fs->gpu_bytes_peak + oit_gpu_mesh_bytes(r->gpu_mesh);
    r->pending_upload = 0;
    return st;
}

/* The frame in bands of rows whose state fits one storage binding
 * (render/gl/band.h; one band where it all fits, the view unchanged), each
 * rendered and blended over its rows of the viewport before the next
 * overwrites the state. The opaque depth's projection is narrowed to the
 * band as the camera is; the depth unit is bound only while a band is
 * captured, not while the blend draws into a target it may belong to. */
static oit_status draw_bands(oit_renderer *r, const oit_scene *scene, const oit_frame *frame,
                             const oit_view *view, oit_frame_stats *fs,
                             oit_stream_frame_stats *ss, oit_error *err)
{
    uint64_t px = scene->pf ? oit_streamer_pixel_bytes(view) : oit_dfb_pixel_bytes(view, 1);
    int rows = 0, h = view->height;
    oit_status st = oit_band_rows(view, px, r->desc.binding_limit, &rows, err);
    for (int y0 = 0; st == OIT_OK && y0 < h; y0 += rows) {
        int y1 = y0 + rows < h ? y0 + rows : h, gl_y = frame->viewport_y + h - y1;
        oit_view band = *view;
        oit_opaque_depth opaque = {.enabled = frame->depth_texture != 0,
                                   .origin = {frame->viewport_x, gl_y}};
        float proj[16];
        if (frame->camera)
            oit_camera_proj_matrix(&view->camera, (float)view->width / (float)h, proj);
        else
            memcpy(proj, frame->projection, sizeof proj);
        memcpy(opaque.proj, proj, sizeof opaque.proj);
        if (rows < h) {
            oit_view_band(view, y0, y1, &band);
            oit_band_projection(proj, h, y0, y1, opaque.proj);
        }
        depth_unit unit;
        if (opaque.enabled)
            depth_unit_bind(r, frame->depth_texture, &unit);
        oit_frame_stats bfs = {0};
        oit_stream_frame_stats bss = {0};
        GLuint state = 0;
        GLint keys_tex = keys_unit_save();
        st = render_state(r, scene, &band, &opaque, &state, &bfs, &bss, err);
        glBindTextureUnit(OIT_TEX_OPAQUE_KEYS, (GLuint)keys_tex);
        if (opaque.enabled)
            depth_unit_restore(&unit);
        if (st == OIT_OK)
            st = blend_ready(r, err);
        if (st == OIT_OK) {
            blend_over(r, frame, &band, frame->viewport_x, gl_y, state);
            st = oit_gl_check("oit_renderer_draw: blend", err);
        }
        /* fs and ss start at zero: adding the first band copies it. */
        oit_frame_stats_add(fs, &bfs);
        oit_stream_frame_stats_add(ss, &bss);
    }
    return st;
}

/* The figures of the draw's work and choices (oit_draw_stats, from
 * order_ms on) that the capture and the streamer report: 0 and NULL for an
 * in-core scene, whose ss DFB's branch of render_state leaves so. */
static void draw_stats_work(const oit_frame_stats *fs, const oit_stream_frame_stats *ss,
                            oit_draw_stats *out)
{
    out->order_ms = ss->order_ms;
    out->pack_ms = ss->pack_ms;
    out->auto_first_k = (uint32_t)ss->first_k;
    out->choice = ss->choice_path;
    out->choice_why = ss->choice_why;
    out->choice_first_k_ms = ss->choice_path ? ss->choice_ms[0] : -1.0;
    out->choice_counted_ms = ss->choice_path ? ss->choice_ms[1] : -1.0;
    out->front_first = (uint32_t)ss->front_first;
    out->second_pass_pixels = fs->second_pass_pixels;
    out->second_pass_packs = fs->second_pass_packs;
    out->capture = fs->capture;
    out->capture_k = fs->capture_k;
    out->capture_asked = ss->capture_asked;
    out->batches = fs->batches;
    out->host_waits = fs->host_waits;
    out->redraws = fs->redraws;
    out->deep_pixels = fs->deep_pixels;
    out->predicted_batches = fs->predicted_batches;
    out->reader_threads = (uint32_t)(ss->reader_threads > 0 ? ss->reader_threads : 0);
}

/* A part file's draw in one band is one streamer frame: the automatic
 * pack mode judges it on the draw's whole wall time and its GPU figure
 * (stream/choice.h); bands are judged each on its own time. */
static void frame_end(oit_renderer *r, const oit_scene *scene, oit_status st, double t0,
                      uint64_t gpu_tag)
{
    if (st == OIT_OK && scene->pf && r->streamer && r->bands == 1)
        oit_streamer_frame_end(r->streamer, oit_time_ms() - t0, gpu_tag);
}

/* The figures that are in, queued for oit_renderer_gpu_poll; the newest
 * also in r->gpu, for oit_draw_stats. */
static void gpu_take(oit_renderer *r)
{
    r->draws++;
    oit_gpu_times t;
    while (oit_gpu_timer_poll(r->timer, &t, 0)) {
        if (r->streamer)
            oit_streamer_gpu_figure(r->streamer, t.frame, t.ms);
        r->gpu = t;
        if (r->gpu_count == GPU_QUEUE) {
            r->gpu_head = (r->gpu_head + 1) % GPU_QUEUE;
            r->gpu_count--;
        }
        r->gpu_queue[(r->gpu_head + r->gpu_count++) % GPU_QUEUE] = t;
    }
}

int oit_renderer_gpu_poll(oit_renderer *r, oit_draw_gpu *out, int wait)
{
    oit_gpu_times t;
    if (!r || !out)
        return 0;
    if (r->gpu_count) {
        t = r->gpu_queue[r->gpu_head];
        r->gpu_head = (r->gpu_head + 1) % GPU_QUEUE;
        r->gpu_count--;
    } else if (!r->timer || !oit_gpu_timer_poll(r->timer, &t, wait)) {
        return 0;
    } else if (r->streamer) {
        oit_streamer_gpu_figure(r->streamer, t.frame, t.ms);
    }
    out->draw = t.frame;
    out->ms = t.ms;
    memcpy(out->phase_ms, t.phase_ms, sizeof out->phase_ms);
    return 1;
}

const char *oit_renderer_gpu_absent(const oit_renderer *r)
{
    if (!r)
        return "no renderer";
    return r->timer ? oit_gpu_timer_absent(r->timer) : NULL;
}

static oit_status name_scene(const oit_scene *scene, oit_status st, oit_error *err);
static void fill_stats(const oit_renderer *r, const oit_scene *scene, const oit_view *view,
                       const oit_frame_stats *fs, const oit_stream_frame_stats *ss,
                       double t0, oit_draw_stats *stats);

oit_status oit_renderer_draw(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                             oit_draw_stats *stats, oit_error *err)
{
    if (!r || !scene || !frame)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_draw: NULL argument");
    double t0 = oit_time_ms();
    oit_view view;
    oit_status st = frame_view(r, scene, frame, NULL, &view, err);
    if (st == OIT_OK && frame->depth_texture)
        st = check_depth_texture(frame, err);
    if (st != OIT_OK)
        return st;
    gl_saved saved;
    gl_save(&saved);
    oit_frame_stats fs = {0};
    oit_stream_frame_stats ss = {0};
    int empty = !scene->pf && scene->info.triangles == 0; /* in core: nothing to draw */
    if (!r->timer)
        st = oit_gpu_timer_create(NULL, &r->timer, err);
    if (st == OIT_OK)
        st = empty ? OIT_OK : bind_scene(r, scene, err);
    oit_gpu_timer_begin_frame(r->timer);
    r->bands = 0;
    if (st == OIT_OK && !empty)
        st = draw_bands(r, scene, frame, &view, &fs, &ss, err);
    frame_end(r, scene, st, t0, oit_gpu_timer_end_frame(r->timer));
    gpu_take(r);
    gl_restore(&saved);
    if (st != OIT_OK)
        return name_scene(scene, st, err);
    if (stats)
        fill_stats(r, scene, &view, &fs, &ss, t0, stats);
    return OIT_OK;
}

/* A failure's message starts with the scene's name. */
static oit_status name_scene(const oit_scene *scene, oit_status st, oit_error *err)
{
    const char *name = scene_name(scene);
    if (err && strncmp(err->message, name, strlen(name)) != 0)
        oit_error_prefix(err, name);
    return st;
}

/* oit_draw_stats of a draw, from the capture's and the streamer's figures. */
static void fill_stats(const oit_renderer *r, const oit_scene *scene, const oit_view *vp,
                       const oit_frame_stats *fsp, const oit_stream_frame_stats *ssp,
                       double t0, oit_draw_stats *stats)
{
    const oit_frame_stats fs = *fsp;
    const oit_stream_frame_stats ss = *ssp;
    const oit_view view = *vp;
    {
        *stats = (oit_draw_stats){.ms = oit_time_ms() - t0, .fragments = fs.fragments,
                                  .max_layers = fs.max_layers,
                                  .overflow_pixels = fs.overflow_pixels, .packs = ss.packs,
                                  .parts_drawn = ss.parts_drawn,
                                  .parts_culled = ss.parts_culled,
                                  .parts_skipped = ss.parts_skipped,
                                  .bytes_uploaded = ss.bytes_uploaded,
                                  .gpu_bytes_peak = ss.gpu_bytes_peak,
                                  .cache_hits = ss.cache_hits,
                                  .cache_bytes = ss.cache_bytes,
                                  .draw_calls = ss.draw_calls,
                                  .parts_clipped = ss.parts_clipped,
                                  .bytes_clipped = ss.bytes_clipped,
                                  .capture_slots = fs.capture_slots,
                                  .capture_slots_k = fs.capture_slots_k,
                                  .capture_fallback =
                                      r->streamer ? oit_streamer_capture_choice(r->streamer)->reason
                                                  : NULL,
                                  .gpu_frame = r->gpu.frame, .draw = r->draws,
                                  .gpu_ms = r->gpu.frame ? r->gpu.ms : -1.0};
        memcpy(stats->gpu_phase_ms, r->gpu.phase_ms, sizeof stats->gpu_phase_ms);
        oit_stream_budget b = {0};
        if (scene->pf)
            oit_streamer_budget(r->streamer, &b);
        stats->gpu_budget = b.total;
        stats->ring_budget = b.ring;
        stats->cache_budget = b.cache;
        stats->capture_budget = b.capture;
        stats->store_budget = b.store;
        stats->gpu_free_bytes = b.free_bytes;
        stats->see_through = (uint32_t)view.shading.see_through;
        stats->opaque = (uint32_t)oit_shading_opaque(&view.shading);
        stats->resident = (uint32_t)b.resident;
        stats->budget_source = b.source;
        draw_stats_work(&fs, &ss, stats);
    }
}

/* One band's (or the whole frame's) image through the capture's resolve:
 * the streamer's or DFB's, as the tools' methods render it. */
static oit_status render_image(oit_renderer *r, const oit_scene *scene, const oit_view *v,
                               oit_image *out, oit_frame_stats *fs, oit_stream_frame_stats *ss,
                               oit_error *err)
{
    static const oit_opaque_depth none = {0};
    if (scene->pf) {
        r->bands++;
        oit_streamer_set_gpu_timer(r->streamer, r->timer);
        oit_streamer_set_opaque(r->streamer, &none);
        return oit_streamer_render(r->streamer, v, out, fs, ss, err);
    }
    const oit_gpu_mesh *list[1] = {r->gpu_mesh};
    oit_dfb_set_opaque(r->dfb, &none);
    oit_dfb_set_gpu_timer(r->dfb, r->timer);
    oit_status st = oit_dfb_render(r->dfb, list, 1, v, out, NULL, fs, err);
    ss->packs = fs->batches;
    ss->draw_calls = 1 + (uint64_t)fs->batches;
    ss->bytes_uploaded = r->pending_upload;
    ss->gpu_bytes_peak = fs->gpu_bytes_peak + oit_gpu_mesh_bytes(r->gpu_mesh);
    r->pending_upload = 0;
    return st;
}

/* The image in bands of rows whose per-pixel state fits one storage
 * binding (render/gl/band.h), each copied into its rows of rgba, as the
 * tools' method interface does (render/method.c). */
static oit_status image_bands(oit_renderer *r, const oit_scene *scene, const oit_view *view,
                              float *rgba, oit_frame_stats *fs, oit_stream_frame_stats *ss,
                              oit_error *err)
{
    uint64_t px = scene->pf ? oit_streamer_pixel_bytes(view) : oit_dfb_pixel_bytes(view, 0);
    int rows = 0, w = view->width, h = view->height;
    oit_status st = oit_band_rows(view, px, r->desc.binding_limit, &rows, err);
    for (int y0 = 0; st == OIT_OK && y0 < h; y0 += rows) {
        int y1 = y0 + rows < h ? y0 + rows : h;
        oit_view band = *view;
        if (rows < h)
            oit_view_band(view, y0, y1, &band);
        /* A frame of one band is read back into rgba itself (the stream
         * and DFB write a given image in place, oit_image_reserve): no
         * second image to fault in and copy (the 1M plant at 1024x1024:
         * ~50 ms a frame on llvmpipe). */
        int direct = y0 == 0 && y1 == h;
        oit_image part = {0};
        if (direct)
            part = (oit_image){.width = w, .height = h, .rgba = rgba};
        oit_frame_stats bfs = {0};
        oit_stream_frame_stats bss = {0};
        st = render_image(r, scene, &band, &part, &bfs, &bss, err);
        if (st == OIT_OK && !direct)
            memcpy(rgba + (size_t)y0 * w * 4, part.rgba,
                   (size_t)w * (size_t)(y1 - y0) * 4 * sizeof *rgba);
        if (!direct)
            oit_image_free(&part);
        oit_frame_stats_add(fs, &bfs);
        oit_stream_frame_stats_add(ss, &bss);
    }
    return st;
}

/* The background alone, as a pixel no fragment reached resolves. */
static void empty_image(const oit_view *view, float *rgba)
{
    oit_pixel_state px;
    float rgb[3];
    oit_pixel_begin(&px);
    oit_pixel_end(&px, &view->shading, rgb);
    for (size_t i = 0; i < (size_t)view->width * (size_t)view->height; i++) {
        memcpy(rgba + 4 * i, rgb, sizeof rgb);
        rgba[4 * i + 3] = 1.0f;
    }
}

oit_status oit_renderer_draw_image(oit_renderer *r, oit_scene *scene, const oit_frame *frame,
                                   const float background[3], float *rgba, size_t rgba_bytes,
                                   oit_draw_stats *stats, oit_error *err)
{
    if (!r || !scene || !frame || !rgba)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_draw_image: NULL argument");
    double t0 = oit_time_ms();
    oit_view view;
    oit_status st = frame_view(r, scene, frame, background, &view, err);
    if (st != OIT_OK)
        return st;
    if (frame->depth_texture)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "oit_renderer_draw_image: "
                             "oit_frame.depth_texture = %u: an image has no opaque depth; "
                             "draw into the caller's framebuffer (oit_renderer_draw)",
                             frame->depth_texture);
    size_t need = (size_t)view.width * (size_t)view.height * 4 * sizeof *rgba;
    if (rgba_bytes < need)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_renderer_draw_image: a %dx%d image "
                             "needs %zu bytes, rgba has %zu", view.width, view.height, need,
                             rgba_bytes);
    gl_saved saved;
    gl_save(&saved);
    oit_frame_stats fs = {0};
    oit_stream_frame_stats ss = {0};
    if (!r->timer)
        st = oit_gpu_timer_create(NULL, &r->timer, err);
    int empty = !scene->pf && scene->info.triangles == 0;
    if (st == OIT_OK && !empty)
        st = bind_scene(r, scene, err);
    oit_gpu_timer_begin_frame(r->timer);
    r->bands = 0;
    if (st == OIT_OK && !empty)
        st = image_bands(r, scene, &view, rgba, &fs, &ss, err);
    frame_end(r, scene, st, t0, oit_gpu_timer_end_frame(r->timer));
    gpu_take(r);
    gl_restore(&saved);
    if (st == OIT_OK && empty) /* nothing in front of the background */
        empty_image(&view, rgba);
    if (st != OIT_OK)
        return name_scene(scene, st, err);
    if (stats)
        fill_stats(r, scene, &view, &fs, &ss, t0, stats);
    return OIT_OK;
}

oit_status oit_scene_share_order(oit_scene *scene, const oit_frame *frame, uint32_t *order,
                                 uint32_t order_count, oit_error *err)
{
    if (!scene || !frame || !order)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_share_order: NULL argument");
    uint32_t n = scene->info.share_count;
    if (order_count < n)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: oit_scene_share_order: order holds "
                             "%u shares, the scene has %u", scene_name(scene), order_count, n);
    oit_view view;
    oit_status st = frame_camera(frame, &view, err);
    if (st == OIT_OK && !scene->share_set)
        order[0] = 0;
    else if (st == OIT_OK)
        st = oit_shares_view_order(scene->order, scene->share_set, &view, scene->ordered, order,
                                   err);
    if (st != OIT_OK)
        oit_error_prefix(err, scene_name(scene));
    return st;
}
