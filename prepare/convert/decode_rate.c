/* Part decode throughput (decode_rate.h). */
#include "prepare/convert/decode_rate.h"
#include "base/clock.h"

#include <string.h>

#include "oit/partfile.h"


/* One pass over every part: decode only, or (checked) the first use's
 * decode with every check on a file opened with deferred part data. */
static oit_status one_pass(const char *path, int checked, oit_partfile_buffer *buf, double *s,
                           oit_error *err)
{
    oit_partfile *pf = NULL;
    oit_partfile_open_desc od = {.defer_part_data = checked != 0};
    oit_status st = oit_partfile_open(path, &od, &pf, err);
    if (st)
        return st;
    uint32_t n = oit_partfile_part_count(pf);
    oit_partfile_part_view v;
    double t0 = oit_time_s();
    for (uint32_t p = 0; p < n && !st; p++)
        st = checked ? oit_partfile_part_load(pf, p, buf, &v, err)
                     : oit_partfile_part_data(pf, p, buf, &v, err);
    *s = oit_time_s() - t0;
    oit_partfile_close(pf);
    return st;
}

oit_status oit_measure_decode(const char *path, int passes, oit_decode_rate *out,
                              oit_error *err)
{
    memset(out, 0, sizeof *out);
    oit_partfile *pf = NULL;
    oit_status st = oit_partfile_open(path, NULL, &pf, err);
    if (st)
        return st;
    out->parts = oit_partfile_part_count(pf);
    const oit_partfile_part *parts = oit_partfile_parts(pf);
    for (uint64_t p = 0; p < out->parts; p++) {
        out->stored_bytes += parts[p].stored_bytes;
        out->decoded_bytes += parts[p].data_bytes;
    }
    oit_partfile_close(pf);
    oit_partfile_buffer buf = {0};
    for (int i = 0; i < passes && !st; i++) {
        double a = 0, b = 0;
        st = one_pass(path, 0, &buf, &a, err);
        if (!st)
            st = one_pass(path, 1, &buf, &b, err);
        out->decode_s = i == 0 || a < out->decode_s ? a : out->decode_s;
        out->checked_s = i == 0 || b < out->checked_s ? b : out->checked_s;
    }
    oit_partfile_buffer_free(&buf);
    return st;
}
