/* The legacy VTK file's attribute sections (vtk_legacy_internal.h):
 * POINT_DATA and CELL_DATA, whose best colour array is kept and every
 * other array skipped. Apart from read_vtk.c as the data that follows the
 * geometry, read by kind of array, not by dataset. */
#include "formats/vtk_legacy_internal.h"

#include <inttypes.h>

static uint64_t leg_cell_total(const leg *L)
{
    return (uint64_t)L->sec[0].ncells + L->sec[1].ncells + L->sec[2].ncells + L->sec[3].ncells;
}

oit_status leg_data(leg *L, int which)
{
    uint64_t n;
    if (!leg_count(L, 1, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "%s: expected a count", L->words[0]);
    uint64_t want = which == 1 ? L->pts.count : leg_cell_total(L);
    if (n != want)
        return leg_fail(L, OIT_ERR_FORMAT, "%s %" PRIu64 " for %" PRIu64 " %s", L->words[0], n,
                        want, which == 1 ? "points" : "cells");
    L->data = which;
    L->tuples = n;
    return OIT_OK;
}

/* A colour array of comps components (rank: its kind) read, or skipped
 * when a better one is already kept. unit: values are 0..1 floats. */
static oit_status leg_colours(leg *L, int rank, leg_type t, int comps, int unit)
{
    vtk_colours *col = L->data == 1 ? &L->pc : &L->cc;
    int *kept = L->data == 1 ? &L->pc_rank : &L->cc_rank;
    if (rank <= *kept)
        return leg_skip(L, t, L->tuples * (uint64_t)comps, "a colour array");
    vtk_colours_free(col, &L->c->budget);
    oit_status st = vtk_colours_alloc(col, &L->c->budget, (size_t)L->tuples, comps, L->c->name,
                                      L->c->err);
    for (uint64_t i = 0; i < L->tuples && st == OIT_OK; i++)
        for (int k = 0; k < comps && st == OIT_OK; k++) {
            double v;
            st = leg_value(L, t, "colours", &v);
            if (st == OIT_OK)
                vtk_colour_set(col, (size_t)i, k, comps, v, unit);
        }
    *kept = rank;
    return st;
}

static oit_status leg_need_data(leg *L)
{
    if (L->data == 0)
        return leg_fail(L, OIT_ERR_FORMAT, "%s outside POINT_DATA or CELL_DATA", L->words[0]);
    return OIT_OK;
}

static oit_status leg_scalars(leg *L)
{
    leg_type t;
    uint64_t comps = 1;
    oit_status st = leg_type_word(L, 2, &t);
    if (st == OIT_OK && L->nwords > 3 && (!leg_count(L, 3, &comps) || comps < 1 || comps > 4))
        return leg_fail(L, OIT_ERR_FORMAT, "SCALARS: expected 1 to 4 components");
    if (st == OIT_OK)
        st = leg_line(L);
    if (st == OIT_OK && !leg_is(L, 0, "LOOKUP_TABLE"))
        return leg_fail(L, OIT_ERR_FORMAT, "SCALARS: expected LOOKUP_TABLE");
    if (st != OIT_OK)
        return st;
    if (t == LT_U8 && comps >= 3)
        return leg_colours(L, 2, t, (int)comps, 0);
    return leg_skip(L, t, L->tuples * comps, "SCALARS");
}

/* VTK 9 follows an array with METADATA and lines up to a blank one. */
oit_status leg_skip_metadata(leg *L)
{
    for (;;) {
        char *line, *p;
        int got;
        oit_status st = oit_rd_line(&L->c->in, &line, &got);
        if (st != OIT_OK || !got)
            return st;
        p = line;
        if (oit_rd_skip_blanks(&p) == '\0')
            return OIT_OK;
    }
}

static int leg_colour_name(const char *w)
{
    static const char *const names[] = {"color", "colour", "rgb"};
    for (size_t i = 0; i < 3; i++)
        for (const char *p = w; *p; p++) {
            size_t k = 0;
            while (names[i][k] && (p[k] | 0x20) == names[i][k])
                k++;
            if (!names[i][k])
                return 1;
        }
    return 0;
}

oit_status leg_field(leg *L)
{
    uint64_t n;
    if (!leg_count(L, 2, &n))
        return leg_fail(L, OIT_ERR_FORMAT, "FIELD: expected an array count");
    oit_status st = OIT_OK;
    for (uint64_t i = 0; i < n && st == OIT_OK;) {
        if ((st = leg_line(L)) != OIT_OK)
            return st;
        if (L->nwords == 0)
            return leg_fail(L, OIT_ERR_FORMAT, "file ends in FIELD after %" PRIu64 " of %" PRIu64
                            " arrays (truncated)", i, n);
        if (leg_is(L, 0, "METADATA")) {
            if ((st = leg_skip_metadata(L)) != OIT_OK)
                return st;
            continue;
        }
        i++;
        if (leg_is(L, 0, "NULL_ARRAY"))
            continue;
        uint64_t comps, tuples;
        leg_type t;
        if (!leg_count(L, 1, &comps) || !leg_count(L, 2, &tuples))
            return leg_fail(L, OIT_ERR_FORMAT, "FIELD array: expected 'name components tuples "
                            "type'");
        if ((st = leg_type_word(L, 3, &t)) != OIT_OK)
            return st;
        if (L->data && t == LT_U8 && (comps == 3 || comps == 4) && tuples == L->tuples &&
            leg_colour_name(L->words[0]))
            st = leg_colours(L, 1, t, (int)comps, 0);
        else
            st = leg_skip(L, t, comps * tuples, "FIELD array");
    }
    return st;
}

/* The keyword lines of an attribute section other than SCALARS/FIELD. */
oit_status leg_attribute(leg *L, int *done)
{
    leg_type t;
    uint64_t n;
    *done = 1;
    if (leg_is(L, 0, "SCALARS"))
        return leg_need_data(L) == OIT_OK ? leg_scalars(L) : OIT_ERR_FORMAT;
    if (leg_is(L, 0, "COLOR_SCALARS")) {
        if (leg_need_data(L) != OIT_OK)
            return OIT_ERR_FORMAT;
        if (!leg_count(L, 2, &n) || n < 1 || n > 4)
            return leg_fail(L, OIT_ERR_FORMAT, "COLOR_SCALARS: expected 1 to 4 components");
        return leg_colours(L, 3, L->binary ? LT_U8 : LT_F32, (int)n, !L->binary);
    }
    int per = leg_is(L, 0, "VECTORS") || leg_is(L, 0, "NORMALS") ? 3
              : leg_is(L, 0, "TENSORS") ? 9 : leg_is(L, 0, "TENSORS6") ? 6
              : leg_is(L, 0, "GLOBAL_IDS") || leg_is(L, 0, "PEDIGREE_IDS") ? 1 : 0;
    int typ = 2;
    if (leg_is(L, 0, "TEXTURE_COORDINATES")) {
        if (!leg_count(L, 2, &n) || n < 1 || n > 3)
            return leg_fail(L, OIT_ERR_FORMAT, "TEXTURE_COORDINATES: expected 1 to 3 dimensions");
        per = (int)n, typ = 3;
    }
    if (per) {
        if (leg_need_data(L) != OIT_OK)
            return OIT_ERR_FORMAT;
        oit_status st = leg_type_word(L, typ, &t);
        return st == OIT_OK ? leg_skip(L, t, L->tuples * (uint64_t)per, "an attribute array")
                            : st;
    }
    if (leg_is(L, 0, "LOOKUP_TABLE")) {
        if (!leg_count(L, 2, &n))
            return leg_fail(L, OIT_ERR_FORMAT, "LOOKUP_TABLE: expected a count");
        return leg_skip(L, L->binary ? LT_U8 : LT_F32, 4 * n, "LOOKUP_TABLE");
    }
    *done = 0;
    return OIT_OK;
}
