/* The automatic pack mode's judge (choice.h). */
#include "view/stream/choice.h"

#include <stdio.h>
#include <string.h>

const char *oit_path_name(oit_path p)
{
    switch (p) {
    case OIT_PATH_FIRSTK:
        return "first-k";
    case OIT_PATH_COUNTED:
        return "counted";
    default:
        return "?";
    }
}

void oit_choice_init(oit_choice *c, unsigned candidates, oit_path seed)
{
    memset(c, 0, sizeof *c);
    c->candidates = candidates | 1u << seed;
    c->held = seed;
    c->path = seed;
    c->cur = -1;
    c->why = "seed";
    for (int p = 0; p < OIT_PATHS; p++)
        c->backoff[p] = OIT_CHOICE_BAR_FIRST;
}

static int candidate(const oit_choice *c, oit_path p)
{
    return p >= 0 && p < OIT_PATHS && (c->candidates >> p & 1u);
}

/* GPU time enters the costs only where every measured path has it. */
static int gpu_basis(const oit_choice *c, const oit_choice_view *v)
{
    int any = 0;
    for (int p = 0; p < OIT_PATHS; p++) {
        if (!candidate(c, (oit_path)p) || !v->cost[p].frames)
            continue;
        if (!v->cost[p].gpu_frames)
            return 0;
        any = 1;
    }
    return any;
}

static double view_cost(const oit_choice *c, const oit_choice_view *v, oit_path p)
{
    const oit_path_cost *k = &v->cost[p];
    if (!candidate(c, p) || !k->frames)
        return -1.0;
    return gpu_basis(c, v) ? k->gpu_ms : k->wall_ms;
}

double oit_choice_cost(const oit_choice *c, oit_path p)
{
    if (c->cur < 0 || p < 0 || p >= OIT_PATHS)
        return -1.0;
    return view_cost(c, &c->views[c->cur], p);
}

static void view_reset(oit_choice_view *v, uint64_t key, oit_path start)
{
    memset(v, 0, sizeof *v);
    v->key = key;
    v->held = v->next = start;
}

/* The view of key, or a free or the least recently used one re-seeded. */
static int find_view(oit_choice *c, uint64_t key, int *fresh)
{
    int victim = 0;
    for (int i = 0; i < OIT_CHOICE_VIEWS; i++) {
        if (c->views[i].used && c->views[i].key == key) {
            *fresh = 0;
            return i;
        }
        if (c->views[i].used < c->views[victim].used)
            victim = i;
    }
    *fresh = 1;
    view_reset(&c->views[victim], key, c->held);
    return victim;
}

/* The cheapest measured candidate of v (ties: the held path). */
static oit_path cheapest(const oit_choice *c, const oit_choice_view *v)
{
    oit_path best = v->held;
    double bc = view_cost(c, v, best);
    for (int p = 0; p < OIT_PATHS; p++) {
        double pc = view_cost(c, v, (oit_path)p);
        if (pc >= 0.0 && (bc < 0.0 || pc < bc))
            best = (oit_path)p, bc = pc;
    }
    return best;
}

/* p lost a comparison: not probed on any view for its bar, longer each
 * time. */
static void bar(oit_choice *c, oit_path p)
{
    c->bar[p] = c->backoff[p];
    c->backoff[p] = c->backoff[p] * 2 > OIT_CHOICE_BAR_MOST ? OIT_CHOICE_BAR_MOST
                                                           : c->backoff[p] * 2;
}

/* The held path measured slower than best: best is held from now on (the
 * old one barred unless its one figure was the start-up frame's). */
static void give_way(oit_choice *c, oit_choice_view *v, oit_path best, const char *why)
{
    if (!v->cost[v->held].cold)
        bar(c, v->held);
    v->held = v->next = best;
    v->why = why;
}

oit_path oit_choice_begin(oit_choice *c, uint64_t key)
{
    int fresh = 0;
    int first = c->clock == 0;
    c->cur = find_view(c, key, &fresh);
    oit_choice_view *v = &c->views[c->cur];
    v->used = ++c->clock;
    /* GPU figures that came in since the view's last frame may have
     * turned the comparison. */
    oit_path best = cheapest(c, v);
    if (!fresh && v->next == v->held && best != v->held)
        give_way(c, v, best, "measured faster");
    c->path = v->next;
    c->why = fresh ? (first ? "seed" : "new view") : v->why;
    return c->path;
}

/* After a probe of p: kept where it measured cheaper than the held path
 * (which is then barred: it was just measured), else back, with p barred. */
static void judge_probe(oit_choice *c, oit_choice_view *v, oit_path p)
{
    double cp = view_cost(c, v, p), ch = view_cost(c, v, v->held);
    if (ch >= 0.0 && cp < ch) {
        give_way(c, v, p, "kept: measured faster");
        return;
    }
    bar(c, p);
    v->next = v->held;
    v->why = "back: measured slower";
}

void oit_choice_end(oit_choice *c, double wall_ms, oit_path suggest)
{
    if (c->cur < 0)
        return;
    oit_choice_view *v = &c->views[c->cur];
    oit_path p = c->path;
    oit_path_cost *k = &v->cost[p];
    if (!k->frames || wall_ms < k->wall_ms)
        k->wall_ms = wall_ms;
    k->cold = !k->frames && c->clock == 1;
    c->wall_ms = wall_ms;
    k->frames++;
    for (int q = 0; q < OIT_PATHS; q++)
        if (q != (int)p && c->bar[q])
            c->bar[q]--;
    if (p != v->held) {
        judge_probe(c, v, p);
    } else {
        oit_path best = cheapest(c, v);
        v->why = "held";
        v->next = v->held;
        if (best != v->held)
            give_way(c, v, best, "measured faster");
        else if (candidate(c, suggest) && suggest != p && !c->bar[suggest])
            v->next = suggest, v->why = "probe";
    }
    c->held = v->held;
}

void oit_choice_tag_gpu(oit_choice *c, uint64_t tag)
{
    if (!tag || c->cur < 0)
        return;
    unsigned i = c->pending_next++ % OIT_CHOICE_PENDING;
    c->pending[i].tag = tag;
    c->pending[i].key = c->views[c->cur].key;
    c->pending[i].path = c->path;
    c->pending[i].wall_ms = c->wall_ms;
}

void oit_choice_gpu(oit_choice *c, uint64_t tag, double gpu_ms)
{
    for (unsigned i = 0; tag && i < OIT_CHOICE_PENDING; i++) {
        if (c->pending[i].tag != tag)
            continue;
        c->pending[i].tag = 0;
        for (int j = 0; j < OIT_CHOICE_VIEWS; j++) {
            oit_choice_view *v = &c->views[j];
            if (!v->used || v->key != c->pending[i].key)
                continue;
            oit_path_cost *k = &v->cost[c->pending[i].path];
            double ms = gpu_ms > c->pending[i].wall_ms ? gpu_ms : c->pending[i].wall_ms;
            if (!k->gpu_frames || ms < k->gpu_ms)
                k->gpu_ms = ms;
            k->gpu_frames++;
        }
        return;
    }
}

void oit_choice_describe(const oit_choice *c, char *out, size_t n)
{
    if (!n)
        return;
    out[0] = '\0';
    size_t used = 0;
    for (int p = 0; p < OIT_PATHS && used < n; p++) {
        if (!candidate(c, (oit_path)p))
            continue;
        double ms = oit_choice_cost(c, (oit_path)p);
        int w = ms < 0.0 ? snprintf(out + used, n - used, "%s%s -", used ? ", " : "",
                                    oit_path_name((oit_path)p))
                         : snprintf(out + used, n - used, "%s%s %.1f ms", used ? ", " : "",
                                    oit_path_name((oit_path)p), ms);
        if (w < 0)
            return;
        used += (size_t)w;
    }
}
