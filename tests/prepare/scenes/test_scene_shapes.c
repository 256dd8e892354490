/* Unit test of the scene solids: each primitive, written through the
 * emitter and the PLY writer and read back independently, must be closed
 * with every edge used once in each direction (consistent winding), have
 * positive signed volume (counter-clockwise seen from outside) close to the
 * analytic volume of the faceted shape, and make exactly the triangles its
 * cost function promised. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/lib/scene_ply_check.h"
#include "prepare/scenes/shapes.h"
#include "tests/lib/test_check.h"
#include "tests/lib/test_files.h"


typedef void (*shape_fn)(oit_emit *e, int seg);

static char path[600];

static void box_fn(oit_emit *e, int seg) { oit_shape_box(e, oit_v3_make(-1, 2, 3), oit_v3_make(1, 2.5f, 7)); }
static void ibeam_fn(oit_emit *e, int seg) { oit_shape_ibeam(e, oit_v3_make(0, 0, 0), oit_v3_make(4, 1, 2), 0, 1); }
/* (width z, up x, along y) is right-handed, the one above is not. */
static void ibeam_up_x_fn(oit_emit *e, int seg) { oit_shape_ibeam(e, oit_v3_make(0, 0, 0), oit_v3_make(1, 4, 2), 1, 0); }
static void cyl_fn(oit_emit *e, int seg) { oit_shape_cylinder(e, oit_v3_make(1, 1, 1), oit_v3_make(1, 4, 1), 0.5f, seg); }
static void cyl_diag_fn(oit_emit *e, int seg) { oit_shape_cylinder(e, oit_v3_make(0, 0, 0), oit_v3_make(2, 2, 1), 0.5f, seg); }
static void sphere_fn(oit_emit *e, int seg) { oit_shape_sphere(e, oit_v3_make(3, 0, 0), 2.0f, seg); }
static void tank_fn(oit_emit *e, int seg) { oit_shape_tank(e, oit_v3_make(0, 1, 0), oit_v3_make(0, 5, 0), 1.5f, seg); }
static void torus_fn(oit_emit *e, int seg) { oit_shape_torus(e, oit_v3_make(0, 0, 0), oit_v3_make(0, 0, 1), 2, 0.5f, 1, 0, 2 * seg, seg); }
static void band_fn(oit_emit *e, int seg) { oit_shape_torus(e, oit_v3_make(0, 0, 0), oit_v3_make(0, 1, 0), 3, 0.5f, 0.1f, 2, 8 * seg, seg); }

static const oit_v3 ROUTE[5] = {{0, 0, 0}, {3, 0, 0}, {3, 4, 0}, {3, 4, -2}, {6, 4, -2}};
static void pipe_fn(oit_emit *e, int seg) { oit_shape_pipe(e, ROUTE, 5, 0.2f, 0.3f, seg); }

/* Area of a regular seg-gon inscribed in the unit circle, over pi. */
static double polygon_factor(int seg)
{
    return seg / (2 * OIT_PI) * sin(2 * OIT_PI / seg);
}

static void check_shape(const char *name, shape_fn fn, int seg, uint64_t cost, size_t parts,
                        double volume, double tol)
{
    oit_ply_writer_desc d = {.path = path, .vertex_rgba = 1};
    oit_ply_writer *w;
    oit_error err = {0};
    oit_emit e;
    CHECK(!oit_ply_writer_open(&d, &w, &err), "open: %s", err.message);
    oit_emit_init(&e, w, &err);
    oit_emit_color(&e, 10, 20, 30, 128);
    fn(&e, seg);
    CHECK(!oit_emit_flush(&e), "emit: %s", err.message);
    oit_emit_free(&e);
    CHECK(!oit_ply_writer_close(w, NULL, &err), "close: %s", err.message);
    test_ply p;
    if (test_ply_load(&p, path)) {
        CHECK(0, "%s: %s", name, p.why);
        return;
    }
    size_t open = test_ply_open_edges(&p), comps, inverted, multi;
    test_ply_components(&p, &comps, &inverted, &multi);
    double v = test_ply_volume(&p, 0, p.faces);
    printf("%-12s seg %3d: %6zu triangles (cost %6llu) %2zu solids, %zu bad edges, %zu inside out, "
           "volume %.5f (expected %.5f)\n",
           name, seg, p.faces, (unsigned long long)cost, comps, open, inverted, v, volume);
    CHECK(p.faces == cost, "%s: %zu triangles, cost function says %llu", name, p.faces, (unsigned long long)cost);
    CHECK(open == 0, "%s: %zu edges not matched by exactly one reverse edge", name, open);
    CHECK(comps == parts && inverted == 0, "%s: %zu solids (expected %zu), %zu inside out", name, comps, parts, inverted);
    CHECK(fabs(v - volume) <= tol * volume, "%s: volume %.6f, expected %.6f within %.0f%%", name, v, volume, 100 * tol);
    test_ply_free(&p);
}

int main(void)
{
    test_tmp_path(path, sizeof path, "scene_shape.ply");
    check_shape("box", box_fn, 0, OIT_BOX_TRIS, 1, 2 * 0.5 * 4, 1e-6);
    /* flanges 0.15 of the height each, web 0.12 of the width, 4 long */
    check_shape("ibeam", ibeam_fn, 0, OIT_IBEAM_TRIS, 1, 4 * (2 * 0.15 * 2 + 0.7 * 0.12 * 2), 1e-5);
    check_shape("ibeam/up x", ibeam_up_x_fn, 0, OIT_IBEAM_TRIS, 1, 4 * (2 * 0.15 * 2 + 0.7 * 0.12 * 2), 1e-5);
    static const int segs[] = {3, 8, 24};
    for (int i = 0; i < 3; i++) {
        int s = segs[i];
        double pf = polygon_factor(s);
        check_shape("cylinder", cyl_fn, s, oit_shape_cylinder_cost(s), 1, pf * OIT_PI * 0.25 * 3, 1e-5);
        check_shape("cylinder/xyz", cyl_diag_fn, s, oit_shape_cylinder_cost(s), 1, pf * OIT_PI * 0.25 * 3, 1e-4);
        if (s < 8)
            continue;
        /* Doubly curved solids: the smooth volume scaled by the ring's
         * polygon factor, with a tolerance that shrinks as the faceting
         * error (1 - factor) does: 22% at 8, 4% at 24. */
        double tol = 2 * (1 - pf) + 0.02;
        check_shape("sphere", sphere_fn, s, oit_shape_sphere_cost(s), 1, pf * 4.0 / 3 * OIT_PI * 8, tol);
        check_shape("tank", tank_fn, s, oit_shape_tank_cost(s), 1,
                    pf * (OIT_PI * 1.5 * 1.5 * 4 + 4.0 / 3 * OIT_PI * 1.5 * 1.5 * 1.5), tol);
        check_shape("torus", torus_fn, s, oit_shape_torus_cost(2 * s, s), 1,
                    pf * 2 * OIT_PI * OIT_PI * 2 * 0.25, tol);
        check_shape("twisted band", band_fn, s, oit_shape_torus_cost(8 * s, s), 1,
                    pf * 2 * OIT_PI * 3 * OIT_PI * 0.5 * 0.05, tol);
        /* Path length: legs 3+4+2+3 less (2 - pi/2) * bend per elbow. */
        double len = 12 - 3 * (2 - OIT_PI / 2) * 0.3;
        check_shape("pipe", pipe_fn, s, oit_shape_pipe_cost(5, s), 1, pf * OIT_PI * 0.04 * len, 0.03);
    }
    remove(path);
    return test_verdict();
}
