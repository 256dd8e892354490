/* Stage progress bars (progress.h). */
#include "preprocess/progress.h"

#include <stdio.h>

void oit_progress_start(oit_progress *p, const char *stage, uint64_t total, int enabled)
{
    p->stage = stage;
    p->total = total ? total : 1;
    p->enabled = enabled;
    p->shown = -1;
    oit_progress_update(p, 0);
}

void oit_progress_update(oit_progress *p, uint64_t done)
{
    if (!p->enabled)
        return;
    int pct = (int)(done >= p->total ? 100 : done * 100 / p->total);
    if (pct == p->shown)
        return;
    p->shown = pct;
    char bar[41];
    for (int i = 0; i < 40; i++)
        bar[i] = i < pct * 40 / 100 ? '#' : '.';
    bar[40] = 0;
    fprintf(stderr, "\r%-10s [%s] %3d%%", p->stage, bar, pct);
    fflush(stderr);
}

void oit_progress_end(oit_progress *p)
{
    if (!p->enabled)
        return;
    oit_progress_update(p, p->total);
    fputc('\n', stderr);
}
