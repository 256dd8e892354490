/* The scenes oitgen can generate. Each emits closed, outward-wound,
 * per-object coloured geometry into an emitter and is a pure function of its
 * arguments (same arguments, same triangles in the same order). Argument
 * ranges are checked by oitgen before a scene runs; a scene fails only on
 * I/O (its emitter's sticky status) or bad input (instances). */
#ifndef OIT_SCENES_SCENE_H
#define OIT_SCENES_SCENE_H

#include <stdint.h>

#include "prepare/scenes/emit.h"

typedef struct oit_scene_args {
    uint64_t seed;
    uint64_t count;     /* quads, instances */
    double coverage;    /* quads: fraction of the [-1,1]^2 square per quad */
    uint64_t triangles; /* plant: target triangle count */
    int clashes;        /* plant: 1 lets objects run through each other */
    const char *input;  /* instances: mesh to replicate */
    const char *hard_case; /* hard: which case (oit_scene_hard_case_name) */
} oit_scene_args;

/* Triangles a scene will make, for progress; 0 when unknown. */
uint64_t oit_scene_quads_estimate(const oit_scene_args *a);
uint64_t oit_scene_plant_estimate(const oit_scene_args *a);

oit_status oit_scene_quads(oit_emit *e, const oit_scene_args *a, oit_error *err);
oit_status oit_scene_instances(oit_emit *e, const oit_scene_args *a, oit_error *err);
oit_status oit_scene_plant(oit_emit *e, const oit_scene_args *a, oit_error *err);
oit_status oit_scene_demo(oit_emit *e, const oit_scene_args *a, oit_error *err);
oit_status oit_scene_hard(oit_emit *e, const oit_scene_args *a, oit_error *err);
/* The hard cases by index, NULL past the last. */
const char *oit_scene_hard_case_name(int i);
/* 1 when the case must be written as doubles offset by offset[] (far). */
int oit_scene_hard_offset(const oit_scene_args *a, double offset[3]);

/* HSV (h in turns, s and v in 0..1) to 8-bit RGB, for scene palettes. */
void oit_scene_hsv(float h, float s, float v, uint8_t rgb[3]);

#endif
