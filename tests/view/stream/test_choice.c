/* view/stream/choice.h: the automatic pack mode keeps a path only where this
 * process measured it faster on the view.
 *
 * Scripted frames with made-up times (no GL): a probe measured slower is
 * never kept and is barred for 8, then 16 frames; a probe measured faster
 * is kept; a tie keeps the held path; one noisy frame does not flip a
 * choice; a changed view starts from the last view's path with no figures
 * and a view seen again keeps its own, while a path that lost on one view
 * stays barred on the next; GPU figures count only where every
 * measured path has them, late and out of order, and unknown ones are
 * dropped, and a cost is one frame's own (the larger of its wall and GPU
 * time); the view key sees the camera, the size and the section planes.
 * Each check was seen to fail with the rule broken (a probe kept whatever
 * it measured; views never re-seeded; GPU figures compared one-sided). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "view/stream/choice.h"

static int failures;

#define CHECK(cond, ...)                                                                       \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                               \
            fprintf(stderr, __VA_ARGS__);                                                      \
            fprintf(stderr, "\n");                                                             \
            failures++;                                                                        \
        }                                                                                      \
    } while (0)

#define FK OIT_PATH_FIRSTK
#define CT OIT_PATH_COUNTED
#define NONE OIT_PATHS
#define BOTH (1u << FK | 1u << CT)

/* One frame of view key: its path, then its end after the path's time
 * (ms[path]) with the fixed rule's suggestion. */
static oit_path frame(oit_choice *c, uint64_t key, const double ms[2], oit_path suggest)
{
    oit_path p = oit_choice_begin(c, key);
    oit_choice_end(c, ms[p], suggest);
    return p;
}

/* The path of the next frame of key, begun (and ended at ms). */
static const char *why_next(oit_choice *c, uint64_t key, oit_path *p, double ms)
{
    *p = oit_choice_begin(c, key);
    const char *why = c->why;
    oit_choice_end(c, ms, NONE);
    return why;
}

/* Past the start-up frame (of another view), on view key: a frame whose
 * fixed rule suggests counted, then counted's probe, ended with suggest. */
static void start_probing_counted(oit_choice *c, uint64_t key, const double ms[2],
                                  oit_path suggest)
{
    oit_choice_init(c, BOTH, FK);
    frame(c, 1000, ms, NONE);
    frame(c, key, ms, CT);
    CHECK(frame(c, key, ms, suggest) == CT, "view %llu: counted not probed",
          (unsigned long long)key);
}

static void test_slower_probe_never_kept(void)
{
    oit_choice c;
    oit_choice_init(&c, BOTH, FK);
    const double ms[2] = {100.0, 200.0}; /* counted twice first-k's time */
    CHECK(oit_choice_begin(&c, 1) == FK && !strcmp(c.why, "seed"), "first frame: %s", c.why);
    oit_choice_end(&c, ms[FK], CT); /* the fixed rule: a deep view, try counted */
    oit_path p = oit_choice_begin(&c, 1);
    CHECK(p == CT && !strcmp(c.why, "probe"), "the suggestion is probed: %s %s",
          oit_path_name(p), c.why);
    oit_choice_end(&c, ms[CT], CT);
    int counted = 0, first_probe = -1, second_probe = -1;
    for (int f = 0; f < 40; f++) {
        p = frame(&c, 1, ms, p == FK ? CT : FK);
        if (p == CT) {
            counted++;
            if (first_probe < 0)
                first_probe = f;
            else if (second_probe < 0)
                second_probe = f;
        }
        CHECK(p == FK || c.views[0].held == FK, "frame %d: counted held after measuring slower",
              f);
    }
    /* back, barred 8 frames, probed, barred 16, probed */
    CHECK(first_probe == 8 && second_probe == 8 + 1 + 16 && counted == 2,
          "probes of the slower path at %d and %d (%d in all), want 8, 25 (2)", first_probe,
          second_probe, counted);
    CHECK(fabs(oit_choice_cost(&c, FK) - 100.0) < 1e-9 && fabs(oit_choice_cost(&c, CT) - 200.0) < 1e-9,
          "costs %.1f %.1f", oit_choice_cost(&c, FK), oit_choice_cost(&c, CT));
    char text[96];
    oit_choice_describe(&c, text, sizeof text);
    CHECK(!strcmp(text, "first-k 100.0 ms, counted 200.0 ms"), "described as '%s'", text);
}

static void test_faster_probe_kept(void)
{
    oit_choice c;
    const double ms[2] = {200.0, 120.0};
    start_probing_counted(&c, 7, ms, FK);
    oit_path p;
    const char *why = why_next(&c, 7, &p, ms[CT]);
    CHECK(p == CT && !strcmp(why, "kept: measured faster"), "after a faster probe: %s %s",
          oit_path_name(p), why);
    /* counted frames suggest first-k: barred for 8 frames after losing
     * (the one above and 7 more) */
    int probes = 0;
    for (int f = 0; f < 7; f++)
        probes += frame(&c, 7, ms, FK) == FK;
    CHECK(probes == 0, "first-k probed %d times within its bar", probes);
    CHECK(oit_choice_begin(&c, 7) == FK && !strcmp(c.why, "probe"),
          "first-k not probed after its bar: %s", c.why);
    oit_choice_end(&c, ms[FK], NONE); /* slower again: back */
    /* one noisy counted frame (5x) does not flip it */
    oit_choice_begin(&c, 7);
    oit_choice_end(&c, 600.0, NONE);
    CHECK(oit_choice_begin(&c, 7) == CT, "a noisy frame moved auto off counted");
    oit_choice_end(&c, 120.0, NONE);
}

/* The first frame carries start-up: a path measured only there and
 * beaten is measured again at once, and wins back where it is faster warm. */
static void test_cold_start(void)
{
    oit_choice c;
    oit_choice_init(&c, BOTH, FK);
    oit_choice_begin(&c, 9);
    oit_choice_end(&c, 900.0, CT); /* first-k, cold */
    CHECK(oit_choice_begin(&c, 9) == CT, "the probe");
    oit_choice_end(&c, 300.0, FK); /* counted, kept: 300 < 900 */
    oit_path p = oit_choice_begin(&c, 9);
    CHECK(p == CT && !strcmp(c.why, "kept: measured faster"), "counted kept: %s %s",
          oit_path_name(p), c.why);
    oit_choice_end(&c, 300.0, FK);
    p = oit_choice_begin(&c, 9);
    CHECK(p == FK && !strcmp(c.why, "probe"),
          "first-k, measured only cold, not probed again at once: %s %s", oit_path_name(p),
          c.why);
    oit_choice_end(&c, 200.0, NONE); /* warm first-k: faster */
    p = oit_choice_begin(&c, 9);
    CHECK(p == FK && !strcmp(c.why, "kept: measured faster"), "warm first-k: %s %s",
          oit_path_name(p), c.why);
    oit_choice_end(&c, 200.0, CT);
    /* a path measured on a later frame is barred as usual: counted now */
    CHECK(c.bar[CT] > 0, "counted, beaten warm, not barred");
}

/* A path that lost on one view is barred on the next as well: the views a
 * session moves between are alike, and a probe on each new view would
 * cost a slow frame each. */
static void test_bar_crosses_views(void)
{
    oit_choice c;
    const double ms[2] = {100.0, 250.0};
    start_probing_counted(&c, 1, ms, CT);
    int probes = 0;
    for (uint64_t v = 2; v < 2 + OIT_CHOICE_BAR_FIRST / 2; v++) { /* its 8 frames */
        probes += frame(&c, v, ms, CT) == CT;
        probes += frame(&c, v, ms, CT) == CT;
    }
    CHECK(probes == 0, "counted, slower on view 1, probed %d times on the views after it",
          probes);
    /* the bar runs out on frames of any view */
    CHECK(frame(&c, 99, ms, CT) == FK && frame(&c, 99, ms, CT) == CT,
          "counted not probed again after its bar ran out");
}

static void test_tie_keeps_held(void)
{
    oit_choice c;
    oit_choice_init(&c, BOTH, FK);
    const double ms[2] = {150.0, 150.0};
    frame(&c, 3, ms, CT);
    CHECK(frame(&c, 3, ms, NONE) == CT, "the probe");
    oit_path p;
    const char *why = why_next(&c, 3, &p, ms[FK]);
    CHECK(p == FK && !strcmp(why, "back: measured slower"), "a tie kept the probe: %s %s",
          oit_path_name(p), why);
}

static void test_view_reseeds(void)
{
    oit_choice c;
    oit_choice_init(&c, BOTH, FK);
    const double a[2] = {300.0, 100.0}, b[2] = {50.0, 400.0};
    frame(&c, 1, a, CT);
    frame(&c, 1, a, NONE); /* the probe, kept */
    CHECK(frame(&c, 1, a, NONE) == CT, "view 1 holds counted");
    oit_path p = oit_choice_begin(&c, 2);
    CHECK(p == CT && !strcmp(c.why, "new view") && oit_choice_cost(&c, FK) < 0.0 &&
              oit_choice_cost(&c, CT) < 0.0,
          "a new view: %s %s, costs %.1f %.1f (want counted, none)", oit_path_name(p), c.why,
          oit_choice_cost(&c, FK), oit_choice_cost(&c, CT));
    oit_choice_end(&c, b[CT], FK);
    CHECK(frame(&c, 2, b, NONE) == FK, "view 2 probes first-k");
    CHECK(frame(&c, 2, b, NONE) == FK, "view 2 keeps first-k, measured 8x faster there");
    /* view 1 again: its own figures, counted */
    p = oit_choice_begin(&c, 1);
    CHECK(p == CT && fabs(oit_choice_cost(&c, CT) - 100.0) < 1e-9 &&
              fabs(oit_choice_cost(&c, FK) - 300.0) < 1e-9,
          "view 1 again: %s, costs %.1f %.1f", oit_path_name(p), oit_choice_cost(&c, FK),
          oit_choice_cost(&c, CT));
    oit_choice_end(&c, a[CT], NONE);
    /* more views than remembered: the oldest is forgotten, re-seeded */
    for (uint64_t k = 10; k < 10 + OIT_CHOICE_VIEWS; k++)
        frame(&c, k, a, NONE);
    oit_choice_begin(&c, 1);
    CHECK(!strcmp(c.why, "new view") && oit_choice_cost(&c, CT) < 0.0,
          "view 1 after %d others: %s, counted %.1f", OIT_CHOICE_VIEWS, c.why,
          oit_choice_cost(&c, CT));
    oit_choice_end(&c, 1.0, NONE);
}

static void test_gpu_figures(void)
{
    oit_choice c;
    oit_choice_init(&c, BOTH, FK);
    /* first-k: 100 ms on the host but 300 on the GPU; counted 150 on the
     * host, its GPU figure not in yet */
    oit_choice_begin(&c, 5);
    oit_choice_end(&c, 100.0, CT);
    oit_choice_tag_gpu(&c, 41);
    oit_choice_begin(&c, 5);
    oit_choice_end(&c, 150.0, NONE);
    oit_choice_tag_gpu(&c, 42);
    oit_choice_gpu(&c, 41, 300.0);
    oit_choice_gpu(&c, 99, 1.0); /* an unknown frame: dropped */
    oit_path p = oit_choice_begin(&c, 5);
    CHECK(p == FK && fabs(oit_choice_cost(&c, FK) - 100.0) < 1e-9 &&
              fabs(oit_choice_cost(&c, CT) - 150.0) < 1e-9,
          "missing GPU figure: wall time alone, %s %.1f %.1f", oit_path_name(p),
          oit_choice_cost(&c, FK), oit_choice_cost(&c, CT));
    oit_choice_end(&c, 100.0, NONE);
    oit_choice_tag_gpu(&c, 0); /* no figure will come */
    oit_choice_gpu(&c, 42, 120.0); /* counted's comes in late */
    CHECK(fabs(oit_choice_cost(&c, FK) - 300.0) < 1e-9 &&
              fabs(oit_choice_cost(&c, CT) - 150.0) < 1e-9,
          "with both GPU figures: %.1f %.1f, want 300 150", oit_choice_cost(&c, FK),
          oit_choice_cost(&c, CT));
    p = oit_choice_begin(&c, 5);
    CHECK(p == CT && !strcmp(c.why, "measured faster"),
          "GPU figures make counted cheaper: %s %s", oit_path_name(p), c.why);
    oit_choice_end(&c, 150.0, NONE);
    oit_choice_gpu(&c, 42, 1.0); /* taken already: dropped */
    CHECK(fabs(oit_choice_cost(&c, CT) - 150.0) < 1e-9, "a figure taken twice: %.1f",
          oit_choice_cost(&c, CT));
    /* a cost is some frame's own time: counted again, 140 ms on the host
     * and 145 on the GPU, so 145 (not the 120 GPU ms of a frame that took
     * 150 on the host, nor the 140 host ms of one that took 145 on the GPU) */
    oit_choice_end(&c, 140.0, NONE);
    oit_choice_tag_gpu(&c, 43);
    oit_choice_gpu(&c, 43, 145.0);
    oit_choice_begin(&c, 5);
    CHECK(fabs(oit_choice_cost(&c, CT) - 145.0) < 1e-9, "counted's cost %.1f, want 145",
          oit_choice_cost(&c, CT));
    oit_choice_end(&c, 140.0, NONE);
}

static void test_candidates(void)
{
    oit_choice c;
    oit_choice_init(&c, 1u << FK, FK);
    const double ms[2] = {500.0, 1.0};
    for (int f = 0; f < 20; f++)
        CHECK(frame(&c, 1, ms, CT) == FK, "frame %d: a path that is no candidate", f);
    CHECK(oit_choice_cost(&c, CT) < 0.0, "a cost for a path never drawn");
}

static void test_view_key(void)
{
    oit_view v;
    memset(&v, 0, sizeof v);
    v.camera.eye[2] = 5.0f;
    v.camera.fovy_deg = 45.0f;
    v.width = v.height = 64;
    uint64_t k = oit_view_key(&v);
    oit_view w = v;
    CHECK(oit_view_key(&w) == k, "equal views, different keys");
    w.camera.eye[0] = 1e-3f;
    CHECK(oit_view_key(&w) != k, "a moved eye, the same key");
    w = v;
    w.width = 128;
    CHECK(oit_view_key(&w) != k, "another size, the same key");
    w = v;
    w.clip.count = 1;
    w.clip.plane[0][0] = 1.0f;
    CHECK(oit_view_key(&w) != k, "a section plane, the same key");
    w = v;
    w.model[0] = 2.0f;
    CHECK(oit_view_key(&w) != k, "another model matrix, the same key");
}

int main(void)
{
    test_slower_probe_never_kept();
    test_faster_probe_kept();
    test_cold_start();
    test_bar_crosses_views();
    test_tie_keeps_held();
    test_view_reseeds();
    test_gpu_figures();
    test_candidates();
    test_view_key();
    if (failures)
        fprintf(stderr, "%d failures\n", failures);
    else
        printf("choice: all checks passed\n");
    return failures ? 1 : 0;
}
