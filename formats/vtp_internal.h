/* The VTK XML PolyData reader's inside (read_vtp.c), shared by its files:
 * read_vtp.c (the pieces turned into points, cells and colours), vtp_xml.c
 * (the file held whole and its elements walked into arrays and pieces) and
 * vtp_decode.c (one DataArray decoded: ascii, base64, raw, zlib). read_vtp.c
 * uses the other two; nothing outside formats/ includes it. */
#ifndef OIT_FORMATS_VTP_INTERNAL_H
#define OIT_FORMATS_VTP_INTERNAL_H

#include "formats/vtk_internal.h"
#include "formats/zlib_load.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

enum { VT_BAD, VT_I8, VT_U8, VT_I16, VT_U16, VT_I32, VT_U32, VT_I64, VT_U64, VT_F32, VT_F64 };
static const unsigned vt_size[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 4, 8};
enum { FMT_ASCII, FMT_BINARY, FMT_APPENDED };
enum { SEC_VERTS, SEC_LINES, SEC_POLYS, SEC_STRIPS, SEC_N };
enum { ROLE_OTHER, ROLE_POINTS, ROLE_PDATA, ROLE_CDATA, ROLE_CONN, ROLE_OFFS };

typedef struct vtp_array {
    size_t at;                /* byte offset of its tag, for messages */
    const char *name;         /* not NUL-terminated                    */
    size_t name_len;
    int type, comps, format, role, sec;
    uint64_t offset;          /* appended: from the '_'                */
    size_t text, text_end;    /* inline: the content's bytes           */
} vtp_array;

typedef struct vtp_piece {
    size_t at;
    uint64_t npoints, ncells[SEC_N];
    size_t first, count;               /* its arrays: arrays[first, first+count) */
    const char *scalars[2];            /* PointData / CellData Scalars=   */
    size_t scalars_len[2];
} vtp_piece;

typedef struct vtp {
    oit_rd_ctx *c;
    unsigned char *buf;
    size_t len, cap;
    int big, header64, zlib;
    size_t appended, appended_end; /* 0: none */
    int appended_b64;
    vtp_array *arrays;
    size_t narrays, arrays_cap;
    vtp_piece *pieces;
    size_t npieces, pieces_cap;
    oit_zlib z;
    unsigned char *dec; /* the decoded bytes of the array being read */
    size_t dec_len, dec_cap;
} vtp;

/* The error st naming the file and the byte offset at; inline so that
 * each file of the reader has it without one of them owning the others'
 * messages. */
static inline oit_status vtp_fail(vtp *V, size_t at, oit_status st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static inline oit_status vtp_fail(vtp *V, size_t at, oit_status st, const char *fmt, ...)
{
    char msg[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return oit_error_set(V->c->err, st, "%s: byte offset %zu: %s", V->c->name, at, msg);
}

static inline int vtp_xml_space(unsigned char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r';
}

typedef struct vtp_view {
    const unsigned char *b;
    int type, big, native_double;
    size_t count;
} vtp_view;

/* Value i of the array, as a double (inline: it runs per value). */
static inline double vtp_get(const vtp_view *v, size_t i)
{
    if (v->native_double) {
        double d;
        memcpy(&d, v->b + i * sizeof d, sizeof d);
        return d;
    }
    const unsigned char *b = v->b + i * vt_size[v->type];
    uint64_t u = 0;
    for (unsigned k = 0; k < vt_size[v->type]; k++)
        u |= (uint64_t)b[v->big ? vt_size[v->type] - 1 - k : k] << (8 * k);
    switch (v->type) {
    case VT_I8: return (int8_t)u;
    case VT_I16: return (int16_t)u;
    case VT_I32: return (int32_t)u;
    case VT_I64: return (double)(int64_t)u;
    case VT_F32: { uint32_t x = (uint32_t)u; float f; memcpy(&f, &x, 4); return f; }
    case VT_F64: { double d; memcpy(&d, &u, 8); return d; }
    default: return (double)u;
    }
}

/* ---- vtp_xml.c ---- */

/* Reads the whole file into V->buf (NUL-terminated), charged to the
 * budget. */
oit_status vtp_slurp(vtp *V);

/* Walks the file's elements: the VTKFile root's attributes, each Piece and
 * its DataArrays (role, section, format, where their data is) into
 * V->pieces and V->arrays, and where AppendedData starts. Nothing is
 * decoded. */
oit_status vtp_walk_file(vtp *V);

/* ---- vtp_decode.c ---- */

/* Decodes array a, which must hold `count` values, into dec (moved out to
 * *owned so that several arrays can be held at once). */
oit_status vtp_decode(vtp *V, const vtp_array *a, size_t count, vtp_view *view,
                      unsigned char **owned, size_t *owned_cap);

#endif
