/* Random driver answers fed to what decides the stencil-routed capture,
 * each against a model written here from the headers' words (no GL;
 * seeded, so a failure reproduces):
 *  - oit_stencil_pick_samples on random sample-count tables of the colour
 *    and depth-stencil formats with random NV sample-query modes: it may
 *    only accept when the count GL allocates for K (the smallest supported
 *    count >= K, of both) is one count of both and true multisamples
 *    (multisamples = samples, no supersampling, conformant), and must then
 *    accept with that count;
 *  - oit_capture_choose with a self-test that passes at a random set of
 *    sample counts (not only "K and below") or fails otherwise: the counts
 *    tried (K, then with fewer_ok each power of two below K down to 2, in
 *    that order), and STENCIL only at the first that passes, at K itself
 *    for K-slot packs;
 *  - oit_capture_create's arguments over every fill, cut, K and
 *    stencil_k: a fill or cut out of its enum, a stencil fill of counted
 *    batches, samples routed exactly by anything but a stencil fill, or
 *    other than 2..K for first-K and K for K-slot batches: refused
 *    before any GL;
 *  - oit_stencil_probe_verdict on the probe's true fill (samples in any
 *    order, garbage past the covering ones) and on that fill with one
 *    random fault: a count off, a fragment lost, a sample holding a
 *    triangle that misses the centre, a triangle twice. */
#include <stdio.h>
#include <string.h>

#include "view/render/capture/capture.h"
#include "view/render/capture/capture_choice.h"
#include "view/render/capture/capture_stencil_probe.h"
#include "tests/lib/test_check.h"

static uint32_t rnd(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* ---- the sample mode ---- */

static void random_modes(oit_sample_modes *m, const char *what, uint32_t *seed)
{
    static const int counts[] = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32};
    memset(m, 0, sizeof *m);
    m->what = what;
    for (int i = 0; i < 10 && m->n < OIT_SAMPLE_MODES_MAX; i++) {
        if (rnd(seed) % 3 == 0)
            continue;
        oit_sample_mode *o = &m->mode[m->n++];
        o->samples = counts[i];
        o->multisamples = o->samples;
        o->scale_x = o->scale_y = 1;
        o->conformant = 1;
        switch (rnd(seed) % 6) {
        case 0: /* 8 x 2 style: half multisampled, supersampled in x */
            if (o->samples % 2 == 0) {
                o->multisamples = o->samples / 2;
                o->scale_x = 2;
            }
            break;
        case 1:
            o->conformant = 0;
            break;
        case 2: /* a driver's inconsistent answer: fewer multisamples, no scale */
            o->multisamples = o->samples > 1 ? o->samples - 1 : 1;
            break;
        default:
            break;
        }
    }
    for (int i = m->n - 1; i > 0; i--) { /* "in any order" */
        int j = (int)(rnd(seed) % (uint32_t)(i + 1));
        oit_sample_mode t = m->mode[i];
        m->mode[i] = m->mode[j];
        m->mode[j] = t;
    }
}

/* The count GL allocates for K, or NULL. */
static const oit_sample_mode *model_alloc(const oit_sample_modes *m, int K)
{
    const oit_sample_mode *b = NULL;
    for (int i = 0; i < m->n; i++)
        if (m->mode[i].samples >= K && (!b || m->mode[i].samples < b->samples))
            b = &m->mode[i];
    return b;
}

static int model_true(const oit_sample_mode *m)
{
    return m->multisamples == m->samples && m->scale_x == 1 && m->scale_y == 1 && m->conformant;
}

static void check_pick(void)
{
    uint32_t seed = 0x51ed270bu;
    int accepted = 0, refused = 0;
    for (int c = 0; c < 4000; c++) {
        oit_sample_modes col, ds;
        random_modes(&col, "colour", &seed);
        random_modes(&ds, "depth-stencil", &seed);
        int K = 2 + (int)(rnd(&seed) % 15);
        const oit_sample_mode *a = model_alloc(&col, K), *b = model_alloc(&ds, K);
        int want = a && b && a->samples == b->samples && model_true(a) && model_true(b);
        int got_samples = -1;
        oit_error err = {0};
        oit_status s = oit_stencil_pick_samples(K, &col, &ds, &got_samples, &err);
        if (s == OIT_OK)
            accepted++;
        else
            refused++;
        CHECK((s == OIT_OK) == want && (s == OIT_OK || s == OIT_ERR_UNSUPPORTED),
              "case %d K=%d: %s, the model %s (allocated %d/%d samples)", c, K,
              s == OIT_OK ? "accepted" : err.message, want ? "accepts" : "refuses",
              a ? a->samples : 0, b ? b->samples : 0);
        CHECK(s != OIT_OK || !want || got_samples == a->samples,
              "case %d K=%d: %d samples, GL allocates %d", c, K, got_samples, a->samples);
        CHECK(s != OIT_OK || got_samples >= K, "case %d: %d samples for K=%d", c, got_samples,
              K);
        if (s != OIT_OK && c < 1)
            printf("e.g. %s\n", err.message);
    }
    printf("sample modes: %d accepted, %d refused\n", accepted, refused);
    CHECK(accepted > 200 && refused > 200, "the cases do not reach both verdicts");
}

/* ---- the choice ---- */

typedef struct fake {
    uint32_t pass;     /* bit k: the self-test passes at k samples */
    oit_status other;  /* returned at try number fail_at instead, when not OK */
    int fail_at;
    int tried[32], n;
} fake;

static oit_status verdict(void *ctx, int k, oit_error *err)
{
    fake *f = ctx;
    int i = f->n++;
    if (i < 32)
        f->tried[i] = k;
    if (f->other != OIT_OK && i == f->fail_at)
        return oit_error_set(err, f->other, "fake: out of memory at %d", k);
    if (k >= 0 && k < 32 && (f->pass >> k & 1u))
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_UNSUPPORTED, "fake self-test failed at K=%d", k);
}

static void check_choose(void)
{
    uint32_t seed = 0x0badc0deu;
    int stencil = 0, array = 0, errors = 0;
    for (int c = 0; c < 4000; c++) {
        int K = 2 + (int)(rnd(&seed) % 15);
        int fewer_ok = (int)(rnd(&seed) % 2);
        oit_render_capture asked =
            (oit_render_capture[]){OIT_RENDER_CAPTURE_AUTO, OIT_RENDER_CAPTURE_STENCIL,
                                   OIT_RENDER_CAPTURE_ARRAY}[rnd(&seed) % 3];
        fake f = {.pass = rnd(&seed) & rnd(&seed) & 0x1fffcu};
        if (rnd(&seed) % 8 == 0) {
            f.other = OIT_ERR_NOMEM;
            f.fail_at = (int)(rnd(&seed) % 3);
        }
        /* the model: the tries in order, the first passing one taken */
        int tries[8], nt = 0;
        for (int k = K; asked != OIT_RENDER_CAPTURE_ARRAY && k >= 2;) {
            tries[nt++] = k;
            if (!fewer_ok)
                break;
            int p = 1;
            while (p * 2 < k)
                p *= 2;
            k = p >= 2 ? p : 0;
        }
        int want_k = 0, want_n = 0;
        oit_status want = OIT_OK;
        for (int i = 0; i < nt; i++) {
            want_n = i + 1;
            if (f.other != OIT_OK && i == f.fail_at) {
                want = f.other;
                break;
            }
            if (f.pass >> tries[i] & 1u) {
                want_k = tries[i];
                break;
            }
        }
        if (want == OIT_OK && !want_k && asked == OIT_RENDER_CAPTURE_STENCIL)
            want = OIT_ERR_GL; /* the driver's limit */
        oit_capture_choice ch;
        oit_error err = {0};
        oit_status s = oit_capture_choose(asked, NULL, K, fewer_ok, verdict, &f, &ch, &err);
        int same_tries = f.n == want_n;
        for (int i = 0; same_tries && i < nt && i < f.n; i++)
            same_tries = f.tried[i] == tries[i];
        CHECK(s == want, "case %d (asked %d, K=%d, fewer_ok %d, passes 0x%x): %s, expected %s",
              c, (int)asked, K, fewer_ok, f.pass, oit_status_name(s), oit_status_name(want));
        CHECK(same_tries, "case %d (K=%d, fewer_ok %d): tried %d counts (first %d), the model %d "
              "(first %d)", c, K, fewer_ok, f.n, f.n ? f.tried[0] : 0, want_n,
              nt ? tries[0] : 0);
        if (s != OIT_OK || want != OIT_OK) {
            errors++;
            continue;
        }
        CHECK(ch.slots == (want_k ? OIT_RENDER_CAPTURE_STENCIL : OIT_RENDER_CAPTURE_ARRAY) &&
                  ch.stencil_k == want_k,
              "case %d (asked %d, K=%d, fewer_ok %d, passes 0x%x): %s at %d samples, the model "
              "%d", c, (int)asked, K, fewer_ok, f.pass,
              ch.slots == OIT_RENDER_CAPTURE_STENCIL ? "stencil" : "array", ch.stencil_k, want_k);
        CHECK(ch.slots != OIT_RENDER_CAPTURE_STENCIL || (ch.stencil_k >= 2 && ch.stencil_k <= K &&
                                                  (fewer_ok || ch.stencil_k == K)),
              "case %d: routed %d samples at K=%d (fewer_ok %d)", c, ch.stencil_k, K, fewer_ok);
        CHECK((ch.reason[0] != 0) == (want_k != K && nt > 0), "case %d: reason '%s' at K=%d, "
              "stencil %d", c, ch.reason, K, want_k);
        if (ch.slots == OIT_RENDER_CAPTURE_STENCIL)
            stencil++;
        else
            array++;
    }
    printf("choices: %d stencil, %d array, %d errors\n", stencil, array, errors);
    CHECK(stencil > 200 && array > 200 && errors > 200, "the cases do not reach every outcome");
}

/* ---- the routed capture's arguments ---- */

static void check_routed_args(void)
{
    int valid = 0;
    for (int fill = -1; fill <= 6; fill++)
        for (int cut = -1; cut <= 5; cut++)
            for (int K = -1; K <= 18; K++)
                for (int sk = -1; sk <= 18; sk++) {
                    /* the model of capture.h's table, written here */
                    int fill_ok = fill == 0 || fill == 1 || fill == 2 || fill == 5;
                    int cut_ok = cut >= 0 && cut <= 4;
                    int firstk = cut == OIT_RENDER_PACK_FIRSTK || cut == OIT_RENDER_PACK_AUTO;
                    int routed_ok = sk == 0 || (fill == OIT_RENDER_CAPTURE_STENCIL && sk >= 2 &&
                                                sk <= K && (firstk || sk == K));
                    int ok = K >= 2 && K <= 16 && fill_ok && cut_ok && routed_ok &&
                             !(fill == OIT_RENDER_CAPTURE_STENCIL &&
                               cut == OIT_RENDER_PACK_COUNTED);
                    if (ok) { /* would build GL objects: test_capture_routed's */
                        valid++;
                        continue;
                    }
                    oit_capture *c = (oit_capture *)&valid;
                    oit_error err = {0};
                    oit_capture_desc d = {.fill = (oit_render_capture)fill,
                                          .cut = (oit_render_pack)cut, .K = K, .stencil_k = sk};
                    oit_status s = oit_capture_create(&d, &c, &err);
                    CHECK(s == OIT_ERR_ARGUMENT && c == NULL,
                          "fill %d, cut %d at K=%d with %d samples: %s, expected refused", fill,
                          cut, K, sk, oit_status_name(s));
                }
    printf("capture arguments: %d valid combinations left to test_capture_routed\n", valid);
    /* K 2..16 (15 values), 0 samples: 4 fills x 5 cuts less stencil x
     * counted; stencil routed exactly: first-K's two cuts 2..K samples
     * (120 a cut), the two K-slot cuts (budget, disjoint) K samples */
    int want = 15 * (4 * 5 - 1) + 2 * 120 + 2 * 15;
    CHECK(valid == want, "%d valid combinations, the model says %d", valid, want);
}

/* ---- the probe's verdict ---- */

static int popcount(uint32_t m)
{
    int n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

static void check_probe(void)
{
    uint32_t seed = 0x7a11feedu;
    int faults[4] = {0};
    for (int c = 0; c < 1500; c++) {
        int K = 2 + (int)(rnd(&seed) % 15);
        static oit_stencil_probe p;
        oit_stencil_probe_build(&p, K);
        int px_n = p.width * p.height;
        uint32_t counts[OIT_PROBE_MAX_COLS * OIT_PROBE_ROWS];
        static uint32_t prims[OIT_PROBE_MAX_COLS * OIT_PROBE_ROWS * 16];
        for (int px = 0; px < px_n; px++) {
            uint32_t cov = p.cover[px];
            int n = 0;
            for (int q = 0; q < K; q++)
                if (cov >> q & 1u)
                    prims[px * K + n++] = (uint32_t)q;
            for (int i = n - 1; i > 0; i--) { /* routing order is the driver's */
                int j = (int)(rnd(&seed) % (uint32_t)(i + 1));
                uint32_t t = prims[px * K + i];
                prims[px * K + i] = prims[px * K + j];
                prims[px * K + j] = t;
            }
            for (int i = n; i < K; i++) /* past the covering ones: not read */
                prims[px * K + i] = rnd(&seed) % 2 ? OIT_STENCIL_UNWRITTEN : rnd(&seed) % 40;
            counts[px] = (uint32_t)n;
        }
        oit_error err = {0};
        oit_status s = oit_stencil_probe_verdict(&p, prims, counts, &err);
        CHECK(s == OIT_OK, "case %d K=%d: the true fill refused: %s", c, K, err.message);
        /* one fault at a random pixel with a covering triangle */
        int px;
        do
            px = (int)(rnd(&seed) % (uint32_t)px_n);
        while (p.cover[px] == 0);
        int n = popcount(p.cover[px]), f = (int)(rnd(&seed) % 4);
        uint32_t *slot = &prims[px * K + (int)(rnd(&seed) % (uint32_t)n)];
        uint32_t missing = 0;
        for (int q = 0; q < K; q++)
            if (!(p.cover[px] >> q & 1u))
                missing = (uint32_t)q + 1;
        if (f == 2 && !missing)
            f = 0;
        if (f == 3 && n < 2)
            f = 1;
        switch (f) {
        case 0: counts[px] += rnd(&seed) % 2 ? 1u : (uint32_t)-1; break;
        case 1: *slot = OIT_STENCIL_UNWRITTEN; break;
        case 2: *slot = missing - 1; break;
        default: /* another covering triangle of px, now twice */
            *slot = prims[px * K + (slot == &prims[px * K] ? 1 : 0)];
            break;
        }
        faults[f]++;
        s = oit_stencil_probe_verdict(&p, prims, counts, &err);
        CHECK(s == OIT_ERR_UNSUPPORTED, "case %d K=%d: fault %d at pixel %d accepted", c, K, f,
              px);
    }
    printf("probe faults: %d counts, %d lost, %d not covering, %d twice\n", faults[0], faults[1],
           faults[2], faults[3]);
}

int main(void)
{
    check_pick();
    check_choose();
    check_routed_args();
    check_probe();
    return test_verdict();
}
