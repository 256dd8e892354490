/* The tools' rendering methods, every one run by liboit (include/oit/
 * liboit.h: oit_renderer_desc.method names it), so that oitstream, its
 * viewer, oitbench and oitstream-mpi render as any program that embeds
 * liboit does and hold no renderer of their own. A run is one method on
 * one scene: a part file (the stream, options.source's path) or the
 * tools' in-core mesh (the others; liboit borrows it, not copying). Each
 * frame's view gives the camera (oit_frame.camera: no matrix round trip),
 * the shading (oit_renderer_set_shading where it changes), the
 * background, the model matrix and the section planes. */
#ifndef OIT_TOOLS_COMMON_METHOD_RUN_H
#define OIT_TOOLS_COMMON_METHOD_RUN_H

#include "oit/liboit.h"
#include "view/render/gl/gpu_timer.h"
#include "view/render/image/image.h"
#include "view/render/image/view.h"

struct oit_gl;

typedef struct oit_run_source {
    /* the part file (.oitp) of a PART_FILE method; for the others, the
     * file the mesh was read from, which names it in their errors */
    const char *path;
    /* liboit's settings, zero meaning default; the method, K, epsilon,
     * ambiguity_px and binding_limit come from the options, the shading
     * from each frame's view. */
    oit_renderer_desc desc;
} oit_run_source;

typedef struct oit_run_options {
    int max_layers; /* K; 0: liboit's default */
    /* NULL: a GL method runs in a headless context of the run's own. Else
     * in this one, current on the calling thread (the viewer's window). */
    struct oit_gl *gl;
    const float *threshold; /* a method with OIT_RENDER_METHOD_EPSILON; NULL: its default */
    float ambiguity_px;     /* the reference's; 0: 1/64 */
    const oit_run_source *source; /* NULL: no part file, liboit's defaults */
    uint64_t store_limit;   /* liboit's binding_limit */
} oit_run_options;

typedef struct oit_run oit_run;

/* Opens method m on mesh (in-core methods; it must outlive the run) or
 * on opt->source->path (PART_FILE methods). */
oit_status oit_run_open(const oit_render_method_info *m, const oit_mesh *mesh,
                        const oit_run_options *opt, oit_run **out, oit_error *err);
/* out is allocated by the call; counts and ambiguous (width*height) may be
 * NULL, and are filled only where the method's flags say it can. Errors
 * name the tools' flags (flag_spelling.h). */
oit_status oit_run_render(oit_run *run, const oit_view *view, oit_image *out, uint32_t *counts,
                          uint8_t *ambiguous, oit_frame_stats *stats, oit_error *err);
/* "llvmpipe (LLVM 15.0.6, 256 bits)", "Embree 3.13.5 (CPU reference)", ... */
const char *oit_run_renderer(const oit_run *run);
const oit_render_method_info *oit_run_method(const oit_run *run);
/* GPU time of earlier frames, oldest first (oit_renderer_gpu_poll). */
int oit_run_gpu_poll(oit_run *run, oit_gpu_times *out, int wait);
/* NULL when the method's frames are timed on the GPU, else why not. */
const char *oit_run_gpu_absent(const oit_run *run);
void oit_run_close(oit_run *run);

/* liboit's figures of the last frame, and the descriptor its renderer
 * draws with (every default resolved: oit_renderer_get_desc), of a
 * PART_FILE method: NULL and 0 for the others or before a frame. */
const oit_draw_stats *oit_run_stream_stats(const oit_run *run);
int oit_run_stream_desc(const oit_run *run, oit_renderer_desc *out);

/* The tools' view in liboit's spelling, for the runs and oitstream-mpi
 * alike: the resolved shading onto d's (and see_through); the frame of v
 * (viewport size, camera: cam, which fr points to, the model matrix, the
 * section planes), framebuffer 0. */
void oit_run_shading(const oit_shading *in, oit_renderer_desc *d);
/* The tools' camera as liboit's oit_frame_camera, field for field (an
 * orthographic camera by its height, a perspective one by fovy). */
oit_frame_camera oit_run_camera(const oit_camera *c);
void oit_run_frame(const oit_view *v, oit_frame_camera *cam, oit_frame *fr);

#endif
