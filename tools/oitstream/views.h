/* oitstream's views, shading, output names and stream settings from its
 * command line,
 * shared with oitstream-mpi (tools/oitstream_mpi), which takes the same
 * options. */
#ifndef OIT_OITSTREAM_VIEWS_H
#define OIT_OITSTREAM_VIEWS_H

#include <stddef.h>

#include "oit/liboit.h"
#include "oit/mesh.h"
#include "oit/partfile.h"
#include "view/render/image/view.h"
#include "tools/oitstream/cli_args.h"

/* The cameras of --view, --orbit, --walk or --azimuth/--elevation (with
 * --ortho), in the model's coordinates; *out allocated by the call. */
oit_status make_views(const oit_stream_args *a, const oit_mesh_info *info,
                      oit_camera **out, int *count, oit_error *err);
/* The shading options with the model's attributes and defaults resolved. */
oit_shading make_shading(const oit_stream_args *a, const oit_mesh_info *info);
/* --out's file for view index of views: FILE.png for one view, FILE_007.png
 * for several, DIR/frame_007.png for a folder (created when missing). */
oit_status output_path(const char *out, int index, int views, char *buf, size_t cap,
                       oit_error *err);
/* --up auto resolved: the model's up axis (formats/up_axis.h; a part file
 * by its source's name), said on stderr where it is not y and the
 * default views use it. */
int stream_up_axis(const oit_stream_args *a, oit_partfile *pf, const oit_mesh_info *info);
/* The captures' K: --max-layers, else the part file's (its parts were cut
 * for it), else 16; pf may be NULL (a mesh). */
int stream_max_layers(const oit_stream_args *a, oit_partfile *pf);
/* The command line's liboit descriptor (oit_stream_args.stream) for a
 * run of views frames: one frame (outside the window) has no next frame
 * to keep parts for, so the default cache is off there. */
oit_renderer_desc stream_renderer_desc(const oit_stream_args *a, int views);

#endif
