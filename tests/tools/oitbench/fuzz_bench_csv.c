/* libFuzzer target: arbitrary bytes through the results.csv reader that
 * `oitbench plot` runs on files it did not write itself (via fmemopen).
 * Errors are fine; crashes, leaks, reads past a field and sanitizer reports
 * are not. A table that reads must hold what the contract promises. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tools/oitbench/bench_csv.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    FILE *f = fmemopen((void *)data, size, "rb");
    if (!f)
        return 0;
    oit_bench_table t;
    oit_error err;
    if (oit_bench_csv_read(f, "fuzz.csv", &t, &err) == OIT_OK) {
        for (size_t i = 0; i < t.count; i++) {
            const oit_bench_row *r = &t.rows[i];
            /* an ok row has every figure; the reader promised it */
            if (r->ok && (!isfinite(r->ms_median) || !isfinite(r->rmse) || !r->has_gpu))
                abort();
            if (strlen(r->method) == 0 || (r->summary != (r->view < 0)))
                abort();
        }
        oit_bench_table_free(&t);
    } else if (strncmp(err.message, "fuzz.csv: ", 10) != 0) {
        abort(); /* every message names the file */
    }
    fclose(f);
    return 0;
}
