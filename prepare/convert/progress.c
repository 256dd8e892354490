/* Stage progress (progress.h). */
#include "prepare/convert/progress.h"

#include <stdio.h>

#include "base/clock.h"

void oit_progress_start(oit_progress *p, const char *stage, uint64_t total,
                        oit_progress_mode mode, double period_s)
{
    p->stage = stage;
    p->total = total ? total : 1;
    p->mode = mode;
    p->shown = p->seen = -1;
    p->period_s = period_s > 0.0 ? period_s : OIT_PROGRESS_PERIOD_S;
    p->start = p->last = mode == OIT_PROGRESS_LINES ? oit_time_s() : 0.0;
    p->lines = 0;
    oit_progress_update(p, 0);
}

static void bar(oit_progress *p, int pct)
{
    char b[41];
    for (int i = 0; i < 40; i++)
        b[i] = i < pct * 40 / 100 ? '#' : '.';
    b[40] = 0;
    fprintf(stderr, "\r%-10s [%s] %3d%%", p->stage, b, pct);
    fflush(stderr);
}

static void line(oit_progress *p, int pct, double now)
{
    fprintf(stderr, "progress: %-10s %3d%%  %.1f s\n", p->stage, pct, now - p->start);
    fflush(stderr);
    p->last = now;
    p->lines++;
}

void oit_progress_update(oit_progress *p, uint64_t done)
{
    if (p->mode == OIT_PROGRESS_OFF)
        return;
    int pct = (int)(done >= p->total ? 100 : done * 100 / p->total);
    if (pct == p->shown)
        return;
    if (p->mode == OIT_PROGRESS_BAR) {
        p->shown = pct;
        bar(p, pct);
        return;
    }
    if (pct == p->seen)
        return;
    p->seen = pct;
    double now = oit_time_s();
    if (now - p->last < p->period_s || pct == 100)
        return; /* 100% is the end's line */
    p->shown = pct;
    line(p, pct, now);
}

void oit_progress_end(oit_progress *p)
{
    if (p->mode == OIT_PROGRESS_BAR) {
        oit_progress_update(p, p->total);
        fputc('\n', stderr);
    } else if (p->mode == OIT_PROGRESS_LINES) {
        double now = oit_time_s();
        if (p->lines || now - p->start >= p->period_s)
            line(p, 100, now);
    }
}
