/* A voxel occupancy grid for placing solids without clashes.
 *
 * Scenes that model engineered plants keep their objects apart, as plant
 * design does (clash detection is part of every design review): a solid is
 * placed only when the boxes that cover it are clear of everything placed
 * before, by a clearance. Boxes are marked conservatively (every voxel they
 * touch), so two boxes that never share a voxel are disjoint: the test is
 * exact in the direction that matters, never calling a clash clear. */
#ifndef OIT_SCENES_OCCUPANCY_H
#define OIT_SCENES_OCCUPANCY_H

#include <stdint.h>

#include "prepare/scenes/emit.h"

typedef struct oit_occupancy {
    oit_v3 origin;
    float voxel;
    int dims[3];
    uint64_t *bits; /* owned: dims[0] * dims[1] * dims[2] bits */
} oit_occupancy;

/* A grid over lo..hi with cubic voxels of edge `voxel`; boxes outside it are
 * clipped to it. Returns OIT_ERR_NOMEM when the bits cannot be allocated. */
oit_status oit_occupancy_init(oit_occupancy *o, oit_v3 lo, oit_v3 hi, float voxel);
void oit_occupancy_free(oit_occupancy *o);
/* Empties the grid and moves it to a new origin (same size). */
void oit_occupancy_reset(oit_occupancy *o, oit_v3 origin);

/* 1 when the box lo..hi grown by `clearance` on every side touches no
 * marked voxel. */
int oit_occupancy_clear(const oit_occupancy *o, oit_v3 lo, oit_v3 hi, float clearance);
/* Marks every voxel the box lo..hi touches. */
void oit_occupancy_mark(oit_occupancy *o, oit_v3 lo, oit_v3 hi);

#endif
