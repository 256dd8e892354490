/* The legacy VTK reader's inside (read_vtk.c), shared by its files: read_vtk.c
 * (the file's sections, its points and cells), vtk_legacy_values.c (lines,
 * words and values, ASCII or BINARY) and vtk_legacy_attributes.c (POINT_DATA
 * and CELL_DATA: colours kept, other arrays skipped). read_vtk.c uses the
 * other two, the attributes use the values; nothing outside formats/
 * includes it. */
#ifndef OIT_FORMATS_VTK_LEGACY_INTERNAL_H
#define OIT_FORMATS_VTK_LEGACY_INTERNAL_H

#include "formats/vtk_internal.h"

typedef enum leg_type {
    LT_BAD, LT_BIT, LT_U8, LT_I8, LT_U16, LT_I16, LT_U32, LT_I32, LT_U64, LT_I64, LT_F32, LT_F64
} leg_type;

typedef struct leg {
    oit_rd_ctx *c;
    int binary, new_cells, ugrid;
    int have_points;
    oit_rd_vtable pts;
    vtk_cells sec[4]; /* POLYDATA: verts, lines, polys, strips (VTK's id order) */
    vtk_colours pc, cc;
    int pc_rank, cc_rank; /* kind of the colour array kept (higher wins) */
    int data;             /* 0 none, 1 POINT_DATA, 2 CELL_DATA */
    uint64_t tuples;      /* of the current POINT_DATA / CELL_DATA */
    char *words[8];
    size_t lens[8];
    int nwords;
} leg;

/* The error st with the message (printf's fmt), naming the line in an ASCII
 * file, the byte offset in a BINARY one: leg_fail(L, st, fmt, ...). */
#define leg_fail(L, ...) oit_rd_fail_here(&(L)->c->in, (L)->binary, __VA_ARGS__)

/* ---- vtk_legacy_values.c ---- */

/* Whether word i is the keyword lit (case-insensitive, as VTK's reader
 * takes them). */
int leg_is(const leg *L, int i, const char *lit);

/* Next line with content, split into words (NUL-terminated); 0 words at the
 * end of the file. */
oit_status leg_line(leg *L);

/* Word i as a non-negative integer; 0 when it is missing or not one. */
int leg_count(const leg *L, int i, uint64_t *out);

/* The data type named by word i; strings and unknown names are refused. */
oit_status leg_type_word(leg *L, int i, leg_type *t);

/* One value of type t: a token in ASCII, big-endian bytes in BINARY. */
oit_status leg_value(leg *L, leg_type t, const char *what, double *out);

/* n values of type t skipped. */
oit_status leg_skip(leg *L, leg_type t, uint64_t n, const char *what);

/* v as an index of one of the points read (an integer below their count). */
oit_status leg_index(leg *L, double v, const char *what, uint32_t *id);

/* ---- vtk_legacy_attributes.c ---- */

/* POINT_DATA (which 1) or CELL_DATA (2): its count must be the points' or
 * the cells'; the arrays that follow are of it. */
oit_status leg_data(leg *L, int which);

/* A FIELD of arrays: a colour array kept (unsigned_char, 3 or 4
 * components, named like a colour), the rest skipped. */
oit_status leg_field(leg *L);

/* VTK 9 follows an array with METADATA and lines up to a blank one. */
oit_status leg_skip_metadata(leg *L);

/* The keyword lines of an attribute section other than FIELD (SCALARS,
 * COLOR_SCALARS, VECTORS, ...): *done = 0 when the line is none of them. */
oit_status leg_attribute(leg *L, int *done);

#endif
