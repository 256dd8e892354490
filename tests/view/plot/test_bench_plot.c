/* oitbench's charts below the command line: the font's placement and
 * colour (and the status line's upper case, and its named fields wrapped
 * to the width), chart axes (ranges, log and
 * linear tick positions, labels), that a marker lands on the pixel its data
 * maps to in its colour, polylines, the Pareto front and the rmse floor as
 * pure functions, results.csv written and read back, malformed CSV refused
 * with the file and line named, and a speed chart written as a PNG of the
 * expected size that shows its series. No GL. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/render/image/image.h"
#include "tools/oitbench/bench_csv.h"
#include "tools/oitbench/bench_plot.h"
#include "view/plot/chart.h"
#include "view/plot/text_overlay.h"
#include "tests/lib/test_check.h"

static const float red[3] = {1.0f, 0.0f, 0.0f};
static const float blue[3] = {0.0f, 0.0f, 1.0f};

static const float *pixel(const oit_image *img, int x, int y)
{
    return img->rgba + 4 * ((size_t)y * (size_t)img->width + (size_t)x);
}

static int is_colour(const oit_image *img, int x, int y, const float rgb[3])
{
    const float *p = pixel(img, x, y);
    return p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
}

static void test_text(void)
{
    oit_image img;
    oit_error err;
    CHECK(oit_text_width("abc", 2) == (3 * 6 - 1) * 2, "width %d", oit_text_width("abc", 2));
    CHECK(oit_text_width("", 2) == 0, "empty width %d", oit_text_width("", 2));
    if (oit_image_alloc(&img, 64, 64, &err) != OIT_OK)
        return;
    memset(img.rgba, 0, sizeof(float) * 4 * 64 * 64);
    /* 'l' has its top row at columns 1 and 2 */
    oit_text_draw(&img, 10, 10, "l", blue, 1);
    CHECK(is_colour(&img, 11, 10, blue) && is_colour(&img, 12, 10, blue), "'l' top row not blue");
    CHECK(!is_colour(&img, 10, 10, blue), "'l' column 0 drawn");
    /* turned upwards: column u goes to -y, row v to +x */
    oit_text_draw_up(&img, 30, 50, "l", red, 1);
    CHECK(is_colour(&img, 30, 49, red) && !is_colour(&img, 30, 50, red),
          "upward 'l' misplaced");
    /* scale 3: every font pixel a 3x3 block */
    oit_text_draw(&img, 40, 40, "l", red, 3);
    CHECK(is_colour(&img, 43, 40, red) && is_colour(&img, 45, 42, red) &&
          !is_colour(&img, 42, 40, red), "scale 3 'l' misplaced");
    /* off-image text is clipped, not a crash */
    oit_text_draw(&img, -100, 60, "clipped text", red, 4);
    oit_image_free(&img);
}

/* The viewer's status line keeps drawing lower case as upper case. */
/* The status line of named fields wraps between fields to the image's
 * width, one band of whole lines, and leaves the rows below alone. */
static void test_status_fields(void)
{
    static const float grey[3] = {0.1f, 0.1f, 0.1f}, green[3] = {0.0f, 1.0f, 0.0f};
    const char *f[] = {"ab", "cd", "efghij", "k"};
    oit_image wide = {0}, narrow = {0};
    oit_error err = {0};
    CHECK(oit_image_alloc(&wide, 200, 40, &err) == OIT_OK &&
              oit_image_alloc(&narrow, 60, 40, &err) == OIT_OK, "alloc: %s", err.message);
    for (int y = 0; y < 40; y++)
        for (int x = 0; x < 200; x++) {
            oit_image_put_rgb(&wide, x, y, green);
            if (x < 60)
                oit_image_put_rgb(&narrow, x, y, green);
        }
    int line = oit_text_line_height(1);
    /* "ab  cd  efghij  k" is 17 characters: one line at 200 px */
    int band = oit_text_status_fields(&wide, f, 4, 1);
    CHECK(band == line, "wide: band %d, want %d", band, line);
    CHECK(is_colour(&wide, 199, line - 1, grey) && is_colour(&wide, 0, line, green),
          "wide: band rows");
    /* 60 px hold 10 characters: "ab  cd", then "efghij  k" */
    band = oit_text_status_fields(&narrow, f, 4, 1);
    CHECK(band == 2 * line, "narrow: band %d, want %d", band, 2 * line);
    CHECK(is_colour(&narrow, 59, 2 * line - 1, grey) && is_colour(&narrow, 0, 2 * line, green),
          "narrow: band rows");
    int lit = 0;
    for (int y = line; y < 2 * line; y++)
        for (int x = 0; x < 60; x++)
            lit += is_colour(&narrow, x, y, (const float[3]){1, 1, 1});
    CHECK(lit > 0, "narrow: nothing written on the second line");
    /* at the edge: 4 + 2 + 4 characters fit 10, 5 + 2 + 4 do not */
    const char *fit[] = {"abcd", "efgh"}, *over[] = {"abcde", "efgh"};
    band = oit_text_status_fields(&narrow, fit, 2, 1);
    CHECK(band == line, "10 characters in 60 px: band %d, want %d", band, line);
    band = oit_text_status_fields(&narrow, over, 2, 1);
    CHECK(band == 2 * line, "11 characters in 60 px: band %d, want %d", band, 2 * line);
    CHECK(oit_text_status_fields(&narrow, f, 0, 1) == 0, "no fields: a band");
    oit_image_free(&wide);
    oit_image_free(&narrow);
}

static void test_status_line_upper_case(void)
{
    oit_image a, b;
    oit_error err;
    if (oit_image_alloc(&a, 80, 20, &err) != OIT_OK || oit_image_alloc(&b, 80, 20, &err) != OIT_OK)
        return;
    memset(a.rgba, 0, sizeof(float) * 4 * 80 * 20);
    memset(b.rgba, 0, sizeof(float) * 4 * 80 * 20);
    oit_text_status_line(&a, "fps ok", 1);
    oit_text_status_line(&b, "FPS OK", 1);
    CHECK(!memcmp(a.rgba, b.rgba, sizeof(float) * 4 * 80 * 20), "status line: case shows");
    CHECK(is_colour(&a, 0, 0, (const float[3]){0.1f, 0.1f, 0.1f}), "status band missing");
    oit_image_free(&a);
    oit_image_free(&b);
}

static void check_ticks(const char *what, oit_chart_axis a, const double *want, int n)
{
    double t[32];
    int got = oit_chart_ticks(&a, t, 32);
    CHECK(got == n, "%s: %d ticks, expected %d", what, got, n);
    for (int i = 0; i < got && i < n; i++)
        CHECK(fabs(t[i] - want[i]) <= 1e-9 * fabs(want[i]) + 1e-12, "%s: tick %d = %g, expected %g",
              what, i, t[i], want[i]);
}

static void test_axes(void)
{
    const double decades[] = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1};
    check_ticks("log 1e-6..0.1", (oit_chart_axis){NULL, OIT_CHART_LOG10, 1e-6, 0.1}, decades, 6);
    const double one[] = {1, 2, 5, 10};
    check_ticks("log 1..10", (oit_chart_axis){NULL, OIT_CHART_LOG10, 1, 10}, one, 4);
    const double lin[] = {0, 2, 4, 6, 8, 10};
    check_ticks("linear 0..10", (oit_chart_axis){NULL, OIT_CHART_LINEAR, 0, 10}, lin, 6);
    const double neg[] = {-0.2, -0.1, 0, 0.1, 0.2};
    check_ticks("linear -0.2..0.2", (oit_chart_axis){NULL, OIT_CHART_LINEAR, -0.2, 0.2}, neg, 5);
    double t[32];
    int n = oit_chart_ticks(&(oit_chart_axis){NULL, OIT_CHART_LOG10, 1e-20, 1}, t, 32);
    CHECK(n >= 5 && n <= 9 && t[0] == 1e-20, "21 decades: %d ticks from %g", n, n ? t[0] : 0);
    CHECK(oit_chart_ticks(&(oit_chart_axis){NULL, OIT_CHART_LOG10, 0, 10}, t, 32) == 0,
          "a log axis from 0 has ticks");

    oit_chart_axis a = {NULL, OIT_CHART_LOG10, 0, 0};
    oit_chart_axis_fit(&a, 0.0016, 0.024, 0);
    CHECK(a.lo == 1e-3 && fabs(a.hi - 0.1) < 1e-15, "log fit [%g, %g]", a.lo, a.hi);
    oit_chart_axis_fit(&a, 1e-3, 1e-2, 0); /* data on decades: a margin beyond */
    CHECK(fabs(a.lo - 1e-4) < 1e-18 && fabs(a.hi - 0.1) < 1e-15, "log fit on decades [%g, %g]",
          a.lo, a.hi);
    oit_chart_axis_fit(&a, NAN, -1, 0);
    CHECK(a.lo == 1 && a.hi == 10, "log fit of nothing [%g, %g]", a.lo, a.hi);
    oit_chart_axis l = {NULL, OIT_CHART_LINEAR, 0, 0};
    oit_chart_axis_fit(&l, 8, 8, 1);
    CHECK(l.lo == 0 && l.hi == 10, "linear fit of 8 from 0 [%g, %g]", l.lo, l.hi);
    oit_chart_axis_fit(&l, 3, 7, 0);
    CHECK(l.lo <= 3 - 0.1 && l.hi >= 7 + 0.1 && l.lo >= 2 && l.hi <= 8, "linear fit [%g, %g]",
          l.lo, l.hi);

    char b[32];
    oit_chart_tick_label(&(oit_chart_axis){NULL, OIT_CHART_LOG10, 1e-7, 1}, 1e-6, b, sizeof b);
    CHECK(!strcmp(b, "1e-6"), "label of 1e-6: '%s'", b);
    oit_chart_tick_label(&(oit_chart_axis){NULL, OIT_CHART_LOG10, 1e-3, 1}, 0.01, b, sizeof b);
    CHECK(!strcmp(b, "0.01"), "label of 0.01: '%s'", b);
    oit_chart_tick_label(&(oit_chart_axis){NULL, OIT_CHART_LINEAR, 0, 3}, 2.5, b, sizeof b);
    CHECK(!strcmp(b, "2.5"), "label of 2.5 on 0..3: '%s'", b);
    oit_chart_tick_label(&(oit_chart_axis){NULL, OIT_CHART_LINEAR, 0, 300}, 100, b, sizeof b);
    CHECK(!strcmp(b, "100"), "label of 100 on 0..300: '%s'", b);
}

static void test_marker_and_line(void)
{
    oit_chart c;
    oit_error err;
    oit_chart_desc d = {800, 600, "title", "subtitle",
                        {"x (units)", OIT_CHART_LINEAR, 0, 10},
                        {"y (units, log)", OIT_CHART_LOG10, 1e-3, 10}, 2, 0};
    if (oit_chart_create(&c, &d, &err) != OIT_OK) {
        CHECK(0, "create: %s", err.message);
        return;
    }
    CHECK(c.img.width == 800 && c.img.height == 600, "image %dx%d", c.img.width, c.img.height);
    int px, py;
    CHECK(oit_chart_map(&c, 5, 0.1, &px, &py), "(5, 0.1) does not map");
    int want_x = (int)lround(c.plot.x0 + 0.5 * (c.plot.x1 - c.plot.x0));
    int want_y = (int)lround(c.plot.y1 - 0.5 * (c.plot.y1 - c.plot.y0));
    CHECK(px == want_x && py == want_y, "(5, 0.1) at (%d, %d), expected (%d, %d)", px, py, want_x,
          want_y);
    CHECK(!oit_chart_map(&c, 5, 0, &px, &py) && !oit_chart_map(&c, 11, 1, &px, &py) &&
          !oit_chart_map(&c, NAN, 1, &px, &py), "points off the axes map");
    const float white[3] = {1, 1, 1};
    CHECK(is_colour(&c.img, c.plot.x0 + 3, c.plot.y0 + 3, white), "plot background not white");
    CHECK(is_colour(&c.img, c.plot.x0, (c.plot.y0 + c.plot.y1) / 2,
                    (const float[3]){0.1f, 0.1f, 0.1f}), "no frame on the left edge");
    oit_chart_point(&c, 5, 0.1, OIT_CHART_CIRCLE, red);
    CHECK(is_colour(&c.img, want_x, want_y, red), "marker centre not red");
    CHECK(is_colour(&c.img, want_x + 4, want_y, red), "marker too small");
    CHECK(!is_colour(&c.img, want_x + 9, want_y, red), "marker too large");
    /* the diagonal of the plot passes through its centre */
    double lx[2] = {0, 10}, ly[2] = {1e-3, 10};
    int cx = c.plot.x0 + (c.plot.x1 - c.plot.x0) / 4, cy = c.plot.y1 - (c.plot.y1 - c.plot.y0) / 4;
    oit_chart_polyline(&c, lx, ly, 2, blue, 0);
    int hit = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            hit |= is_colour(&c.img, cx + dx, cy + dy, blue);
    CHECK(hit, "diagonal misses the quarter point (%d, %d)", cx, cy);
    /* a line from far outside the x range stops at the frame */
    double hx[2] = {-10, 20}, hy[2] = {0.01, 0.01};
    oit_chart_polyline(&c, hx, hy, 2, blue, 0);
    int row = (int)lround(c.plot.y1 - 0.25 * (c.plot.y1 - c.plot.y0));
    CHECK(is_colour(&c.img, c.plot.x0 + 5, row, blue), "clipped line missing inside the plot");
    for (int dy = -1; dy <= 1; dy++)
        CHECK(!is_colour(&c.img, c.plot.x0 - 5, row + dy, blue) &&
              !is_colour(&c.img, c.plot.x1 + 5, row + dy, blue), "line not clipped to the plot");
    /* labels of one crowded point: the first beside it, then stacked, then none */
    int placed = 0, first = oit_chart_point_label(&c, 2, 1, "label", red);
    for (int i = 0; i < 30; i++)
        placed += oit_chart_point_label(&c, 2, 1, "label", red);
    printf("crowded point: %d of 31 labels placed\n", first + placed);
    CHECK(first && placed >= 4 && placed < 30, "crowded labels: first %d, then %d of 30", first,
          placed);
    CHECK(!oit_chart_point_label(&c, 20, 1, "off", red), "label of a point off the axes drawn");
    CHECK(oit_chart_note(&c, "one", red) && oit_chart_note(&c, "two", red) &&
          !oit_chart_note(&c, "three", red), "note lines not as reserved");
    oit_chart_free(&c);
    oit_chart_desc small = {800, 300, NULL, NULL, d.x, d.y, 12, 0};
    CHECK(oit_chart_create(&c, &small, &err) == OIT_ERR_ARGUMENT, "12 notes fit in 300 rows");
    oit_chart_desc bad_axis = {800, 600, NULL, NULL, d.x, {NULL, OIT_CHART_LOG10, 0, 1}, 0, 0};
    CHECK(oit_chart_create(&c, &bad_axis, &err) == OIT_ERR_ARGUMENT, "log axis from 0 accepted");
}

/* A legend longer than the chart stops with a line saying so. */
static void test_legend_overflow(void)
{
    oit_chart c;
    oit_error err;
    oit_chart_desc d = {800, 400, NULL, NULL, {NULL, OIT_CHART_LINEAR, 0, 1},
                        {NULL, OIT_CHART_LINEAR, 0, 1}, 0, 0};
    if (oit_chart_create(&c, &d, &err) != OIT_OK) {
        CHECK(0, "create: %s", err.message);
        return;
    }
    int shown = 0;
    for (int i = 0; i < 40; i++)
        shown += oit_chart_legend(&c, "series", OIT_CHART_CIRCLE, red, 1);
    printf("legend: %d of 40 entries fit in 400 rows\n", shown);
    CHECK(shown > 5 && shown < 40, "%d legend entries shown in 400 rows", shown);
    CHECK(!oit_chart_legend(&c, "late", OIT_CHART_CIRCLE, red, 0), "entry after a full legend");
    const float ink[3] = {0.1f, 0.1f, 0.1f};
    int marked = 0;
    for (int y = c.legend_y; y < c.legend_y + 22 && y < c.img.height; y++)
        for (int x = c.legend_x; x < c.img.width; x++)
            marked |= is_colour(&c.img, x, y, ink);
    CHECK(marked, "no \"(more not shown)\" line under the last entry");
    oit_chart_free(&c);
}

static void test_pareto(void)
{
    const double x[] = {1, 2, 3, 2, 1, NAN, 4};
    const double y[] = {5, 3, 1, 4, 5, 0, 1};
    unsigned char f[7];
    int n = oit_bench_pareto_front(x, y, 7, f);
    const unsigned char want[7] = {1, 1, 1, 0, 1, 0, 0};
    CHECK(n == 4, "front of %d, expected 4", n);
    for (int i = 0; i < 7; i++)
        CHECK(f[i] == want[i], "point %d: on front %d, expected %d", i, f[i], want[i]);
}

/* Two entries over two views: "dfb" ran, "stream@0.1" did not (its reason
 * has a quote and a comma, which the CSV must carry). */
static void fake_result(oit_bench_result *r, oit_bench_method m[2], oit_bench_cell cells[4],
                        uint32_t layers[2], double ref_ms[2])
{
    memset(r, 0, sizeof *r);
    memset(m, 0, 2 * sizeof *m);
    memset(cells, 0, 4 * sizeof *cells);
    layers[0] = 7;
    layers[1] = 12;
    snprintf(m[0].name, sizeof m[0].name, "dfb");
    m[0].runnable = 1;
    m[0].cells = cells;
    for (int v = 0; v < 2; v++) {
        cells[v] = (oit_bench_cell){.ok = 1, .ms_median = 2.0 + v, .ms_p95 = 3.0 + v,
                                    .gpu_bytes_peak = 1000000u * (v + 1),
                                    .gpu_mesh_bytes = 600000u, .max_layers = 7 + 5 * v,
                                    .fragments = 10,
                                    .diff = {v ? 0.002 : 0.0, 0.5, 0.1, v ? 40.0 : INFINITY, 3},
                                    .gpu_ms_median = -1.0,
                                    .pct_over_outside_ambiguity = v ? 0.0 : 0.05};
    }
    m[0].ms_median = 2.0;
    m[0].ms_p95 = 4.0;
    m[0].gpu_bytes_peak = 2000000;
    m[0].gpu_mesh_bytes = 600000;
    m[0].max_layers = 12;
    m[0].rmse_mean = 0.001;
    m[0].psnr_min = 40.0;
    m[0].pct_over_outside_ambiguity_worst = 0.05;
    m[0].triangles = 1234;
    snprintf(m[1].name, sizeof m[1].name, "stream@0.1");
    m[1].geometry = OIT_BENCH_GEOMETRY_PART_FILE;
    m[1].triangles = 5678;
    snprintf(m[1].reason, sizeof m[1].reason, "needs a \"part file\", not a mesh");
    m[1].cells = cells + 2;
    m[1].ms_median = m[1].ms_p95 = m[1].rmse_mean = m[1].psnr_min = NAN;
    r->methods = m;
    r->method_count = 2;
    r->views = 2;
    r->ref_layers = layers;
    r->ref_ms = ref_ms;
}

/* The fake result written as results.csv (1234 triangles) and read back. */
static oit_status fake_table(const char *name, oit_bench_table *t, oit_error *err)
{
    oit_bench_result r;
    oit_bench_method m[2];
    oit_bench_cell cells[4];
    uint32_t layers[2];
    double ref_ms[2] = {1, 1};
    fake_result(&r, m, cells, layers, ref_ms);
    FILE *f = tmpfile();
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: no temporary file", name);
    oit_bench_csv_write(f, &r, 1234);
    rewind(f);
    oit_status s = oit_bench_csv_read(f, name, t, err);
    fclose(f);
    return s;
}

static void test_csv_round_trip(void)
{
    oit_bench_table t;
    oit_error err;
    CHECK(fake_table("round-trip.csv", &t, &err) == OIT_OK, "%s", err.message);
    CHECK(t.count == 6, "%zu rows, expected 6", t.count);
    if (t.count != 6)
        return;
    const oit_bench_row *v1 = &t.rows[2], *sum_stream = &t.rows[5];
    CHECK(!v1->summary && !strcmp(v1->method, "dfb") && v1->view == 1 && v1->ok &&
          v1->ms_median == 3.0 && v1->gpu_bytes_peak == 2000000 && v1->max_layers == 12 &&
          fabs(v1->rmse - 0.002) < 1e-12 && v1->view_max_layers == 12 && v1->triangles == 1234,
          "view row dfb/1 read back wrong");
    CHECK(isinf(t.rows[0].psnr), "psnr inf read back as %g", t.rows[0].psnr);
    CHECK(sum_stream->summary && !sum_stream->ok && sum_stream->view == -1 &&
          !strcmp(sum_stream->reason, "needs a \"part file\", not a mesh") &&
          isnan(sum_stream->rmse) && !sum_stream->has_gpu && sum_stream->view_max_layers == 12,
          "summary row stream@0.1 read back wrong (reason '%s')", sum_stream->reason);
    CHECK(v1->geometry == OIT_BENCH_GEOMETRY_SOURCE_MESH && v1->drawn_triangles == 1234 &&
          sum_stream->geometry == OIT_BENCH_GEOMETRY_PART_FILE &&
          sum_stream->drawn_triangles == 5678,
          "geometry read back wrong (%d %llu, %d %llu)", v1->geometry,
          (unsigned long long)v1->drawn_triangles, sum_stream->geometry,
          (unsigned long long)sum_stream->drawn_triangles);
    CHECK(v1->mesh_counted && v1->gpu_mesh_bytes == 600000 && t.rows[4].mesh_counted &&
          t.rows[4].gpu_mesh_bytes == 600000 && sum_stream->gpu_mesh_bytes == 0,
          "gpu_mesh_bytes read back wrong (%d %llu, summary %llu)", v1->mesh_counted,
          (unsigned long long)v1->gpu_mesh_bytes, (unsigned long long)t.rows[4].gpu_mesh_bytes);
    CHECK(t.rows[0].pct_over_outside_ambiguity == 0.05 && v1->pct_over_outside_ambiguity == 0.0 &&
          t.rows[4].pct_over_outside_ambiguity == 0.05 &&
          isnan(sum_stream->pct_over_outside_ambiguity),
          "pct_over_1_255_outside_ambiguity read back wrong (%g %g, summary %g %g)",
          t.rows[0].pct_over_outside_ambiguity, v1->pct_over_outside_ambiguity,
          t.rows[4].pct_over_outside_ambiguity, sum_stream->pct_over_outside_ambiguity);
    CHECK(oit_bench_rmse_floor(&t) == 1e-4, "rmse floor %g, expected 1e-4 (least 0.001)",
          oit_bench_rmse_floor(&t));
    oit_bench_table_free(&t);
}

#define HDR OIT_BENCH_CSV_HEADER "\n"
#define OK_ROW "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3,source_mesh,16,2.5,40,0.25\n"
#define ROW_19 "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3,source_mesh,16,2.5,40\n"
#define ROW_18 "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3,source_mesh,16,2.5\n"
#define OLD_ROW "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3\n"

/* text (len bytes; an empty one read from an empty file) must fail to read
 * with OIT_ERR_FORMAT, the message starting "bad.csv: line LINE: " and
 * holding says, and keep no rows. */
static void expect_malformed(const char *what, const char *text, size_t len, int line,
                             const char *says)
{
    char *copy = malloc(len + 1);
    memcpy(copy, text, len);
    FILE *f = len ? fmemopen(copy, len, "rb") : tmpfile();
    oit_bench_table t;
    oit_error err = {0};
    oit_status s = f ? oit_bench_csv_read(f, "bad.csv", &t, &err) : OIT_ERR_IO;
    char where[32];
    snprintf(where, sizeof where, "bad.csv: line %d: ", line);
    CHECK(s == OIT_ERR_FORMAT && !strncmp(err.message, where, strlen(where)) &&
          strstr(err.message, says),
          "%s: status %d, message '%s' (expected '%s...%s')", what, (int)s, err.message, where,
          says);
    CHECK(t.rows == NULL && t.count == 0, "%s: rows kept after a failure", what);
    if (f)
        fclose(f);
    free(copy);
}

/* The header and OK_ROW with field k (from 0) replaced by value. */
static void ok_row_with(int k, const char *value, char *out, size_t n)
{
    const char *p = OK_ROW;
    size_t o = (size_t)snprintf(out, n, "%s", HDR);
    for (int i = 0; *p && o < n; i++) {
        size_t len = strcspn(p, ",\n");
        o += (size_t)snprintf(out + o, n - o, "%.*s%c", (int)(i == k ? strlen(value) : len),
                              i == k ? value : p, p[len]);
        p += len + 1;
    }
}

/* Every malformed text must fail with OIT_ERR_FORMAT naming file and line. */
static void test_csv_malformed(void)
{
    static const struct { const char *text; size_t len; int line; const char *says; } cases[] = {
        {"", 0, 1, "empty"},
        {"row,method\n", 0, 1, "header"},
        {HDR, 0, 2, "no rows"},
        {HDR "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16\n", 0, 2, "14 fields"},
        {HDR "view,pll,0,not_runnable,,,100,3,,,,,\"no\",16,3,source_mesh,16,2.5,,\n", 0, 2, "gpu_bytes_peak"},
        {HDR "view,pll,0,not_runnable,,,,,,,,,\"no\",16,3,source_mesh,16,,40,\n", 0, 2,
         "gpu_mesh_bytes"},
        {HDR OK_ROW "view,pll,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,inf,\"\",17,3,source_mesh,16,2.5,0,0\n", 0, 3, "triangles"},
        {HDR OK_ROW "\n", 0, 3, "empty line"},
        {HDR "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3,part_file,-4,,40,0\n", 0, 2,
         "drawn_triangles"},
        {HDR ROW_18, 0, 2, "18 fields"},
        {HDR ROW_19, 0, 2, "19 fields"},
        {OIT_BENCH_CSV_HEADER_19 "\n" OK_ROW, 0, 2, "more than 19 fields"},
        {HDR "view,pll,0,not_runnable,,,,,,,,,\"no\",16,3,source_mesh,16,,,5\n", 0, 2,
         "pct_over_1_255_outside_ambiguity"},
        {OIT_BENCH_CSV_HEADER_18 "\n" OK_ROW, 0, 2, "more than 18 fields"},
        {HDR "view,dfb,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3\n", 0, 2, "15 fields"},
        {OIT_BENCH_CSV_HEADER_15 "\n" OLD_ROW "view,pll,0,ok,1.0,2.0,100,3,0.01,0.1,0.5,inf,\"\",16,3,"
         "source_mesh,16,2.5\n", 0, 3, "more than 15 fields"},
        {HDR "view,dfb,0,ok,1.0\0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3,source_mesh,16,2.5,40,0\n",
         sizeof(HDR "view,dfb,0,ok,1.0\0,2.0,100,3,0.01,0.1,0.5,40.0,\"\",16,3,source_mesh,16,2.5,40,0\n") - 1, 2, "NUL"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char what[32];
        snprintf(what, sizeof what, "case %zu", i);
        expect_malformed(what, cases[i].text, cases[i].len ? cases[i].len : strlen(cases[i].text),
                         cases[i].line, cases[i].says);
    }
    /* One good row with one bad field (line 2). */
    static const struct { int field; const char *value, *says; } fields[] = {
        {3, "maybe", "status"},
        {4, "", "ms_median"},
        {4, "-1", "ms_median"},
        {4, "nan", "ms_median"},
        {6, "1e3", "gpu_bytes_peak"},
        {12, "\"oops", "quoted"},
        {12, "\"\"x", "quoted"},
        {12, "", "not quoted"},
        {12, "\"why\"", "ok row"},
        {0, "summary", "summary"},
        {1, "d f b", "method"},
        {15, "mesh", "geometry"},
        {17, "-2", "gpu_ms_median"},
        {17, "fast", "gpu_ms_median"},
        {18, "", "gpu_mesh_bytes"},
        {18, "101", "gpu_mesh_bytes"}, /* more than its gpu_bytes_peak, which holds it */
        {18, "-1", "gpu_mesh_bytes"},
        {18, "4k", "gpu_mesh_bytes"},
        {19, "", "pct_over_1_255_outside_ambiguity"},
        {19, "-1", "pct_over_1_255_outside_ambiguity"},
        {19, "100.5", "pct_over_1_255_outside_ambiguity"},
        {19, "nan", "pct_over_1_255_outside_ambiguity"},
    };
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++) {
        char text[1024], what[64];
        ok_row_with(fields[i].field, fields[i].value, text, sizeof text);
        snprintf(what, sizeof what, "field %d '%s'", fields[i].field, fields[i].value);
        expect_malformed(what, text, strlen(text), 2, fields[i].says);
    }
    /* a long header-only line beyond the reader's limit */
    char *big = malloc(10000);
    memset(big, 'x', 9999);
    big[9999] = '\n';
    FILE *f = fmemopen(big, 10000, "rb");
    oit_bench_table t;
    oit_error err = {0};
    CHECK(f && oit_bench_csv_read(f, "long.csv", &t, &err) == OIT_ERR_FORMAT &&
          strstr(err.message, "longer than"), "a 10000-byte line: '%s'", err.message);
    if (f)
        fclose(f);
    free(big);
    CHECK(oit_bench_csv_load("/nonexistent/results.csv", &t, &err) == OIT_ERR_IO &&
          strstr(err.message, "/nonexistent/results.csv"), "missing file: '%s'", err.message);
}

/* text read as a results.csv into t (OIT_OK expected). */
static oit_status read_text(const char *text, const char *name, oit_bench_table *t,
                            oit_error *err)
{
    size_t n = strlen(text);
    char *copy = malloc(n + 1);
    memcpy(copy, text, n + 1);
    FILE *f = fmemopen(copy, n, "rb");
    oit_status s = f ? oit_bench_csv_read(f, name, t, err) : OIT_ERR_IO;
    if (f)
        fclose(f);
    free(copy);
    return s;
}

/* A file of the oitbench before the geometry columns still reads: its rows
 * say no geometry (-1) and drew the file's triangle count; that and the
 * file before gpu_mesh_bytes say their GPU bytes left the mesh out. */
static void test_csv_old_format(void)
{
    oit_bench_table t = {0};
    oit_error err = {0};
    oit_status s = read_text(OIT_BENCH_CSV_HEADER_15 "\n" OLD_ROW, "old.csv", &t, &err);
    CHECK(s == OIT_OK && t.count == 1 && t.rows[0].geometry == -1 &&
          t.rows[0].drawn_triangles == 16 && !t.rows[0].mesh_counted,
          "older results.csv: status %d '%s'", (int)s, err.message);
    oit_bench_table_free(&t);
    s = read_text(OIT_BENCH_CSV_HEADER_18 "\n" ROW_18, "old18.csv", &t, &err);
    CHECK(s == OIT_OK && t.count == 1 && t.rows[0].gpu_ms_median == 2.5 &&
          t.rows[0].gpu_bytes_peak == 100 && !t.rows[0].mesh_counted &&
          t.rows[0].gpu_mesh_bytes == 0,
          "results.csv before gpu_mesh_bytes: status %d '%s'", (int)s, err.message);
    oit_bench_table_free(&t);
    s = read_text(OIT_BENCH_CSV_HEADER_19 "\n" ROW_19, "old19.csv", &t, &err);
    CHECK(s == OIT_OK && t.count == 1 && t.rows[0].mesh_counted &&
          t.rows[0].gpu_mesh_bytes == 40 && isnan(t.rows[0].pct_over_outside_ambiguity),
          "results.csv before pct_over_1_255_outside_ambiguity: status %d '%s'", (int)s,
          err.message);
    oit_bench_table_free(&t);
    s = read_text(HDR OK_ROW, "new.csv", &t, &err);
    CHECK(s == OIT_OK && t.count == 1 && t.rows[0].mesh_counted &&
          t.rows[0].gpu_mesh_bytes == 40 && t.rows[0].pct_over_outside_ambiguity == 0.25,
          "results.csv: status %d '%s'", (int)s, err.message);
    oit_bench_table_free(&t);
}

/* The memory chart of a file (text) that reads, and its height: one note
 * line more for a file whose in-core figures left the mesh out. */
static int memory_chart_height(const char *dir, const char *text, const char *name)
{
    oit_bench_table t = {0};
    oit_error err = {0};
    char path[1024];
    snprintf(path, sizeof path, "%s/test_bench_plot_%s.png", dir, name);
    oit_status s = read_text(text, name, &t, &err);
    if (s == OIT_OK)
        s = oit_bench_plot_memory_depth(&t, 1, "fake", NULL, path, &err);
    oit_bench_table_free(&t);
    oit_image img = {0};
    if (s == OIT_OK)
        s = oit_image_read(path, &img, &err);
    CHECK(s == OIT_OK, "memory chart of %s: %s", name, err.message);
    int h = s == OIT_OK ? img.height : -1;
    oit_image_free(&img);
    return h;
}

static void test_memory_chart_old_note(const char *dir)
{
    int now = memory_chart_height(dir, HDR OK_ROW, "mem_new");
    int old = memory_chart_height(dir, OIT_BENCH_CSV_HEADER_18 "\n" ROW_18, "mem_old");
    printf("memory chart: %d rows (gpu_mesh_bytes), %d (older file)\n", now, old);
    CHECK(now > 0 && old == now + 22, "an older file's memory chart has %d rows, the "
          "current one's %d: expected one note line (22 rows) more saying the mesh is left "
          "out", old, now);
}

static void test_speed_chart_file(const char *dir)
{
    oit_bench_table t;
    oit_error err;
    oit_status s = fake_table("chart.csv", &t, &err);
    CHECK(s == OIT_OK, "%s", err.message);
    char path[1024];
    snprintf(path, sizeof path, "%s/test_bench_plot_speed.png", dir);
    CHECK(oit_bench_plot_speed_error(&t, "fake", NULL, path, &err) == OIT_OK, "%s", err.message);
    oit_image img;
    if (oit_image_read(path, &img, &err) != OIT_OK) {
        CHECK(0, "%s", err.message);
        oit_bench_table_free(&t);
        return;
    }
    /* four note lines (the front, what dfb and stream@0.1 drew, stream@0.1
     * not run) under 720 rows */
    CHECK(img.width == 1100 && img.height == 720 + 4 * 22, "speed chart %dx%d", img.width,
          img.height);
    float c0[3];
    oit_chart_series_colour(0, c0);
    size_t found = 0;
    for (int y = 0; y < img.height; y++)
        for (int x = 0; x < img.width; x++) {
            const float *p = pixel(&img, x, y);
            found += fabsf(p[0] - c0[0]) < 0.003f && fabsf(p[1] - c0[1]) < 0.003f &&
                     fabsf(p[2] - c0[2]) < 0.003f;
        }
    printf("speed chart: %zu pixels of dfb's colour\n", found);
    CHECK(found >= 50, "dfb's marker and label missing (%zu pixels of its colour)", found);
    oit_image_free(&img);
    oit_bench_table_free(&t);
}

int main(void)
{
    const char *dir = getenv("OIT_TEST_TMP");
    test_text();
    test_status_line_upper_case();
    test_status_fields();
    test_axes();
    test_marker_and_line();
    test_legend_overflow();
    test_pareto();
    test_csv_round_trip();
    test_csv_malformed();
    test_csv_old_format();
    test_memory_chart_old_note(dir ? dir : "/tmp");
    test_speed_chart_file(dir ? dir : "/tmp");
    return test_verdict();
}
