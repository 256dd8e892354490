/* CRC-32C (Castagnoli), the part file's checksum (docs/part-file.md).
 *
 * Chosen over CRC-32 because x86-64 (SSE 4.2) and ARMv8 compute it in
 * hardware, so checking a multi-gigabyte file on open costs little. The
 * running value is passed back in, so a writer can checksum a section it
 * streams out piece by piece: crc = oit_crc32c(crc, chunk, n), starting at 0.
 */
#ifndef OIT_PARTFILE_CHECKSUM_H
#define OIT_PARTFILE_CHECKSUM_H

#include <stddef.h>
#include <stdint.h>

uint32_t oit_crc32c(uint32_t crc, const void *data, size_t size);
/* The table-driven path alone, whatever the CPU (tests compare the two). */
uint32_t oit_crc32c_portable(uint32_t crc, const void *data, size_t size);

#endif
