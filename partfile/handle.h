/* The part file handle's inside, shared by the reader (read.c: open, close,
 * accessors), its checks (validate.c: everything open verifies before a
 * caller sees a record), the part decoder (part_blob.c) and the helpers all
 * of them report through (handle.c). Dependencies point one way: read.c ->
 * validate.c -> part_blob.c -> handle.c, and read.c uses the lower two too.
 * Nothing outside partfile/ includes it. */
#ifndef OIT_PARTFILE_HANDLE_H
#define OIT_PARTFILE_HANDLE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "oit/partfile.h"

#include "partfile/layout.h"

struct oit_partfile {
    char *name;
    const uint8_t *base;
    size_t size;
    void *map; /* owned mapping, or NULL for open_memory */
    pf_header hdr;
    pf_section sec[PF_SECTION_COUNT]; /* indexed by type - 1 */
    pf_meta meta;
    double origin[3];
    char *source_name, *options;
    oit_partfile_part *parts;
    oit_partfile_piece *pieces;
    uint64_t piece_count;
    oit_partfile_grid *grids; /* unified: 0 = top, then SUBGRIDS */
    uint32_t grid_count;
    oit_partfile_cell *cells; /* unified; subgrid list_first shifted */
    uint64_t cell_count;
    uint32_t *lists;
    uint64_t list_count;
    oit_partfile_slab *slabs;
    uint32_t slab_count;
    uint32_t *slab_list;
    uint64_t slab_list_count;
    unsigned char *part_ok; /* per part, with defer_part_data only */
    oit_partfile_summary summary;
};

/* ---- handle.c ---- */

/* OIT_ERR_NOMEM naming the file. */
oit_status pf_nomem(const oit_partfile *pf, oit_error *err);

/* OIT_ERR_FORMAT, the message (printf's fmt) prefixed with the file's name:
 * what every check returns for a file that breaks the format. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
oit_status pf_bad(const oit_partfile *pf, oit_error *err, const char *fmt, ...);

/* A malloc'd copy of count records of size bytes at p (1 byte when count is
 * 0, so NULL means out of memory); the caller has bounded count * size by
 * the section's size. */
void *pf_copy_out(const uint8_t *p, uint64_t count, size_t size);

/* ---- validate.c ---- */

/* Every check of open, in order: header, section table, checksums (of the
 * part data too unless deferred), then each section's records and the
 * cross-references; without deferred also every part's decoded streams.
 * Loads the management sections into pf's host arrays on the way. */
oit_status pf_validate_all(oit_partfile *pf, bool deferred, oit_error *err);

/* Drops n mapped bytes from `from` out of the process's resident pages
 * (they stay in the page cache): checked or streamed part data must not
 * hold a many-GB file resident. Nothing for an in-memory file. */
void pf_drop_checked(const oit_partfile *pf, const uint8_t *from, size_t n);

/* ---- part_blob.c (and oit_partfile_buffer_free) ---- */

/* Checks part i's stored checksum, decodes it into buf (grown as needed)
 * and checks every decoded value against its records. */
oit_status pf_validate_blob(const oit_partfile *pf, uint32_t i, oit_partfile_buffer *buf,
                            oit_error *err);
/* Decodes part i into buf without the value checks (a part already
 * validated once). */
oit_status pf_decode_blob(const oit_partfile *pf, uint32_t i, oit_partfile_buffer *buf,
                          oit_error *err);

#endif