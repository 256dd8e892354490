/* Section planes as a command line gives them (clip.h, oit_clip_given):
 * parsed and checked once before the file is read, then placed at the
 * model's origin. Placing must give the very floats that parsing the text
 * at that origin gives (oit_clip_add_text, the reference's and liboit's
 * path), every refusal must come at parse time and name the setting, and a
 * refused plane must leave what was given before it untouched. No GL. */
#include <string.h>

#include "view/render/image/clip.h"
#include "tests/lib/test_check.h"

static const char *const planes[] = {"1,0,0,-0.5", "0,-2,0.25,3e-3", "1e-3,1e-3,1,-123456.789",
                                     "-0.3,0.7,0.1,0", "0,0,-1,1e6", "0.1,0.2,0.3,0.4"};
enum { N = sizeof planes / sizeof planes[0] };

/* Placed at origin o against parsed at o: the same bits, plane by plane. */
static void same_as_text(const oit_clip_given *g, const double o[3])
{
    oit_clip placed, parsed;
    memset(&parsed, 0, sizeof parsed);
    oit_error err = {0};
    CHECK(oit_clip_place(g, o, "--clip", &placed, &err) == OIT_OK, "place: %s", err.message);
    for (int i = 0; i < g->count; i++)
        CHECK(oit_clip_add_text(&parsed, planes[i], o, "--clip", &err) == OIT_OK, "%s", err.message);
    CHECK(placed.count == g->count && parsed.count == g->count, "%d planes placed, %d parsed",
          placed.count, parsed.count);
    CHECK(!memcmp(placed.plane, parsed.plane, sizeof placed.plane),
          "placed at (%g, %g, %g): not the floats the text gives there", o[0], o[1], o[2]);
}

int main(void)
{
    oit_clip_given g;
    memset(&g, 0, sizeof g);
    oit_error err = {0};
    for (int i = 0; i < N; i++)
        CHECK(oit_clip_given_add_text(&g, planes[i], "--clip", &err) == OIT_OK, "%s: %s", planes[i],
              err.message);
    CHECK(g.count == N, "%d planes kept of %d", g.count, N);
    const double origins[][3] = {{0, 0, 0}, {1e5, -2e5, 3.25}, {-0.1, 0.2, 7e6}};
    for (int i = 0; i < 3; i++)
        same_as_text(&g, origins[i]);
    oit_clip none;
    CHECK(oit_clip_place(&g, NULL, "--clip", &none, &err) == OIT_OK && none.count == N,
          "NULL origin: %s", err.message);

    /* Refusals at parse time, naming the setting; nothing added. */
    oit_clip_given before = g;
    CHECK(oit_clip_given_add_text(&g, "0,0,1,0", "--clip", &err) == OIT_ERR_ARGUMENT,
          "a seventh plane was taken");
    CHECK(strstr(err.message, "--clip") && strstr(err.message, "at most"), "%s", err.message);
    oit_clip_given one;
    memset(&one, 0, sizeof one);
    const char *bad[] = {"0,0,0,1", "1,2,3", "1,2,3,4,5", "a,b,c,d", "1,0,0,inf", NULL};
    for (int i = 0; bad[i]; i++) {
        err.message[0] = 0;
        CHECK(oit_clip_given_add_text(&one, bad[i], "--clip", &err) == OIT_ERR_ARGUMENT,
              "'%s' was taken", bad[i]);
        CHECK(strstr(err.message, "--clip") != NULL, "'%s': the error names no setting: %s", bad[i],
              err.message);
    }
    CHECK(one.count == 0, "refused planes were kept: %d", one.count);
    CHECK(!memcmp(&before, &g, sizeof g), "a refused plane changed the given ones");
    return test_verdict();
}
