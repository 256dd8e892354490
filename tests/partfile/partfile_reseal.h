/* Test helper: recomputes a part file's checksums after a deliberate edit, so
 * that only the reader's semantic checks stand between the edit and use. */
#ifndef OIT_TESTS_PARTFILE_RESEAL_H
#define OIT_TESTS_PARTFILE_RESEAL_H

#include "partfile/checksum.h"
#include "partfile/layout.h"

#include <string.h>

/* Part i's checksum of its stored streams, in its PARTS record. */
static inline void reseal_part(uint8_t *buf, size_t size, uint32_t i)
{
    pf_section parts;
    memcpy(&parts, buf + PF_HEADER_BYTES + (PF_SEC_PARTS - 1) * PF_ENTRY_BYTES, sizeof parts);
    oit_partfile_part p;
    uint64_t at = parts.offset + (uint64_t)i * sizeof p;
    if (at + sizeof p > size)
        return;
    memcpy(&p, buf + at, sizeof p);
    if (p.data_offset > size || p.stored_bytes > size - p.data_offset)
        return;
    p.data_crc = oit_crc32c(0, buf + p.data_offset, p.stored_bytes);
    memcpy(buf + at, &p, sizeof p);
}

/* Every section checksum whose range lies in the buffer, then the table's. */
static inline void reseal(uint8_t *buf, size_t size)
{
    if (size < PF_TABLE_END)
        return;
    for (uint32_t t = 0; t < PF_SECTION_COUNT; t++) {
        pf_section s;
        uint8_t *e = buf + PF_HEADER_BYTES + t * PF_ENTRY_BYTES;
        memcpy(&s, e, sizeof s);
        if (s.offset > size || s.size > size - s.offset)
            continue;
        s.crc = oit_crc32c(0, buf + s.offset, s.size);
        memcpy(e, &s, sizeof s);
    }
    uint32_t crc = oit_crc32c(oit_crc32c(0, buf, offsetof(pf_header, table_crc)),
                              buf + PF_HEADER_BYTES, PF_SECTION_COUNT * PF_ENTRY_BYTES);
    memcpy(buf + offsetof(pf_header, table_crc), &crc, sizeof crc);
}

#endif
