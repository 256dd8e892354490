/* Closed solids built on emit.h: boxes, I-beams, cylinders, spheres, tanks,
 * tori and pipe runs with elbows. Each has a cost function giving the exact
 * triangle count it will emit, so scenes can plan against a triangle budget
 * before emitting anything. All solids are closed, wound counter-clockwise
 * seen from outside, and share vertices within the solid (watertight by
 * index). */
#ifndef OIT_SCENES_SHAPES_H
#define OIT_SCENES_SHAPES_H

#include "prepare/scenes/emit.h"

/* Axis-aligned box. */
enum { OIT_BOX_TRIS = 12, OIT_IBEAM_TRIS = 44 };
void oit_shape_box(oit_emit *e, oit_v3 lo, oit_v3 hi);
/* A box on 8 corners: corner i lies on the +x side of its frame when bit 0
 * is set, +y for bit 1, +z for bit 2; the frame must be right-handed for the
 * faces to point outward. */
void oit_shape_hexahedron(oit_emit *e, const oit_v3 corner[8]);

/* I-profile filling the box lo..hi: flanges stacked along axis `up`, running
 * along axis `along` (0 x, 1 y, 2 z, different). One closed prism. */
void oit_shape_ibeam(oit_emit *e, oit_v3 lo, oit_v3 hi, int along, int up);

/* Cylinder p0..p1 with flat caps. */
uint64_t oit_shape_cylinder_cost(int seg);
void oit_shape_cylinder(oit_emit *e, oit_v3 p0, oit_v3 p1, float r, int seg);

/* UV sphere: seg around, seg/2 stacks. */
uint64_t oit_shape_sphere_cost(int seg);
void oit_shape_sphere(oit_emit *e, oit_v3 c, float r, int seg);

/* Tank: cylinder p0..p1 ending in two hemispherical heads (outside p0..p1). */
uint64_t oit_shape_tank_cost(int seg);
void oit_shape_tank(oit_emit *e, oit_v3 p0, oit_v3 p1, float r, int seg);

/* Torus around unit axis n through c: major radius R (seg_major rings),
 * minor radius r (seg_minor points per ring). twist_turns rotates an
 * elliptical section (r by r * aspect) whole turns around the loop, making a
 * twisted band when aspect < 1. */
uint64_t oit_shape_torus_cost(int seg_major, int seg_minor);
void oit_shape_torus(oit_emit *e, oit_v3 c, oit_v3 n, float R, float r, float aspect,
                     int twist_turns, int seg_major, int seg_minor);

/* Pipe run through points p[0..n-1] (n >= 2, consecutive legs at right
 * angles, each leg longer than 2 * bend where it meets an elbow): straight
 * tubes joined by elbows (quarter tori of radius bend), flat caps at both
 * ends. */
enum { OIT_PIPE_MAX_POINTS = 8 };
uint64_t oit_shape_pipe_cost(int n, int seg);
void oit_shape_pipe(oit_emit *e, const oit_v3 *p, int n, float r, float bend, int seg);

#endif
