/* The renderer's modes, one enum per axis: how a part file's parts are cut
 * into packs (oit_render_pack), in which order (oit_render_schedule), and
 * how the K-slot fills are made (oit_render_capture). liboit's descriptor
 * (oit/liboit.h, oit_renderer_desc) takes them, and the streamer and the
 * capture inside it work with the same values: no second spelling to keep
 * in step. */
#ifndef OIT_RENDER_MODES_H
#define OIT_RENDER_MODES_H

#ifdef __cplusplus
extern "C" {
#endif

/* The capture's layers a pixel, K (oit_renderer_desc.K). */
#define OIT_RENDER_K_MIN 2
#define OIT_RENDER_K_MAX 16
/* The most threads that read a part file's parts
 * (oit_renderer_desc.reader_threads). */
#define OIT_RENDER_READER_THREADS_MAX 64

/* How a part file's parts are cut into packs, each captured as one batch. */
typedef enum oit_render_pack {
    OIT_RENDER_PACK_AUTO = 0,    /* FIRSTK while K slots a pixel hold the view,
                                    COUNTED for deep views, each kept where it
                                    measures faster (oit_draw_stats.choice).
                                    With epsilon > 0, COUNTED and FIRSTK packs
                                    are cut front first, so that saturated
                                    pixels skip the parts behind them */
    OIT_RENDER_PACK_COUNTED,     /* packs cut by upload bytes only, each counted,
                                    stored and sorted per pixel (no layer limit) */
    OIT_RENDER_PACK_BUDGET,      /* K slots a pixel: parts share a pack while
                                    their layer bounds per tile stay <= K */
    OIT_RENDER_PACK_DISJOINT,    /* K slots a pixel: parts with disjoint screen
                                    rects */
    OIT_RENDER_PACK_FIRSTK       /* packs as COUNTED, each drawn once into up to
                                    K slots a pixel; pixels with more take a
                                    second pass for themselves alone */
} oit_render_pack;

typedef enum oit_render_schedule {
    OIT_RENDER_SCHEDULE_TREE = 0, /* the management tree's order (default) */
    OIT_RENDER_SCHEDULE_WAVE = 1  /* wavefronts of the visibility order     */
} oit_render_schedule;

typedef enum oit_render_capture {
    OIT_RENDER_CAPTURE_AUTO = 0,
    OIT_RENDER_CAPTURE_ARRAY = 1,
    OIT_RENDER_CAPTURE_STENCIL = 2,
    /* every pack captured in compute shaders, no raster pipeline, no
     * per-pixel limit */
    OIT_RENDER_CAPTURE_COMPUTE = 5
} oit_render_capture;

/* What a rendering method does (oit_render_method_info.flags). */
typedef enum oit_render_method_flag {
    OIT_RENDER_METHOD_GL = 1u << 0,        /* draws with GL: a context must be current */
    OIT_RENDER_METHOD_COUNTS = 1u << 1,    /* fills per-pixel fragment counts        */
    OIT_RENDER_METHOD_AMBIGUITY = 1u << 2, /* flags pixels where raster and ray
                                              disagree within the ambiguity radius */
    OIT_RENDER_METHOD_PART_FILE = 1u << 3, /* draws part files (else in-core scenes) */
    OIT_RENDER_METHOD_EPSILON = 1u << 4,   /* reads a threshold: epsilon            */
    OIT_RENDER_METHOD_CLIP = 1u << 5       /* honours section planes (oit_frame.clip) */
} oit_render_method_flag;

#ifdef __cplusplus
}
#endif
#endif
