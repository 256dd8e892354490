/* The registry's "stream" method: a part file rendered through liboit's
 * public API (include/oit/liboit.h: oit_scene_open, oit_renderer_draw_image),
 * behind the tools' method interface (render/method.h), so oitstream, its
 * viewer and oitbench stream as any program that embeds liboit does, and
 * print the figures it gives (oit_draw_stats). The image is the capture's
 * own resolve over the view's background, bit for bit the streamer's.
 *
 * options.source points to an oit_stream_source; options.max_layers is K,
 * options.threshold (where given) the early termination epsilon and
 * options.store_limit the renderer's binding_limit. Each frame's view
 * gives the camera (oit_frame.camera: no matrix round trip), the shading
 * (resolved: the renderer is made anew when it changes), the background,
 * the model matrix and the section planes. */
#ifndef OIT_TOOLS_COMMON_METHOD_STREAM_H
#define OIT_TOOLS_COMMON_METHOD_STREAM_H

#include "oit/liboit.h"
#include "render/method.h"

typedef struct oit_stream_source {
    const char *path;       /* the part file (.oitp) */
    /* liboit's settings, zero meaning default; K, epsilon and
     * binding_limit come from the method options, the shading from each
     * frame's view. */
    oit_renderer_desc desc;
} oit_stream_source;

extern const oit_method oit_method_stream;

/* The tools' view in liboit's spelling, for the stream method and
 * oitstream-mpi alike: the resolved shading onto d's (and see_through);
 * the frame of v (viewport size, camera: cam, which fr points to, the
 * model matrix, the section planes), framebuffer 0. */
void oit_stream_shading(const oit_shading *in, oit_renderer_desc *d);
/* The tools' camera as liboit's oit_frame_camera, field for field (an
 * orthographic camera by its height, a perspective one by fovy). */
oit_frame_camera oit_stream_camera(const oit_camera *c);
void oit_stream_frame(const oit_view *v, oit_frame_camera *cam, oit_frame *fr);

/* liboit's figures of st's last frame; NULL when st is not the stream
 * method or has not rendered. */
const oit_draw_stats *oit_method_stream_stats(const oit_method_state *st);
/* The descriptor st's renderer draws with, every default resolved
 * (oit_renderer_get_desc); 0 when st is not the stream method or has not
 * rendered. */
int oit_method_stream_desc(const oit_method_state *st, oit_renderer_desc *out);

#endif
