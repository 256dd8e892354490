/* The choice of the K-slot fill (capture_choice.h) with the self-test's
 * verdicts injected, no GL: what auto, stencil and array pick when the
 * self-test passes at K, only at fewer samples, or nowhere; that stencil
 * is refused with the self-test's own reason, never silently replaced;
 * that K-slot packs try K alone; that a failure other than "unsupported"
 * stops the choice; and the names the figures give what was asked. */
#include <stdio.h>
#include <string.h>

#include "view/render/capture/capture_choice.h"
#include "tests/lib/test_check.h"

/* The injected self-test: passes at `from` samples and fewer (0: never),
 * records the counts tried. */
typedef struct fake {
    int from;
    oit_status other; /* returned at every try instead, when not OIT_OK */
    int tried[16], n;
} fake;

static oit_status verdict(void *ctx, int k, oit_error *err)
{
    fake *f = ctx;
    f->tried[f->n++] = k;
    if (f->other != OIT_OK)
        return oit_error_set(err, f->other, "fake: out of memory at %d", k);
    if (f->from && k <= f->from)
        return OIT_OK;
    return oit_error_set(err, OIT_ERR_UNSUPPORTED, "fake self-test failed at K=%d", k);
}

static void tries(const fake *f, const int *want, int n, const char *what)
{
    int ok = f->n == n;
    for (int i = 0; ok && i < n; i++)
        ok = f->tried[i] == want[i];
    CHECK(ok, "%s: tried %d counts (first %d), not %d (first %d)", what, f->n,
          f->n ? f->tried[0] : 0, n, n ? want[0] : 0);
}

int main(void)
{
    oit_capture_choice c;
    oit_error err = {0};

    fake f = {.from = 16};
    oit_status s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 8, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.slots == OIT_RENDER_CAPTURE_STENCIL && c.stencil_k == 8 && !c.reason[0],
          "auto, self-test passing: %s slots at %d, reason '%s'",
          oit_capture_asked_name(c.slots), c.stencil_k, c.reason);
    tries(&f, (const int[]){8}, 1, "auto, passing");

    f = (fake){.from = 0};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 8, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.slots == OIT_RENDER_CAPTURE_ARRAY && c.stencil_k == 0 &&
              strstr(c.reason, "failed at K=8"),
          "auto, self-test failing: %s slots, reason '%s' (not K=8's)",
          oit_capture_asked_name(c.slots), c.reason);
    tries(&f, (const int[]){8, 4, 2}, 3, "auto first-k, failing");

    f = (fake){.from = 8};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 16, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.slots == OIT_RENDER_CAPTURE_STENCIL && c.stencil_k == 8 &&
              strstr(c.reason, "failed at K=16"),
          "auto first-k, passing at 8 of 16: %s at %d, reason '%s'",
          oit_capture_asked_name(c.slots), c.stencil_k, c.reason);
    tries(&f, (const int[]){16, 8}, 2, "auto first-k, passing at 8");

    f = (fake){.from = 4};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 6, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.stencil_k == 4, "auto first-k K=6: %d samples, not 4", c.stencil_k);
    tries(&f, (const int[]){6, 4}, 2, "auto first-k K=6");

    /* K-slot packs: a part of K layers in fewer samples would lose fragments */
    f = (fake){.from = 4};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 8, 0, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.slots == OIT_RENDER_CAPTURE_ARRAY && strstr(c.reason, "failed at K=8"),
          "auto K-slot, passing at 4 of 8: %s slots", oit_capture_asked_name(c.slots));
    tries(&f, (const int[]){8}, 1, "auto K-slot");

    f = (fake){.from = 0};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_STENCIL, "caller.capture", 8, 0, verdict, &f, &c, &err);
    printf("stencil refused: %s\n", err.message);
    /* the driver's limit, not the caller's input (tools: exit 1, not 3) */
    CHECK(s == OIT_ERR_GL && strstr(err.message, "caller.capture = stencil") &&
              strstr(err.message, "fake self-test failed at K=8"),
          "stencil, self-test failing: %s '%s', not the refusal with its reason",
          oit_status_name(s), err.message);

    f = (fake){.from = 2};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_STENCIL, NULL, 4, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.slots == OIT_RENDER_CAPTURE_STENCIL && c.stencil_k == 2,
          "stencil first-k passing at 2 of 4: %s", oit_status_name(s));

    f = (fake){.from = 16};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_ARRAY, NULL, 8, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_OK && c.slots == OIT_RENDER_CAPTURE_ARRAY && f.n == 0 && !c.reason[0],
          "array: %s slots after %d self-tests", oit_capture_asked_name(c.slots), f.n);

    f = (fake){.from = 16, .other = OIT_ERR_NOMEM};
    s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 8, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_ERR_NOMEM && f.n == 1, "auto, self-test out of memory: %s after %d tries",
          oit_status_name(s), f.n);

    s = oit_capture_choose(OIT_RENDER_CAPTURE_COMPUTE, NULL, 8, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_ERR_ARGUMENT, "compute asked as a K-slot fill: %s", oit_status_name(s));
    s = oit_capture_choose(OIT_RENDER_CAPTURE_AUTO, NULL, 17, 1, verdict, &f, &c, &err);
    CHECK(s == OIT_ERR_ARGUMENT, "K=17: %s", oit_status_name(s));

    const char *names[] = {oit_capture_asked_name(OIT_RENDER_CAPTURE_AUTO),
                           oit_capture_asked_name(OIT_RENDER_CAPTURE_ARRAY),
                           oit_capture_asked_name(OIT_RENDER_CAPTURE_STENCIL),
                           oit_capture_asked_name(OIT_RENDER_CAPTURE_COMPUTE)};
    CHECK(names[0] && !strcmp(names[0], "auto") && names[1] && !strcmp(names[1], "array") &&
              names[2] && !strcmp(names[2], "stencil") && names[3] &&
              !strcmp(names[3], "compute") && !oit_capture_asked_name((oit_render_capture)99),
          "the asked captures' names");
    return test_verdict();
}
