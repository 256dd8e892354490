/* Section planes: what the tools, liboit's oit_frame.clip and Python's
 * oit.render(clip=...) set, defined and checked here once.
 *
 * Convention: a plane (a, b, c, d) KEEPS the points p of world space (the
 * camera's space: after oit_view.model, the scene's coordinates less its
 * origin) where a px + b py + c pz + d >= 0, and removes the rest, as
 * oit_camera_frustum's planes do. With several planes a point is kept only
 * where every one keeps it (their intersection), so (0, 0, 1, 0) keeps
 * z >= 0 and (0, 0, -1, 0) beside it keeps only the plane z = 0.
 *
 * Exact, per pixel: a fragment is kept when every plane keeps the point
 * where its pixel centre's ray meets its triangle's plane (the tie rule's
 * t, shade.h), tested in view space with the planes of oit_clip_eye; the
 * GL methods test it in the fragment stage (frag_glsl.h oit_clipped) and
 * the Embree reference on each hit, with the same float operations, so
 * they agree but where a hit lies within rounding of a plane. */
#ifndef OIT_RENDER_CLIP_H
#define OIT_RENDER_CLIP_H

#include "oit/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OIT_CLIP_MAX 6

/* count 0 (all zero): no plane. plane[i] for i < count: (a, b, c, d). */
typedef struct oit_clip {
    int count;
    float plane[OIT_CLIP_MAX][4];
} oit_clip;

/* The one check: count in 0..OIT_CLIP_MAX, every number finite, every
 * normal (a, b, c) non-zero. what names the setting in the message
 * ("oit_frame.clip"; a tool its flag). */
oit_status oit_clip_check(const oit_clip *c, const char *what, oit_error *err);

/* Appends the plane "a,b,c,d" given in the file's coordinates (origin, the
 * point the positions are relative to, or NULL: 0; d is shifted by
 * n . origin in double) and checks the result with oit_clip_check. */
oit_status oit_clip_add_text(oit_clip *c, const char *text, const double origin[3],
                             const char *what, oit_error *err);

/* Planes as a command line gives them, in the file's coordinates and in
 * double, parsed and checked once (oit_clip_given_add_text) before the
 * file is read, and placed once its origin is known (oit_clip_place). */
typedef struct oit_clip_given {
    int count;
    double plane[OIT_CLIP_MAX][4];
} oit_clip_given;
/* Appends "a,b,c,d" to g when the planes so far and it pass oit_clip_check
 * (placed at origin 0); else OIT_ERR_ARGUMENT naming what and the text. */
oit_status oit_clip_given_add_text(oit_clip_given *g, const char *text, const char *what,
                                   oit_error *err);
/* g's planes relative to origin (NULL: 0), d shifted by n . origin in
 * double, into *out (replaced), then checked. */
oit_status oit_clip_place(const oit_clip_given *g, const double origin[3], const char *what,
                          oit_clip *out, oit_error *err);

/* The planes in the view space of a camera whose view matrix (world to
 * eye, rigid, column-major; oit_camera_view_matrix) is m, in double from
 * the float matrix, rounded: what the fragment stage and the reference
 * test. Planes past count are set to 0. */
void oit_clip_eye(const oit_clip *c, const float m[16], float out[OIT_CLIP_MAX][4]);

/* 1 when every plane of eye (view space, oit_clip_eye) keeps the point
 * o + dir * t, computed in float in the order the fragment stage's
 * oit_clipped() computes it (GLSL precise), so that the reference and the
 * GL methods round alike. */
int oit_clip_keeps(int count, const float eye[OIT_CLIP_MAX][4], const float o[3],
                   const float dir[3], float t);

/* The planes in model space for a model matrix mm (column-major, affine;
 * a plane p on M x is M^T p on x). */
void oit_clip_model(const oit_clip *c, const double mm[16], double out[OIT_CLIP_MAX][4]);

/* 1 when the box [lo, hi] lies wholly on the removed side of one of the
 * planes (model space, oit_clip_model), by more than a margin that covers
 * the rounding of the per-pixel test: nothing of it can be kept. */
int oit_clip_box_outside(int count, const double planes[OIT_CLIP_MAX][4], const float lo[3],
                         const float hi[3]);

#ifdef __cplusplus
}
#endif
#endif
