/* partfile/share.h: shares of the management tree over real part files.
 * Usage: test_share [multi:]FILE.oitp...   (multi: the file lists a part in
 *        several leaf cells, so a share count that splits them may be refused)
 *
 * For each file and 1, 2, 3, 4, 7 and 16 shares, asserts:
 *   - complete: every part a cell lists is in exactly one share, no other
 *     part is in any; the shares' parts and triangles add up to the file's;
 *   - balanced: for up to 4 shares on files of at least 64 parts, the
 *     largest share holds at most 1.6 times the mean (the tree is cut by
 *     triangles; a cut by cells or parts, or always in half, misses this);
 *   - contiguous and ordered: for 200 random views (eyes outside, on the
 *     bounds and inside, and parallel directions) each share's parts form
 *     ONE run in the view's full part order (oit_order_compute), and
 *     oit_shares_order lists every share once, the non-empty ones in the
 *     order of their runs. */
#include "oit/partfile.h"
#include "partfile/order.h"
#include "partfile/share.h"
#include "tests/lib/test_rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;

static void check(int ok, const char *file, unsigned n, const char *what)
{
    if (!ok) {
        failures++;
        fprintf(stderr, "FAIL: %s, %u shares: %s\n", file, n, what);
    }
}

static void check_complete(const oit_partfile *pf, const oit_shares *s, const char *file,
                           unsigned n)
{
    uint32_t parts = oit_partfile_part_count(pf), listed = 0, in_shares = 0;
    uint64_t triangles = 0, tri_shares = 0;
    const oit_partfile_part *pp = oit_partfile_parts(pf);
    for (uint32_t p = 0; p < parts; p++) {
        uint32_t sh = oit_shares_of_part(s, p);
        check(sh == OIT_SHARE_NONE || sh < n, file, n, "a part's share is out of range");
        if (sh != OIT_SHARE_NONE) {
            listed++;
            triangles += pp[p].index_count / 3;
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        in_shares += oit_shares_parts(s, i);
        tri_shares += oit_shares_triangles(s, i);
    }
    oit_partfile_summary sum = {0};
    oit_partfile_get_summary(pf, &sum);
    check(listed == parts, file, n, "a part is in no share");
    check(in_shares == listed, file, n, "share part counts do not add up to the parts");
    check(tri_shares == triangles && triangles == sum.triangles, file, n,
          "share triangles do not add up to the file's");
}

static void check_balance(const oit_partfile *pf, const oit_shares *s, const char *file,
                          unsigned n)
{
    uint64_t most = 0, total = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint64_t t = oit_shares_triangles(s, i);
        total += t;
        most = t > most ? t : most;
    }
    double ratio = total ? (double)most * n / (double)total : 1.0;
    printf("%s: %u shares: largest %.3f x the mean\n", file, n, ratio);
    if (n <= 4 && oit_partfile_part_count(pf) >= 64)
        check(ratio <= 1.6, file, n, "shares are not balanced by triangles");
}

static float unit(rng *r)
{
    return (float)rnd(r, 1u << 24) / (float)(1u << 24);
}

/* One view: runs of shares in the order, and oit_shares_order against them. */
static void check_view(oit_order *o, oit_shares *s, const oit_partfile *pf, const float v[3],
                       int parallel, uint32_t *parts, uint32_t *got, uint32_t *runs,
                       uint8_t *seen, const char *file, unsigned n)
{
    uint32_t count = 0;
    oit_error err = {0};
    oit_status st = parallel ? oit_order_compute_parallel(o, v, NULL, parts, &count, &err)
                             : oit_order_compute(o, v, parts, &count, &err);
    check(st == OIT_OK, file, n, "the order failed");
    memset(seen, 0, n);
    uint32_t nruns = 0, prev = OIT_SHARE_NONE;
    int split = 0;
    for (uint32_t i = 0; i < count; i++) {
        uint32_t sh = oit_shares_of_part(s, parts[i]);
        if (sh == prev)
            continue;
        if (seen[sh])
            split = 1;
        seen[sh] = 1;
        runs[nruns++] = sh;
        prev = sh;
    }
    check(!split, file, n, "a share's parts are not one run in a view's order");
    oit_shares_order(s, parts, count, got);
    memset(seen, 0, n);
    int perm = 1, same = 1;
    for (uint32_t i = 0; i < n; i++) {
        perm &= got[i] < n && !seen[got[i]];
        if (got[i] < n)
            seen[got[i]] = 1;
        if (!split && i < nruns)
            same &= got[i] == runs[i];
    }
    check(perm, file, n, "oit_shares_order is not a permutation of the shares");
    check(same, file, n, "oit_shares_order differs from the order of the runs");
    (void)pf;
}

static void check_views(const oit_partfile *pf, oit_shares *s, const char *file, unsigned n)
{
    oit_error err = {0};
    oit_order *o = NULL;
    if (oit_order_create(pf, &o, &err) != OIT_OK) {
        check(0, file, n, err.message);
        return;
    }
    uint32_t parts = oit_partfile_part_count(pf);
    uint32_t *buf = calloc(parts + 1, sizeof *buf), *got = calloc(n, sizeof *got),
             *runs = calloc(parts + 1, sizeof *runs);
    uint8_t *seen = calloc(n, 1);
    oit_partfile_summary sum = {0};
    oit_partfile_get_summary(pf, &sum);
    rng r = {0x5eedu + n};
    for (int i = 0; i < 200 && buf && got && runs && seen; i++) {
        float v[3], c[3], h[3];
        for (int k = 0; k < 3; k++) {
            c[k] = 0.5f * (sum.bounds_min[k] + sum.bounds_max[k]);
            h[k] = 0.5f * (sum.bounds_max[k] - sum.bounds_min[k]);
        }
        /* Eyes from inside the bounds to three times out; every 4th view
         * parallel. */
        float reach = 3.0f * unit(&r);
        for (int k = 0; k < 3; k++)
            v[k] = c[k] + (2.0f * unit(&r) - 1.0f) * h[k] * reach;
        int parallel = i % 4 == 3;
        if (parallel)
            for (int k = 0; k < 3; k++)
                v[k] = 2.0f * unit(&r) - 1.0f;
        check_view(o, s, pf, v, parallel, buf, got, runs, seen, file, n);
    }
    free(buf);
    free(got);
    free(runs);
    free(seen);
    oit_order_destroy(o);
}

int main(int argc, char **argv)
{
    static const unsigned counts[] = {1, 2, 3, 4, 7, 16};
    for (int f = 1; f < argc; f++) {
        /* multi:FILE lists a part in several leaf cells */
        int multi = strncmp(argv[f], "multi:", 6) == 0;
        const char *name = argv[f] + (multi ? 6 : 0);
        oit_error err = {0};
        oit_partfile *pf = NULL;
        oit_partfile_open_desc d = {1};
        if (oit_partfile_open(name, &d, &pf, &err) != OIT_OK) {
            fprintf(stderr, "FAIL: %s\n", err.message);
            return 1;
        }
        for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
            oit_shares *s = NULL;
            oit_status st = oit_shares_create(pf, counts[i], &s, &err);
            if (st != OIT_OK) {
                /* A file that lists a part in several leaf cells (the
                 * corpus's hand-made one) may be refused, by name. */
                check(multi && st == OIT_ERR_FORMAT && strstr(err.message, "two shares"),
                      name, counts[i], err.message);
                continue;
            }
            check_complete(pf, s, name, counts[i]);
            check_balance(pf, s, name, counts[i]);
            check_views(pf, s, name, counts[i]);
            oit_shares_destroy(s);
        }
        oit_shares *s = NULL;
        check(oit_shares_create(pf, 0, &s, &err) == OIT_ERR_ARGUMENT && !s, name, 0,
              "0 shares accepted");
        check(oit_shares_create(pf, OIT_SHARES_MAX + 1, &s, &err) == OIT_ERR_ARGUMENT && !s,
              name, OIT_SHARES_MAX + 1, "too many shares accepted");
        oit_partfile_close(pf);
    }
    if (failures)
        fprintf(stderr, "share: %d failure(s)\n", failures);
    else
        printf("share: ok\n");
    return failures ? 1 : 0;
}
