/* The viewer's section-plane keys (viewer.h; planes: view/render/image/clip.h).
 *   X  no plane yet: one through the model's centre, facing the viewer
 *      (the near half is cut away); else the planes off, and on again
 *   ]  the first plane moves along its normal, cutting more away
 *   [  the first plane moves back
 * Each step is 1/25 of the model's bounding radius. The note names the
 * plane as --clip takes it: in the file's coordinates (origin added back). */
#ifndef OIT_OITSTREAM_VIEWER_CLIP_H
#define OIT_OITSTREAM_VIEWER_CLIP_H

#include <stddef.h>

#include "view/render/image/view.h"

typedef struct oit_viewer_clip {
    oit_clip planes; /* as set (--clip, X, [ and ]) */
    int off;         /* X turned them off */
} oit_viewer_clip;

/* Applies key: returns 1 when it changed the planes (note says how, for
 * stdout), -1 when it was a plane key that could do nothing (note says
 * why, for the screen), 0 for any other key. */
int oit_viewer_clip_key(oit_viewer_clip *c, char key, const oit_camera *cam,
                        const float centre[3], float radius, const double origin[3],
                        char *note, size_t cap);

/* The planes a frame renders with. */
oit_clip oit_viewer_clip_shown(const oit_viewer_clip *c);

#endif
