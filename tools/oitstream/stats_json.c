/* JSON writer for oitstream --stats (stats_json.h). */
#include "tools/oitstream/stats_json.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void oit_stats_format_view(const oit_camera *c, const double origin[3], char *buf, size_t cap)
{
    double o[3] = {0, 0, 0};
    if (origin)
        memcpy(o, origin, sizeof o);
    snprintf(buf, cap, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g",
             o[0] + c->eye[0], o[1] + c->eye[1], o[2] + c->eye[2], o[0] + c->target[0],
             o[1] + c->target[1], o[2] + c->target[2],
             c->up[0], c->up[1], c->up[2], c->fovy_deg, c->znear,
             isinf(c->zfar) ? 2.0f * c->znear + 1.0f : c->zfar);
    /* The projection, as --view's fields (view.h, oit_camera_parse). */
    size_t n = strlen(buf);
    if (c->projection == OIT_PROJ_ORTHOGRAPHIC && n < cap)
        n += (size_t)snprintf(buf + n, cap - n, ":ortho=%.9g", c->ortho_height);
    if ((c->window[0] != 0.0f || c->window[1] != 0.0f || c->window[2] != 0.0f ||
         c->window[3] != 0.0f) && n < cap)
        n += (size_t)snprintf(buf + n, cap - n, ":window=%.9g,%.9g,%.9g,%.9g", c->window[0],
                              c->window[1], c->window[2], c->window[3]);
    if (isinf(c->zfar) && n < cap)
        snprintf(buf + n, cap - n, ":far=inf");
}

static void put_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            fprintf(f, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(f, "\\u%04x", ch);
        else
            fputc(ch, f);
    }
    fputc('"', f);
}

static void put_frame(FILE *f, const oit_stats_frame *fr, int last)
{
    const oit_frame_stats *s = &fr->st;
    fprintf(f, "    {\"method\": ");
    put_string(f, fr->method);
    fprintf(f, ", \"view\": ");
    put_string(f, fr->view);
    fprintf(f,
            ", \"ms\": %.3f, \"fragments\": %llu, \"max_layers\": %u, \"overflow_pixels\": %llu, "
            "\"gpu_bytes_peak\": %llu, \"batches\": %u, \"second_pass_pixels\": %llu, "
            "\"second_pass_packs\": %u, \"fragments_saturated\": %llu",
            isfinite(s->ms) ? s->ms : -1.0, (unsigned long long)s->fragments, s->max_layers,
            (unsigned long long)s->overflow_pixels, (unsigned long long)s->gpu_bytes_peak,
            s->batches, (unsigned long long)s->second_pass_pixels, s->second_pass_packs,
            (unsigned long long)s->fragments_saturated);
    if (fr->has_stream)
        fprintf(f, ", \"packs\": %u, \"parts_drawn\": %llu, \"parts_culled\": %llu, "
                "\"parts_skipped\": %llu, \"bytes_uploaded\": %llu, \"cache_hits\": %llu, "
                "\"cache_bytes\": %llu, \"epsilon\": %.9g, \"draw_calls\": %llu, "
                "\"order_ms\": %.3f, \"pack_ms\": %.3f, \"auto_first_k\": %d, "
                "\"front_first\": %d",
                fr->stream.packs, (unsigned long long)fr->stream.parts_drawn,
                (unsigned long long)fr->stream.parts_culled,
                (unsigned long long)fr->stream.parts_skipped,
                (unsigned long long)fr->stream.bytes_uploaded,
                (unsigned long long)fr->stream.cache_hits,
                (unsigned long long)fr->stream.cache_bytes, (double)fr->stream.epsilon,
                (unsigned long long)fr->stream.draw_calls, fr->stream.order_ms,
                fr->stream.pack_ms, fr->stream.first_k, fr->stream.front_first);
    fprintf(f, "}%s\n", last ? "" : ",");
}

oit_status oit_stats_json_write(const char *path, const oit_stats_run *run, oit_error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return oit_error_set(err, OIT_ERR_IO, "%s: cannot open for writing", path);
    fprintf(f, "{\n  \"model\": ");
    put_string(f, run->model);
    fprintf(f, ",\n  \"triangles\": %llu,\n  \"renderer\": ", run->triangles);
    put_string(f, run->renderer);
    fprintf(f, ",\n  \"width\": %d,\n  \"height\": %d,\n  \"frames\": [\n", run->width,
            run->height);
    for (size_t i = 0; i < run->frame_count; i++)
        put_frame(f, &run->frames[i], i + 1 == run->frame_count);
    fprintf(f, "  ]\n}\n");
    if (ferror(f) | (fclose(f) != 0))
        return oit_error_set(err, OIT_ERR_IO, "%s: write failed", path);
    return OIT_OK;
}
