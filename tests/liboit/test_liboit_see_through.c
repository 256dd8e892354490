/* oit_renderer_desc.see_through (oitstream --see-through) through liboit's
 * offscreen API, on the OBJ assembly of tests/corpus/obj (an opaque blue
 * and an opaque green box, MTL d 1 and no d, and a red cover of d 0.3 in
 * front of half the blue one), held in core (DFB) and converted with
 * oitprep (streamed):
 *
 * - without it, the opaque boxes hide what is behind them: their pixels
 *   are the same over a white and over a black background (transmittance
 *   0), the draw says opaque = 1, and their back faces are not stored;
 * - with it, every triangle takes shading.alpha: no pixel is the same over
 *   both backgrounds, the image changes over the boxes, the draw says
 *   see_through = 1 and opaque = 0, and the stored fragments rise by at
 *   least one a pixel the boxes covered (their back faces);
 * - the in-core and the streamed scene store the same fragments;
 * - see_through = 2 is refused, naming the field.
 *
 * usage: test_liboit_see_through OITPREP WORKDIR ASSEMBLY.OBJ */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit/offscreen.h"
#include "tests/lib/test_check.h"

enum { W = 160, H = 120 };

typedef struct frame {
    uint8_t *white, *black; /* the scene over each background */
    oit_draw_stats stats;   /* of the draw over white          */
} frame;

static oit_offscreen *make_offscreen(int see_through)
{
    oit_offscreen_desc d = {.renderer = {.see_through = see_through}};
    oit_offscreen *o = NULL;
    oit_error err = {0};
    oit_status s = oit_offscreen_create(&d, &o, &err);
    CHECK(s == OIT_OK, "oit_offscreen_create (see_through %d): %s", see_through, err.message);
    return o;
}

/* The view of tests/tools/oitstream/test_materials.sh: the cover in front
 * of half the blue box. */
static uint8_t *draw(oit_offscreen *o, oit_scene *scene, const float bg[4],
                     oit_draw_stats *stats, const char *what)
{
    oit_offscreen_view v = {.width = W, .height = H, .format = OIT_PIXELS_RGBA8,
                            .eye = {0, 0, 6}, .up = {0, 1, 0}, .fovy_deg = 45,
                            .znear = 0.5f, .zfar = 20};
    memcpy(v.background, bg, sizeof v.background);
    uint8_t *px = malloc((size_t)W * H * 4);
    oit_error err = {0};
    oit_status s = oit_offscreen_render(o, scene, &v, px, (size_t)W * H * 4, stats, &err);
    CHECK(s == OIT_OK, "%s: %s", what, err.message);
    if (s != OIT_OK) {
        free(px);
        return NULL;
    }
    return px;
}

static frame render(oit_offscreen *o, oit_scene *scene, const char *what)
{
    static const float white[4] = {1, 1, 1, 1}, black[4] = {-1, -1, -1, 1};
    frame f = {0};
    oit_draw_stats ignored;
    f.white = draw(o, scene, white, &f.stats, what);
    f.black = draw(o, scene, black, &ignored, what);
    printf("%s: %llu fragments, see_through %u, opaque %u\n", what,
           (unsigned long long)f.stats.fragments, f.stats.see_through, f.stats.opaque);
    return f;
}

static int same_pixel(const uint8_t *a, const uint8_t *b, size_t p)
{
    return memcmp(a + 4 * p, b + 4 * p, 3) == 0;
}

/* Pixels the same over both backgrounds: nothing shows through them. */
static uint64_t hidden_pixels(const frame *f)
{
    uint64_t n = 0;
    for (size_t p = 0; f->white && f->black && p < (size_t)W * H; p++)
        n += same_pixel(f->white, f->black, p);
    return n;
}

static void check_scene(oit_offscreen *solid, oit_offscreen *see, oit_scene *scene,
                        const char *kind, uint64_t fragments[2])
{
    char what[64];
    snprintf(what, sizeof what, "%s", kind);
    frame a = render(solid, scene, what);
    snprintf(what, sizeof what, "%s see-through", kind);
    frame b = render(see, scene, what);
    if (!a.white || !a.black || !b.white || !b.black)
        goto done;
    uint64_t hidden = hidden_pixels(&a), hidden_see = hidden_pixels(&b), changed = 0;
    for (size_t p = 0; p < (size_t)W * H; p++)
        changed += !same_pixel(a.white, b.white, p);
    printf("%s: %llu pixels hide the background, %llu see-through; %llu pixels change\n", kind,
           (unsigned long long)hidden, (unsigned long long)hidden_see,
           (unsigned long long)changed);
    /* The two boxes cover about a tenth of the frame from there. */
    CHECK(hidden > (uint64_t)W * H / 20, "%s: only %llu opaque pixels: opaque triangles do not "
          "hide what is behind them", kind, (unsigned long long)hidden);
    CHECK(hidden_see == 0, "%s: see_through leaves %llu pixels opaque", kind,
          (unsigned long long)hidden_see);
    CHECK(changed >= hidden, "%s: see_through changes %llu pixels, fewer than the %llu opaque "
          "ones", kind, (unsigned long long)changed, (unsigned long long)hidden);
    CHECK(a.stats.opaque == 1 && a.stats.see_through == 0, "%s: stats opaque %u see_through %u",
          kind, a.stats.opaque, a.stats.see_through);
    CHECK(b.stats.opaque == 0 && b.stats.see_through == 1,
          "%s see-through: stats opaque %u see_through %u", kind, b.stats.opaque,
          b.stats.see_through);
    /* A ray through a box meets a face going in and one going out: the
     * second is stored only when the box is seen through (edge pixels,
     * where the ray meets an edge, aside). */
    CHECK(b.stats.fragments >= a.stats.fragments + hidden * 9 / 10,
          "%s: %llu fragments see-through, %llu without: behind %llu opaque pixels fewer than "
          "one more each", kind, (unsigned long long)b.stats.fragments,
          (unsigned long long)a.stats.fragments, (unsigned long long)hidden);
    fragments[0] = a.stats.fragments;
    fragments[1] = b.stats.fragments;
done:
    free(a.white);
    free(a.black);
    free(b.white);
    free(b.black);
}

static oit_scene *open_scene(const char *path)
{
    oit_scene *s = NULL;
    oit_error err = {0};
    oit_status st = oit_scene_open(path, NULL, &s, &err);
    CHECK(st == OIT_OK, "%s: %s", path, err.message);
    return s;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s OITPREP WORKDIR ASSEMBLY.OBJ\n", argv[0]);
        return 2;
    }
    char part[4096], cmd[13000];
    snprintf(part, sizeof part, "%s/see_through_assembly.oitp", argv[2]);
    snprintf(cmd, sizeof cmd, "'%s' '%s' -o '%s' > '%s.log' 2>&1", argv[1], argv[3], part, part);
    CHECK(system(cmd) == 0, "%s failed", cmd);

    oit_offscreen_desc bad = {.renderer = {.see_through = 2}};
    oit_offscreen *o = NULL;
    oit_error err = {0};
    oit_status s = oit_offscreen_create(&bad, &o, &err);
    CHECK(s == OIT_ERR_ARGUMENT && strstr(err.message, "see_through = 2"),
          "see_through 2: %s: %s", oit_status_name(s), err.message);
    oit_offscreen_destroy(o);

    oit_offscreen *solid = make_offscreen(0), *see = make_offscreen(1);
    if (!solid || !see)
        return test_verdict();
    uint64_t core[2] = {0}, streamed[2] = {0};
    oit_scene *mesh = open_scene(argv[3]);
    if (mesh)
        check_scene(solid, see, mesh, "in core", core);
    oit_scene *pf = open_scene(part);
    if (pf)
        check_scene(solid, see, pf, "part file", streamed);
    CHECK(core[0] == streamed[0] && core[1] == streamed[1],
          "in core and streamed store different fragments: %llu/%llu vs %llu/%llu",
          (unsigned long long)core[0], (unsigned long long)core[1],
          (unsigned long long)streamed[0], (unsigned long long)streamed[1]);
    oit_offscreen_destroy(solid);
    oit_offscreen_destroy(see);
    oit_scene_close(mesh);
    oit_scene_close(pf);
    return test_verdict();
}
