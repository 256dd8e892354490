/* oitbench's measurement: every entry of a list (a method, at a threshold
 * for those that take one) over an orbit of views, interleaved view-major
 * (warm-up then timed frames per entry, entries round-robin) so that clock
 * or thermal drift hits all alike, each view's image compared with the
 * Embree reference of that view. An entry that cannot open, or fails on a
 * view, is kept with the reason. */
#ifndef OIT_OITBENCH_BENCH_RUN_H
#define OIT_OITBENCH_BENCH_RUN_H

#include <stdint.h>

#include "oit/partfile.h"
#include "oit/render_modes.h"
#include "view/render/image/image.h"
#include "tools/common/method_run.h"
#include "tools/common/methods.h"

/* Which triangles a method drew (bench_models.h): the source mesh in core,
 * or the part file's, clipped at its part boundaries (the stream's, or an
 * in-core method's when the source mesh is not at hand). */
typedef enum oit_bench_geometry {
    OIT_BENCH_GEOMETRY_SOURCE_MESH = 0,
    OIT_BENCH_GEOMETRY_PART_FILE
} oit_bench_geometry;

/* "source mesh", "part file" or, when the part file holds more triangles
 * than the source (its planes cut some), "part file (clipped)", for
 * reports; the CSV spells them source_mesh and part_file. */
const char *oit_bench_geometry_label(oit_bench_geometry g, uint64_t drawn, uint64_t source);

/* One method on one view. */
typedef struct oit_bench_cell {
    int ok;                  /* rendered all its frames of this view */
    double ms_median, ms_p95;
    /* Every GPU buffer and texture at the peak, the mesh an in-core method
     * uploaded included (oit_frame_stats.gpu_bytes_peak), and that mesh's
     * part of it (gpu_mesh_bytes; 0 for the stream and the reference). */
    uint64_t gpu_bytes_peak, gpu_mesh_bytes;
    uint32_t max_layers;
    uint64_t fragments;      /* of the last timed frame */
    oit_image_diff diff;     /* last timed frame against the reference */
    /* diff's % of pixels off by > 1/255 over the pixels outside the
     * reference's ambiguity mask (OIT_RENDER_METHOD_AMBIGUITY: a pixel
     * centre within the ambiguity radius of an edge, where raster and ray
     * may disagree): ~0 for an exact method, whose diff may not be */
    double pct_over_outside_ambiguity;
    double gpu_ms_median;    /* GPU time (view/render/gl/gpu_timer.h); -1: not timed */
    /* the most host waits on the GPU of a timed frame
     * (oit_frame_stats.host_waits: the stream's; 0 where not counted) */
    uint32_t host_waits_max;
} oit_bench_cell;

/* What to run: a method, and the threshold oit_run_options.threshold
 * passes it (< 0: none, the method's default); name labels it in every output
 * ("stream", "stream@0.01"). */
#define OIT_BENCH_NAME_MAX 64
typedef struct oit_bench_entry {
    const char *method;
    float epsilon;
    char name[OIT_BENCH_NAME_MAX];
} oit_bench_entry;

typedef struct oit_bench_method {
    const oit_render_method_info *method;
    char name[OIT_BENCH_NAME_MAX];
    float epsilon;           /* as oit_bench_entry */
    oit_bench_geometry geometry; /* what it draws */
    uint64_t triangles;      /* how many triangles that is */
    uint64_t source_triangles; /* the source model's (oit_bench_desc) */
    oit_run *state;
    int runnable;            /* opened and rendered every view */
    char reason[512];        /* why not, when !runnable */
    double *ms;              /* every timed frame, all views */
    double *gpu_ms;          /* the same frames' GPU time; -1: none */
    uint64_t *gpu_frame;     /* their GPU timer numbers (oit_frame_stats.gpu_frame) */
    size_t ms_count;
    oit_bench_cell *cells;   /* one per view */
    /* summary over views that rendered */
    double ms_median, ms_p95;
    double gpu_ms_median; /* -1: not timed on the GPU */
    uint64_t gpu_bytes_peak, gpu_mesh_bytes; /* as oit_bench_cell's, the most over views */
    uint32_t max_layers;
    uint32_t host_waits_max; /* the cells' most */
    double rmse_mean, max_abs_worst, pct_over_worst, psnr_min;
    double pct_over_outside_ambiguity_worst; /* the cells' most */
} oit_bench_method;

typedef struct oit_bench_desc {
    const oit_mesh *mesh;        /* what the in-core methods draw */
    oit_bench_geometry mesh_geometry; /* and what it is */
    /* what the reference draws and the views frame: the source mesh when
     * there is one; NULL: mesh */
    const oit_mesh *reference_mesh;
    oit_partfile *partfile;      /* the stream's; NULL when there is none */
    uint64_t partfile_triangles; /* its stored triangles */
    uint64_t source_triangles;   /* the source model's, for the labels */
    const oit_bench_entry *entries;
    int entry_count;
    int views, width, height, frames, warmup, max_layers;
    oit_render_capture capture; /* the stream's --capture; 0: auto */
    oit_shading_mode shading;    /* transparent or translucent */
    oit_colour_space colour_space; /* where compositing happens (shade.h) */
    int up_axis; /* the views' up axis: 0 x, 1 y, 2 z (formats/up_axis.h) */
    /* progress lines ("oitbench: ...") go here; NULL: silent */
    FILE *progress;
} oit_bench_desc;

typedef struct oit_bench_result {
    oit_bench_method *methods;
    int method_count, views;
    char renderer[256];          /* GL renderer, or why there is none */
    double *ref_ms;              /* reference time per view */
    /* per view, the most hits the reference ray met at one pixel: the
     * view's depth complexity, whatever the methods report */
    uint32_t *ref_layers;
    /* per view, % of pixels in the reference's ambiguity mask */
    double *ref_ambiguous_pct;
} oit_bench_result;

/* Fails only when the reference cannot render (nothing to measure against)
 * or memory runs out; a method's failure is recorded in its entry. */
oit_status oit_bench_run(const oit_bench_desc *d, oit_bench_result *out, oit_error *err);
void oit_bench_result_free(oit_bench_result *r);

/* Nearest-rank percentile (0..100) of v (n > 0), sorted in place. */
double oit_bench_percentile(double *v, size_t n, double pct);

#endif
