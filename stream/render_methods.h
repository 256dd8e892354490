/* The rendering methods oitstream offers, behind one small interface so that
 * a new method (the part-file streamer) is one more table entry. A method
 * is opened once per run (context, uploads), renders any number of views,
 * and is closed. Only methods with uses_gl create a GL context. */
#ifndef OIT_STREAM_RENDER_METHODS_H
#define OIT_STREAM_RENDER_METHODS_H

#include "render/view.h"
#include "stream/streamer.h"

typedef struct oit_method_state oit_method_state;

typedef struct oit_method_options {
    int max_layers; /* K of the capture backends */
    /* the part-file streamer (methods with needs_partfile) */
    oit_partfile *partfile;
    oit_pack_mode pack;
    oit_pack_schedule schedule;
    unsigned long long upload_budget; /* bytes; 0: default */
    /* NULL: GL methods make their own headless context. Else they render in
     * this one, current on the calling thread (the viewer's window), and do
     * not destroy it. */
    struct oit_gl *gl;
    /* The streamer's early termination, f2b's alpha threshold, guarded's
     * contribution threshold (0: none); < 0: the method's default (stream:
     * 0, exact; f2b, guarded: their seed's values). */
    float epsilon;
    unsigned long long slot_budget; /* the streamer's capture slots, bytes; 0: default */
    /* The streamer's residency cache, bytes; 0: default (OIT_STREAM_CACHE_DEFAULT);
     * OIT_STREAM_CACHE_OFF: none. */
    unsigned long long cache_budget;
    int read_inline; /* the streamer reads parts on the render thread, no reader thread */
    float ambiguity_px; /* the reference's ambiguity radius, pixels; 0: 1/64 */
} oit_method_options;

typedef struct oit_render_method {
    const char *name;
    int uses_gl;
    int has_counts; /* can fill per-pixel fragment counts (--show layers) */
    int has_ambiguity; /* can flag raster-vs-ray ambiguous pixels (--ambiguity) */
    oit_status (*open)(const oit_mesh *mesh, const oit_method_options *opt,
                       oit_method_state **out, oit_error *err);
    /* out is allocated by the call; counts and ambiguous (width*height) may
     * be NULL, and are only passed where has_counts / has_ambiguity. */
    oit_status (*render)(oit_method_state *st, const oit_view *view, oit_image *out,
                         uint32_t *counts, uint8_t *ambiguous, oit_frame_stats *stats,
                         oit_error *err);
    /* "llvmpipe (LLVM 15.0.6, 256 bits)", "Embree 3.13.5 (CPU)", ... */
    const char *(*renderer)(const oit_method_state *st);
    void (*close)(oit_method_state *st);
    /* Renders opt->partfile (mesh is then empty) instead of the mesh. */
    int needs_partfile;
    /* The streamer's figures of the last frame; NULL for other methods. */
    const oit_stream_frame_stats *(*stream_stats)(const oit_method_state *st);
    /* Takes oit_method_options.epsilon as a threshold (early termination or
     * fragment culling), so a benchmark can sweep it. */
    int takes_epsilon;
} oit_render_method;

/* NULL when no method has that name. */
const oit_render_method *oit_render_method_find(const char *name);
/* Writes "dfb|reference|array|...|f2b" (the table's names) into buf, for
 * --help and error messages; OIT_METHOD_NAMES_MAX bytes hold them all. */
#define OIT_METHOD_NAMES_MAX 256
void oit_render_method_names(char *buf, size_t cap);

#endif
