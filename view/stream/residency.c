/* Residency cache bookkeeping (residency.h). */
#include "view/stream/residency.h"

#include <stdlib.h>

#define NONE 0xFFFFFFFFu

/* One record per part of the file, so lookups are O(1); resident parts are
 * linked in address order. */
typedef struct slot {
    uint64_t offset, bytes;
    uint64_t last_frame;
    uint32_t prev, next;
    uint8_t resident;
} slot;

struct oit_residency {
    uint64_t capacity, used;
    uint32_t part_count, resident;
    slot *slots;
    uint32_t first, last; /* lowest and highest resident part by address */
    uint64_t cursor;      /* where the next sweep starts */
    uint32_t cursor_next; /* first resident part at or after cursor; NONE: none */
    uint64_t frame;
    uint64_t full_frame;  /* a sweep found no room in this frame */
};

oit_status oit_residency_create(uint64_t capacity, uint32_t part_count, oit_residency **out,
                                oit_error *err)
{
    *out = NULL;
    oit_residency *r = calloc(1, sizeof *r);
    if (r)
        r->slots = calloc((size_t)part_count + 1, sizeof *r->slots);
    if (!r || !r->slots) {
        oit_residency_destroy(r);
        return oit_error_set(err, OIT_ERR_NOMEM, "residency cache: cannot track %u parts",
                             part_count);
    }
    r->capacity = capacity;
    r->part_count = part_count;
    r->first = r->last = r->cursor_next = NONE;
    *out = r;
    return OIT_OK;
}

void oit_residency_destroy(oit_residency *r)
{
    if (!r)
        return;
    free(r->slots);
    free(r);
}

void oit_residency_begin_frame(oit_residency *r)
{
    r->frame++;
}

int oit_residency_lookup(oit_residency *r, uint32_t part, uint64_t *offset)
{
    if (part >= r->part_count || !r->slots[part].resident)
        return 0;
    r->slots[part].last_frame = r->frame;
    *offset = r->slots[part].offset;
    return 1;
}

int oit_residency_peek(const oit_residency *r, uint32_t part, uint64_t *offset)
{
    if (part >= r->part_count || !r->slots[part].resident)
        return 0;
    *offset = r->slots[part].offset;
    return 1;
}

static void unlink_part(oit_residency *r, uint32_t p)
{
    slot *s = &r->slots[p];
    if (s->prev != NONE)
        r->slots[s->prev].next = s->next;
    else
        r->first = s->next;
    if (s->next != NONE)
        r->slots[s->next].prev = s->prev;
    else
        r->last = s->prev;
    s->resident = 0;
    r->used -= s->bytes;
    r->resident--;
}

/* Links p at [offset, offset + bytes), just before part `before` (NONE: at
 * the end), which is where that range sits in address order. */
static void link_part(oit_residency *r, uint32_t p, uint64_t offset, uint64_t bytes,
                      uint32_t before)
{
    slot *s = &r->slots[p];
    *s = (slot){offset, bytes, r->frame, NONE, before, 1};
    s->prev = before != NONE ? r->slots[before].prev : r->last;
    if (s->prev != NONE)
        r->slots[s->prev].next = p;
    else
        r->first = p;
    if (before != NONE)
        r->slots[before].prev = p;
    else
        r->last = p;
    r->used += bytes;
    r->resident++;
}

static int evictable(const oit_residency *r, uint32_t p)
{
    return r->slots[p].last_frame + 2 <= r->frame;
}

int oit_residency_insert(oit_residency *r, uint32_t part, uint64_t bytes, uint64_t *offset)
{
    if (part >= r->part_count || r->slots[part].resident || bytes > r->capacity ||
        r->full_frame == r->frame)
        return 0;
    uint64_t start = r->cursor;
    uint32_t e = r->cursor_next;
    for (int wrapped = 0;;) {
        uint64_t end = e == NONE ? r->capacity : r->slots[e].offset;
        if (end - start >= bytes) {
            link_part(r, part, start, bytes, e);
            r->cursor = start + bytes;
            r->cursor_next = e;
            *offset = start;
            return 1;
        }
        if (e == NONE) {
            if (wrapped)
                break;
            wrapped = 1;
            start = 0;
            e = r->first;
            continue;
        }
        uint32_t next = r->slots[e].next;
        if (evictable(r, e))
            unlink_part(r, e);
        else
            start = r->slots[e].offset + r->slots[e].bytes;
        e = next;
    }
    /* Two passes evicted every evictable part: what is left is this frame's
     * and the last one's. The sweep may have unlinked cursor_next. */
    r->full_frame = r->frame;
    r->cursor = 0;
    r->cursor_next = r->first;
    return 0;
}

uint64_t oit_residency_bytes(const oit_residency *r)
{
    return r->used;
}

uint32_t oit_residency_parts(const oit_residency *r)
{
    return r->resident;
}

uint64_t oit_residency_capacity(const oit_residency *r)
{
    return r->capacity;
}
