/* Which way is up in a model (0 x, 1 y, 2 z), for the default views of the
 * tools and of liboit's offscreen API: what the file's format says where it
 * says it, else what its bounds suggest, else y (the convention of scanned
 * meshes and of GL). */
#ifndef OIT_FORMATS_UP_AXIS_H
#define OIT_FORMATS_UP_AXIS_H

/* path: the model's file name (a part file's source name: its extension is
 * what counts, a trailing .gz skipped); bounds of its triangles. *why (may
 * be NULL) gets a static phrase for a message: "glTF is Y-up", "STEP and
 * IGES are Z-up", "flat in z", "the default".
 *   - .gltf .glb: y, as the glTF specification fixes;
 *   - .step .stp .iges .igs: z, as CAD systems write them;
 *   - any other: z where the z extent is below half of both the x and the
 *     y extent (a plant, a building, a board modelled Z-up: wide, flat in
 *     z), else y. A Y-up model is never flat in z alone by that test unless
 *     it is deep and low (then a z-up view shows it from above, which is
 *     what such a model needs too); a tall Z-up model keeps y (the caller's
 *     choice overrides: the tools' up axis option). */
int oit_up_axis_guess(const char *path, const float bmin[3], const float bmax[3],
                      const char **why);

#endif
