/* The layers of one pixel (oit_renderer_pick, oit/liboit.h) for
 * oitstream --pick X,Y, as JSON, and for the viewer's I key and click. */
#ifndef OIT_OITSTREAM_PICK_JSON_H
#define OIT_OITSTREAM_PICK_JSON_H

#include <stdio.h>

#include "oit/liboit.h"
#include "view/render/image/view.h"

typedef struct oit_pick_request {
    const char *model;  /* as given: a part file (.oitp) is picked part by part */
    int part_file;
    const oit_mesh *mesh; /* in core: the scene (not a part file) */
    const char *method; /* liboit's name: the reference picks through Embree */
    const oit_view *view;
    int x, y;
    const double *origin; /* the model's (oit_mesh_info.origin): points in file
                             coordinates; NULL: the scene's own */
} oit_pick_request;

/* Every layer into *layers (allocated, n of them; NULL when none); errors
 * name the model. */
oit_status oit_pick_get(const oit_pick_request *rq, oit_pick_layer **layers, size_t *n,
                        oit_error *err);
/* Picks and prints; errors name the model. */
oit_status oit_pick_print(const oit_pick_request *rq, FILE *out, oit_error *err);

#endif
