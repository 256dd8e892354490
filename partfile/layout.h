/* On-disk layout of the part file shared by its reader and writer
 * (docs/part-file.md is the specification; keep the two in step).
 * Every struct here is the exact little-endian record; the asserts pin it.
 */
#ifndef OIT_PARTFILE_LAYOUT_H
#define OIT_PARTFILE_LAYOUT_H

#include <stddef.h>
#include <stdint.h>

#include "oit/partfile.h"

#define PF_MAGIC "OITPART"           /* 8 bytes with its NUL */
#define PF_HEADER_BYTES 64u
#define PF_ENTRY_BYTES 32u
#define PF_SECTION_ALIGN 8u
#define PF_K_MAX 1024u
#define PF_ALIGN_MIN 8u
#define PF_ALIGN_MAX (1u << 20)
#define PF_INDEX16_MAX_VERTICES 65536u

/* Section types in table order (the table lists each exactly once). */
enum {
    PF_SEC_META = 1,
    PF_SEC_PARTS,
    PF_SEC_PIECES,
    PF_SEC_GRID,
    PF_SEC_SUBGRIDS,
    PF_SEC_SLABS,
    PF_SEC_PART_DATA,
    PF_SECTION_COUNT = PF_SEC_PART_DATA
};

#define PF_TABLE_END (PF_HEADER_BYTES + PF_SECTION_COUNT * PF_ENTRY_BYTES)

typedef struct pf_header {
    char magic[8];
    uint32_t version;
    uint32_t flags;          /* none defined: must be 0 */
    uint32_t header_bytes;   /* 64 */
    uint32_t section_count;  /* 7 */
    uint32_t K;
    uint32_t part_align;
    uint64_t file_bytes;
    uint64_t part_count;
    uint64_t triangle_count;
    uint32_t table_crc;      /* CRC-32C of bytes [0,56) then the table */
    uint32_t reserved;
} pf_header;

typedef struct pf_section {
    uint32_t type;
    uint32_t flags; /* none defined: must be 0 */
    uint64_t offset;
    uint64_t size;
    uint32_t crc;   /* CRC-32C of [offset, offset+size) */
    uint32_t reserved;
} pf_section;

typedef struct pf_meta {
    float bounds_min[3];
    float bounds_max[3];
    uint32_t attributes;
    uint32_t reserved;
    uint64_t triangles_in;
    uint64_t triangles_dropped;
    uint64_t triangles_split;
    uint32_t source_name_bytes; /* the name follows, then the options */
    uint32_t options_bytes;
} pf_meta;

/* Head of GRID and SUBGRIDS: grids, then cells, then the u32 part list. */
typedef struct pf_grid_block {
    uint32_t grid_count;
    uint32_t reserved;
    uint64_t cell_count;
    uint64_t list_count;
} pf_grid_block;

/* Head of SLABS: slabs, then the u32 inside-part list. */
typedef struct pf_slab_block {
    uint32_t slab_count;
    uint32_t reserved;
    uint64_t list_count;
} pf_slab_block;

_Static_assert(sizeof(pf_header) == PF_HEADER_BYTES, "header layout");
_Static_assert(offsetof(pf_header, table_crc) == 56, "header layout");
_Static_assert(sizeof(pf_section) == PF_ENTRY_BYTES, "section entry layout");
_Static_assert(sizeof(pf_meta) == 64, "META layout");
_Static_assert(sizeof(pf_grid_block) == 24, "grid block layout");
_Static_assert(sizeof(pf_slab_block) == 16, "slab block layout");
_Static_assert(sizeof(oit_partfile_part) == 144, "part record layout");
_Static_assert(sizeof(oit_partfile_piece) == 48, "piece record layout");
_Static_assert(sizeof(oit_partfile_grid) == 64, "grid record layout");
_Static_assert(sizeof(oit_partfile_cell) == 24, "cell record layout");
_Static_assert(sizeof(oit_partfile_slab) == 48, "slab record layout");
_Static_assert(sizeof(float) == 4, "IEEE-754 binary32");
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the part file reader and writer need a little-endian host"
#endif

static inline const char *pf_section_name(uint32_t type)
{
    static const char *const names[] = {"?",     "META",     "PARTS", "PIECES",
                                        "GRID",  "SUBGRIDS", "SLABS", "PART_DATA"};
    return type <= PF_SECTION_COUNT ? names[type] : "?";
}

static inline uint64_t pf_align_up(uint64_t x, uint64_t a)
{
    return (x + (a - 1)) & ~(a - 1);
}

/* Bytes of a GRID/SUBGRIDS block and of SLABS, padded to 8; callers bound
 * the counts first so that none of these products overflows. */
static inline uint64_t pf_grid_block_bytes(uint64_t grids, uint64_t cells, uint64_t list)
{
    return pf_align_up(sizeof(pf_grid_block) + grids * sizeof(oit_partfile_grid) +
                           cells * sizeof(oit_partfile_cell) + list * 4u,
                       8);
}

static inline uint64_t pf_slab_block_bytes(uint64_t slabs, uint64_t list)
{
    return pf_align_up(sizeof(pf_slab_block) + slabs * sizeof(oit_partfile_slab) + list * 4u, 8);
}

static inline uint32_t pf_vertex_stride(uint32_t attributes)
{
    return attributes ? 16u : 12u;
}

#endif
