/* Choices between frames (streamer_internal.h): the automatic pack
 * mode's path (view/stream/choice.h) and early termination's front-first
 * packs, from what the frames measured. */
#include "view/stream/streamer_internal.h"

#include <stdlib.h>
#include <string.h>

/* Early termination's choice for the next frame: front-first packs while
 * they let whole parts be skipped; after a frame that skipped none, plain
 * packs, front first tried again every OIT_STREAM_PROBE_FRAMES frames. */
static void adapt_front(oit_streamer *s, oit_stream_frame_stats *ss)
{
    ss->front_first = s->front_now;
    if (s->front_now && ss->parts_skipped == 0)
        s->front_now = 0, s->plain_frames = 0;
    else if (s->front_first && !s->front_now && ++s->plain_frames >= OIT_STREAM_PROBE_FRAMES)
        s->front_now = 1;
}

/* The automatic mode's path for this frame (view/stream/choice.h). A frame
 * still open is judged first, on the streamer's own time. */
void oit_streamer_choose(oit_streamer *s, const oit_view *view)
{
    if (!s->adaptive)
        return;
    if (s->frame.open)
        oit_choice_end(&s->judge, s->frame.ms, s->frame.suggest);
    s->frame.open = 0;
    oit_path p = oit_choice_begin(&s->judge, oit_view_key(view));
    s->first_k = p == OIT_PATH_FIRSTK;
    oit_capture_set_first_k(s->capture, s->first_k);
    /* a first-K frame keeps its counts for a counted probe of its view
     * where the rule may suggest one */
    oit_capture_settings cs = oit_capture_get_settings(s->capture);
    cs.no_counts = s->frame.adapted && s->frame.suggest != OIT_PATH_COUNTED;
    oit_capture_apply(s->capture, &cs);
}

/* What the frame's path was chosen from (the judge's figures before the
 * frame ends). */
void oit_streamer_choice_stats(const oit_streamer *s, oit_stream_frame_stats *ss)
{
    ss->choice_ms[OIT_PATH_FIRSTK] = ss->choice_ms[OIT_PATH_COUNTED] = -1.0;
    if (!s->adaptive)
        return;
    for (int i = 0; i < OIT_PATHS; i++)
        ss->choice_ms[i] = oit_choice_cost(&s->judge, (oit_path)i);
    ss->choice_path = oit_path_name(s->judge.path);
    ss->choice_why = s->judge.why;
}

/* A first frame more than 1 pixel in 50 of which got more than K
 * fragments in a pack (first-K's second pass took them; a counted frame's
 * counts say it would have) is drawn again counted where it ended short
 * (render): the engine and the 1M plant at 1024x1024, 26-64 layers, send
 * 5-16% there and were 20-30% faster counted. */
int oit_streamer_deep_view(const oit_view *view, const oit_frame_stats *fs)
{
    return fs->deep_pixels * 50 > (uint64_t)view->width * view->height;
}

/* The fixed rule's seed: a frame where any pixel got more than K
 * fragments in a pack suggests counted packs, one where none did
 * suggests first-K. First-K draws a pack again for such pixels, however
 * few, while a still view's next counted frame is predicted from this
 * one's counts: one geometry pass, no second (the 332K-triangle CAD
 * assembly at 128x128 on llvmpipe: 29 pixels over K, first-K's pass 2 73
 * ms of a 148 ms frame, DFB 124). A moving view takes no probe (a probe
 * is a view's, view/stream/choice.h). A counted frame over K still suggests
 * first-K every OIT_CHOICE_BAR_MOST-th frame, so that the rule never
 * decides alone; the judge keeps a suggested path only if it measures
 * faster. */
static int over_k(const oit_frame_stats *fs)
{
    return fs->deep_pixels > 0;
}

void oit_streamer_adapt(oit_streamer *s, const oit_frame_stats *fs, oit_stream_frame_stats *ss,
                        double ms, int judged_now)
{
    adapt_front(s, ss);
    ss->first_k = s->adaptive ? s->first_k : 0;
    if (!s->adaptive)
        return;
    int over = over_k(fs);
    oit_path suggest = over ? OIT_PATH_COUNTED : OIT_PATH_FIRSTK;
    if (!s->first_k && over && ++s->frame.deep_counted % OIT_CHOICE_BAR_MOST == 0)
        suggest = OIT_PATH_FIRSTK;
    /* the probe's programs and store made in this frame, not the probe's:
     * its time is what the judge weighs (the 1M plant at 1024x1024: the
     * cold probe took 955 ms against 852 warm, DFB 768) */
    if (s->first_k && suggest == OIT_PATH_COUNTED)
        oit_capture_ready_counted(s->capture);
    s->frame.ms = ms;
    s->frame.suggest = suggest;
    s->frame.adapted = 1;
    s->frame.open = 1;
    if (judged_now)
        oit_streamer_frame_end(s, ms, 0);
}

void oit_streamer_frame_end(oit_streamer *s, double wall_ms, uint64_t gpu_tag)
{
    if (!s->adaptive)
        return;
    if (s->frame.open)
        oit_choice_end(&s->judge, wall_ms, s->frame.suggest);
    s->frame.open = 0;
    oit_choice_tag_gpu(&s->judge, gpu_tag);
}

void oit_streamer_gpu_figure(oit_streamer *s, uint64_t gpu_tag, double gpu_ms)
{
    if (s->adaptive)
        oit_choice_gpu(&s->judge, gpu_tag, gpu_ms);
}
