/* The counted capture's steps (capture_counted.h), shared by its batches
 * (capture_counted.c) and its predicted batches
 * (capture_counted_predicted.c); internal to those two files. */
#ifndef OIT_RENDER_CAPTURE_COUNTED_STEPS_H
#define OIT_RENDER_CAPTURE_COUNTED_STEPS_H

#include "view/render/capture/capture_counted.h"

/* The most bands of a batch one slot of the band table holds. */
enum { OIT_COUNTED_BANDS = 62 };

/* k->offsets = the exclusive scan of the frame's counts (pixels + 1
 * entries, the last = the fragments), the counts over `over` counted. */
oit_status oit_counted_scan_counts(oit_counted *k, const oit_counted_frame *f, uint32_t over,
                                   oit_error *err);
/* Rows [y0, y1) of the scan in offsets cut in bands into batch j's slot of
 * the band table: one where they fit the store (fit), else of at most
 * target fragments. */
void oit_counted_split(oit_counted *k, const oit_counted_frame *f, GLuint offsets, size_t j, int y0,
                       int y1, uint64_t fit, uint64_t target);
/* The band of rows r of the scan in offsets judged against the store into
 * the judge's words; with first, the scan's counts over K added to the
 * frame's deep pixels. */
void oit_counted_judge(oit_counted *k, const oit_counted_frame *f, GLuint offsets, const int r[4],
                       int first);
/* The band r of k->offsets judged, stored and resolved as the judge says. */
oit_status oit_counted_judged_store(oit_counted *k, const oit_counted_frame *f,
                                    const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                    int first, oit_error *err);
/* The end rows of the bands the last frame cut batch j in, within r's rows
 * (the last r's end); returns how many. */
int oit_counted_foreseen_bands(const oit_counted *k, size_t j, const int r[4],
                               int ends[OIT_COUNTED_BANDS + 1]);
/* The store sized for the need. */
oit_status oit_counted_reserve_need(oit_counted *k, oit_error *err);
/* The predicted passes' programs, where not built yet. */
void oit_counted_build_predicted(oit_counted *k);

/* capture_counted_predicted.c: batch j's counts, scanned in *offsets,
 * kept as the next frame's prediction (buffers exchanged) where the
 * budget leaves room for it; whether batch j of frame f is drawn
 * predicted; and that batch. */
void oit_counted_keep_prediction(oit_counted *k, const oit_counted_frame *f, size_t j,
                                 GLuint *offsets, uint64_t *cap);
int oit_counted_predicts(const oit_counted *k, const oit_counted_frame *f, size_t j);
oit_status oit_counted_predicted_batch(oit_counted *k, const oit_counted_frame *f,
                                       const oit_gpu_mesh *const *meshes, int n, const int r[4],
                                       uint64_t fit, uint64_t target, oit_error *err);

#endif
