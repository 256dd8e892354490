/* oitstream option parsing (cli_args.h). */
#include "tools/oitstream/cli_args.h"

#include "base/args.h"
#include "tools/common/mesh_formats.h"
#include "tools/common/render_args.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A finite number a float holds. */
static int parse_float(const char *s, float *out)
{
    double v;
    if (oit_parse_double(s, -FLT_MAX, FLT_MAX, &v))
        return -1;
    *out = (float)v;
    return 0;
}

static int parse_rgb(const char *s, float rgb[3])
{
    double v[3];
    if (oit_parse_doubles(s, ',', v, 3) != 3)
        return -1;
    for (int c = 0; c < 3; c++) {
        if (!(v[c] >= 0.0 && v[c] <= 1.0))
            return -1;
        rgb[c] = (float)v[c];
    }
    /* view.h reads all-zero as "default"; black is spelled negative. */
    if (rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f)
        rgb[0] = rgb[1] = rgb[2] = -1.0f;
    return 0;
}

/* Bytes with an optional K, M or G (binary) suffix; their range is
 * liboit's to check (oit_renderer_desc_check). */
static int parse_bytes(const char *s, uint64_t *out)
{
    return oit_parse_bytes(s, 0, UINT64_MAX, out);
}

static oit_status bad(oit_error *err, const char *opt, const char *val, const char *want)
{
    return oit_error_set(err, OIT_ERR_ARGUMENT, "%s '%s': expected %s", opt, val ? val : "",
                         want);
}

/* Options that take a value; returns 0 when opt is not one of them. */
static int value_option(oit_stream_args *a, const char *opt, const char *v, oit_status *s,
                        oit_error *err)
{
    *s = OIT_OK;
    if (!strcmp(opt, "--method")) a->method = v;
    else if (!strcmp(opt, "--out")) a->out = v;
    else if (!strcmp(opt, "--stats")) a->stats_path = v;
    else if (!strcmp(opt, "--mask")) a->mask = v;
    /* liboit's oit_renderer_desc.program_cache: a folder or "off" */
    else if (!strcmp(opt, "--program-cache")) a->stream.program_cache = v;
    else if (!strcmp(opt, "--ambiguity")) a->ambiguity_out = v;
    else if (!strcmp(opt, "--ambiguity-px")) {
        double px;
        if (oit_parse_double(v, 0.0, 4.0, &px) || !(px > 0.0))
            *s = bad(err, opt, v, "a radius in pixels, in (0, 4]");
        else
            a->ambiguity_px = (float)px;
    }
    else if (!strcmp(opt, "--pick")) {
        char tail;
        a->pick = 1;
        if (sscanf(v, "%d,%d%c", &a->pick_x, &a->pick_y, &tail) != 2 || a->pick_x < 0 ||
            a->pick_y < 0)
            *s = bad(err, opt, v, "X,Y: a pixel, 0,0 the top left");
    }
    else if (!strcmp(opt, "--size")) {
        if (oit_parse_size(v, 1, 16384, &a->width, &a->height))
            *s = bad(err, opt, v, "WxH, 1..16384");
    } else if (!strcmp(opt, "--view")) {
        int code = oit_camera_parse(&a->view, v, NULL);
        if (code != 0)
            *s = oit_error_set(err, OIT_ERR_ARGUMENT, "%s '%s': %s", opt, v,
                               oit_camera_parse_error(code));
        a->have_view = 1;
        a->view_text = v;
    } else if (!strcmp(opt, "--ortho")) {
        if (!strcmp(v, "fit"))
            a->ortho = -1.0f;
        else if (parse_float(v, &a->ortho) || !(a->ortho > 0.0f))
            *s = bad(err, opt, v, "a view height > 0, or fit");
    } else if (!strcmp(opt, "--azimuth")) {
        if (parse_float(v, &a->azimuth)) *s = bad(err, opt, v, "degrees");
    } else if (!strcmp(opt, "--elevation")) {
        if (parse_float(v, &a->elevation) || fabsf(a->elevation) > 90.0f)
            *s = bad(err, opt, v, "degrees in [-90, 90]");
    } else if (!strcmp(opt, "--walk")) {
        a->walk = v;
    } else if (!strcmp(opt, "--orbit")) {
        if (oit_parse_int(v, 1, 100000, &a->orbit)) *s = bad(err, opt, v, "a view count >= 1");
    } else if (!strcmp(opt, "--shading")) {
        if (!strcmp(v, "transparent")) a->shading.mode = OIT_SHADING_TRANSPARENT;
        else if (!strcmp(v, "translucent")) a->shading.mode = OIT_SHADING_TRANSLUCENT;
        else *s = bad(err, opt, v, "transparent or translucent");
    } else if (!strcmp(opt, "--colour-space") || !strcmp(opt, "--color-space")) {
        if (!strcmp(v, "srgb")) a->shading.colour_space = OIT_COLOUR_SRGB;
        else if (!strcmp(v, "linear")) a->shading.colour_space = OIT_COLOUR_LINEAR;
        else *s = bad(err, opt, v, "srgb or linear");
    } else if (!strcmp(opt, "--alpha")) {
        if (parse_float(v, &a->shading.alpha) || !(a->shading.alpha > 0.0f) ||
            a->shading.alpha > 1.0f)
            *s = bad(err, opt, v, "a number in (0, 1]");
    } else if (!strcmp(opt, "--absorption")) {
        if (parse_float(v, &a->shading.absorption) || !(a->shading.absorption > 0.0f))
            *s = bad(err, opt, v, "a number > 0");
    } else if (!strcmp(opt, "--background")) {
        if (parse_rgb(v, a->shading.background)) *s = bad(err, opt, v, "r,g,b in [0, 1]");
    } else if (!strcmp(opt, "--max-layers")) {
        if (oit_parse_int(v, INT_MIN, INT_MAX, &a->max_layers)) *s = bad(err, opt, v, "an integer");
        else *s = oit_tool_check_k(a->max_layers, "--max-layers", err);
    } else if (!strcmp(opt, "--show")) {
        if (!strcmp(v, "layers")) a->show_layers = 1;
        else if (strcmp(v, "colour") && strcmp(v, "color")) *s = bad(err, opt, v, "layers or colour");
    } else if (!strcmp(opt, "--pack")) {
        if (!strcmp(v, "auto")) a->stream.pack = OIT_RENDER_PACK_AUTO;
        else if (!strcmp(v, "counted")) a->stream.pack = OIT_RENDER_PACK_COUNTED;
        else if (!strcmp(v, "disjoint")) a->stream.pack = OIT_RENDER_PACK_DISJOINT;
        else if (!strcmp(v, "budget")) a->stream.pack = OIT_RENDER_PACK_BUDGET;
        else if (!strcmp(v, "first-k")) a->stream.pack = OIT_RENDER_PACK_FIRSTK;
        else *s = bad(err, opt, v, "auto, counted, first-k, budget or disjoint");
    } else if (!strcmp(opt, "--capture")) {
        *s = oit_tool_parse_capture(v, opt, &a->stream.capture, err);
    } else if (!strcmp(opt, "--schedule")) {
        if (!strcmp(v, "wave")) a->stream.schedule = OIT_RENDER_SCHEDULE_WAVE;
        else if (!strcmp(v, "tree")) a->stream.schedule = OIT_RENDER_SCHEDULE_TREE;
        else *s = bad(err, opt, v, "wave or tree");
    } else if (!strcmp(opt, "--upload-budget")) {
        if (parse_bytes(v, &a->stream.upload_budget))
            *s = bad(err, opt, v, "bytes, with an optional K, M or G suffix");
    } else if (!strcmp(opt, "--cache-budget")) {
        /* As liboit's oit_renderer_desc.cache_budget: "off"
         * (OIT_RENDER_CACHE_OFF) no cache. */
        if (!strcmp(v, "off"))
            a->stream.cache_budget = OIT_RENDER_CACHE_OFF;
        else if (parse_bytes(v, &a->stream.cache_budget))
            *s = bad(err, opt, v, "off or bytes, with an optional K, M or G suffix");
    } else if (!strcmp(opt, "--gpu-budget")) {
        if (parse_bytes(v, &a->stream.gpu_budget))
            *s = bad(err, opt, v, "bytes, with an optional K, M or G suffix");
    } else if (!strcmp(opt, "--upload-threads")) {
        /* 0 read on the render thread before threads were counted */
        int n = 0;
        if (oit_parse_int(v, 0, OIT_RENDER_READER_THREADS_MAX, &n))
            *s = bad(err, opt, v, "0..64 threads");
        a->stream.reader_threads = (uint32_t)n;
        a->stream.read_on_draw_thread = n == 0;
    } else if (!strcmp(opt, "--slot-budget")) {
        if (parse_bytes(v, &a->stream.slot_budget))
            *s = bad(err, opt, v, "bytes, with an optional K, M or G suffix");
    } else if (!strcmp(opt, "--store-budget")) {
        if (parse_bytes(v, &a->stream.store_budget))
            *s = bad(err, opt, v, "bytes, with an optional K, M or G suffix");
    } else if (!strcmp(opt, "--epsilon")) {
        a->have_epsilon = 1;
        /* in [0, 1): liboit's OIT_RENDER_EPSILON_ZERO (-1) is not for users,
         * whose 0 is the method's own zero */
        if (parse_float(v, &a->stream.epsilon) || !(a->stream.epsilon >= 0.0f) ||
            !(a->stream.epsilon < 1.0f))
            *s = bad(err, opt, v, "a threshold in [0, 1)");
    } else if (!strcmp(opt, "--window-frames")) {
        if (oit_parse_int(v, 1, 100000000, &a->window_frames))
            *s = bad(err, opt, v, "a frame count >= 1");
    } else if (!strcmp(opt, "--window-script")) a->window_script = v;
    else if (!strcmp(opt, "--window-screenshot")) a->window_screenshot = v;
    else if (!strcmp(opt, "--shot-size")) {
        if (oit_parse_size(v, 1, 16384, &a->shot_width, &a->shot_height))
            *s = bad(err, opt, v, "WxH, each 1..16384");
    }
    else if (!strcmp(opt, "--preview")) {
        /* the values of oit_viewer_preview, in its order */
        static const char *const names[] = {"auto", "lowres", "wboit", "unsorted", "off"};
        int found = -1;
        for (int i = 0; i < 5; i++)
            if (!strcmp(v, names[i]))
                found = i;
        if (found < 0) *s = bad(err, opt, v, "auto, lowres, wboit, unsorted or off");
        else a->preview = found;
        a->have_preview = 1;
    } else if (!strcmp(opt, "--clip")) {
        *s = oit_clip_given_add_text(&a->clip, v, opt, err);
    } else if (!strcmp(opt, "--still")) {
        if (oit_parse_int(v, 1, 60000, &a->still_ms))
            *s = bad(err, opt, v, "milliseconds, 1..60000");
    } else if (!strcmp(opt, "--up")) {
        if (!strcmp(v, "auto")) a->up_axis = -1;
        else if (!strcmp(v, "x")) a->up_axis = 0;
        else if (!strcmp(v, "y")) a->up_axis = 1;
        else if (!strcmp(v, "z")) a->up_axis = 2;
        else *s = bad(err, opt, v, "auto, x, y or z");
    }
    else if (!strcmp(opt, "--gain")) {
        if (parse_float(v, &a->gain) || !(a->gain > 0.0f)) *s = bad(err, opt, v, "a number > 0");
    } else
        return 0;
    return 1;
}

static oit_status positional(oit_stream_args *a, const char *arg, oit_error *err)
{
    if (a->compare && !a->compare_a) a->compare_a = arg;
    else if (a->compare && !a->compare_b) a->compare_b = arg;
    else if (!a->compare && !a->model) a->model = arg;
    else return oit_error_set(err, OIT_ERR_ARGUMENT, "unexpected argument '%s'", arg);
    return OIT_OK;
}

static oit_status check_combination(const oit_stream_args *a, oit_error *err)
{
    if (a->help)
        return OIT_OK;
    if (a->compare && (!a->compare_a || !a->compare_b))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--compare needs two images");
    if (!a->compare && !a->model)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "no model given (see --help)");
    if ((a->window_frames || a->window_script || a->window_screenshot || a->no_overlay ||
         a->have_preview || a->still_ms || a->shot_width) &&
        !a->window)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--window-frames, --window-script, "
                             "--window-screenshot, --shot-size, --no-overlay, --preview and "
                             "--still need --window");
    if (a->window && (a->orbit || a->out || a->ambiguity_out))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--window shows one interactive view: "
                             "it excludes --orbit, --out and --ambiguity");
    /* The stream's settings are checked by liboit, before any I/O (every
     * other method ignores them), its errors naming its fields, which
     * fail() spells as flags (flag_spelling.h); which methods take
     * --epsilon, main.c asks the method's flags (OIT_RENDER_METHOD_EPSILON). */
    oit_status s = oit_renderer_desc_check(&a->stream, err);
    if (s != OIT_OK)
        return s;
    if (a->pick && (a->window || a->orbit || a->walk || a->out || a->ambiguity_out ||
                    a->show_layers))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--pick prints the layers of one pixel of "
                             "one view: it excludes --window, --orbit, --walk, --out, "
                             "--ambiguity and --show");
    if (a->pick && (a->pick_x >= a->width || a->pick_y >= a->height))
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--pick %d,%d lies outside the %dx%d "
                             "image (--size)", a->pick_x, a->pick_y, a->width, a->height);
    if ((a->have_view != 0) + (a->orbit != 0) + (a->walk != NULL) > 1)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--view, --orbit and --walk exclude each "
                             "other");
    if (a->window && a->walk)
        return oit_error_set(err, OIT_ERR_ARGUMENT, "--window shows one interactive view: it "
                             "excludes --walk");
    return OIT_OK;
}

oit_status oit_stream_args_parse(int argc, char **argv, oit_stream_args *a, oit_error *err)
{
    memset(a, 0, sizeof *a);
    a->method = NULL;
    a->width = a->height = 1024;
    a->elevation = 20.0f;
    a->gain = 1.0f;
    a->max_layers = 0; /* the part file's K, else 16 */
    a->up_axis = -1; /* auto: the model's (formats/up_axis.h) */
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        oit_status s = OIT_OK;
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) a->help = 1;
        else if (!strcmp(arg, "--compare")) a->compare = 1;
        else if (!strcmp(arg, "--json")) a->json = 1;
        else if (!strcmp(arg, "--quiet")) a->quiet = 1;
        else if (!strcmp(arg, "--window")) a->window = 1;
        else if (!strcmp(arg, "--no-overlay")) a->no_overlay = 1;
        else if (!strcmp(arg, "--see-through")) a->shading.see_through = 1;
        else if (!strncmp(arg, "--", 2)) {
            const char *v = i + 1 < argc ? argv[i + 1] : NULL;
            if (!value_option(a, arg, v ? v : "", &s, err))
                return oit_error_set(err, OIT_ERR_ARGUMENT, "unknown option '%s' (see --help)", arg);
            if (!v)
                return oit_error_set(err, OIT_ERR_ARGUMENT, "%s needs a value", arg);
            i++;
        } else
            s = positional(a, arg, err);
        if (s != OIT_OK)
            return s;
    }
    return check_combination(a, err);
}

void oit_stream_usage(FILE *f, const char *method_list)
{
    fprintf(f,
        "usage: oitstream MODEL [options]\n"
        "       oitstream --compare A B [--json] [--out DIFF.png] [--gain G]\n"
        "\n"
        "Renders MODEL (a mesh, formats below, or a part file .oitp made by\n"
        "oitprep) with exact order-independent transparency and writes the image.\n"
        ".step .stp .iges .igs are read through Open CASCADE, tessellated at a\n"
        "deflection of a thousandth of the bounding box's diagonal (oitprep\n"
        "--deflection converts at another), with their faces' colours and alpha.\n"
        "\n"
        "  --method M          %s\n"
        "                      (default: stream for a part file, dfb otherwise; the\n"
        "                      others load a part file's triangles in core). Exact:\n"
        "                      dfb, reference, compute (rasterized, sorted and\n"
        "                      composited in compute shaders), stream, pll, ppll4\n"
        "                      (paged lists), b3d (per-pixel arrays sized to the\n"
        "                      deepest pixel); dp and ddp (dual depth peeling)\n"
        "                      without depth ties, ddp transparent only. Bounded:\n"
        "                      array, stencil (K slots a pixel, --max-layers: exact\n"
        "                      up to K layers; a pixel with more loses them and\n"
        "                      counts as overflow). Approximate: guarded, f2b (see\n"
        "                      --epsilon), wboit, unsorted\n"
        "  --pack P            stream: counted (packs cut by upload bytes only, each\n"
        "                      counted, stored and sorted per pixel as DFB does, with\n"
        "                      no layer limit, stored in bands of rows from its one\n"
        "                      count where its fragments exceed --store-budget;\n"
        "                      a view drawn again is stored at the offsets its\n"
        "                      last frame counted, not counted first: one pass,\n"
        "                      a second for pixels that got more; --stats:\n"
        "                      predicted_batches), or K slots a\n"
        "                      pixel: disjoint (a part joins a pack while its screen\n"
        "                      rectangle misses the pack's) or budget (the sum of the\n"
        "                      layer bounds per 32x32 tile stays <= K; a pixel that\n"
        "                      gets more loses them and counts as overflow), or\n"
        "                      first-k (packs as counted, each drawn once into up to\n"
        "                      K slots a pixel of its rectangle within --slot-budget\n"
        "                      while every fragment is counted; only if some pixel got\n"
        "                      more, the pack is drawn again for those pixels alone,\n"
        "                      stored and sorted as counted does: exact, no limit;\n"
        "                      --stats reports second_pass_pixels/_packs). auto\n"
        "                      (default): first-k or counted, as this process\n"
        "                      measured them on each view: first-k first (counted\n"
        "                      for one image outside --window); the\n"
        "                      other tried for a frame of a still view when any\n"
        "                      pixel got more than K fragments in a pack (counted,\n"
        "                      then predicted from first-k's counts: one geometry\n"
        "                      pass) or none did (first-k; over K every 256th\n"
        "                      counted frame too); a try is kept only if its least\n"
        "                      frame time on the view (wall, or GPU time where\n"
        "                      larger) is lower, else not tried on any view for 8,\n"
        "                      16, ... 256 frames; a new view starts from the last\n"
        "                      view's path (--stats: choice, choice_why,\n"
        "                      choice_first_k_ms, choice_counted_ms, deep_pixels,\n"
        "                      auto_first_k), the same image\n"
        "                      either way. With --epsilon, counted and first-k packs\n"
        "                      are cut front first (pack i takes at most K*2^i layers\n"
        "                      a 32x32 tile, so the front layers saturate pixels\n"
        "                      before the parts behind are read) while a frame skips\n"
        "                      parts; after one that skips none, plain packs, front\n"
        "                      first tried again every 8th frame (--stats: front_first)\n"
        "  --capture C         stream: how K-slot fills are made, for K-slot packs\n"
        "                      (budget, disjoint) and first-k's first pass: stencil\n"
        "                      (Wang & Xie's stencil-routed A-buffer: MSAA samples\n"
        "                      filled in order by the stencil), array (slots through\n"
        "                      an atomic counter) or auto (default): stencil where\n"
        "                      its start-up self-test passes on this driver (at K;\n"
        "                      first-k also at the largest power of two below K that\n"
        "                      passes), else array. stencil where the self-test\n"
        "                      fails is an error giving its reason; counted packs\n"
        "                      have no K-slot fill. --stats and the viewer's status\n"
        "                      line say what ran (capture_slots) and why auto fell\n"
        "                      back (capture_fallback); llvmpipe does not route per\n"
        "                      sample, so auto takes array there. compute: no K-slot\n"
        "                      fill and no layer limit; every pack binned into tiles,\n"
        "                      rasterized, ordered and composited in compute shaders\n"
        "                      (--pack auto then cuts counted packs, the largest;\n"
        "                      budget and disjoint packs are cut by their rule;\n"
        "                      first-k, whose first pass is a K-slot fill, is\n"
        "                      refused).\n"
        "                      Same image\n"
        "  --schedule S        stream: tree (default: packs of consecutive parts in the\n"
        "                      management tree's depth-first order) or wave (packs\n"
        "                      filled front to back across the whole screen, keeping\n"
        "                      the order only between parts whose rectangles overlap:\n"
        "                      fewer packs, larger resolve rectangles; with --pack\n"
        "                      disjoint, packs by level: each pack the parts whose\n"
        "                      overlapping predecessors are all drawn, no two of\n"
        "                      them sharing a pixel; the same image byte for byte)\n"
        "  --upload-budget B   stream: bytes of the upload ring, a persistently mapped\n"
        "                      GPU buffer that a reader thread fills with the parts\n"
        "                      of later packs while the GPU draws earlier ones; it\n"
        "                      grows with what the frames read to at most B\n"
        "                      (>= 64K, default 64M, never more than the file's parts\n"
        "                      take; 0 also means the default); a pack never exceeds\n"
        "                      it. A file within it and the cache budget is read once\n"
        "                      into a ring of its size and drawn from there, with no\n"
        "                      cache buffer\n"
        "  --cache-budget B    stream: bytes of GPU memory that keep parts uploaded in\n"
        "                      one frame for the next ones, drawn without reading or\n"
        "                      uploading them again; it grows with the parts the\n"
        "                      frames draw to at most B (>= 64K, default 256M, never\n"
        "                      more than the file's parts take; 0 also means the\n"
        "                      default, as in liboit; off: no cache; the default is\n"
        "                      off when oitstream draws a single frame outside\n"
        "                      --window: no later frame would draw from it)\n"
        "  --program-cache DIR stream: the folder where linked GL programs are kept\n"
        "                      for later runs on the same driver (GL program\n"
        "                      binaries, checked before use; a bad entry is built\n"
        "                      again), made if missing; off: none. Default:\n"
        "                      $OIT_PROGRAM_CACHE (a folder or off), else\n"
        "                      $XDG_CACHE_HOME/oit, else ~/.cache/oit. A folder that\n"
        "                      cannot be written is no cache, not an error\n"
        "  --gpu-budget B      stream: GPU bytes for the upload ring, the cache and the\n"
        "                      capture together (>= 1M). Default: half the free memory\n"
        "                      the driver reports (GL_NVX_gpu_memory_info or\n"
        "                      GL_ATI_meminfo), so that a model that fits stays\n"
        "                      resident after its first frame; where the driver\n"
        "                      reports none (llvmpipe), no total: the budgets below\n"
        "                      alone. Its split: the capture's slots and store\n"
        "                      (their defaults, or each an eighth of a small total),\n"
        "                      the file resident where it\n"
        "                      fits the rest less 64M (or an eighth) for pixels,\n"
        "                      else a ring of a quarter of the rest (<= 64M) and the\n"
        "                      cache what is left, less the frame's per-pixel buffers.\n"
        "                      --upload-budget, --cache-budget, --slot-budget and\n"
        "                      --store-budget replace their shares; more than B\n"
        "                      together is an error.\n"
        "                      --stats: budget (the figures and their source)\n"
        "  --upload-threads N  stream: threads that read and decode parts while the\n"
        "                      GPU draws, each taking the next part in the packs'\n"
        "                      order, 0..64 (0: none, parts are read on the render\n"
        "                      thread, no overlap; default: the cores there are, less\n"
        "                      one, at least 1; --stats: reader_threads)\n"
        "  --slot-budget B     stream: bytes of the K-fragment capture slots (>= 64K,\n"
        "                      default 32M for disjoint and budget, 64M for counted,\n"
        "                      first-k and auto; 0 also means the default), a larger\n"
        "                      frame captured in screen tiles; for first-k, the\n"
        "                      slots of a pack's rectangle (K shrinks to fit, a pack\n"
        "                      too wide for 2 is captured counted)\n"
        "  --store-budget B    stream: bytes of the counted and first-k fragment\n"
        "                      stores (>= 64K, default 256M; 0 also means the\n"
        "                      default), grown to what a frame stores: counted's\n"
        "                      store and its predictions (a pack past it is stored\n"
        "                      in bands of rows, each drawing it again), first-k's\n"
        "                      second pass (in bands of rows that fit). Other packs\n"
        "                      have none\n"
        "  --epsilon E         in [0, 1). stream: drop fragments behind pixels whose\n"
        "                      transmittance fell below E, and neither upload nor draw\n"
        "                      parts whose whole footprint did (error <= E per channel;\n"
        "                      default 0: exact); f2b: its alpha threshold, the same\n"
        "                      test\n"
        "                      (default 0.02); guarded: its contribution threshold\n"
        "                      (default 0.0025); 0 discards nothing; reference: draws\n"
        "                      the exact image and counts the fragments behind\n"
        "                      pixels below E (--stats: fragments_saturated)\n"
        "  --size WxH          image size, W and H in 1..16384 (default 1024x1024)\n"
        "  --view ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy[,znear,zfar][:FIELD]...\n"
        "                      camera; without it --azimuth/--elevation frame the model;\n"
        "                      projection FIELDs: ortho=H (orthographic, H high; znear\n"
        "                      may be <= 0), window=l,r,b,t (off-centre: the frustum's\n"
        "                      sides at distance 1, or ortho's sides), far=inf\n"
        "                      (infinite far plane)\n"
        "  --ortho H|fit       orthographic, the view volume H high (fit: as high as the\n"
        "                      perspective's frustum at the target), for any view\n"
        "  --azimuth DEG       any angle (default 0)\n"
        "  --elevation DEG     in [-90, 90] (default 20)\n"
        "  --orbit N           N views around the model, 1..100000 (azimuth i*360/N,\n"
        "                      elevation 20)\n"
        "  --walk FILE         a camera path: one view a line in --view syntax (file\n"
        "                      coordinates; # comments and blank lines skipped);\n"
        "                      frames are written and reported as for --orbit\n"
        "  --out PATH          FILE.png (8-bit sRGB) or FILE.pfm (float, linear light),\n"
        "                      or a folder (frame_000.png ...)\n"
        "  --shading S         transparent (default) or translucent\n"
        "  --colour-space S    where compositing happens: srgb (default) on the\n"
        "                      sRGB-encoded colours as given; linear: colours and\n"
        "                      --background decoded (exact sRGB EOTF), composited in\n"
        "                      linear light, the result encoded to sRGB for PNG;\n"
        "                      PFM holds linear light in both\n"
        "  --alpha A           alpha where the model gives none, in (0, 1] (default\n"
        "                      0.35); a model's own alpha (PLY/OFF alpha, glTF\n"
        "                      materials, MTL d/Tr, STEP transparency) wins, and its triangles of alpha 1\n"
        "                      (glTF OPAQUE, MTL d 1) are opaque: drawn once, hiding\n"
        "                      what is behind them\n"
        "  --see-through       --alpha on every triangle: the model's alpha and opaque\n"
        "                      materials are ignored (its colours are kept)\n"
        "  --absorption X      translucent optical depth across the model, > 0 (default 4)\n"
        "  --background r,g,b  default 1,1,1\n"
        "  --max-layers K      fragments per pixel per batch for array/stencil/stream,\n"
        "                      2..16 (default: the part file's K, else 16); pixels\n"
        "                      with more count as overflow. stream: a part with more\n"
        "                      layers than K (a wide part) is captured with more\n"
        "                      slots per pixel over smaller screen tiles\n"
        "  --show layers       write the fragments-per-pixel heat map (dfb,\n"
        "                      reference, stream)\n"
        "  --stats FILE.json   per-frame figures: wall ms and gpu_ms (GL timestamp\n"
        "                      queries, read without stalling; -1 where the driver has\n"
        "                      none, gpu_timer says why) with gpu_phase_ms (upload,\n"
        "                      pass1, pass2, resolve, readback, binning, sweep,\n"
        "                      other); a summary of\n"
        "                      warm medians; for stream, the budget it chose, and\n"
        "                      per frame host_waits (the host's waits on the GPU\n"
        "                      within it: read-backs, fences that blocked; not the\n"
        "                      final read-back) and redraws (first-k frames drawn\n"
        "                      again after outgrowing their second pass's store);\n"
        "                      gpu_bytes_peak, every GPU buffer and texture the\n"
        "                      method held at its peak: an in-core method's working\n"
        "                      memory and the mesh it uploaded (gpu_mesh_bytes, its\n"
        "                      triangle and draw-record buffers), the stream's ring,\n"
        "                      cache, capture and per-pixel state (gpu_mesh_bytes 0).\n"
        "                      With --window: frame counters (frames_rendered,\n"
        "                      exact_frames, preview_frames, presented, shown, view),\n"
        "                      rewritten after every frame\n"
        "  --ambiguity PATH    (reference) also write a mask, named like --out, that is\n"
        "                      white where rasterization and ray casting may disagree:\n"
        "                      the hit set changes within 1/64 pixel of the centre\n"
        "                      (depth ties are not ambiguous: the tie rule orders them)\n"
        "  --ambiguity-px P    that radius in pixels instead, in (0, 4]\n"
        "  --pick X,Y          instead of an image, print as JSON every layer of pixel\n"
        "                      X,Y (0,0 the top left) front to back: depth (the tie\n"
        "                      rule's key along the pixel's ray), point (where it\n"
        "                      meets the triangle, file coordinates), alpha, colour,\n"
        "                      transmittance in front of it, part (null in core),\n"
        "                      source_triangle, group and material (null: no reader\n"
        "                      keeps names yet). The layers of the exact image: the\n"
        "                      reference's ray and tie rule (through Embree for\n"
        "                      --method reference on a mesh); a rasterizing method\n"
        "                      may differ by a triangle on edge pixels only\n"
        "                      (--ambiguity shows them). A part file is walked a part\n"
        "                      at a time. Needs no GL.\n"
        "  --quiet             no per-frame lines\n"
        "  --up auto|x|y|z     the model's up axis for the default views; z: seen\n"
        "                      from -y, x to the right. auto (default): y for glTF\n"
        "                      (its specification), z for STEP and IGES (as CAD\n"
        "                      writes them), else z where the model is flat in z\n"
        "                      (its z extent under half its x and y extents: a\n"
        "                      Z-up plant or building), else y; a part file by its\n"
        "                      source's name. Said on stderr when it is not y\n"
        "  --clip nx,ny,nz,d   a section plane, in file coordinates: keeps what lies\n"
        "                      where nx*x + ny*y + nz*z + d >= 0 and cuts the rest\n"
        "                      away, exactly per pixel (a fragment is kept when its\n"
        "                      point on its pixel's ray is kept); repeatable, up to 6\n"
        "                      planes (what all of them keep); the normal must not be\n"
        "                      0. Every method clips; stream neither uploads nor\n"
        "                      draws parts wholly cut away (--stats: parts_clipped,\n"
        "                      bytes_clipped)\n"
        "  --window            open an interactive window instead of writing images\n"
        "                      (--size is the window's). It renders only when the\n"
        "                      view or a setting changes: while the camera moves a\n"
        "                      preview (see --preview), then the exact frame once\n"
        "                      it was still for --still ms; the status line says\n"
        "                      which. Keys (H or ? shows them in the window):\n"
        "                      left-drag orbits, right-drag/wheel zooms, W/A/S/D and\n"
        "                      Space/C fly; 1..9, 0 pick the first ten methods above\n"
        "                      in --method's order (the same key for every input; a\n"
        "                      method this input or machine cannot run says why on\n"
        "                      screen), M/N next/previous method (all of them); L\n"
        "                      layer heat map, T transparent/translucent, E early\n"
        "                      termination, U up axis y/z/x, V perspective/\n"
        "                      orthographic, X section plane (one\n"
        "                      through the centre facing you, or the planes off/on),\n"
        "                      [ and ] move section plane 1, R resets the view, O\n"
        "                      opens another file (type its path, Enter; or drop a\n"
        "                      file on the window), P saves the first free\n"
        "                      oitstream_NNN.png (never replacing one): the view\n"
        "                      rendered offscreen at --shot-size, exact, without\n"
        "                      the overlay, its name, size and --view on stdout;\n"
        "                      G the same of the window as shown; Esc/Q quits\n"
        "  --preview P         --window, while the camera moves: lowres (the same\n"
        "                      method at 1/2..1/4 of the resolution, upscaled, the\n"
        "                      scale adapted to frames near 30 ms), wboit or\n"
        "                      unsorted (those methods at full size), off (exact\n"
        "                      frames throughout); auto (default): lowres when an\n"
        "                      exact frame takes more than 40 ms, else off\n"
        "  --still MS          --window: stillness before the exact frame, 1..60000\n"
        "                      (default 200)\n"

        "  --window-frames N   render N exact frames back to back, then stop,\n"
        "                      1..100000000 (a benchmark: the window otherwise\n"
        "                      renders only on changes)\n"
        "  --window-script K   press the keys K, one per exact frame (e.g. 2LT), then\n"
        "                      stop\n"
        "  --window-screenshot PATH  write the last frame shown (PNG) when stopping\n"
        "  --shot-size WxH     --window: the size of P's screenshots, each side\n"
        "                      1..16384 (default: the window's)\n"
        "  --no-overlay        no status line in the window's image\n"
        "  --compare A B       print RMSE, max abs error, %% of pixels off by more than\n"
        "                      1/255 and PSNR of two images (.png/.pfm), both in the\n"
        "                      sRGB-encoded space (a PFM's linear light is encoded on\n"
        "                      reading, so 1/255 is one 8-bit step); --json for JSON,\n"
        "                      --out DIFF.png writes |A-B| * gain (--gain G > 0, default 1);\n"
        "                      --mask M adds the figures outside M's non-black pixels\n"
        "\n"
        OIT_TOOL_MESH_FORMATS_HELP
        "\n"
        "Exit status: 0 ok, 1 runtime failure, 2 usage error, 3 bad input.\n",
        method_list);
}
