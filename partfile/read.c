/* Part file reader (docs/part-file.md): open, close and the accessors.
 * Every check open runs is in validate.c; a caller sees only records that
 * passed them. The top of the reader: it uses validate.c (open's checks),
 * part_blob.c (a part's decode and its buffer) and handle.c, and none of
 * them uses it. */
#include "partfile/handle.h"


#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- open ------------------------------------------------------------------------ */

static void fill_summary(oit_partfile *pf)
{
    oit_partfile_summary *s = &pf->summary;
    s->version = pf->hdr.version;
    s->K = pf->hdr.K;
    s->triangles = pf->hdr.triangle_count;
    s->triangles_in = pf->meta.triangles_in;
    s->triangles_dropped = pf->meta.triangles_dropped;
    s->triangles_split = pf->meta.triangles_split;
    s->parts = pf->hdr.part_count;
    s->pieces = pf->piece_count;
    s->slabs = pf->slab_count;
    s->cut_slabs = 0;
    s->measured_bounds = (pf->hdr.flags & OIT_PARTFILE_FLAG_MEASURED_BOUNDS) != 0;
    for (uint32_t i = 0; i < pf->slab_count; i++)
        s->cut_slabs += pf->slabs[i].d0 == pf->slabs[i].d1;
    s->cells = pf->cell_count;
    s->subgrids = pf->grid_count - 1;
    s->attributes = pf->meta.attributes;
    s->part_align = pf->hdr.part_align;
    s->bytes = pf->size;
    s->data_bytes = pf->sec[PF_SEC_PART_DATA - 1].size;
    memcpy(s->bounds_min, pf->meta.bounds_min, sizeof s->bounds_min);
    memcpy(s->origin, pf->origin, sizeof s->origin);
    memcpy(s->bounds_max, pf->meta.bounds_max, sizeof s->bounds_max);
    for (uint32_t g = 0; g < pf->grid_count; g++)
        s->subgrid_depth = pf->grids[g].depth > s->subgrid_depth ? pf->grids[g].depth
                                                                  : s->subgrid_depth;
    for (uint32_t i = 0; i < pf->hdr.part_count; i++) {
        const oit_partfile_part *p = &pf->parts[i];
        s->layer_bound = p->layer_bound > s->layer_bound ? p->layer_bound : s->layer_bound;
        s->parts_index16 += p->index_bits == 16;
        s->parts_index32 += p->index_bits == 32;
    }
}

static oit_status open_common(oit_partfile *pf, const oit_partfile_open_desc *desc,
                              oit_partfile **out, oit_error *err)
{
    bool deferred = desc && desc->defer_part_data;
    oit_status s = pf_validate_all(pf, deferred, err);
    if (!s && deferred) {
        pf->part_ok = calloc(pf->hdr.part_count ? pf->hdr.part_count : 1, 1);
        if (!pf->part_ok)
            s = pf_nomem(pf, err);
    }
    if (s) {
        oit_partfile_close(pf);
        return s;
    }
    fill_summary(pf);
    *out = pf;
    return OIT_OK;
}

static oit_partfile *new_handle(const char *name)
{
    oit_partfile *pf = calloc(1, sizeof *pf);
    if (!pf)
        return NULL;
    size_t n = strlen(name) + 1;
    pf->name = malloc(n);
    if (!pf->name) {
        free(pf);
        return NULL;
    }
    memcpy(pf->name, name, n);
    return pf;
}

oit_status oit_partfile_open_memory(const void *data, size_t size, const char *name,
                                    const oit_partfile_open_desc *desc, oit_partfile **out,
                                    oit_error *err)
{
    *out = NULL;
    name = name ? name : "(memory)";
    oit_partfile *pf = new_handle(name);
    if (!pf)
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", name);
    pf->base = data;
    pf->size = data ? size : 0;
    return open_common(pf, desc, out, err);
}

oit_status oit_partfile_open(const char *path, const oit_partfile_open_desc *desc,
                             oit_partfile **out, oit_error *err)
{
    *out = NULL;
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return oit_error_set(err, OIT_ERR_IO, "%s: not a regular file", path);
    }
    oit_partfile *pf = new_handle(path);
    if (!pf) {
        close(fd);
        return oit_error_set(err, OIT_ERR_NOMEM, "%s: out of memory", path);
    }
    pf->size = (size_t)st.st_size;
    if (pf->size) {
        void *m = mmap(NULL, pf->size, PROT_READ, MAP_PRIVATE, fd, 0);
        if (m == MAP_FAILED) {
            oit_error_set(err, OIT_ERR_IO, "%s: cannot map %zu bytes: %s", path, pf->size,
                          strerror(errno));
            close(fd);
            oit_partfile_close(pf);
            return OIT_ERR_IO;
        }
        pf->map = m;
        pf->base = m;
    }
    close(fd);
    return open_common(pf, desc, out, err);
}

void oit_partfile_close(oit_partfile *pf)
{
    if (!pf)
        return;
    if (pf->map)
        munmap(pf->map, pf->size);
    free(pf->name);
    free(pf->source_name);
    free(pf->options);
    free(pf->parts);
    free(pf->pieces);
    free(pf->grids);
    free(pf->cells);
    free(pf->lists);
    free(pf->slabs);
    free(pf->slab_list);
    free(pf->part_ok);
    free(pf);
}

/* ---- accessors ---------------------------------------------------------------- */

void oit_partfile_get_summary(const oit_partfile *pf, oit_partfile_summary *out)
{
    *out = pf->summary;
}

const char *oit_partfile_name(const oit_partfile *pf) { return pf->name; }
const char *oit_partfile_source_name(const oit_partfile *pf) { return pf->source_name; }
const char *oit_partfile_options(const oit_partfile *pf) { return pf->options; }
uint32_t oit_partfile_part_count(const oit_partfile *pf) { return (uint32_t)pf->hdr.part_count; }
const oit_partfile_part *oit_partfile_parts(const oit_partfile *pf) { return pf->parts; }
uint64_t oit_partfile_piece_count(const oit_partfile *pf) { return pf->piece_count; }
const oit_partfile_piece *oit_partfile_pieces(const oit_partfile *pf) { return pf->pieces; }
uint32_t oit_partfile_grid_count(const oit_partfile *pf) { return pf->grid_count; }
uint32_t oit_partfile_slab_count(const oit_partfile *pf) { return pf->slab_count; }

oit_status oit_partfile_validate_part(oit_partfile *pf, uint32_t part, oit_error *err)
{
    if (part >= pf->hdr.part_count)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: part %u of %llu does not exist",
                             pf->name, part, (unsigned long long)pf->hdr.part_count);
    if (!pf->part_ok || pf->part_ok[part])
        return OIT_OK;
    oit_partfile_buffer buf = {0};
    oit_status s = pf_validate_blob(pf, part, &buf, err);
    oit_partfile_buffer_free(&buf);
    if (!s)
        pf->part_ok[part] = 1;
    return s;
}

static void fill_view(const oit_partfile *pf, uint32_t part, const oit_partfile_buffer *buf,
                      oit_partfile_part_view *out)
{
    const oit_partfile_part *p = &pf->parts[part];
    const uint8_t *blob = buf->data;
    out->blob = blob;
    out->positions = (const float *)(const void *)blob;
    out->rgba = p->attributes ? blob + 12 : NULL;
    out->stride = pf_vertex_stride(p->attributes);
    out->index_bits = p->index_bits;
    out->indices = blob + p->index_offset;
    out->index_count = p->index_count;
    out->sources = blob + oit_partfile_source_offset(p);
}

oit_status oit_partfile_part_load(oit_partfile *pf, uint32_t part, oit_partfile_buffer *buf,
                                  oit_partfile_part_view *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (part >= pf->hdr.part_count)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: part %u of %llu does not exist",
                             pf->name, part, (unsigned long long)pf->hdr.part_count);
    if (!pf->part_ok || pf->part_ok[part])
        return oit_partfile_part_data(pf, part, buf, out, err);
    oit_status s = pf_validate_blob(pf, part, buf, err);
    if (s)
        return s;
    pf->part_ok[part] = 1;
    fill_view(pf, part, buf, out);
    return OIT_OK;
}

oit_status oit_partfile_part_data(const oit_partfile *pf, uint32_t part,
                                  oit_partfile_buffer *buf, oit_partfile_part_view *out,
                                  oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (part >= pf->hdr.part_count)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: part %u of %llu does not exist",
                             pf->name, part, (unsigned long long)pf->hdr.part_count);
    if (pf->part_ok && !pf->part_ok[part])
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "%s: part %u has not passed oit_partfile_validate_part", pf->name,
                             part);
    /* Validated bytes decode to validated values: the codecs are
     * deterministic and the mapping is read-only. */
    oit_status s = pf_decode_blob(pf, part, buf, err);
    if (s)
        return s;
    fill_view(pf, part, buf, out);
    return OIT_OK;
}

void oit_partfile_drop_part_data(const oit_partfile *pf, uint32_t first, uint32_t count)
{
    uint64_t n = pf->hdr.part_count;
    if (first >= n || count == 0)
        return;
    uint64_t last = count > n - first ? n - 1 : (uint64_t)first + count - 1;
    const oit_partfile_part *a = &pf->parts[first], *b = &pf->parts[last];
    uint64_t end = b->data_offset + b->stored_bytes;
    if (end > a->data_offset)
        pf_drop_checked(pf, pf->base + a->data_offset, (size_t)(end - a->data_offset));
}

const oit_partfile_grid *oit_partfile_grid_at(const oit_partfile *pf, uint32_t grid)
{
    return grid < pf->grid_count ? &pf->grids[grid] : NULL;
}

const oit_partfile_cell *oit_partfile_cells(const oit_partfile *pf, uint32_t grid)
{
    return grid < pf->grid_count ? &pf->cells[pf->grids[grid].cell_first] : NULL;
}

const uint32_t *oit_partfile_cell_parts(const oit_partfile *pf, uint32_t grid, uint64_t cell,
                                        uint32_t *count)
{
    *count = 0;
    if (grid >= pf->grid_count || cell >= pf->grids[grid].cell_count)
        return NULL;
    const oit_partfile_cell *c = &pf->cells[pf->grids[grid].cell_first + cell];
    *count = c->list_count;
    return pf->lists + c->list_first;
}

const oit_partfile_slab *oit_partfile_slab_at(const oit_partfile *pf, uint32_t slab)
{
    return slab < pf->slab_count ? &pf->slabs[slab] : NULL;
}

const uint32_t *oit_partfile_slab_inside(const oit_partfile *pf, uint32_t slab, uint32_t *count)
{
    *count = 0;
    if (slab >= pf->slab_count)
        return NULL;
    *count = pf->slabs[slab].inside_count;
    return pf->slab_list + pf->slabs[slab].inside_first;
}
