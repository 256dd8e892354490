/* oitstream --pick X,Y: the layers of one pixel (oit_renderer_pick,
 * oit/liboit.h) as JSON on stdout. */
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
} oit_pick_request;

/* Picks and prints; errors name the model. */
oit_status oit_pick_print(const oit_pick_request *rq, FILE *out, oit_error *err);

#endif
