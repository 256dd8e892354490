/* oit_mesh_read: picks the reader by file extension (case-insensitive),
 * assimp's adapter taking the rest (assimp_internal.h), and
 * the file-path entries of the streaming readers. */
#include "formats/assimp_internal.h"
#include "formats/readers_internal.h"
#include "formats/vtk_internal.h"

#include <ctype.h>
#include <string.h>

static int ext_is(const char *ext, const char *want)
{
    for (; *ext && *want; ext++, want++)
        if (tolower((unsigned char)*ext) != *want)
            return 0;
    return *ext == '\0' && *want == '\0';
}

/* The extension that names the format, a trailing ".gz" set aside; NULL
 * where the name has none (no dot, or nothing after the last). */
static const char *mesh_ext(const char *path, char *buf, size_t cap)
{
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    size_t n = strlen(base);
    if (n > 3 && base[n - 3] == '.' && tolower((unsigned char)base[n - 2]) == 'g' &&
        tolower((unsigned char)base[n - 1]) == 'z')
        n -= 3;
    size_t d = n;
    while (d > 0 && base[d - 1] != '.')
        d--;
    if (d == 0 || d == n)
        return NULL;
    if (n - d >= cap)
        return "";
    memcpy(buf, base + d, n - d);
    buf[n - d] = '\0';
    return buf;
}

oit_status oit_mesh_read(const char *path, const oit_read_desc *desc, oit_triangle_sink sink,
                         void *user, oit_mesh_info *info, oit_error *err)
{
    if (!path)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "oit_mesh_read: no path given");
    /* NAME.obj.gz is an OBJ: the readers inflate gzip whatever the name. */
    char ext_buf[16];
    const char *ext = mesh_ext(path, ext_buf, sizeof ext_buf);
    if (!ext)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "%s: no file extension to tell its "
                             "format by (expected .ply .obj .off .stl .gltf .glb .vtk .vtp "
                             ".step .stp .iges .igs, or one that assimp imports: .fbx .dae "
                             ".3ds .3mf ...; NAME.EXT.gz for gzip)", path);
    if (ext_is(ext, "ply"))
        return oit_read_ply(path, desc, sink, user, info, err);
    if (ext_is(ext, "obj"))
        return oit_read_obj(path, desc, sink, user, info, err);
    if (ext_is(ext, "off"))
        return oit_read_off(path, desc, sink, user, info, err);
    if (ext_is(ext, "stl"))
        return oit_read_stl(path, desc, sink, user, info, err);
    if (ext_is(ext, "gltf") || ext_is(ext, "glb"))
        return oit_read_gltf(path, desc, sink, user, info, err);
    if (ext_is(ext, "vtk"))
        return oit_rd_with_file(path, oit_read_vtk_stream, desc, sink, user, info, err);
    if (ext_is(ext, "vtp"))
        return oit_rd_with_file(path, oit_read_vtp_stream, desc, sink, user, info, err);
    if (ext_is(ext, "step") || ext_is(ext, "stp"))
        return oit_read_step(path, desc, sink, user, info, err);
    if (ext_is(ext, "iges") || ext_is(ext, "igs"))
        return oit_read_iges(path, desc, sink, user, info, err);
    /* Last: assimp takes what no reader of ours does, and refuses (naming
     * every extension) what it does not import either. */
    return oit_read_assimp(path, desc, sink, user, info, err);
}

/* Here, not in mesh.c, so that what the plugins take of mesh.c (the info
 * helpers) does not bring every reader into each of them. */
static oit_status load_sink(void *user, const oit_triangle *tris, size_t count, oit_error *err)
{
    return oit_mesh_append((oit_mesh *)user, tris, count, err);
}

oit_status oit_mesh_load(const char *path, const oit_read_desc *desc, oit_mesh *out,
                         oit_error *err)
{
    memset(out, 0, sizeof *out);
    oit_status s = oit_mesh_read(path, desc, load_sink, out, &out->info, err);
    if (s != OIT_OK)
        oit_mesh_free(out);
    return s;
}

/* The file-path entry of a streaming reader: oit_read_FMT reads path
 * (gzip or not) with oit_read_FMT_stream. Defines oit_read_ply,
 * oit_read_obj, oit_read_off and oit_read_stl (oit/mesh.h). */
#define PATH_READER(FMT)                                                                   \
    oit_status oit_read_##FMT(const char *path, const oit_read_desc *desc,                \
                              oit_triangle_sink sink, void *user, oit_mesh_info *info,   \
                              oit_error *err)                                              \
    {                                                                                      \
        return oit_rd_with_file(path, oit_read_##FMT##_stream, desc, sink, user, info,     \
                                err);                                                      \
    }

PATH_READER(ply)
PATH_READER(obj)
PATH_READER(off)
PATH_READER(stl)
