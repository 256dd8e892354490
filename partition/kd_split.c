/* Split choice for the kd subdivision (kd_split.h). */
#include "partition/kd_split.h"

int oit_kd_split_cells(const float lo[3], const float hi[3], int axis, float pos,
                       float origin[3], float cell_size[3])
{
    for (int k = 0; k < 3; k++) {
        origin[k] = lo[k];
        cell_size[k] = hi[k] - lo[k];
    }
    float below = pos - lo[axis], above = hi[axis] - pos;
    float w = below > above ? below : above;
    origin[axis] = pos - w;
    cell_size[axis] = w;
    volatile float plane = origin[axis] + w; /* as stream/order.c computes it */
    return w > 0 && plane == pos && origin[axis] <= lo[axis] && plane + w >= hi[axis];
}

typedef struct split_score {
    uint32_t parts, cut, imbalance;
} split_score;

static int better(split_score a, split_score b)
{
    if (a.parts != b.parts)
        return a.parts < b.parts;
    if (a.cut != b.cut)
        return a.cut < b.cut;
    return a.imbalance < b.imbalance;
}

static int score(const oit_kd_piece_box *pieces, uint32_t count, int axis, float m,
                 uint32_t max_layers, uint32_t total, split_score *out)
{
    uint32_t below = 0, above = 0, cut = 0;
    for (uint32_t i = 0; i < count; i++) {
        const oit_kd_piece_box *p = &pieces[i];
        int b = p->lo[axis] < m || p->hi[axis] <= m, a = p->hi[axis] > m;
        below += b ? p->weight : 0;
        above += a ? p->weight : 0;
        cut += a && b ? p->weight : 0;
    }
    uint32_t larger = below > above ? below : above;
    if (larger >= total)
        return 0;
    /* Big nodes split near the middle: peeling one part at a time would
     * make the tree (and the sets held along its path) as deep as the node
     * has parts. */
    if (total > 4 * max_layers && larger > total - total / 4)
        return 0;
    out->parts = (below + max_layers - 1) / max_layers + (above + max_layers - 1) / max_layers;
    out->cut = cut;
    out->imbalance = larger - (below + above - larger);
    return 1;
}

int oit_kd_choose_split(const oit_kd_piece_box *pieces, uint32_t count, const float lo[3],
                        const float hi[3], uint32_t max_layers, int *axis, float *pos)
{
    uint32_t total = 0;
    for (uint32_t i = 0; i < count; i++)
        total += pieces[i].weight;
    int found = 0;
    split_score best = {0, 0, 0};
    for (int a = 0; a < 3; a++) {
        for (int j = 1; j < 16; j++) {
            double md = (double)lo[a] + ((double)hi[a] - lo[a]) * j / 16.0;
            float m = (float)md, origin[3], cell[3];
            if ((double)m != md || !(m > lo[a] && m < hi[a]) ||
                !oit_kd_split_cells(lo, hi, a, m, origin, cell))
                continue;
            split_score s;
            if (score(pieces, count, a, m, max_layers, total, &s) && (!found || better(s, best))) {
                best = s;
                *axis = a;
                *pos = m;
                found = 1;
            }
        }
    }
    return found;
}
