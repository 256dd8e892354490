/* liboit's scenes (liboit_internal.h): a part file or mesh opened, or a
 * mesh made from the caller's arrays, checked and kept for drawing. */
#include "liboit/liboit_internal.h"

#include "formats/up_axis.h"
#include "oit/offscreen.h"

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
void oit_lib_scene_unshare(oit_scene *s)
{
    if (!s || atomic_fetch_sub(&s->shares, 1u) != 1u)
        return;
    oit_shares_destroy(s->share_set);
    oit_order_destroy(s->order);
    free(s->ordered);
    oit_partfile_close(s->pf);
    if (!s->mesh_borrowed)
        oit_mesh_free(&s->mesh);
    free(s->name);
    free(s);
}

/* oit_scene_info.up_axis: formats/up_axis.h's 0 x, 1 y, 2 z as an
 * oit_up_axis. */
static uint32_t scene_up(const char *name, const float bmin[3], const float bmax[3])
{
    static const oit_up_axis of[3] = {OIT_UP_X, OIT_UP_Y, OIT_UP_Z};
    return (uint32_t)of[oit_up_axis_guess(name, bmin, bmax, NULL)];
}

static oit_status mesh_scene(oit_mesh *mesh, const char *name, oit_scene **out, oit_error *err)
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
    s->info.up_axis = scene_up(name, mi->bounds_min, mi->bounds_max);
    *out = s;
    return OIT_OK;
}

oit_status oit_scene_borrow_mesh(const oit_mesh *mesh, const char *name, oit_scene **out,
                                 oit_error *err)
{
    *out = NULL;
    if (!mesh || (mesh->count && !mesh->tris))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_scene_borrow_mesh: %s",
                             mesh ? "mesh->tris is NULL" : "NULL mesh");
    oit_mesh view = *mesh;
    oit_status s = mesh_scene(&view, name ? name : "mesh", out, err);
    if (s == OIT_OK)
        (*out)->mesh_borrowed = 1;
    return s;
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
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: oit_scene_desc share %u of %u: "
                                 "shares are of part files (oitprep), this is a mesh",
                                 path, desc->share_index, desc->share_count);
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
    s->info.up_axis = scene_up(oit_partfile_source_name(s->pf), sum.bounds_min, sum.bounds_max);
    st = open_share(s, desc, err);
    if (st != OIT_OK) {
        oit_lib_scene_unshare(s);
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
    oit_lib_scene_unshare(scene);
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
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: %s.vertex_count = %llu: fewer than "
                             "one triangle's 3",
                             name, D, (unsigned long long)d->vertex_count);
    if (d->colour_type != OIT_COLOUR_UINT8 && d->colour_type != OIT_COLOUR_FLOAT)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: %s.colour_type = %d is not an "
                             "oit_colour_type",
                             name, D, (int)d->colour_type);
    if (d->colour_rate != OIT_COLOUR_PER_VERTEX && d->colour_rate != OIT_COLOUR_PER_TRIANGLE)
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: %s.colour_rate = %d is not an "
                             "oit_colour_rate",
                             name, D, (int)d->colour_rate);
    if (d->indices) {
        if (d->index_count == 0 || d->index_count % 3)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: %s.index_count = %llu is not a "
                                 "positive multiple of 3",
                                 name, D, (unsigned long long)d->index_count);
        for (uint64_t i = 0; i < d->index_count; i++)
            if (d->indices[i] >= d->vertex_count)
                return oit_error_set(err, OIT_ERR_ARGUMENT,
                                     "%s: %s.indices[%llu] = %u: not "
                                     "below vertex_count %llu",
                                     name, D, (unsigned long long)i, d->indices[i],
                                     (unsigned long long)d->vertex_count);
        *triangles = d->index_count / 3;
    } else {
        if (d->index_count != 0)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: %s.index_count = %llu without "
                                 "indices",
                                 name, D, (unsigned long long)d->index_count);
        if (d->vertex_count % 3)
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: %s.vertex_count = %llu: a soup "
                                 "(indices NULL) needs a multiple of 3",
                                 name, D, (unsigned long long)d->vertex_count);
        *triangles = d->vertex_count / 3;
    }
    for (uint64_t i = 0; i < 3 * d->vertex_count; i++)
        if (!isfinite(d->positions[i]))
            return oit_error_set(err, OIT_ERR_ARGUMENT,
                                 "%s: %s.positions[%llu] (vertex "
                                 "%llu) is not finite",
                                 name, D, (unsigned long long)i, (unsigned long long)(i / 3));
    if ((uint64_t)SIZE_MAX / sizeof(oit_triangle) < *triangles)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: %llu triangles do not fit in memory", name,
                             (unsigned long long)*triangles);
    return OIT_OK;
}

oit_status oit_scene_create_mesh(const oit_scene_mesh_desc *d, oit_scene **out, oit_error *err)
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
