/* oitstream-mpi: `mpirun -np N oitstream-mpi FILE.oitp [oitstream options]`.
 * Each rank streams one share of the part file (partfile/share.h: one whole
 * subtree of the management tree, balanced by triangles), keeps its frame's
 * premultiplied colour C and transmittance T (no background), and IceT
 * blends the ranks' images in the shares' visibility order for the view
 * (icetCompositeOrder, ICET_COMPOSITE_MODE_BLEND, float RGBA: alpha = 1 - T,
 * exact for transparent shading, where T is one number a pixel). Rank 0
 * adds the background (C + T bg, in the compositing space, as the capture's
 * resolve does), writes the images and the figures: per rank its share and
 * render ms, and per frame the compositing ms and IceT's bytes sent.
 * Each rank streams through liboit's public API, as any program that
 * embeds it: its share is an oit_scene (oit_scene_desc.share_count and
 * share_index), drawn by an oit_renderer made from oitstream's descriptor
 * into a float target cleared to 0, which leaves C and 1 - T, ordered by
 * oit_scene_share_order. Translucent shading over more than one rank is
 * refused (by liboit, at the first draw): its absorbing medium and the
 * per-channel T cross share boundaries, which one RGBA image a rank cannot
 * carry. */
#include <math.h>
#include <mpi.h>
#include <sys/resource.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <IceT.h>
#include <IceTMPI.h>

/* Leak checking before the GL context goes and MPI_Finalize (run): Mesa
 * and OpenMPI unload libraries and components there, after which LSan can
 * no longer name the module of their own never-freed allocations, so no
 * suppression (tests/tools/oitstream_mpi/lsan-openmpi.supp) could match
 * them. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define OIT_LEAK_CHECK 1
#endif
#elif defined(__SANITIZE_ADDRESS__)
#define OIT_LEAK_CHECK 1
#endif
#ifdef OIT_LEAK_CHECK
#include <sanitizer/lsan_interface.h>
#endif

#include "base/clock.h"
#include "base/json.h"
#include "oit/liboit.h"
#include "partfile/triangles.h"
#include "view/render/gl/gl_context.h"
#include "view/render/gl/gl_util.h"
#include "view/render/image/clip.h"
#include "view/render/image/image.h"
#include "view/render/image/shade.h"
#include "tools/common/exit_code.h"
#include "tools/common/flag_spelling.h"
#include "tools/common/method_run.h"
#include "tools/oitstream/cli_args.h"
#include "tools/oitstream/stats_json.h"
#include "tools/oitstream/views.h"

/* Per rank a frame: render ms, parts, triangles, fragments, parts drawn,
 * peak host memory so far (getrusage's ru_maxrss, bytes) and the frame's
 * GPU bytes at peak (liboit's: capture, ring, cache, tiles). */
enum { FIGS = 7 };

typedef struct mpi_run {
    int rank, ranks;
    const oit_stream_args *args;
    oit_mesh_info info;
    int K; /* stream_max_layers: --max-layers or the file's */
    oit_scene *scene; /* this rank's share */
    oit_renderer *renderer;
    oit_view view;
    unsigned tex, fbo; /* GL_RGBA32F of the view's size, cleared to 0 each frame */
    float *rgba;       /* the rank's premultiplied colour and 1 - T, GL rows */
    IceTInt *order;
    double *figs;    /* rank 0: ranks x FIGS of the current frame */
    int follows;     /* stopped because another rank failed: nothing to say */
} mpi_run;

/* One line for the run, not one a rank: the lowest rank whose failure is
 * its own says it (naming the rank unless every rank failed alike, as on a
 * bad file), and every rank exits with that failure's code, so mpirun sees
 * one status and prints no abort of its own (its note on a non-zero exit
 * remains; `mpirun -q` keeps it away). */
static int report(const mpi_run *r, oit_status s, const oit_error *err)
{
    int own = s != OIT_OK && !r->follows, mine = own ? r->rank : r->ranks;
    int first = r->ranks, owners = 0;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(&own, &owners, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    int code = s == OIT_OK ? 0 : oit_tool_exit_code(err->status);
    if (first == r->ranks) /* no rank failed */
        return 0;
    if (r->rank == first) {
        oit_error e = *err; /* liboit names its fields, a tool its flags */
        oit_flags_spell_error(&e);
        if (owners == r->ranks)
            fprintf(stderr, "oitstream-mpi: %s\n", e.message);
        else
            fprintf(stderr, "oitstream-mpi: rank %d: %s\n", r->rank, e.message);
    }
    MPI_Bcast(&code, 1, MPI_INT, first, MPI_COMM_WORLD);
    return code;
}

/* What oitstream does that one composited image cannot. */
static oit_status check_args(const oit_stream_args *a, oit_error *err)
{
    size_t n = a->model ? strlen(a->model) : 0;
    if (a->compare || a->window)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--compare and --window are oitstream's; "
                             "oitstream-mpi renders a part file to images");
    if (n < 5 || strcmp(a->model + n - 5, ".oitp") != 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: oitstream-mpi renders a part file "
                             "(.oitp, made by oitprep)", a->model ? a->model : "(no model)");
    if (a->method && strcmp(a->method, "stream") != 0)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--method %s: oitstream-mpi streams "
                             "(--method stream) only", a->method);
    if (a->show_layers || a->ambiguity_out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--show layers and --ambiguity need an "
                             "in-core method; oitstream-mpi streams");
    return OIT_OK;
}

/* The float target liboit blends the share into: over 0, its Result
 * (liboit.h) leaves C and 1 - t, t = T for transparent shading. */
static oit_status make_target(mpi_run *r, oit_error *err)
{
    glCreateTextures(GL_TEXTURE_2D, 1, &r->tex);
    glTextureStorage2D(r->tex, 1, GL_RGBA32F, r->view.width, r->view.height);
    glCreateFramebuffers(1, &r->fbo);
    glNamedFramebufferTexture(r->fbo, GL_COLOR_ATTACHMENT0, r->tex, 0);
    if (glCheckNamedFramebufferStatus(r->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glGetError() != GL_NO_ERROR)
        return oit_error_set(err, OIT_ERR_GL, "cannot make a %dx%d float RGBA target",
                             r->view.width, r->view.height);
    return OIT_OK;
}

static oit_status open_share(mpi_run *r, int views, oit_error *err)
{
    const oit_stream_args *a = r->args;
    r->view.width = a->width;
    r->view.height = a->height;
    r->view.shading = make_shading(a, &r->info);
    /* oitstream's section planes: every rank cuts its share alike, and
     * culls the parts wholly cut away before reading them */
    oit_status s = oit_clip_place(&a->clip, r->info.origin, "--clip", &r->view.clip, err);
    /* parts are checked when first drawn, as oitstream's stream method does */
    oit_scene_desc sd = {.defer_validation = 1, .share_count = (uint32_t)r->ranks,
                         .share_index = (uint32_t)r->rank};
    if (s == OIT_OK)
        s = oit_scene_open(a->model, &sd, &r->scene, err);
    /* oitstream's descriptor, checked there (cli_args.c), with K and the
     * view's shading */
    oit_renderer_desc d = stream_renderer_desc(a, views);
    d.K = (uint32_t)r->K;
    oit_run_shading(&r->view.shading, &d);
    if (s == OIT_OK)
        s = oit_renderer_create(&d, &r->renderer, err);
    return s == OIT_OK ? make_target(r, err) : s;
}

/* All ranks learn whether any failed, so each stops at the same point and
 * meets the same collectives after. */
static oit_status agree(mpi_run *r, oit_status s, oit_error *err)
{
    int ok = s == OIT_OK, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (s != OIT_OK || all_ok)
        return s;
    r->follows = 1;
    return oit_error_set(err, OIT_ERR_IO, "another rank failed");
}

/* This rank's share of the frame: C and 1 - T, read back in GL rows. */
static oit_status draw_share(mpi_run *r, const oit_frame *frame, oit_draw_stats *ds,
                             oit_error *err)
{
    static const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(r->fbo, GL_COLOR, 0, zero);
    oit_frame f = *frame;
    f.framebuffer = r->fbo;
    oit_status s = oit_renderer_draw(r->renderer, r->scene, &f, ds, err);
    if (s != OIT_OK)
        return s;
    size_t bytes = (size_t)r->view.width * (size_t)r->view.height * 4 * sizeof *r->rgba;
    glGetTextureImage(r->tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)bytes, r->rgba);
    if (glGetError() != GL_NO_ERROR)
        return oit_error_set(err, OIT_ERR_GL, "cannot read back the share's %dx%d pixels",
                             r->view.width, r->view.height);
    return OIT_OK;
}

/* Rank 0: the blended C and 1 - T over the background, as the capture's
 * resolve finishes a pixel (shade.h: C + T bg; linear light encoded). */
static oit_status finish_image(const mpi_run *r, const float *blended, oit_image *out,
                               oit_error *err)
{
    oit_status s = oit_image_alloc(out, r->view.width, r->view.height, err);
    if (s != OIT_OK)
        return s;
    const oit_shading *sh = &r->view.shading;
    int linear = sh->colour_space == OIT_COLOUR_LINEAR;
    float bg[3];
    for (int k = 0; k < 3; k++) {
        float b = sh->background[k] < 0.0f ? 0.0f : sh->background[k];
        bg[k] = linear ? (float)oit_srgb_decode(b) : b;
    }
    int w = r->view.width, h = r->view.height;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const float *p = &blended[((size_t)(h - 1 - y) * w + x) * 4];
            float *o = &out->rgba[((size_t)y * w + x) * 4];
            float t = 1.0f - p[3];
            for (int k = 0; k < 3; k++) {
                float v = p[k] + t * bg[k];
                o[k] = linear ? (float)oit_srgb_encode(v) : v;
            }
            o[3] = 1.0f;
        }
    return OIT_OK;
}

static void print_frame(const mpi_run *r, int index, double frame_ms, double comp_ms,
                        double bytes)
{
    if (r->args->quiet)
        return;
    printf("frame %d: %d ranks %dx%d %.2f ms (composite %.2f ms, %.2f MiB sent by IceT)\n",
           index, r->ranks, r->view.width, r->view.height, frame_ms, comp_ms,
           bytes / 1048576.0);
    for (int k = 0; k < r->ranks; k++) {
        const double *f = &r->figs[k * FIGS];
        printf("frame %d: rank %d: %.0f parts, %.0f triangles, %.2f ms, %.0f fragments, "
               "%.0f parts drawn, peak %.1f MiB host, %.1f MiB GPU\n", index, k, f[1], f[2],
               f[0], f[3], f[4], f[5] / 1048576.0, f[6] / 1048576.0);
    }
}

typedef struct frame_figs {
    double frame_ms, composite_ms, bytes;
    double *ranks; /* ranks x FIGS */
    char view[256];
} frame_figs;

static oit_status render_frame(mpi_run *r, int index, int views, frame_figs *ff, oit_error *err)
{
    double t0 = oit_time_ms();
    _Static_assert(sizeof(IceTInt) == sizeof(uint32_t), "IceT's ranks are 32-bit");
    oit_frame_camera cam;
    oit_frame fr;
    oit_run_frame(&r->view, &cam, &fr);
    oit_status s = oit_scene_share_order(r->scene, &fr, (uint32_t *)r->order,
                                         (uint32_t)r->ranks, err);
    oit_draw_stats ds = {0};
    if (s == OIT_OK)
        s = draw_share(r, &fr, &ds, err);
    oit_scene_info si = {0};
    if (s == OIT_OK)
        s = oit_scene_get_info(r->scene, &si, err);
    struct rusage ru = {0};
    getrusage(RUSAGE_SELF, &ru);
    double mine[FIGS] = {oit_time_ms() - t0, (double)si.share_parts,
                         (double)si.share_triangles, (double)ds.fragments,
                         (double)ds.parts_drawn, (double)ru.ru_maxrss * 1024.0, /* KiB */
                         (double)ds.gpu_bytes_peak};
    /* Every rank reaches the collectives, failed or not, so none hangs. */
    s = agree(r, s, err);
    if (s != OIT_OK)
        return s;
    MPI_Gather(mine, FIGS, MPI_DOUBLE, r->figs, FIGS, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    /* The shares' order is rank order: share i is rank i. */
    icetCompositeOrder(r->order);
    static const IceTFloat black[4] = {0, 0, 0, 0};
    /* Compositing time without the wait for the slowest rank's render. */
    MPI_Barrier(MPI_COMM_WORLD);
    double c0 = oit_time_ms();
    IceTImage img = icetCompositeImage(r->rgba, NULL, NULL, NULL, NULL, black);
    double comp = oit_time_ms() - c0, bytes = 0.0, sent = 0.0;
    icetGetDoublev(ICET_BYTES_SENT, &sent);
    MPI_Reduce(&sent, &bytes, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    double frame = oit_time_ms() - t0, frame_max = 0.0, comp_max = 0.0;
    MPI_Reduce(&frame, &frame_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(&comp, &comp_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    if (r->rank != 0)
        return OIT_OK;
    ff->frame_ms = frame_max;
    ff->composite_ms = comp_max;
    ff->bytes = bytes;
    memcpy(ff->ranks, r->figs, sizeof(double) * FIGS * (size_t)r->ranks);
    oit_stats_format_view(&r->view.camera, r->info.origin, ff->view, sizeof ff->view);
    print_frame(r, index, frame_max, comp_max, bytes);
    if (!r->args->out)
        return OIT_OK;
    oit_image out = {0};
    char path[4096];
    s = output_path(r->args->out, index, views, path, sizeof path, err);
    if (s == OIT_OK)
        s = finish_image(r, icetImageGetColorcf(img), &out, err);
    if (s == OIT_OK)
        s = oit_image_write(&out, path, err);
    oit_image_free(&out);
    return s;
}

static oit_status write_stats(const mpi_run *r, const frame_figs *ff, int n, oit_error *err)
{
    FILE *f = fopen(r->args->stats_path, "w");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot write the figures",
                             r->args->stats_path);
    oit_json w;
    oit_json_init(&w, f, r->args->stats_path);
    oit_json_begin_object(&w, NULL, OIT_JSON_BLOCK);
    oit_json_string(&w, "model", r->args->model);
    oit_json_string(&w, "method", "stream-mpi");
    oit_json_int(&w, "ranks", r->ranks);
    oit_json_int(&w, "width", r->view.width);
    oit_json_int(&w, "height", r->view.height);
    oit_json_begin_array(&w, "frames", OIT_JSON_BLOCK);
    for (int i = 0; i < n; i++) {
        oit_json_begin_object(&w, NULL, OIT_JSON_BLOCK);
        oit_json_string(&w, "view", ff[i].view);
        oit_json_fixed(&w, "ms", ff[i].frame_ms, 3);
        oit_json_fixed(&w, "composite_ms", ff[i].composite_ms, 3);
        oit_json_uint(&w, "bytes_exchanged", (unsigned long long)ff[i].bytes);
        oit_json_begin_array(&w, "ranks", OIT_JSON_BLOCK);
        for (int k = 0; k < r->ranks; k++) {
            const double *g = &ff[i].ranks[k * FIGS];
            oit_json_begin_object(&w, NULL, OIT_JSON_INLINE);
            oit_json_int(&w, "rank", k);
            oit_json_uint(&w, "parts", (unsigned long long)g[1]);
            oit_json_uint(&w, "triangles", (unsigned long long)g[2]);
            oit_json_fixed(&w, "ms", g[0], 3);
            oit_json_uint(&w, "fragments", (unsigned long long)g[3]);
            oit_json_uint(&w, "parts_drawn", (unsigned long long)g[4]);
            oit_json_uint(&w, "host_peak_bytes", (unsigned long long)g[5]);
            oit_json_uint(&w, "gpu_peak_bytes", (unsigned long long)g[6]);
            oit_json_end(&w);
        }
        oit_json_end(&w);
        oit_json_end(&w);
    }
    oit_json_end(&w);
    oit_json_end(&w);
    return oit_json_close(&w, err);
}

static oit_status setup_icet(const mpi_run *r, oit_error *err)
{
    icetResetTiles();
    icetAddTile(0, 0, r->view.width, r->view.height, 0);
    icetStrategy(ICET_STRATEGY_REDUCE);
    icetSingleImageStrategy(ICET_SINGLE_IMAGE_STRATEGY_AUTOMATIC);
    icetCompositeMode(ICET_COMPOSITE_MODE_BLEND);
    icetSetColorFormat(ICET_IMAGE_COLOR_RGBA_FLOAT);
    icetSetDepthFormat(ICET_IMAGE_DEPTH_NONE);
    icetEnable(ICET_ORDERED_COMPOSITE);
    icetDisable(ICET_CORRECT_COLORED_BACKGROUND);
    IceTBoolean ordering = 0;
    icetGetBooleanv(ICET_STRATEGY_SUPPORTS_ORDERING, &ordering);
    if (!ordering)
        return oit_error_set(err, OIT_ERR_UNSUPPORTED, "IceT's reduce strategy does not "
                             "support ordered compositing here");
    return OIT_OK;
}

static oit_status run(mpi_run *r, oit_error *err)
{
    const oit_stream_args *a = r->args;
    oit_camera *cams = NULL;
    int n = 0;
    oit_partfile *pf = NULL;
    oit_status s = oit_partfile_open(a->model, &(oit_partfile_open_desc){1}, &pf, err);
    if (s == OIT_OK) {
        oit_partfile_mesh_info(pf, &r->info);
        r->K = stream_max_layers(a, pf);
        s = make_views(a, &r->info, &cams, &n, err);
        oit_partfile_close(pf);
    }
    oit_gl *gl = NULL;
    if (s == OIT_OK)
        s = oit_gl_create(NULL, &gl, err);
    if (s == OIT_OK)
        s = open_share(r, n, err);
    size_t px = (size_t)a->width * (size_t)a->height;
    frame_figs *ff = NULL;
    if (s == OIT_OK) {
        r->rgba = malloc(px * 4 * sizeof *r->rgba);
        r->order = calloc((size_t)r->ranks, sizeof *r->order);
        r->figs = calloc((size_t)r->ranks * FIGS, sizeof *r->figs);
        ff = calloc((size_t)n, sizeof *ff);
        for (int i = 0; ff && i < n; i++)
            ff[i].ranks = calloc((size_t)r->ranks * FIGS, sizeof(double));
        if (!r->rgba || !r->order || !r->figs || !ff || (n && !ff[n - 1].ranks))
            s = oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate %dx%d frame buffers",
                              a->width, a->height);
    }
    s = agree(r, s, err);
    IceTCommunicator comm = NULL;
    IceTContext ctx = NULL;
    if (s == OIT_OK) {
        comm = icetCreateMPICommunicator(MPI_COMM_WORLD);
        ctx = icetCreateContext(comm);
        s = setup_icet(r, err);
    }
    for (int i = 0; i < n && s == OIT_OK; i++) {
        r->view.camera = cams[i];
        /* rank 0 may fail alone writing the image: the others stop too */
        s = agree(r, render_frame(r, i, n, &ff[i], err), err);
    }
    if (s == OIT_OK && r->rank == 0 && a->stats_path)
        s = write_stats(r, ff, n, err);
    if (ctx)
        icetDestroyContext(ctx);
    if (comm)
        icetDestroyMPICommunicator(comm);
    for (int i = 0; ff && i < n; i++)
        free(ff[i].ranks);
    free(ff);
    free(cams);
    free(r->rgba);
    free(r->order);
    free(r->figs);
    if (r->fbo)
        glDeleteFramebuffers(1, &r->fbo);
    if (r->tex)
        glDeleteTextures(1, &r->tex);
    oit_renderer_destroy(r->renderer);
    oit_scene_close(r->scene);
#ifdef OIT_LEAK_CHECK
    /* All of ours is freed but the context, still reachable. Exits on a
     * leak; no check runs again at exit. */
    __lsan_do_leak_check();
#endif
    oit_gl_destroy(gl);
    return s;
}

int main(int argc, char **argv)
{
    oit_stream_args a;
    oit_error err = {0};
    oit_status s = oit_stream_args_parse(argc, argv, &a, &err);
    if (s == OIT_OK && a.help) {
        /* before MPI starts: --help needs no ranks (and leaves none of
         * MPI's start-up allocations behind); under mpirun rank 0 says it */
        const char *rank = getenv("OMPI_COMM_WORLD_RANK");
        if (!rank || strcmp(rank, "0") == 0) {
            printf("oitstream-mpi: run as `mpirun -np N oitstream-mpi FILE.oitp [options]`: "
                   "each of N ranks streams one share of the part file, IceT blends them in "
                   "order, rank 0 writes --out and --stats. The options are oitstream's "
                   "below; --method is stream, and --compare, --window, --show, --ambiguity "
                   "(and, with more than one rank, --shading translucent) are refused. An "
                   "error is said once, by the first rank that met it, and every rank exits "
                   "with its code (3 bad input); mpirun adds a note of its own on a non-zero "
                   "exit, which `mpirun -q` leaves out.\n\n");
            oit_stream_usage(stdout, "stream");
        }
        return 0;
    }
    MPI_Init(&argc, &argv);
    mpi_run r = {0};
    MPI_Comm_rank(MPI_COMM_WORLD, &r.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &r.ranks);
    if (s == OIT_OK)
        s = check_args(&a, &err);
    r.args = &a;
    if (s == OIT_OK)
        s = run(&r, &err);
    int code = report(&r, s, &err);
    MPI_Finalize();
    return code;
}
