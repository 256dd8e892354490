/* libFuzzer target: the part file reader over arbitrary bytes.
 *
 * Each input is opened twice: as given (mostly stopped by the checksums) and
 * with every checksum recomputed, so mutations reach the record and cross-
 * reference checks. Whatever the reader accepts is then walked the way
 * oitstream would use it; any index or reference out of range there is a
 * reader bug and traps.
 */
#include "oit/partfile.h"

#include "tests/partfile/partfile_reseal.h"

#include <stdlib.h>
#include <string.h>

#define REQUIRE(c)                                                                          \
    do {                                                                                    \
        if (!(c))                                                                           \
            __builtin_trap();                                                               \
    } while (0)

static void walk_part(const oit_partfile *pf, uint32_t i)
{
    const oit_partfile_part *p = &oit_partfile_parts(pf)[i];
    oit_partfile_part_view v;
    oit_partfile_buffer buf = {0};
    REQUIRE(oit_partfile_part_data(pf, i, &buf, &v, NULL) == OIT_OK);
    for (uint64_t j = 0; j < v.index_count; j++) {
        uint32_t x = oit_partfile_index(&v, j);
        REQUIRE(x < p->vertex_count);
        float pos[3];
        memcpy(pos, (const uint8_t *)v.positions + (size_t)x * v.stride, sizeof pos);
        for (int k = 0; k < 3; k++)
            REQUIRE(pos[k] >= p->bounds_min[k] && pos[k] <= p->bounds_max[k]);
    }
    /* The source indices end the blob and name source triangles. */
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    REQUIRE(oit_partfile_source_offset(p) + v.index_count / 3 * 4 == p->data_bytes);
    for (uint64_t t = 0; t < v.index_count / 3; t++)
        REQUIRE(oit_partfile_source(&v, t) < sum.triangles_in);
    oit_partfile_buffer_free(&buf);
}

static void walk(const oit_partfile *pf)
{
    uint32_t parts = oit_partfile_part_count(pf);
    for (uint32_t i = 0; i < parts; i++)
        walk_part(pf, i);
    for (uint32_t g = 0; g < oit_partfile_grid_count(pf); g++) {
        const oit_partfile_grid *gr = oit_partfile_grid_at(pf, g);
        const oit_partfile_cell *cells = oit_partfile_cells(pf, g);
        for (uint64_t c = 0; c < gr->cell_count; c++) {
            uint32_t n;
            const uint32_t *list = oit_partfile_cell_parts(pf, g, c, &n);
            for (uint32_t k = 0; k < n; k++)
                REQUIRE(list[k] < parts);
            REQUIRE(cells[c].subgrid < oit_partfile_grid_count(pf));
            REQUIRE(!cells[c].subgrid ||
                    oit_partfile_grid_at(pf, cells[c].subgrid)->depth == gr->depth + 1);
        }
    }
    for (uint32_t s = 0; s < oit_partfile_slab_count(pf); s++) {
        uint32_t n;
        const uint32_t *inside = oit_partfile_slab_inside(pf, s, &n);
        for (uint32_t k = 0; k < n; k++)
            REQUIRE(inside[k] < parts);
    }
    oit_partfile_summary sum;
    oit_partfile_get_summary(pf, &sum);
    /* Above K a part is wide (docs/part-file.md, PARTS): the file's limit is
     * OIT_PARTFILE_MAX_LAYERS, not K. */
    REQUIRE(sum.layer_bound <= OIT_PARTFILE_MAX_LAYERS);
}

static void open_and_walk(const uint8_t *data, size_t size, bool deferred)
{
    oit_partfile *pf = NULL;
    oit_error err;
    oit_partfile_open_desc od = {.defer_part_data = deferred};
    oit_status st = oit_partfile_open_memory(data, size, "fuzz", &od, &pf, &err);
    REQUIRE((st == OIT_OK) == (pf != NULL));
    if (st == OIT_ERR_FORMAT)
        REQUIRE(strncmp(err.message, "fuzz: ", 6) == 0);
    if (!pf)
        return;
    bool all_ok = true;
    for (uint32_t i = 0; deferred && i < oit_partfile_part_count(pf); i++)
        all_ok = oit_partfile_validate_part(pf, i, NULL) == OIT_OK && all_ok;
    if (all_ok)
        walk(pf);
    oit_partfile_close(pf);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* The reader hands out float pointers: give it an aligned copy, as mmap would. */
    uint8_t *buf = malloc(size ? size : 1);
    if (!buf)
        return 0;
    memcpy(buf, data, size);
    open_and_walk(buf, size, false);
    if (size >= PF_TABLE_END) {
        pf_section parts;
        memcpy(&parts, buf + PF_HEADER_BYTES + (PF_SEC_PARTS - 1) * PF_ENTRY_BYTES, sizeof parts);
        uint64_t n = parts.offset <= size && parts.size <= size - parts.offset
                         ? parts.size / sizeof(oit_partfile_part)
                         : 0;
        for (uint64_t i = 0; i < n; i++)
            reseal_part(buf, size, (uint32_t)i);
        reseal(buf, size);
        open_and_walk(buf, size, false);
        open_and_walk(buf, size, true);
    }
    free(buf);
    return 0;
}
