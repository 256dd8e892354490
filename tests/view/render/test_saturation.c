/* The saturation tiles (view/render/capture/saturation.h) on state buffers written here,
 * against a CPU model of the grid: a tile holds the largest transmittance
 * (over its pixels and channels) of the state when a batch touching it was
 * last updated, 1 when none was, and a rect is covered at epsilon when
 * every tile it touches holds less than epsilon.
 *  - every invocation index of the reduction (a tile's only see-through
 *    pixel handled by invocation k, for each k in 0..255, with values that
 *    fall from tile to tile so a maximum carried over from another
 *    workgroup shows), each tile's value pinned exactly: covered at its
 *    next float up, not at the value itself;
 *  - a frame whose top and bottom halves differ (GL rows run bottom up, the
 *    rects top down), queried at rects that start neither at row 0 nor at
 *    column 0;
 *  - random frame sizes (not multiples of 16), both state layouts, random
 *    update rects that grow and move while the state only falls, each
 *    followed by a wait; every tile value and random query rects checked;
 *  - without waiting, a read-back late by any number of batches is still a
 *    safe bound: nothing reported covered that the model does not cover;
 *  - a new frame forgets the last: tiles it never updated are not covered.
 * A wrong tile is a wrongly skipped part (a missing image region) or one
 * drawn for nothing; the images of the streamer tests cannot tell which
 * tile a rect maps to when both halves saturate alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/gl/frag_glsl.h"
#include "view/render/capture/saturation.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_gl.h"

enum { TS = OIT_SATURATION_TILE };

typedef struct frame {
    int w, h, tx, ty, translucent;
    float *T;      /* w*h*3, GL rows bottom first */
    float *tile;   /* the model's grid, tx*ty */
    unsigned buf;  /* the state buffer */
} frame;

static uint32_t rng(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static int frame_init(frame *f, int w, int h, int translucent)
{
    memset(f, 0, sizeof *f);
    f->w = w, f->h = h, f->translucent = translucent;
    f->tx = (w + TS - 1) / TS, f->ty = (h + TS - 1) / TS;
    f->T = calloc((size_t)w * h * 3, sizeof *f->T);
    f->tile = malloc((size_t)f->tx * f->ty * sizeof *f->tile);
    glCreateBuffers(1, &f->buf);
    glNamedBufferData(f->buf, (GLsizeiptr)((size_t)w * h * oit_state_bytes(translucent)), NULL,
                      GL_DYNAMIC_DRAW);
    for (int i = 0; f->tile && i < f->tx * f->ty; i++)
        f->tile[i] = 1.0f;
    return f->T && f->tile;
}

static void frame_free(frame *f)
{
    glDeleteBuffers(1, &f->buf);
    free(f->T);
    free(f->tile);
}

static float *px(frame *f, int x, int gy)
{
    return &f->T[3 * ((size_t)gy * f->w + x)];
}

/* Writes the state buffer as the capture packs it (frag_glsl.h): T's bits
 * XOR those of 1.0; the transparent layout carries one T (channel 0). */
static void frame_upload(frame *f)
{
    unsigned words = oit_state_bytes(f->translucent) / 4, at = f->translucent ? 4 : 3;
    size_t n = (size_t)f->w * f->h;
    uint32_t *s = calloc(n * words, 4);
    if (!s) {
        CHECK(0, "out of memory");
        return;
    }
    for (size_t p = 0; p < n; p++)
        for (unsigned c = 0; c < (f->translucent ? 3u : 1u); c++) {
            uint32_t b;
            memcpy(&b, &f->T[3 * p + c], 4);
            s[p * words + at + c] = b ^ 0x3f800000u;
        }
    glNamedBufferSubData(f->buf, 0, (GLsizeiptr)(n * words * 4), s);
    free(s);
}

/* rect (top rows first, exclusive ends) clamped, in GL rows; 0 if empty. */
static int gl_box(const frame *f, const int *rect, int g[4])
{
    int r[4] = {0, 0, f->w, f->h};
    if (rect)
        memcpy(r, rect, sizeof r);
    g[0] = r[0] < 0 ? 0 : r[0];
    g[2] = r[2] > f->w ? f->w : r[2];
    g[1] = f->h - r[3] < 0 ? 0 : f->h - r[3];
    g[3] = f->h - r[1] > f->h ? f->h : f->h - r[1];
    return g[2] > g[0] && g[3] > g[1];
}

/* The model of oit_saturation_update: each tile rect touches takes the
 * largest T of its pixels now. */
static void model_update(frame *f, const int *rect)
{
    int g[4];
    if (!gl_box(f, rect, g))
        return;
    for (int ty = g[1] / TS; ty <= (g[3] - 1) / TS; ty++)
        for (int tx = g[0] / TS; tx <= (g[2] - 1) / TS; tx++) {
            float m = 0.0f;
            for (int y = ty * TS; y < (ty + 1) * TS && y < f->h; y++)
                for (int x = tx * TS; x < (tx + 1) * TS && x < f->w; x++)
                    for (int c = 0; c < (f->translucent ? 3 : 1); c++)
                        m = fmaxf(m, px(f, x, y)[c]);
            f->tile[ty * f->tx + tx] = m;
        }
}

static int model_covered(const frame *f, const int *rect, float eps)
{
    int g[4];
    if (!(eps > 0.0f) || !gl_box(f, rect, g))
        return 0;
    for (int ty = g[1] / TS; ty <= (g[3] - 1) / TS; ty++)
        for (int tx = g[0] / TS; tx <= (g[2] - 1) / TS; tx++)
            if (!(f->tile[ty * f->tx + tx] < eps))
                return 0;
    return 1;
}

static int update(oit_saturation *s, frame *f, const int *rect, int wait, const char *what)
{
    oit_error err = {0};
    /* a read-back still in flight would keep this batch's from starting */
    oit_status st = wait ? oit_saturation_wait(s, NULL, &err) : OIT_OK;
    if (st == OIT_OK)
        st = oit_saturation_update(s, f->buf, rect, &err);
    if (st == OIT_OK && wait)
        st = oit_saturation_wait(s, NULL, &err);
    CHECK(st == OIT_OK, "%s: %s", what, err.message);
    if (st == OIT_OK)
        model_update(f, rect);
    return st == OIT_OK;
}

/* The top-down rect of tile (tx, ty), clamped to the frame. */
static void tile_rect(const frame *f, int tx, int ty, int r[4])
{
    int gy1 = (ty + 1) * TS < f->h ? (ty + 1) * TS : f->h;
    r[0] = tx * TS;
    r[2] = (tx + 1) * TS < f->w ? (tx + 1) * TS : f->w;
    r[1] = f->h - gy1;
    r[3] = f->h - ty * TS;
}

/* Every tile's value, exactly: a rect inside it is covered just above the
 * model's value and not at it; returns the tiles that differ. */
static int check_tiles(oit_saturation *s, const frame *f, uint32_t *seed, const char *what)
{
    int bad = 0;
    for (int ty = 0; ty < f->ty; ty++)
        for (int tx = 0; tx < f->tx; tx++) {
            int t[4], r[4];
            tile_rect(f, tx, ty, t);
            /* a random non-empty rect inside the tile */
            r[0] = t[0] + (int)(rng(seed) % (uint32_t)(t[2] - t[0]));
            r[1] = t[1] + (int)(rng(seed) % (uint32_t)(t[3] - t[1]));
            r[2] = r[0] + 1 + (int)(rng(seed) % (uint32_t)(t[2] - r[0]));
            r[3] = r[1] + 1 + (int)(rng(seed) % (uint32_t)(t[3] - r[1]));
            float v = f->tile[ty * f->tx + tx];
            float above = nextafterf(v, 2.0f);
            int at = oit_saturation_covered(s, r, v), up = oit_saturation_covered(s, r, above);
            if (at != model_covered(f, r, v) || up != model_covered(f, r, above)) {
                if (bad++ < 4)
                    CHECK(0, "%s: tile (%d, %d) of %dx%d (rows from the bottom), rect %d,%d-%d,%d: covered "
                          "at %.9g: %d, just above: %d; the model holds %.9g", what, tx, ty,
                          f->w, f->h, r[0], r[1], r[2], r[3], (double)v, at, up, (double)v);
                else
                    test_failures++;
            }
        }
    return bad;
}

/* Random rects (some past the frame's edges) at random thresholds near the
 * tiles' values, against the model. */
static void check_rects(oit_saturation *s, const frame *f, uint32_t *seed, int n,
                        const char *what)
{
    int bad = 0;
    for (int i = 0; i < n; i++) {
        int r[4];
        r[0] = (int)(rng(seed) % (uint32_t)(f->w + 8)) - 4;
        r[1] = (int)(rng(seed) % (uint32_t)(f->h + 8)) - 4;
        r[2] = r[0] + 1 + (int)(rng(seed) % 40u);
        r[3] = r[1] + 1 + (int)(rng(seed) % 40u);
        float v = f->tile[rng(seed) % (uint32_t)(f->tx * f->ty)];
        float eps = rng(seed) % 2 ? nextafterf(v, 2.0f) : v;
        int got = oit_saturation_covered(s, r, eps), want = model_covered(f, r, eps);
        if (got != want && bad++ < 4)
            CHECK(0, "%s: rect %d,%d-%d,%d of %dx%d at %.9g: covered %d, the model says %d",
                  what, r[0], r[1], r[2], r[3], f->w, f->h, (double)eps, got, want);
        else if (got != want)
            test_failures++;
    }
}

static oit_status begin(oit_saturation *s, frame *f)
{
    oit_error err = {0};
    oit_status st = oit_saturation_begin(s, f->w, f->h, f->translucent, &err);
    CHECK(st == OIT_OK, "begin %dx%d: %s", f->w, f->h, err.message);
    return st;
}

/* Tile k (row-major over 16 x 16 tiles) holds zeros but at local pixel
 * (k % 16, k / 16), invocation k of its workgroup; its value falls with k
 * and its largest channel turns with k. The frame is wider and taller than
 * the 16 x 16 tiles by a partial tile. */
static void every_invocation(oit_saturation *s, int translucent)
{
    frame f;
    const char *what = translucent ? "invocations, translucent" : "invocations, transparent";
    if (!frame_init(&f, 16 * TS + 5, 16 * TS + 9, translucent) || begin(s, &f) != OIT_OK) {
        CHECK(0, "%s: set-up failed", what);
        frame_free(&f);
        return;
    }
    for (int k = 0; k < 256; k++) {
        int x = (k % 16) * TS + k % 16, gy = (k / 16) * TS + k / 16;
        float *p = px(&f, x, gy);
        int c = translucent ? k % 3 : 0;
        p[c] = 0.75f - (float)k / 512.0f;
        if (translucent)
            p[(c + 1) % 3] = 0.5f * p[c];
    }
    frame_upload(&f);
    uint32_t seed = 99u + (uint32_t)translucent;
    if (update(s, &f, NULL, 1, what)) {
        int bad = check_tiles(s, &f, &seed, what);
        printf("%s: %dx%d, %d of %d tiles wrong\n", what, f.w, f.h, bad, f.tx * f.ty);
    }
    frame_free(&f);
}

/* Top half saturated (T = 0.001), bottom half clear (T = 0.9) in a frame of
 * 7 x 6.5 tiles: the rects start at neither row nor column 0. */
static void halves(oit_saturation *s)
{
    frame f;
    if (!frame_init(&f, 7 * TS, 6 * TS + 8, 0) || begin(s, &f) != OIT_OK) {
        CHECK(0, "halves: set-up failed");
        frame_free(&f);
        return;
    }
    for (int gy = 0; gy < f.h; gy++)
        for (int x = 0; x < f.w; x++)
            px(&f, x, gy)[0] = gy >= f.h / 2 + 4 ? 0.001f : 0.9f; /* GL rows: top is high */
    frame_upload(&f);
    const int top[4] = {21, 5, 90, 37}, bottom[4] = {17, 70, 101, 99};
    if (update(s, &f, top, 1, "halves") && update(s, &f, bottom, 1, "halves")) {
        int t = oit_saturation_covered(s, top, 0.01f), b = oit_saturation_covered(s, bottom, 0.01f);
        printf("halves: top rect covered %d, bottom rect %d\n", t, b);
        CHECK(t == 1 && b == 0, "halves: the saturated top rect %d,%d-%d,%d is covered: %d, the "
              "clear bottom rect %d,%d-%d,%d: %d (want 1, 0)", top[0], top[1], top[2], top[3],
              t, bottom[0], bottom[1], bottom[2], bottom[3], b);
        uint32_t seed = 7u;
        check_tiles(s, &f, &seed, "halves");
        check_rects(s, &f, &seed, 200, "halves");
    }
    frame_free(&f);
}

/* Lowers T over a random rect by a random factor (T only falls). */
static void darken(frame *f, uint32_t *seed, int r[4])
{
    r[0] = (int)(rng(seed) % (uint32_t)f->w);
    r[1] = (int)(rng(seed) % (uint32_t)f->h);
    r[2] = r[0] + 1 + (int)(rng(seed) % (uint32_t)(f->w - r[0] + 3));
    r[3] = r[1] + 1 + (int)(rng(seed) % (uint32_t)(f->h - r[1] + 3));
    int g[4];
    if (!gl_box(f, r, g))
        return;
    static const float k[4] = {0.0f, 0.01f, 0.2f, 0.7f};
    for (int y = g[1]; y < g[3]; y++)
        for (int x = g[0]; x < g[2]; x++)
            for (int c = 0; c < 3; c++)
                if (rng(seed) % 8)
                    px(f, x, y)[c] *= k[rng(seed) % 4];
}

/* Frames of random sizes: batches over rects that grow and move, each
 * updated (with a wait, or, every other frame, without: then only the
 * safety of a late read-back is checked, and the last batch is waited). */
static void random_frames(oit_saturation *s, int frames)
{
    uint32_t seed = 20250607u;
    for (int i = 0; i < frames; i++) {
        frame f;
        char what[64];
        int translucent = i % 2, sync = i % 3 != 2;
        int w = 17 + (int)(rng(&seed) % 90u), h = 17 + (int)(rng(&seed) % 90u);
        snprintf(what, sizeof what, "frame %d (%dx%d, %s, %s)", i, w, h,
                 translucent ? "translucent" : "transparent", sync ? "waited" : "late");
        if (!frame_init(&f, w, h, translucent) || begin(s, &f) != OIT_OK) {
            CHECK(0, "%s: set-up failed", what);
            frame_free(&f);
            continue;
        }
        for (size_t p = 0; p < (size_t)w * h * 3; p++)
            f.T[p] = 1.0f;
        for (int b = 0; b < 6; b++) {
            int r[4];
            darken(&f, &seed, r);
            frame_upload(&f);
            if (!update(s, &f, r, sync || b == 5, what))
                break;
            if (sync || b == 5) {
                check_tiles(s, &f, &seed, what);
                check_rects(s, &f, &seed, 60, what);
                continue;
            }
            /* late: covered only where the model covers too */
            for (int q = 0; q < 60; q++) {
                int qr[4] = {(int)(rng(&seed) % (uint32_t)w), (int)(rng(&seed) % (uint32_t)h), 0, 0};
                qr[2] = qr[0] + 1 + (int)(rng(&seed) % 30u);
                qr[3] = qr[1] + 1 + (int)(rng(&seed) % 30u);
                float eps = rng(&seed) % 2 ? 0.5f : 0.05f;
                CHECK(!oit_saturation_covered(s, qr, eps) || model_covered(&f, qr, eps),
                      "%s: batch %d: rect %d,%d-%d,%d covered at %.3f, the state is not",
                      what, b, qr[0], qr[1], qr[2], qr[3], (double)eps);
            }
        }
        frame_free(&f);
    }
}

/* A frame saturated everywhere, then a new one of the same size that
 * updates one corner tile: the other tiles hold 1 again. */
static void new_frame_forgets(oit_saturation *s)
{
    frame f;
    if (!frame_init(&f, 50, 40, 0) || begin(s, &f) != OIT_OK) {
        CHECK(0, "forget: set-up failed");
        frame_free(&f);
        return;
    }
    frame_upload(&f); /* T = 0 everywhere */
    update(s, &f, NULL, 1, "forget, frame 1");
    const int all[4] = {0, 0, 50, 40}, corner[4] = {3, 30, 9, 38}, far[4] = {35, 2, 47, 11};
    CHECK(oit_saturation_covered(s, all, 0.01f), "forget: a saturated frame is not covered");
    if (begin(s, &f) == OIT_OK && update(s, &f, corner, 1, "forget, frame 2")) {
        CHECK(oit_saturation_covered(s, corner, 0.01f), "forget: the updated corner is not "
              "covered");
        CHECK(!oit_saturation_covered(s, far, 0.01f), "forget: a tile the new frame never "
              "updated is covered by the last frame's state");
        CHECK(!oit_saturation_covered(s, all, 0.01f), "forget: the new frame is covered whole");
    }
    frame_free(&f);
}

int main(void)
{
    oit_gl *gl = test_gl_open();
    oit_error err = {0};
    oit_saturation *s = NULL;
    if (oit_saturation_create(&s, &err) != OIT_OK) {
        fprintf(stderr, "FAIL: saturation tiles: %s\n", err.message);
        oit_gl_destroy(gl);
        return 1;
    }
    every_invocation(s, 0);
    every_invocation(s, 1);
    halves(s);
    random_frames(s, 12);
    new_frame_forgets(s);
    oit_saturation_destroy(s);
    return test_gl_verdict(gl);
}
