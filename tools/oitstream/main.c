/* oitstream: renders a model with one of the exact methods of
 * tools/common/methods.h from one view, a given camera or an orbit, and writes the
 * image (or the layer heat map) and per-frame figures; or compares two
 * images (--compare). Errors are one line on stderr; the exit status follows
 * oit_tool_exit_code. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/json.h"
#include "tools/common/heap.h"
#include "tools/common/paths.h"
#include "view/render/image/image.h"
#include "tools/oitstream/pick_json.h"
#include "tools/oitstream/cli_args.h"
#include "partfile/triangles.h"
#include "tools/common/methods.h"
#include "tools/common/exit_code.h"
#include "tools/common/flag_spelling.h"
#include "tools/common/method_run.h"
#include "tools/oitstream/stats_json.h"
#include "tools/oitstream/viewer.h"
#include "tools/oitstream/views.h"

static int fail(const oit_error *err)
{
    oit_error e = *err; /* liboit names its fields, a tool its flags */
    oit_flags_spell_error(&e);
    fprintf(stderr, "oitstream: %s\n", e.message);
    return oit_tool_exit_code(err->status);
}

/* ---- --compare ---- */

static oit_status print_diff(const oit_image_diff *d, uint64_t pixels, int json, oit_error *err)
{
    if (json) {
        /* JSON has no infinity: identical images report psnr null. */
        oit_json w;
        oit_json_init(&w, stdout, "standard output");
        oit_json_begin_object(&w, NULL, OIT_JSON_INLINE);
        oit_json_general(&w, "rmse", d->rmse, 9);
        oit_json_general(&w, "max_abs", d->max_abs, 9);
        oit_json_fixed(&w, "pct_over_1_255", d->pct_over_1_255, 6);
        oit_json_fixed(&w, "psnr", d->psnr, 4);
        oit_json_uint(&w, "pixels_over", d->pixels_over);
        oit_json_uint(&w, "pixels", pixels);
        oit_json_end(&w);
        return oit_json_flush(&w, err);
    }
    printf("rmse %.6g  max_abs %.6g  over 1/255: %.4f%% (%llu of %llu pixels)  psnr %.2f dB\n",
           d->rmse, d->max_abs, d->pct_over_1_255, (unsigned long long)d->pixels_over,
           (unsigned long long)pixels, d->psnr);
    return OIT_OK;
}

/* Figures over the pixels where the mask is black: masked pixels of b take
 * a's values, so they contribute no error; pct is taken over the rest. */
static oit_status compare_outside_mask(const oit_stream_args *a, const oit_image img[2],
                                       oit_error *err)
{
    oit_image mask = {0}, b = {0};
    oit_status s = oit_image_read(a->mask, &mask, err);
    if (s == OIT_OK && (mask.width != img[0].width || mask.height != img[0].height))
        s = oit_error_set(err, OIT_ERR_FORMAT, "%s is %dx%d, the images are %dx%d", a->mask,
                          mask.width, mask.height, img[0].width, img[0].height);
    if (s == OIT_OK)
        s = oit_image_alloc(&b, img[1].width, img[1].height, err);
    uint64_t n = (uint64_t)img[0].width * (uint64_t)img[0].height, masked = 0;
    for (uint64_t i = 0; s == OIT_OK && i < n; i++) {
        const float *m = mask.rgba + i * 4;
        int in_mask = m[0] > 0.0f || m[1] > 0.0f || m[2] > 0.0f;
        memcpy(b.rgba + i * 4, (in_mask ? img[0].rgba : img[1].rgba) + i * 4, 4 * sizeof(float));
        masked += (uint64_t)in_mask;
    }
    oit_image_diff d;
    if (s == OIT_OK)
        s = oit_image_compare(&img[0], &b, &d, NULL, 1.0f, err);
    if (s == OIT_OK) {
        double pct = n > masked ? 100.0 * (double)d.pixels_over / (double)(n - masked) : 0.0;
        if (a->json) {
            oit_json w;
            oit_json_init(&w, stdout, "standard output");
            oit_json_begin_object(&w, NULL, OIT_JSON_INLINE);
            oit_json_uint(&w, "masked_pixels", masked);
            oit_json_fixed(&w, "pct_over_1_255_outside_mask", pct, 6);
            oit_json_general(&w, "max_abs_outside_mask", d.max_abs, 9);
            oit_json_uint(&w, "pixels_over_outside_mask", d.pixels_over);
            oit_json_end(&w);
            s = oit_json_flush(&w, err);
        } else
            printf("outside %s (%llu pixels masked): over 1/255: %.4f%% (%llu pixels)  max_abs %.6g\n",
                   a->mask, (unsigned long long)masked, pct, (unsigned long long)d.pixels_over,
                   d.max_abs);
    }
    oit_image_free(&mask);
    oit_image_free(&b);
    return s;
}


/* ---- output paths, checked before any work ---- */

/* The file extension of the last path component: 2 to 5 letters after a
 * dot ("" otherwise), so "x.jpg" is a file but "run_0.01" a folder. */
static const char *path_ext(const char *p)
{
    const char *slash = strrchr(p, '/'), *base = slash ? slash + 1 : p;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base)
        return "";
    size_t n = 0;
    for (const char *c = dot + 1; *c; c++, n++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z')))
            return "";
    return n >= 2 && n <= 5 ? dot : "";
}

/* An --out with an extension must be an image format we write; one without
 * is a folder (created now, as it would be at the first frame). */
static oit_status check_image_out(const char *out, const char *what, const char *const *ins,
                                  size_t n, int folder_ok, int *created, oit_error *err)
{
    const char *ext = out ? path_ext(out) : "";
    if (out && *out && out[strlen(out) - 1] != '/' && *ext) {
        if (strcasecmp(ext, ".png") && strcasecmp(ext, ".pfm"))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s: unknown image extension '%s' "
                                 "(want .png or .pfm%s)", out, what, ext,
                                 folder_ok ? ", or a folder without an extension" : "");
        return oit_output_check(out, what, ins, n, err);
    }
    if (!folder_ok)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "%s: %s needs FILE.png or FILE.pfm",
                             out && *out ? out : "\"\"", what);
    return oit_output_dir_check(out, what, ins, n, created, err);
}

/* created[0], created[1]: --out and --ambiguity folders made by the check. */
static oit_status check_outputs(const oit_stream_args *a, int created[2], oit_error *err)
{
    const char *ins[4] = {a->compare ? a->compare_a : a->model, a->compare_b, a->walk,
                          a->mask};
    oit_status s = OIT_OK;
    if (a->out)
        s = check_image_out(a->out, "--out", ins, 4, !a->compare, &created[0], err);
    if (!s && a->ambiguity_out)
        s = check_image_out(a->ambiguity_out, "--ambiguity", ins, 4, 1, &created[1], err);
    if (!s && a->stats_path)
        s = oit_output_check(a->stats_path, "--stats", ins, 4, err);
    if (!s && a->out && a->stats_path && !strcmp(a->out, a->stats_path))
        s = oit_error_set(err, OIT_ERR_ARGUMENT, "%s: --out and --stats name the same file",
                          a->out);
    return s;
}

static int run_compare(const oit_stream_args *a)
{
    oit_image img[2] = {{0}, {0}}, diff = {0};
    oit_error err = {0};
    oit_image_diff d;
    oit_status s = oit_image_read(a->compare_a, &img[0], &err);
    if (s == OIT_OK)
        s = oit_image_read(a->compare_b, &img[1], &err);
    if (s == OIT_OK && (img[0].width != img[1].width || img[0].height != img[1].height))
        s = oit_error_set(&err, OIT_ERR_FORMAT, "%s is %dx%d but %s is %dx%d", a->compare_a,
                          img[0].width, img[0].height, a->compare_b, img[1].width, img[1].height);
    if (s == OIT_OK)
        s = oit_image_compare(&img[0], &img[1], &d, a->out ? &diff : NULL, a->gain, &err);
    if (s == OIT_OK && a->out)
        s = oit_image_write(&diff, a->out, &err);
    if (s == OIT_OK)
        s = print_diff(&d, (uint64_t)img[0].width * (uint64_t)img[0].height, a->json, &err);
    if (s == OIT_OK && a->mask)
        s = compare_outside_mask(a, img, &err);
    oit_image_free(&img[0]);
    oit_image_free(&img[1]);
    oit_image_free(&diff);
    return s == OIT_OK ? 0 : fail(&err);
}

/* ---- views ---- */

/* ---- output ---- */

static oit_status write_frame(const oit_stream_args *a, int index, int views,
                              const oit_image *colour, const uint32_t *counts, oit_error *err)
{
    char path[4096];
    oit_status s = output_path(a->out, index, views, path, sizeof path, err);
    if (s != OIT_OK || !a->show_layers)
        return s != OIT_OK ? s : oit_image_write(colour, path, err);
    oit_image heat;
    s = oit_image_heatmap(counts, colour->width, colour->height, &heat, err);
    if (s == OIT_OK)
        s = oit_image_write(&heat, path, err);
    oit_image_free(&heat);
    return s;
}

static oit_status write_ambiguity(const oit_stream_args *a, int index, int views,
                                  const uint8_t *amb, int w, int h, oit_error *err)
{
    char path[4096];
    oit_image img;
    oit_status s = output_path(a->ambiguity_out, index, views, path, sizeof path, err);
    if (s == OIT_OK)
        s = oit_image_alloc(&img, w, h, err);
    if (s != OIT_OK)
        return s;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        for (int c = 0; c < 4; c++)
            img.rgba[i * 4 + c] = (c == 3 || amb[i]) ? 1.0f : 0.0f;
    s = oit_image_write(&img, path, err);
    oit_image_free(&img);
    return s;
}

/* ---- rendering ---- */

typedef struct run_ctx {
    const oit_stream_args *args;
    const oit_render_method_info *method;
    oit_run *state;
    oit_view view;
    const double *origin; /* the model's (oit_mesh_info): views print in file coordinates */
    uint32_t *counts;
    uint8_t *ambiguous;
} run_ctx;

/* A cost as --stats prints it: "812.0 ms", "-" where not measured. */
static void format_cost(double ms, char *out, size_t n)
{
    if (ms < 0.0)
        snprintf(out, n, "-");
    else
        snprintf(out, n, "%.1f ms", ms);
}

/* --pack auto's choice of the frame and the costs it weighed. */
static void print_choice(int index, const oit_draw_stats *t)
{
    char fk[32], ct[32];
    format_cost(t->choice_first_k_ms, fk, sizeof fk);
    format_cost(t->choice_counted_ms, ct, sizeof ct);
    printf("frame %d: choice: %s (first-k %s, counted %s; %s)\n", index, t->choice, fk, ct,
           t->choice_why ? t->choice_why : "-");
}

static oit_status render_one(run_ctx *rc, int index, int views, oit_stats_frame *fr,
                             oit_error *err)
{
    oit_image img = {0};
    memset(&fr->st, 0, sizeof fr->st);
    oit_status s = oit_run_render(rc->state, &rc->view, &img, rc->counts, rc->ambiguous,
                                     &fr->st, err);
    if (s == OIT_OK && rc->args->out)
        s = write_frame(rc->args, index, views, &img, rc->counts, err);
    if (s == OIT_OK && rc->ambiguous)
        s = write_ambiguity(rc->args, index, views, rc->ambiguous, img.width, img.height, err);
    oit_image_free(&img);
    fr->method = rc->method->name;
    oit_stats_format_view(&rc->view.camera, rc->origin, fr->view, sizeof fr->view);
    oit_stats_format_clip(&rc->view.clip, rc->origin, fr->clip, sizeof fr->clip);
    oit_renderer_desc used;
    if (s == OIT_OK && oit_run_stream_stats(rc->state) &&
        oit_run_stream_desc(rc->state, &used)) {
        fr->has_stream = 1;
        fr->stream = *oit_run_stream_stats(rc->state);
        fr->epsilon = used.epsilon;
    }
    if (s == OIT_OK && !rc->args->quiet)
        printf("frame %d: %s %dx%d %.2f ms, %llu fragments, max %u layers, %llu overflow pixels, "
               "%.2f MiB GPU at peak (%.2f MiB of it the mesh)\n",
               index, rc->method->name, rc->view.width, rc->view.height, fr->st.ms,
               (unsigned long long)fr->st.fragments, fr->st.max_layers,
               (unsigned long long)fr->st.overflow_pixels,
               (double)fr->st.gpu_bytes_peak / 1048576.0,
               (double)fr->st.gpu_mesh_bytes / 1048576.0);
    if (s == OIT_OK && !rc->args->quiet && fr->has_stream)
        printf("frame %d: %.2f ms (order %.1f, pack %.1f), %u packs, %llu parts (%llu culled, "
               "%llu clipped: %.2f MiB not uploaded), "
               "%llu draw calls, %.2f MiB uploaded, %llu from the cache (%.2f MiB resident), "
               "%llu overflow pixels, %llu second-pass pixels in %u packs, "
               "%u host waits, %u redraws, %.1f MiB GPU at peak\n",
               index, fr->st.ms, fr->stream.order_ms, fr->stream.pack_ms, fr->stream.packs,
               (unsigned long long)fr->stream.parts_drawn,
               (unsigned long long)fr->stream.parts_culled,
               (unsigned long long)fr->stream.parts_clipped,
               (double)fr->stream.bytes_clipped / 1048576.0,
               (unsigned long long)fr->stream.draw_calls,
               (double)fr->stream.bytes_uploaded / 1048576.0,
               (unsigned long long)fr->stream.cache_hits,
               (double)fr->stream.cache_bytes / 1048576.0,
               (unsigned long long)fr->st.overflow_pixels,
               (unsigned long long)fr->st.second_pass_pixels, fr->st.second_pass_packs,
               fr->st.host_waits, fr->st.redraws, (double)fr->stream.gpu_bytes_peak / 1048576.0);
    if (s == OIT_OK && !rc->args->quiet && fr->has_stream && fr->stream.choice)
        print_choice(index, &fr->stream);
    if (s == OIT_OK && !rc->args->quiet && fr->has_stream && fr->stream.capture_asked)
        printf("frame %d: capture %s, K-slot fills %s%s%.0u (--capture %s)%s%s\n", index,
               fr->st.capture ? fr->st.capture : "-",
               fr->st.capture_slots ? fr->st.capture_slots : "none (counted)",
               fr->st.capture_slots_k ? " x" : "", fr->st.capture_slots_k,
               fr->stream.capture_asked,
               fr->stream.capture_fallback && fr->stream.capture_fallback[0]
                   ? "; auto fell back: " : "",
               fr->stream.capture_fallback ? fr->stream.capture_fallback : "");
    return s;
}

/* The GPU timer's figures that are in (wait: all of them), each to the
 * frame of its number among frames[0..n). */
static void take_gpu_times(run_ctx *rc, oit_stats_frame *frames, int n, int wait)
{
    oit_gpu_times t;
    while (oit_run_gpu_poll(rc->state, &t, wait))
        for (int i = 0; i < n; i++)
            if (frames[i].st.gpu_frame == t.frame) {
                frames[i].has_gpu = 1;
                frames[i].gpu = t;
            }
}

/* One line: each frame's GPU time, known only once the frames are done. */
static void print_gpu_summary(const run_ctx *rc, const oit_stats_frame *frames, int n)
{
    const char *why = oit_run_gpu_absent(rc->state);
    if (why) {
        printf("gpu: no GPU time (%s)\n", why);
        return;
    }
    for (int i = 0; i < n; i++) {
        const oit_gpu_times *g = &frames[i].gpu;
        if (!frames[i].has_gpu) {
            printf("frame %d: gpu time lost (not read in time)\n", i);
            continue;
        }
        printf("frame %d: gpu %.2f ms (upload %.2f, pass1 %.2f, pass2 %.2f, resolve %.2f, "
               "readback %.2f, binning %.2f, sweep %.2f, other %.2f), wall %.2f ms\n", i, g->ms,
               g->phase_ms[OIT_GPU_UPLOAD], g->phase_ms[OIT_GPU_PASS1],
               g->phase_ms[OIT_GPU_PASS2], g->phase_ms[OIT_GPU_RESOLVE],
               g->phase_ms[OIT_GPU_READBACK], g->phase_ms[OIT_GPU_BINNING],
               g->phase_ms[OIT_GPU_SWEEP], g->phase_ms[OIT_GPU_OTHER], frames[i].st.ms);
    }
}

static oit_status render_all(run_ctx *rc, const oit_mesh *mesh, const oit_camera *cams, int n,
                             oit_error *err)
{
    const oit_stream_args *a = rc->args;
    oit_stats_frame *frames = calloc((size_t)n, sizeof *frames);
    if (!frames)
        return oit_error_set(err, OIT_ERR_NOMEM, "cannot allocate %d frame records", n);
    oit_status s = OIT_OK;
    for (int i = 0; i < n && s == OIT_OK; i++) {
        rc->view.camera = cams[i];
        s = render_one(rc, i, n, &frames[i], err);
        take_gpu_times(rc, frames, i + 1, 0);
    }
    take_gpu_times(rc, frames, n, 1);
    if (s == OIT_OK && !a->quiet)
        print_gpu_summary(rc, frames, n);
    if (s == OIT_OK && !a->out && !a->quiet) /* say where nothing went */
        fprintf(stderr, "oitstream: %s: %d view%s rendered; no --out given, so no image was "
                "written\n", a->model, n, n == 1 ? "" : "s");
    if (s == OIT_OK && a->stats_path) {
        oit_stats_run run = {a->model, (unsigned long long)mesh->info.triangles,
                             oit_run_renderer(rc->state), a->width, a->height, frames,
                             (size_t)n, oit_shading_opaque(&rc->view.shading),
                             rc->view.shading.see_through,
                             oit_run_gpu_absent(rc->state)};
        s = oit_stats_json_write(a->stats_path, &run, err);
    }
    free(frames);
    return s;
}

static int is_part_file(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && !strcasecmp(path + n - 5, ".oitp");
}

static oit_status check_method(const oit_stream_args *a, const oit_render_method_info **out,
                               oit_error *err)
{
    char names[OIT_METHOD_NAMES_MAX];
    oit_method_names(names, sizeof names);
    *out = oit_method_find(a->method);
    if (!*out)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--method '%s': expected one of %s", a->method,
                             names);
    if (a->show_layers && !((*out)->flags & OIT_RENDER_METHOD_COUNTS))
        return oit_error_set(err, OIT_ERR_ARGUMENT,
                             "--show layers needs a method that counts fragments per pixel "
                             "(dfb, reference or stream), not %s", a->method);
    if (a->ambiguity_out && !((*out)->flags & OIT_RENDER_METHOD_AMBIGUITY))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--ambiguity needs --method reference, not %s",
                             a->method);
    return OIT_OK;
}

/* The readers drop a triangle with a NaN or inf coordinate and go on (the
 * rest is drawn), so the image alone would not show it; oitprep says the
 * same of a conversion. */
static void note_dropped(const char *path, const oit_mesh_info *in)
{
    if (in->nonfinite_dropped)
        fprintf(stderr, "oitstream: %s: %llu triangles in, %llu drawn (dropped %llu with a "
                "non-finite coordinate, NaN or inf; %llu of zero area kept)\n", path,
                (unsigned long long)(in->triangles + in->nonfinite_dropped),
                (unsigned long long)in->triangles, (unsigned long long)in->nonfinite_dropped,
                (unsigned long long)in->zero_area);
}

/* The scene: a mesh file loaded in core, or a part file, which the streamer
 * reads part by part and the other methods load in core. */
static oit_status load_scene(const oit_stream_args *a, const oit_render_method_info *m,
                             oit_partfile **pf, oit_mesh *mesh, oit_error *err)
{
    memset(mesh, 0, sizeof *mesh);
    *pf = NULL;
    if (!is_part_file(a->model)) {
        if ((m->flags & OIT_RENDER_METHOD_PART_FILE))
            return oit_error_set(err, OIT_ERR_ARGUMENT, "--method %s renders a part file "
                                 "(.oitp); convert %s with oitprep first", m->name, a->model);
        oit_status s = oit_mesh_load(a->model, NULL, mesh, err);
        if (s == OIT_OK)
            note_dropped(a->model, &mesh->info);
        return s;
    }
    /* The viewer switches between the streamer and the in-core methods, so
     * it wants both the streamable file and its triangles. */
    oit_partfile_open_desc desc = {(m->flags & OIT_RENDER_METHOD_PART_FILE) || a->window};
    oit_status s = oit_partfile_open(a->model, &desc, pf, err);
    if (s == OIT_OK && (m->flags & OIT_RENDER_METHOD_PART_FILE) && !a->window)
        oit_partfile_mesh_info(*pf, &mesh->info);
    else if (s == OIT_OK)
        s = oit_partfile_load_mesh(*pf, mesh, err);
    return s;
}

/* The viewer's O: a mesh in core, or a part file with its triangles in core
 * too (the viewer switches between the streamer and in-core methods). */
static oit_status window_open_model(void *ctx, const char *path, oit_viewer_scene *out,
                                    oit_error *err)
{
    const oit_stream_args *a = ctx;
    oit_stream_args one = *a;
    one.model = path;
    memset(out, 0, sizeof *out);
    const oit_render_method_info *m = oit_method_find(is_part_file(path) ? "stream" : "dfb");
    oit_status s = load_scene(&one, m, &out->partfile, &out->mesh, err);
    if (s != OIT_OK) {
        oit_mesh_free(&out->mesh);
        oit_partfile_close(out->partfile);
        memset(out, 0, sizeof *out);
        return s;
    }
    out->max_layers = stream_max_layers(a, out->partfile);
    return OIT_OK;
}

static void window_close_model(void *ctx, oit_viewer_scene *scene)
{
    (void)ctx;
    oit_mesh_free(&scene->mesh);
    oit_partfile_close(scene->partfile);
    memset(scene, 0, sizeof *scene);
}

static oit_status run_window(const run_ctx *rc, const oit_mesh *mesh, oit_partfile *pf,
                             const oit_run_options *opt, const oit_camera *cam,
                             oit_error *err)
{
    const oit_stream_args *a = rc->args;
    oit_viewer_desc d = {
        .mesh = mesh, .partfile = pf, .options = *opt, .method = rc->method->name,
        .width = a->width, .height = a->height, .camera = *cam,
        .azimuth = a->azimuth, .elevation = a->elevation, .up_axis = a->up_axis,
        .shading = rc->view.shading, .clip = rc->view.clip, .show_layers = a->show_layers, .overlay = !a->no_overlay,
        .frames = a->window_frames, .script = a->window_script,
        .screenshot = a->window_screenshot, .preview = (oit_viewer_preview)a->preview,
        .shot_width = a->shot_width, .shot_height = a->shot_height,
        .still_ms = a->still_ms, .stats_path = a->stats_path, .model_path = a->model,
        .open_model = window_open_model, .close_model = window_close_model,
        .model_ctx = (void *)a};
    return oit_viewer_run(&d, err);
}

static int run_render(const oit_stream_args *args)
{
    oit_error err = {0};
    oit_stream_args resolved = *args;
    const oit_stream_args *a = &resolved;
    if (!resolved.method)
        resolved.method = is_part_file(args->model) ? "stream" : "dfb";
    run_ctx rc = {.args = a};
    oit_status s = check_method(a, &rc.method, &err);
    if (s == OIT_OK && args->method && a->stream.epsilon > 0.0f &&
        !(rc.method->flags & OIT_RENDER_METHOD_EPSILON))
        s = oit_error_set(&err, OIT_ERR_ARGUMENT, "--epsilon is the early termination of "
                          "--method stream, the threshold of f2b and guarded and what "
                          "reference counts; method '%s' has none", a->method);
    if (s != OIT_OK)
        return fail(&err);
    oit_mesh mesh;
    oit_partfile *pf = NULL;
    s = load_scene(a, rc.method, &pf, &mesh, &err);
    if (s != OIT_OK) {
        oit_partfile_close(pf);
        return fail(&err);
    }
    if (resolved.up_axis < 0)
        resolved.up_axis = stream_up_axis(a, pf, &mesh.info);
    oit_camera *cams = NULL;
    int n = 0;
    int K = stream_max_layers(a, pf);
    oit_run_source so = {.path = a->model};
    oit_run_options opt = {.max_layers = K,
                              .threshold = a->have_epsilon ? &a->stream.epsilon : NULL,
                              .ambiguity_px = a->ambiguity_px, .source = &so};
    rc.view.width = a->width;
    rc.view.height = a->height;
    rc.origin = mesh.info.origin;
    rc.view.shading = make_shading(a, &mesh.info);
    s = oit_clip_place(&a->clip, mesh.info.origin, "--clip", &rc.view.clip, &err);
    if (s == OIT_OK)
        s = make_views(a, &mesh.info, &cams, &n, &err);
    if (s == OIT_OK)
        so.desc = stream_renderer_desc(a, n);
    if (s == OIT_OK && a->show_layers &&
        !(rc.counts = calloc((size_t)a->width * (size_t)a->height, sizeof *rc.counts)))
        s = oit_error_set(&err, OIT_ERR_NOMEM, "cannot allocate the layer count buffer");
    if (s == OIT_OK && a->ambiguity_out &&
        !(rc.ambiguous = calloc((size_t)a->width * (size_t)a->height, 1)))
        s = oit_error_set(&err, OIT_ERR_NOMEM, "cannot allocate the ambiguity mask");
    if (s == OIT_OK && a->pick) {
        rc.view.camera = cams[0];
        oit_pick_request rq = {.model = a->model, .part_file = pf != NULL, .mesh = &mesh,
                               .method = rc.method->name, .view = &rc.view, .x = a->pick_x,
                               .y = a->pick_y, .origin = mesh.info.origin};
        s = oit_pick_print(&rq, stdout, &err);
    } else if (s == OIT_OK && a->window)
        s = run_window(&rc, &mesh, pf, &opt, &cams[0], &err);
    else if (s == OIT_OK)
        s = oit_run_open(rc.method, &mesh, &opt, &rc.state, &err);
    if (s == OIT_OK && !a->window && !a->pick) {
        s = render_all(&rc, &mesh, cams, n, &err);
        oit_run_close(rc.state);
    }
    free(rc.counts);
    free(rc.ambiguous);
    free(cams);
    oit_mesh_free(&mesh);
    oit_partfile_close(pf);
    return s == OIT_OK ? 0 : fail(&err);
}

int main(int argc, char **argv)
{
    oit_tool_heap_setup();
    oit_stream_args a;
    oit_error err = {0};
    if (oit_stream_args_parse(argc, argv, &a, &err) != OIT_OK)
        return fail(&err);
    if (a.help) {
        char names[OIT_METHOD_NAMES_MAX];
        oit_method_names(names, sizeof names);
        oit_stream_usage(stdout, names);
        return 0;
    }
    int created[2] = {0, 0};
    if (check_outputs(&a, created, &err) != OIT_OK)
        return fail(&err);
    int code = a.compare ? run_compare(&a) : run_render(&a);
    if (code != 0 && created[0])
        rmdir(a.out); /* folders this run made, when nothing went into them */
    if (code != 0 && created[1])
        rmdir(a.ambiguity_out);
    return code;
}
